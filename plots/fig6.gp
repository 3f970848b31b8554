# Fig. 6 of Costantini et al. (2005): a) translational (each component) and b) rotational
# velocity distributions scaled by the instantaneous thermal velocity, one curve per snapshot
# (cpd), against the Gaussian (dashed).  Input: `haff veldist DB --run ID -o in`; optional pool:
# `haff veldist DB --pool -o pool` (the snapshots of many runs inside their HCS windows, drawn
# as large black marks, whose tails reach |c| = 4-5).
# usage: gnuplot -e "in='veldist.tsv'; out='fig6.png'[; pool='veldist_pool.tsv']" plots/fig6.gp
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
set yrange [1e-6:1]
set format y "10^{%L}"
set key bottom center
set xlabel "c = V_{x,y} / v_{th}"
set ylabel "P(c)"
set title "a) translational"
# filled marks V_x, open marks V_y (same colour per snapshot); the key says so
plot for [i=0:nb-1] in index i using 3:($4 > 0 ? $4 : NaN) with points pt 7 ps 0.6 lc i+1 title columnheader(1), \
     for [i=0:nb-1] in index i using 3:($5 > 0 ? $5 : NaN) with points pt 6 ps 0.6 lc i+1 notitle, \
     in index 0 using 3:7 with lines dt 2 lw 2 lc rgb "black" title "Gaussian", \
     NaN with points pt 7 ps 0.8 lc rgb "gray40" title "filled: V_x", \
     NaN with points pt 6 ps 0.8 lc rgb "gray40" title "open: V_y", \
     (exists("pool") ? pool : in) index 0 using 3:(exists("pool") && $4 > 0 ? $4 : NaN) \
       with points pt 5 ps 1.1 lc rgb "black" title (exists("pool") ? columnheader(1) : ""), \
     (exists("pool") ? pool : in) index 0 using 3:(exists("pool") && $5 > 0 ? $5 : NaN) \
       with points pt 4 ps 1.1 lc rgb "black" notitle
set xlabel "c = ω / ω_{th}"
set title "b) rotational"
plot for [i=0:nb-1] in index i using 3:($6 > 0 ? $6 : NaN) with points pt 7 ps 0.6 lc i+1 title columnheader(1), \
     in index 0 using 3:7 with lines dt 2 lw 2 lc rgb "black" title "Gaussian", \
     (exists("pool") ? pool : in) index 0 using 3:(exists("pool") && $6 > 0 ? $6 : NaN) \
       with points pt 5 ps 1.1 lc rgb "black" title (exists("pool") ? "pooled" : "")
unset multiplot
