# The state measures of `samples` (issue 15) against cpd for a box below the HCS's critical
# size and one above it: s_perp (shear momentum structure factor at the box's smallest wave
# vectors), s_par (longitudinal), the coarse-grained flow energy over its value for independent
# velocities, and the cell-count variance over Poisson.  Each is ~1 in an uncorrelated gas.
# Input: two TSVs of `SELECT cpd, s_perp, s_par, flow_frac/flow_chaos, count_var, s_rho`.
# usage: gnuplot -e "stable='a.tsv'; unstable='b.tsv'; out='hcs.png'[; ls='..'; lu='..']" plots/hcs.gp
if (!exists("stable")) stable = 'hcs-stable.tsv'
if (!exists("unstable")) unstable = 'hcs-unstable.tsv'
if (!exists("out")) out = 'hcs.png'
if (!exists("ls")) ls = 'stable box'
if (!exists("lu")) lu = 'unstable box'
if (!exists("sthr")) sthr = 10
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 1000,450 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size 1000,450 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
set logscale y
set format y "10^{%L}"
set yrange [0.1:5000]
set xlabel "collisions per particle"
set grid lc rgb "#dddddd"
set key top left opaque box spacing 1.2
set multiplot layout 1,2
set title ls
set ylabel "measure / its uncorrelated value"
plot stable using 1:2 with lines lw 1.5 lc rgb "#d62728" title "s_⊥ (shear)", \
     '' using 1:3 with lines lw 1 lc rgb "#1f77b4" title "s_∥ (sound)", \
     '' using 1:4 with lines lw 1.5 lc rgb "#2ca02c" title "flow energy / chaos", \
     '' using 1:5 with lines lw 1 lc rgb "#9467bd" title "cell-count variance", \
     sthr with lines dt 2 lc rgb "black" title sprintf("HCS ends: 5-cpd mean of s_⊥ > %g", sthr)
set title lu
unset ylabel
set key bottom right
plot unstable using 1:2 with lines lw 1.5 lc rgb "#d62728" title "s_⊥ (shear)", \
     '' using 1:3 with lines lw 1 lc rgb "#1f77b4" title "s_∥ (sound)", \
     '' using 1:4 with lines lw 1.5 lc rgb "#2ca02c" title "flow energy / chaos", \
     '' using 1:5 with lines lw 1 lc rgb "#9467bd" title "cell-count variance", \
     sthr with lines dt 2 lc rgb "black" title sprintf("s_⊥ = %g", sthr)
unset multiplot
