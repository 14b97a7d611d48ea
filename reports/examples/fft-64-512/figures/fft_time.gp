# 2-D transform time against size — written by `swell report`; edit and run `gnuplot fft_time.gp` here to restyle
set terminal pngcairo size 960,600 noenhanced font ',10'
set output 'fft_time.png'
set title '2-D transform time against size'
set xlabel 'n (n × n transform)'
set ylabel 'median time (ms)'
set logscale x 2
set logscale y
set grid
set key outside right top
plot 'fft_time.dat' index 0 with linespoints pt 7 ps 0.6 title 'fftw fp32 c2c', \
     'fft_time.dat' index 1 with linespoints pt 7 ps 0.6 title 'fftw fp32 c2r', \
     'fft_time.dat' index 2 with linespoints pt 7 ps 0.6 title 'fftw fp64 c2c', \
     'fft_time.dat' index 3 with linespoints pt 7 ps 0.6 title 'fftw fp64 c2r', \
     'fft_time.dat' index 4 with linespoints pt 7 ps 0.6 title 'radix2 fp32 c2c', \
     'fft_time.dat' index 5 with linespoints pt 7 ps 0.6 title 'radix2 fp32 c2r', \
     'fft_time.dat' index 6 with linespoints pt 7 ps 0.6 title 'radix2 fp64 c2c', \
     'fft_time.dat' index 7 with linespoints pt 7 ps 0.6 title 'radix2 fp64 c2r'
