# Fig. 3 of Costantini et al. (2005): (1 - alpha^2) cpd against nu0_eff t, one set of points per
# (alpha, a/d) group, with the logarithmic law eq. (31) using the fitted D_e and nu0_eff.
# Input: `haff energy DB --all -o in`.
# usage: gnuplot -e "in='energy.tsv'; out='fig3.png'" plots/fig3.gp      (.png or .svg)
if (!exists("in")) in = 'energy.tsv'
if (!exists("out")) out = 'fig3.png'
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 800,600 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size 800,600 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
stats in using 1 nooutput
nb = STATS_blocks
set xlabel "ν_0^{eff} t"
set ylabel "(1 - α^2) N_{atcoll}/N"
set key bottom right  # the curves rise from the bottom left
plot for [i=0:nb-1] in index i using 8:7 with points pt 7 ps 0.5 title columnheader(1), \
     for [i=0:nb-1] in index i using 8:10 with lines dt 2 lw 2 lc rgb "black" \
         title (i == 0 ? "eq. (31): (1-α^2) ln(1+γν_0 t)/γ" : "")
