# The scaling study (tools/scaling.py): GPU ms per frame against the number
# of spheres, log-log, for each layout and order (left), and the memory of
# the acceleration structures (right). Called by tools/perf-report.sh with
# data=<scaling.dat>, out, device.
set terminal pngcairo size 1100,400 font ",10"
set output out
set multiplot layout 1,2 title "spheres on a floor, ".device
set logscale xy
set grid
set key top left
set xlabel "spheres"
set ylabel "GPU ms per frame"
set datafile missing "?"
plot data using 1:2 with linespoints pt 7 title "04 instances", \
     data using 1:3 with linespoints pt 5 title "04 grouped", \
     data using 1:4 with linespoints pt 9 dt 2 title "04 file order", \
     data using 1:5 with linespoints pt 7 lw 2 title "10 instances", \
     data using 1:6 with linespoints pt 5 lw 2 title "10 grouped", \
     data using 1:7 with linespoints pt 9 lw 2 dt 2 title "10 file order"
set ylabel "acceleration structures, MB"
plot data using 1:8 with linespoints pt 7 title "instances (TLAS)", \
     data using 1:9 with linespoints pt 5 title "grouped (BLAS)"
unset multiplot
