# Fig. 6 of Costantini et al. (2005): a) translational (each component) and b) rotational
# velocity distributions scaled by the instantaneous thermal velocity, one curve per snapshot
# (cpd), against the Gaussian (dashed).  Input: `haff veldist DB --run ID -o in`.
# usage: gnuplot -e "in='veldist.tsv'; out='fig6.png'" plots/fig6.gp      (.png or .svg)
if (!exists("in")) in = 'veldist.tsv'
if (!exists("out")) out = 'fig6.png'
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 1100,500 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size 1100,500 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
stats in using 3 nooutput
nb = STATS_blocks
set multiplot layout 1,2
set logscale y
set yrange [1e-4:1]
set format y "10^{%L}"
set key bottom center
set xlabel "c = V_{x,y} / v_{th}"
set ylabel "P(c)"
set title "a) translational"
plot for [i=0:nb-1] in index i using 3:($4 > 0 ? $4 : NaN) with points pt 7 ps 0.6 title columnheader(1), \
     for [i=0:nb-1] in index i using 3:($5 > 0 ? $5 : NaN) with points pt 6 ps 0.6 notitle, \
     in index 0 using 3:7 with lines dt 2 lw 2 lc rgb "black" title "Gaussian"
set xlabel "c = ω / ω_{th}"
set title "b) rotational"
plot for [i=0:nb-1] in index i using 3:($6 > 0 ? $6 : NaN) with points pt 7 ps 0.6 title columnheader(1), \
     in index 0 using 3:7 with lines dt 2 lw 2 lc rgb "black" title "Gaussian"
unset multiplot
