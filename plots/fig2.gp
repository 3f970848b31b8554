# Fig. 2 of Costantini et al. (2005): energy per dimer against (1 - alpha^2) cpd, one curve per
# (alpha, a/d) group, with the hard-disk Haff reference (dashed); inset: against nu0_eff t with
# Haff's law.  Input: `haff energy DB --all -o in`; optional ref: the same for a database of
# hard-disk runs (drawn as dashed lines; without it the analytic exp(-x/2) is dashed).
# usage: gnuplot -e "in='energy.tsv'; out='fig2.png'[; ref='energy_disks.tsv']" plots/fig2.gp
#        (.png or .svg)
if (!exists("in")) in = 'energy.tsv'
if (!exists("out")) out = 'fig2.png'
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 800,600 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size 800,600 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
stats in using 1 nooutput
nb = STATS_blocks
set multiplot
# the inset's area (with its tick labels) is opaque: a white box over the main panel's points
# (bottom left, below the curves, where the main panel has no data; the key goes top right)
set object 1 rectangle from screen 0.115, 0.125 to screen 0.585, 0.555 fillcolor rgb "white" \
    fillstyle solid 1.0 border lc rgb "gray70" front
set logscale y
set format y "10^{%L}"
set xlabel "(1 - α^2) N_{atcoll}/N"
set ylabel "E(t) / E(0)"
set key top right
set xrange [0:*]
if (exists("ref")) {
  stats ref using 1 nooutput
  nr = STATS_blocks
  plot for [i=0:nb-1] in index i using 7:4 with points pt 7 ps 0.5 title columnheader(1), \
       for [i=0:nr-1] ref index i using 7:4 with lines dt i+2 lw 2 lc rgb "black" title columnheader(1), \
       exp(-x/3) with lines dt 2 lw 3 lc rgb "#d62728" title "exp(-x/3)"
} else {
  plot for [i=0:nb-1] in index i using 7:4 with points pt 7 ps 0.5 title columnheader(1), \
       exp(-x/2) with lines dt 2 lw 2 lc rgb "black" title "hard disks, Haff: exp(-x/2)"
}
# inset: against nu0_eff t, Haff's law 1/(1 + gamma nu0 t)^2 for each group, and the late-time
# t^-2 guide
unset object 1
set size 0.46, 0.43
set origin 0.12, 0.125
set logscale xy
set format x "10^{%L}"
set xlabel "ν_0^{eff} t"
set ylabel "E/E(0)"
set key top right font ",9" samplen 2
set xrange [*:*]
plot for [i=0:nb-1] in index i using ($8 > 0 ? $8 : NaN):4 with points pt 7 ps 0.3 notitle, \
     for [i=0:nb-1] in index i using ($8 > 0 ? $8 : NaN):9 with lines dt 2 lc rgb "black" notitle, \
     (x > 3 ? 30 / x**2 : NaN) with lines lw 2 lc rgb "#d62728" title "∝ t^{-2}"
unset multiplot
