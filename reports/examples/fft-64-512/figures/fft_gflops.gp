# 2-D transform speed (benchFFT GFLOP/s) — written by `swell report`; edit and run `gnuplot fft_gflops.gp` here to restyle
set terminal pngcairo size 960,600 noenhanced font ',10'
set output 'fft_gflops.png'
set title '2-D transform speed (benchFFT GFLOP/s)'
set xlabel 'n (n × n transform)'
set ylabel 'GFLOP/s'
set logscale x 2
set grid
set key outside right top
plot 'fft_gflops.dat' index 0 with linespoints pt 7 ps 0.6 title 'fftw fp32 c2c', \
     'fft_gflops.dat' index 1 with linespoints pt 7 ps 0.6 title 'fftw fp32 c2r', \
     'fft_gflops.dat' index 2 with linespoints pt 7 ps 0.6 title 'fftw fp64 c2c', \
     'fft_gflops.dat' index 3 with linespoints pt 7 ps 0.6 title 'fftw fp64 c2r', \
     'fft_gflops.dat' index 4 with linespoints pt 7 ps 0.6 title 'radix2 fp32 c2c', \
     'fft_gflops.dat' index 5 with linespoints pt 7 ps 0.6 title 'radix2 fp32 c2r', \
     'fft_gflops.dat' index 6 with linespoints pt 7 ps 0.6 title 'radix2 fp64 c2c', \
     'fft_gflops.dat' index 7 with linespoints pt 7 ps 0.6 title 'radix2 fp64 c2r'
