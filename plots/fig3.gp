# Fig. 3 of Costantini et al. (2005): (1 - alpha^2) cpd against nu0_eff t (log axis: the alphas
# span decades of nu0_eff t), one set of points per (alpha, a/d) group, with the logarithmic law
# eq. (31) of the fitted D_e and nu0_eff (dashed).  Groups that haff-fit --alpha-group flags on
# the figure's own runs (inhomogeneous: their box left the homogeneous cooling state; short;
# outliers: plots/README.md, docs/analysis.md) are drawn with open symbols, their flag in the key.
# Input: `haff energy DB --all -o in`; flagged: words ALPHA=FLAG (plots.mk: from
# `haff haff-fit DB --alpha-group`), ALPHA matched to a block's alpha as a number; a bare ALPHA
# says "flagged" alone.  The x axis reaches the last point (PAPER=1: nu0_eff t ~ 10^4).
# usage: gnuplot -e "in='energy.tsv'; out='fig3.png'[; flagged='0.9=inhomogeneous 0.8=short']" plots/fig3.gp
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
# each block's flag ("-": none; "+": a bare ALPHA), from the word of flagged whose alpha is the
# block's
flist = ""
do for [i = 1:words(alist)] {
  f = "-"
  do for [k = 1:words(flagged)] {
    w = word(flagged, k); p = strstrt(w, "=")
    if ((p > 0 ? w[1:p - 1] : w) + 0 == word(alist, i) + 0) { f = p > 0 ? w[p + 1:strlen(w)] : "+" }
  }
  flist = flist . " " . f
}
flagof(i) = word(flist, i + 1)
isflag(i) = flagof(i) ne "-"
label(i) = sprintf("α = %s (%s runs)%s", word(alist, i + 1), word(rlist, i + 1), \
                   isflag(i) ? ": flagged".(flagof(i) eq "+" ? "" : " ".flagof(i)) : "")
# the blocks with points and those with eq. (31)'s curve: nu0t (and x_eq31) are empty where a
# group has no nu0_eff (D_e) (every window short: flag short); such a block is only named in the
# key.  (Plotting every block failed: "all points y value undefined", the figure not made.)
pts = ""; fit = ""; nopts = ""
do for [i = 0:nb - 1] {
  stats in index i using (valid(8) ? 1 : 0) nooutput
  if (STATS_sum > 0) { pts = pts . sprintf(" %d", i) } else { nopts = nopts . sprintf(" %d", i) }
  stats in index i using (valid(8) && valid(10) ? 1 : 0) nooutput
  if (STATS_sum > 0) { fit = fit . sprintf(" %d", i) }
}
set title "Collisions against time, a/d = 1; d = m = T_0 = 1 (ν_0^{eff} t dimensionless)"
set xlabel "ν_0^{eff} t"
set ylabel "x = (1 − α²) · cpd"
set logscale x
set format x "10^{%L}"
# to half a decade past the last point (a fixed 3000 cut α = 0.98 off at PAPER=1's XMAX = 24)
if (strlen(pts) > 0) {
  stats in using 8 nooutput
  set xrange [0.3 : STATS_max * 1.5]
} else {
  set xrange [0.3 : 3000]; set yrange [0 : 16]
  set label 1 "no group has a fitted ν_0^{eff}: nothing to draw" at graph 0.5, graph 0.5 center
}
set key at graph 0.02, graph 0.98 left top Left reverse spacing 1.1 font ",10"
b(k, list) = word(list, k) + 0
points = 'for [k=1:words(pts)] in index b(k, pts) using 8:7 every 3 with points lt b(k, pts) + 1 pt (isflag(b(k, pts)) ? 6 : 7) title label(b(k, pts))'
eq31 = "eq. (31): (1 − α²) ln(1 + γν_0 t)/γ, fitted D_e"
dashed = 'for [k=1:words(fit)] in index b(k, fit) using 8:10 with lines dt 2 lw 1.5 lc rgb "black" title (k == 1 ? eq31 : "")'
named = 'for [k=1:words(nopts)] keyentry with points lt b(k, nopts) + 1 pt (isflag(b(k, nopts)) ? 6 : 7) title label(b(k, nopts)).", no ν_0^{eff}: not drawn"'
# one plot of the parts that have blocks (an empty for [k=1:0] would plot once)
cmd = strlen(pts) > 0 ? points : "NaN notitle"
if (strlen(fit) > 0) { cmd = cmd . ", " . dashed }
if (strlen(nopts) > 0) { cmd = cmd . ", " . named }
plot @cmd
