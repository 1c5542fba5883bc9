# pareto.gp - cacao-bench's plot: error against GPU time, one panel per scene, one marker per
# configuration, the Pareto front through the non-dominated configurations, reference points
# (e.g. AMD CACAO) on the same axes. cacao-bench runs it with gnuplot and these variables:
#   datafile  per scene (in order) three blocks separated by two blank lines, numbers only:
#             configurations "ms error label", front "ms error label" (sorted by time), references
#             "ms error label" (a NaN line where there is none); label indexes the array labels
#   outfile, format ("png" or "svg"), n and scene_names[1..n] (the panels' titles), labels,
#   ylabel, refname ("" = none)
cols = (n < 3) ? n : 3
rows = int((n + cols - 1) / cols)
if (format eq "svg") {
    set terminal svg size 620*cols, 440*rows dynamic font "sans,11"
} else {
    set terminal pngcairo size 620*cols, 440*rows font "sans,10"
}
set output outfile
set termoption noenhanced
set multiplot layout rows, cols title "cacao: error against GPU time (median per frame)"
set xlabel "GPU time per frame, ms (median)"
set ylabel ylabel
set grid
set key outside right top vertical font ",8" samplen 1.5 width -6
set offsets graph 0.05, graph 0.05, graph 0.08, graph 0.08
do for [i = 1:n] {
    set title scene_names[i] noenhanced
    plot datafile index 3*(i-1) using 1:2 with points pt 7 ps 1.0 lc rgb "#1f77b4" title "cacao configuration", \
         datafile index 3*(i-1)+1 using 1:2 with linespoints lw 2 pt 6 ps 1.6 lc rgb "#d62728" title "Pareto front", \
         datafile index 3*(i-1)+1 using 1:2:(labels[int($3)]) with labels offset char 0.8, char 0.6 left font ",7" noenhanced notitle, \
         datafile index 3*(i-1)+2 using 1:2 with points pt 5 ps 1.3 lc rgb "#2ca02c" title refname, \
         datafile index 3*(i-1)+2 using 1:2:(labels[int($3)]) with labels offset char 0.8, char -0.6 left font ",7" tc rgb "#2ca02c" noenhanced notitle
}
unset multiplot
