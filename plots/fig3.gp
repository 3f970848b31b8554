# Fig. 3 of Costantini et al. (2005): (1 - alpha^2) cpd against nu0_eff t (log axis: the alphas
# span decades of nu0_eff t), one set of points per (alpha, a/d) group, with the logarithmic law
# eq. (31) of the fitted D_e and nu0_eff (dashed).  Groups the tables flag inhomogeneous (their
# box left the homogeneous cooling state: plots/README.md) are drawn with open symbols and say so.
# Input: `haff energy DB --all -o in`; flagged: the alphas flagged (words), from fits-groups.tsv.
# usage: gnuplot -e "in='energy.tsv'; out='fig3.png'[; flagged='0.9 0.8']" plots/fig3.gp
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'energy.tsv'
if (!exists("out")) out = 'fig3.png'
if (!exists("flagged")) flagged = ''
eval term(out, 800, 600)
set output out
set datafile separator "\t"
stats in using 1 nooutput
nb = STATS_blocks
# each block's alpha and runs, from its comment line '# dimers alpha=A a_over_d=.. runs=R ..'
alist = system("awk '/^# / { for (i = 2; i <= NF; i++) if ($i ~ /^alpha=/) print substr($i, 7) }' '".in."'")
rlist = system("awk '/^# / { for (i = 2; i <= NF; i++) if ($i ~ /^runs=/) print substr($i, 6) }' '".in."'")
isflag(i) = strstrt(" ".flagged." ", " ".word(alist, i + 1)." ") > 0
label(i) = sprintf("α = %s (%s runs)%s", word(alist, i + 1), word(rlist, i + 1), \
                   isflag(i) ? ": flagged inhomogeneous" : "")
set title "Collisions against time, a/d = 1; d = m = T_0 = 1 (ν_0^{eff} t dimensionless)"
set xlabel "ν_0^{eff} t"
set ylabel "x = (1 − α²) · cpd"
set logscale x
set format x "10^{%L}"
set xrange [0.3:3000]
set key at graph 0.02, graph 0.98 left top Left reverse spacing 1.1 font ",10"
plot for [i=0:nb-1] in index i using 8:7 every 3 with points lt i+1 pt (isflag(i) ? 6 + 0*i : 7) \
       title label(i), \
     for [i=0:nb-1] in index i using 8:10 with lines dt 2 lw 1.5 lc rgb "black" \
         title (i == 0 ? "eq. (31): (1 − α²) ln(1 + γν_0 t)/γ, fitted D_e" : "")
