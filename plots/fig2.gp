# Fig. 2 of Costantini et al. (2005): energy per dimer against x = (1 - alpha^2) cpd, one colour
# per alpha (a/d = FIG2_A), mean over the runs with a band of +- one standard deviation over the
# runs (plots/scripts/energy_band.py); the hard disks (lines); exp(-x/3) (D_e = 3, dashed, drawn
# behind the points).  Lower panel: the same divided by exp(-x/3), where the bands and the
# differences between the alphas can be seen.  Inset: against nu0_eff t (log-log) with Haff's law
# of each group's fitted D_e (dashed) and a t^-2 guide through the latest point.
# Inputs: band = energy_band.py of the dimer runs, bandref = the same of the disk runs (optional),
# in = `haff energy DB --all` of the dimer runs (the inset).
# usage: gnuplot -e "band='b.tsv'; in='energy.tsv'[; bandref='bd.tsv']; out='fig2.png'" plots/fig2.gp
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'energy.tsv'
# without band (a bare `haff energy` file: the tests), the main panel and the lower one from in,
# without bands
nob = !exists("band")
if (nob) band = in
bx(d) = nob ? column(7) : column(1)
bm(d) = nob ? column(4) : column(2)
bs(d) = nob ? 0 : column(3)
if (!exists("out")) out = 'fig2.png'
eval term(out, 820, 820)
set output out
set datafile separator "\t"
stats band using 1 nooutput
nb = STATS_blocks
nr = 0
if (exists("bandref")) { stats bandref using 1 nooutput; nr = STATS_blocks } else { bandref = band }
stats band using (bx(0)) nooutput
xmax = STATS_max
set multiplot title "Energy per dimer, a/d = 1: mean of the runs ± one s.d. (bands); d = m = T_0 = 1"
# --- main panel ---------------------------------------------------------------------------
set lmargin at screen 0.12
set rmargin at screen 0.97
set tmargin at screen 0.93
set bmargin at screen 0.40
set logscale y
set format y "10^{%L}"
set format x ""
unset xlabel
set ylabel "E(t) / E(0)"
set xrange [0:xmax]
set yrange [*:1.1]
set key top right spacing 1.1
set object 1 rectangle from graph 0.0, 0.0 to graph 0.55, 0.53 fillcolor rgb "white" \
    fillstyle solid 1.0 border lc rgb "gray60" front
plot exp(-x/3) with lines dt 2 lw 1.5 lc rgb "black" title "exp(−x/3): D_e = 3", \
     for [i=0:nr-1] bandref index i using 1:2 with lines lw 2.5 dt 2*i+1 \
       lc rgb (i == 0 ? OI8 : OI7) title columnheader(1), \
     (nr > 1 ? NaN : NaN) with lines lc rgb "white" title (nr > 1 ? "(the disk lines coincide: x scales α out)" : ""), \
     for [i=0:nb-1] band index i using (bx(0)):(bm(0) - bs(0)):(bm(0) + bs(0)) with filledcurves fs transparent solid 0.25 lc i+1 notitle, \
     for [i=0:nb-1] band index i using (bx(0)):(bm(0)) every 12 with points lt i+1 title columnheader(1)
unset object 1
# --- lower panel: over exp(-x/3) -------------------------------------------------------------
set tmargin at screen 0.375
set bmargin at screen 0.08
unset logscale y
set format y "%.2f"
set format x "%g"
set xlabel "x = (1 − α²) · cpd"
set ylabel "E / E(0) / exp(−x/3)"
set yrange [*:*]
set key top left horizontal
plot 1 with lines dt 2 lw 1.5 lc rgb "black" notitle, \
     for [i=0:nb-1] band index i using (bx(0)):((bm(0) - bs(0)) * exp(bx(0) / 3)):((bm(0) + bs(0)) * exp(bx(0) / 3)) \
       with filledcurves fs transparent solid 0.25 lc i+1 notitle, \
     for [i=0:nb-1] band index i using (bx(0)):(bm(0) * exp(bx(0) / 3)) with lines lt i+1 notitle
# --- inset: against nu0_eff t, log-log --------------------------------------------------------
stats in using 4 nooutput
ymin = STATS_min
stats in using 8 nooutput
xl = STATS_max
stats in using ($8 == xl ? $4 : NaN) nooutput
yl = STATS_max
set lmargin at screen 0.21
set rmargin at screen 0.57
set tmargin at screen 0.645
set bmargin at screen 0.475
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "ν_0^{eff} t" offset 0,0.8 font ",10"
set ylabel "E/E(0)" offset 1.5,0 font ",10"
set xtics font ",9"
set ytics font ",9"
set xrange [0.1:*]
set yrange [ymin / 2 : 2]
unset grid
set key at graph 0.02, graph 0.42 left top Left reverse font ",9" samplen 1.5 spacing 0.9
# the t^-2 guide through the latest point of the data, drawn over its last decade
plot for [i=0:nb-1] in index i using ($8 > 0 ? $8 : NaN):4 every 4 with points lt i+1 ps 0.3 notitle, \
     for [i=0:nb-1] in index i using ($8 > 0 ? $8 : NaN):9 with lines dt 2 lw 1 lc rgb "black" \
       title (i == 0 ? "Haff's law, fitted D_e" : ""), \
     (x > xl / 10 && x < xl * 3 ? 2 * yl * (xl / x)**2 : NaN) with lines lw 1.5 lc rgb OI2 \
       title "∝ t^{−2}"
unset multiplot
