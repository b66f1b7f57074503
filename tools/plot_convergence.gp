# Chapter 11's convergence: RMSE against samples per hit (left) and against
# GPU time (right), one line per sample pattern. Called by tools/perf-report.sh.
set terminal pngcairo size 900,360 font ",10"
set output out
set multiplot layout 1,2 title "chapter 11, ".device
set logscale xy
set grid
set key bottom left
set xlabel "samples per hit"
set ylabel "RMSE vs converged reference"
plot data index 0 using 2:4 with linespoints pt 7 title "uniform", \
     data index 1 using 2:4 with linespoints pt 5 title "stratified", \
     data index 2 using 2:4 with linespoints pt 9 title "hammersley"
set xlabel "GPU ms per frame"
plot data index 0 using 3:4 with linespoints pt 7 title "uniform", \
     data index 1 using 3:4 with linespoints pt 5 title "stratified", \
     data index 2 using 3:4 with linespoints pt 9 title "hammersley"
unset multiplot
