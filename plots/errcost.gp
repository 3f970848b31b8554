# Error against run time (issue 5): standard error of the ensemble mean of D_e (eq. 31 fits,
# one per run) against the total CPU seconds of the runs, one curve per run length (points:
# 2, 4, 8, ... runs, their own sd/sqrt(R); thin dashed, same colour: sd of all the runs of that
# length / sqrt(R)), with the 1/sqrt(CPU) law through the longest runs' last point.
# Input: `plots/scripts/errcost.sh HAFF L:DB... > in` (blocks per run length).
# usage: gnuplot -e "in='errcost.tsv'; out='errcost.png'[; title='...']" plots/errcost.gp
if (!exists("in")) in = 'errcost.tsv'
if (!exists("out")) out = 'errcost.png'
if (!exists("title")) title = 'D_e at one (α, a/d): error against cost'
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 800,600 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size 800,600 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
stats in using 3 nooutput
nb = STATS_blocks
# fast runs can all take the same (quantised) CPU time: give a single x value a range of its own
if (STATS_min == STATS_max && STATS_min > 0) { set xrange [STATS_min / 2 : STATS_max * 2] }
stats in using 5 nooutput
if (STATS_min == STATS_max && STATS_min > 0) { set yrange [STATS_min / 2 : STATS_max * 2] }
# reference: the last point of the last block (all runs of the longest length)
stats in index (nb - 1) using 3 nooutput
c1 = STATS_max
stats in index (nb - 1) using ($3 == c1 ? $5 : NaN) nooutput
e1 = STATS_max
set logscale xy
set format y "10^{%L}"
set xlabel "total CPU time of the runs (s)"
set ylabel "standard error of ⟨D_e⟩ over the runs"
set title title
set key top right spacing 1.4
set grid lc rgb "#dddddd"
plot for [i=0:nb-1] in index i using 3:5 with linespoints pt 7 ps 0.9 lc i+1 title columnheader(1), \
     for [i=0:nb-1] in index i using 3:7 with lines dt 2 lw 1 lc i+1 notitle, \
     e1 * sqrt(c1 / x) with lines dt 2 lw 2 lc rgb "black" title "∝ (CPU time)^{-1/2}"
