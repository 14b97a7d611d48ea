# Time relative to FFTW (same kind, precision and size) — written by `swell report`; edit and run `gnuplot fft_ratio_to_fftw.gp` here to restyle
set terminal pngcairo size 960,600 noenhanced font ',10'
set output 'fft_ratio_to_fftw.png'
set title 'Time relative to FFTW (same kind, precision and size)'
set xlabel 'n (n × n transform)'
set ylabel 'time / FFTW time'
set logscale x 2
set logscale y
set grid
set key outside right top
plot 'fft_ratio_to_fftw.dat' index 0 with linespoints pt 7 ps 0.6 title 'radix2 fp32 c2c', \
     'fft_ratio_to_fftw.dat' index 1 with linespoints pt 7 ps 0.6 title 'radix2 fp32 c2r', \
     'fft_ratio_to_fftw.dat' index 2 with linespoints pt 7 ps 0.6 title 'radix2 fp64 c2c', \
     'fft_ratio_to_fftw.dat' index 3 with linespoints pt 7 ps 0.6 title 'radix2 fp64 c2r'
