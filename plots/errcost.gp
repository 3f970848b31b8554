# Error against run time (issues 5 and 15): the standard error of the ensemble mean of D_e
# (eq. 31 fits, one per run; filled points) and the total error sqrt(stat^2 + sys^2) with the
# group's systematic error D_e_sys (open points, dashed) against the total CPU seconds of the
# runs, one colour per run length (2, 4, 8, ... runs), with the 1/sqrt(CPU) law through the
# longest runs' last point.  A longer run stops paying where its total error is no lower than a
# shorter one's at the same CPU time.
# Input: `plots/scripts/errcost.sh HAFF L:DB... > in` (blocks per run length); optional in2, the
# same for a second box (then two panels: in2 left, in right).
# usage: gnuplot -e "in='errcost.tsv'; out='errcost.png'[; title='...'][; in2='..'; title2='..'
#        ; suptitle='..']" plots/errcost.gp
if (!exists("in")) in = 'errcost.tsv'
if (!exists("out")) out = 'errcost.png'
if (!exists("title")) title = 'D_e at one (α, a/d): error against cost'
two = exists("in2")
if (!exists("title2")) title2 = ''
if (!exists("suptitle")) suptitle = ''
W = two ? 1200 : 800
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size W,600 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size W,600 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
set logscale xy
set format y "10^{%L}"
set xlabel "total CPU time of the runs (s)"
set key top right spacing 1.3 font ",9"
set grid lc rgb "#dddddd"
if (two) { set multiplot layout 1,2 title suptitle }
do for [p = (two ? 0 : 1) : 1] {
  f = p == 0 ? in2 : in
  set title (p == 0 ? title2 : title)
  stats f using 3 nooutput
  nb = STATS_blocks
  # fast runs can all take the same (quantised) CPU time: give a single x value a range of its own
  if (STATS_min == STATS_max && STATS_min > 0) { set xrange [STATS_min / 2 : STATS_max * 2] } else { set xrange [*:*] }
  stats f using 5 nooutput
  if (STATS_min == STATS_max && STATS_min > 0) { set yrange [STATS_min / 2 : STATS_max * 2] } else { set yrange [*:*] }
  stats f index (nb - 1) using 3 nooutput
  c1 = STATS_max
  stats f index (nb - 1) using ($3 == c1 ? $5 : NaN) nooutput
  e1 = STATS_max
  set ylabel (p == 1 || !two ? "error of ⟨D_e⟩" : "error of ⟨D_e⟩")
  plot for [i=0:nb-1] f index i using 3:5 with linespoints pt 7 ps 0.9 lc i+1 title columnheader(1), \
       for [i=0:nb-1] f index i using 3:(column(9) > 0 ? column(9) : NaN) with linespoints dt 2 \
         lw 2 pt 6 ps 1.1 lc i+1 notitle, \
       e1 * sqrt(c1 / x) with lines dt 3 lw 2 lc rgb "black" title "stat ∝ (CPU time)^{-1/2}", \
       NaN with linespoints dt 2 lw 2 pt 6 lc rgb "gray40" title "total, √(stat² + sys²)"
}
if (two) { unset multiplot }
