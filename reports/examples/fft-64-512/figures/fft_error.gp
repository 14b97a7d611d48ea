# Accuracy against the long-double oracle — written by `swell report`; edit and run `gnuplot fft_error.gp` here to restyle
set terminal pngcairo size 960,600 noenhanced font ',10'
set output 'fft_error.png'
set title 'Accuracy against the long-double oracle'
set xlabel 'n (n × n transform)'
set ylabel 'relative L2 error'
set logscale x 2
set logscale y
set grid
set key outside right top
plot 'fft_error.dat' index 0 with points pt 7 title 'fftw fp32 c2c', \
     'fft_error.dat' index 1 with points pt 7 title 'fftw fp32 c2r', \
     'fft_error.dat' index 2 with points pt 7 title 'fftw fp64 c2c', \
     'fft_error.dat' index 3 with points pt 7 title 'fftw fp64 c2r', \
     'fft_error.dat' index 4 with points pt 7 title 'radix2 fp32 c2c', \
     'fft_error.dat' index 5 with points pt 7 title 'radix2 fp32 c2r', \
     'fft_error.dat' index 6 with points pt 7 title 'radix2 fp64 c2c', \
     'fft_error.dat' index 7 with points pt 7 title 'radix2 fp64 c2r', \
     'fft_error.dat' index 8 with lines dt 2 lw 1.5 title 'bound fp32', \
     'fft_error.dat' index 9 with lines dt 2 lw 1.5 title 'bound fp64'
