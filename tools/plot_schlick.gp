# Schlick's error against the exact Fresnel reflectance of glass (n = 1.517),
# from chapter 09's printed table:
#   build/bin/09_fresnel --headless --frames 1 --width 8 --height 8 | grep -E '^ *[0-9]+ ' > schlick.dat
#   gnuplot -e "data='schlick.dat'; out='docs/images/09_schlick_error.png'" tools/plot_schlick.gp
set terminal pngcairo size 720,380 font ",10"
set output out
set xlabel "angle of incidence (degrees)"
set ylabel "reflectance"
set y2label "error (approximation - exact)"
set y2tics
set ytics nomirror
set key top left
set grid
set xrange [0:90]
plot data using 1:2 with lines lw 2 title "exact", \
     data using 1:3 with lines lw 2 dt 2 title "Schlick, f0 from the IOR (0.042)", \
     data using 1:5 with lines lw 2 dt 3 title "Schlick, f0 = 0.08 (thesis)", \
     data using 1:4 axes x1y2 with linespoints lw 1 pt 7 ps 0.5 title "error, f0 from the IOR", \
     data using 1:6 axes x1y2 with linespoints lw 1 pt 5 ps 0.5 title "error, f0 = 0.08"
