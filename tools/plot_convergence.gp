# Chapter 11's convergence, one line per sample pattern: RMSE against
# accumulated samples (progressive, one per frame; left), against samples per
# hit in one frame (middle) and against that frame's GPU time (right).
# Called by tools/perf-report.sh with data=<convergence.dat>, out, device.
set terminal pngcairo size 1260,380 font ",10"
set output out
set multiplot layout 1,3 title "chapter 11, ".device
set logscale xy
set grid
set key bottom left
set ylabel "RMSE vs converged reference"
set xlabel "accumulated samples (1 per frame)"
plot data index 0 using 2:3 with linespoints pt 7 title "uniform", \
     data index 1 using 2:3 with linespoints pt 5 title "stratified", \
     data index 2 using 2:3 with linespoints pt 9 title "hammersley", \
     data index 3 using 2:3 with linespoints pt 11 lw 2 title "sobol (default)", \
     data index 0 using 2:(0.05*$2**-0.5) with lines dt 2 lc "gray" title "N^-0.5"
set xlabel "samples per hit, one frame"
plot data index 4 using 2:4 with linespoints pt 7 title "uniform", \
     data index 5 using 2:4 with linespoints pt 5 title "stratified", \
     data index 6 using 2:4 with linespoints pt 9 title "hammersley", \
     data index 7 using 2:4 with linespoints pt 11 lw 2 title "sobol"
set xlabel "GPU ms per frame"
plot data index 4 using 3:4 with linespoints pt 7 title "uniform", \
     data index 5 using 3:4 with linespoints pt 5 title "stratified", \
     data index 6 using 3:4 with linespoints pt 9 title "hammersley", \
     data index 7 using 3:4 with linespoints pt 11 lw 2 title "sobol"
unset multiplot
