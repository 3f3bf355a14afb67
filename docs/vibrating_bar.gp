# Convergence plot of the axial vibrating bar study (docs/verification.md).
# Run from the repository root after `vibrating_bar_study`:  gnuplot docs/vibrating_bar.gp
set datafile separator ','
set terminal pngcairo size 1200,500 font ',10'
set output 'docs/images/vibrating_bar_convergence.png'
set logscale xy
set format y '10^{%L}'
set xlabel 'cells along the bar'
set xrange [6:700]
set key bottom left
set grid
sel(name, col) = strcol(1) eq name ? column(col) : NaN
set multiplot layout 1,2
set title 'Velocity errors over one period (v0/c = 1e-4, timestep multiplier 0.2)'
set ylabel 'relative error'
plot 'verification/vibrating_bar.csv' every ::1 using 2:(sel('linear',6)) w lp lc 1 pt 7 title 'v_{cm} at t^n, linear', \
     '' every ::1 using 2:(sel('gimp',6)) w lp lc 1 pt 4 dt 2 title 'v_{cm} at t^n, gimp', \
     '' every ::1 using 2:(sel('cpdi',6)) w lp lc 1 pt 6 dt 3 title 'v_{cm} at t^n, cpdi', \
     '' every ::1 using 2:(sel('linear',8)) w lp lc 2 pt 7 title 'v_{cm} at t^n - dt/2, linear', \
     '' every ::1 using 2:(sel('gimp',8)) w lp lc 2 pt 4 dt 2 title 'v_{cm} at t^n - dt/2, gimp', \
     '' every ::1 using 2:(sel('cpdi',8)) w lp lc 2 pt 6 dt 3 title 'v_{cm} at t^n - dt/2, cpdi', \
     '' every ::1 using 2:(sel('linear',10)) w lp lc 3 pt 7 title 'particle L2 at T, linear', \
     0.4/x lc rgb 'gray' dt 4 title 'slope 1', 2/x**2 lc rgb 'black' dt 4 title 'slope 2'
set title 'Energy over one period'
set ylabel 'max |E - E_0| / E_0'
plot 'verification/vibrating_bar.csv' every ::1 using 2:(sel('linear',12)) w lp lc 1 pt 7 title 'kinetic + strain, linear', \
     '' every ::1 using 2:(sel('gimp',12)) w lp lc 1 pt 4 dt 2 title 'kinetic + strain, gimp', \
     '' every ::1 using 2:(sel('cpdi',12)) w lp lc 1 pt 6 dt 3 title 'kinetic + strain, cpdi', \
     '' every ::1 using 2:(sel('linear',14)) w lp lc 2 pt 7 title 'leapfrog energy, linear', \
     '' every ::1 using 2:(sel('gimp',14)) w lp lc 2 pt 4 dt 2 title 'leapfrog energy, gimp', \
     '' every ::1 using 2:(sel('cpdi',14)) w lp lc 2 pt 6 dt 3 title 'leapfrog energy, cpdi', \
     0.2/x lc rgb 'gray' dt 4 title 'slope 1'
unset multiplot
