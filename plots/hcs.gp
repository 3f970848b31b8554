# The state measures of `samples` (issue 15) against cpd for a box below the HCS's critical
# size and one above it: s_perp (shear momentum structure factor at the box's smallest wave
# vectors), s_par (longitudinal), the coarse-grained flow energy over its value for independent
# velocities, and the cell-count variance over Poisson.  Each is ~1 in an uncorrelated gas.
# Input: two TSVs of `SELECT cpd, s_perp, s_par, flow_frac/flow_chaos, count_var, s_rho`.
# L_c: the HCS's critical box edge for hard disks (D_e = 2) at alpha and area fraction eta
# (docs/analysis.md, "Critical size of the HCS"): boxes larger than L_c grow shear vortices.
# usage: gnuplot -e "stable='a.tsv'; unstable='b.tsv'; out='hcs.png'[; ls='..'; lu='..';
#        alpha=0.8; eta=0.05]" plots/hcs.gp
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("stable")) stable = 'hcs-stable.tsv'
if (!exists("unstable")) unstable = 'hcs-unstable.tsv'
if (!exists("out")) out = 'hcs.png'
if (!exists("ls")) ls = 'stable box'
if (!exists("lu")) lu = 'unstable box'
if (!exists("sthr")) sthr = 10
if (!exists("alpha")) alpha = 0.8
if (!exists("eta")) eta = 0.05
# L_c in units of d (docs/analysis.md): sqrt(2 pi D_e eta*/(1 - alpha^2)) / (n d chi)
etas = 1.0 / ((7 - 3 * alpha) * (1 + alpha) / 8 - (1 - alpha**2) / 4)
chi = (1 - 7 * eta / 16) / (1 - eta)**2
Lc = sqrt(2 * pi * 2 * etas / (1 - alpha**2)) / (4 * eta / pi * chi)
eval term(out, 1100, 500)
set output out
set datafile separator "\t"
set logscale y
set format y "10^{%L}"
set yrange [0.1:5000]
set xlabel "collisions per particle (cpd)"
set key top left opaque box lc rgb "gray80" spacing 1.2 font ",10"
set multiplot layout 1,2 title sprintf("State measures below and above the HCS's critical box edge " \
  . "L_c = %.0f d (α = %g, η = %g)\nL_c: the box edge beyond which shear vortices grow " \
  . "(docs/analysis.md); one run each; d = m = T_0 = 1", Lc, alpha, eta) font ",11"
thr = sprintf("HCS ends: 5-cpd mean of s_⊥ > %g", sthr)
set title ls
set ylabel "measure / its uncorrelated value"
plot stable using 1:2 with lines lw 2 lt 2 title "s_⊥ (shear)", \
     '' using 1:3 with lines lw 1.2 lt 1 title "s_∥ (sound)", \
     '' using 1:4 with lines lw 2 lt 3 dt 1 title "flow energy / chaos", \
     '' using 1:5 with lines lw 1.2 lt 4 title "cell-count variance", \
     sthr with lines dt 2 lw 1.5 lc rgb "black" title thr
set title lu
set ylabel "measure / its uncorrelated value"
set key bottom right
plot unstable using 1:2 with lines lw 2 lt 2 title "s_⊥ (shear)", \
     '' using 1:3 with lines lw 1.2 lt 1 title "s_∥ (sound)", \
     '' using 1:4 with lines lw 2 lt 3 title "flow energy / chaos", \
     '' using 1:5 with lines lw 1.2 lt 4 title "cell-count variance", \
     sthr with lines dt 2 lw 1.5 lc rgb "black" title thr
unset multiplot
