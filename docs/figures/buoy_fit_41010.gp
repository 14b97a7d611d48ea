# 41010.data_spec: fitted JONSWAP against measured Hs and Tp — written by `swell fit --spectrum`; edit and run `gnuplot buoy_fit_41010.gp` here to restyle
set terminal pngcairo size 1100,800 noenhanced font ',10'
set output 'buoy_fit_41010.png'
set multiplot layout 2,1 title '41010.data_spec: fitted JONSWAP against measured Hs and Tp'
set grid
set key outside right top
set xlabel 'days from 2020-06-01T00:00Z'
set ylabel 'Hs [m]'
plot 'buoy_fit_41010.dat' using 1:($7==0?$4:NaN):5:6 with yerrorbars pt 7 ps 0.5 lc rgb '#1f77b4' title 'fitted JONSWAP Hs, 95 % quasi-likelihood interval', \
     'buoy_fit_41010.dat' using 1:($7==1?$4:NaN) with points pt 6 ps 0.6 lc rgb '#1f77b4' title 'fitted Hs, flagged: not one JONSWAP', \
     'buoy_fit_41010.dat' using 1:3 with lines lw 1.5 lc rgb '#2ca02c' title '4 sqrt(m0) of the bands', \
     'buoy_fit_41010.dat' using 1:2 with steps lw 1 lc rgb '#d62728' title 'WVHT (summary, 0.1 m)'
set ylabel 'period [s]'
plot 'buoy_fit_41010.dat' using 1:($7==0?$10:NaN):11:12 with yerrorbars pt 7 ps 0.5 lc rgb '#1f77b4' title 'fitted JONSWAP Tp, 95 % quasi-likelihood interval', \
     'buoy_fit_41010.dat' using 1:($7==1?$10:NaN) with points pt 6 ps 0.6 lc rgb '#1f77b4' title 'fitted Tp, flagged: not one JONSWAP', \
     'buoy_fit_41010.dat' using 1:8 with steps lw 1.5 lc rgb '#2ca02c' title 'Tp of the peak band', \
     'buoy_fit_41010.dat' using 1:9 with points pt 2 ps 0.6 lc rgb '#d62728' title 'dominant period (SwP or WWP)'
unset multiplot
