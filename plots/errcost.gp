# Error against run time (issues 5 and 15): the expected standard error of the ensemble mean of
# R runs' D_e, sd(all runs)/sqrt(R) (eq. 31 fits, one per run; filled points, R written beside
# each) and the total error sqrt(stat^2 + sys^2) with the
# group's systematic error D_e_sys (open points, dashed) against the total CPU seconds of the
# runs, one colour per run length (2, 4, 8, ... runs), with the 1/sqrt(CPU) law through the
# longest runs' last point.  A longer run stops paying where its total error is no lower than a
# shorter one's at the same CPU time.
# Input: `plots/scripts/errcost.sh HAFF L:DB... > in` (blocks per run length); optional in2, the
# same for a second box (then two panels: in2 left, in right).
# usage: gnuplot -e "in='errcost.tsv'; out='errcost.png'[; title='...'][; in2='..'; title2='..'
#        ; suptitle='..']" plots/errcost.gp
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'errcost.tsv'
if (!exists("out")) out = 'errcost.png'
if (!exists("title")) title = 'D_e at one (α, a/d): error against cost'
two = exists("in2")
if (!exists("title2")) title2 = ''
if (!exists("suptitle")) suptitle = ''
W = two ? 1200 : 800
eval term(out, W, 620)
set output out
set datafile separator "\t"
set logscale xy
set format y "10^{%L}"
set format x "10^{%L}"
set xlabel "total CPU time of the R runs (s)"
set key top right spacing 1.2 font ",10"
# one x and one y range for both panels (from every point of both files; one column at a time:
# stats of two columns fits a line and warns when there are two points)
stats in using 3 nooutput
x0 = STATS_min; x1 = STATS_max
stats in using 7 nooutput
y0 = STATS_min; y1 = STATS_max
stats in using (column(9) > 0 ? column(9) : 0) nooutput
y1 = STATS_max > y1 ? STATS_max : y1
if (two) {
  stats in2 using 3 nooutput
  x0 = STATS_min < x0 ? STATS_min : x0; x1 = STATS_max > x1 ? STATS_max : x1
  stats in2 using 7 nooutput
  y0 = STATS_min < y0 ? STATS_min : y0; y1 = STATS_max > y1 ? STATS_max : y1
  stats in2 using (column(9) > 0 ? column(9) : 0) nooutput
  y1 = STATS_max > y1 ? STATS_max : y1
}
set xrange [x0 / 2 : x1 * 3]
set yrange [y0 / 2 : y1 * 15]   # room above the curves for the key
if (two) { set multiplot layout 1,2 title suptitle."; R = 4, 8, … runs (R = 2 left out: its sd is noise); d = m = T_0 = 1" }
do for [p = (two ? 0 : 1) : 1] {
  f = p == 0 ? in2 : in
  set title (p == 0 ? title2 : title)
  stats f using 3 nooutput
  nb = STATS_blocks
  stats f index (nb - 1) using 3 nooutput
  c1 = STATS_max
  stats f index (nb - 1) using ($3 == c1 ? $7 : NaN) nooutput
  e1 = STATS_max
  set ylabel "error of ⟨D_e⟩"
  # the blocks with a total error (it is empty where the systematic part was not measured: a
  # window too short for eq. 31, flag short); a block with none is left out of the dashed curves
  tot = ""
  set autoscale xy   # stats keeps to the axis ranges: counting needs none
  do for [i=0:nb-1] {
    stats f index i using (column(9) > 0 ? 1 : 0) nooutput
    if (STATS_sum > 0) { tot = tot . " " . sprintf("%d", i) }
  }
  set xrange [x0 / 2 : x1 * 3]
  set yrange [y0 / 2 : y1 * 15]
  # the dashed totals only when some block has one (gnuplot plots an empty for [k=1:0] once)
  if (strlen(tot) > 0) {
  plot for [i=0:nb-1] f index i using 3:7 with linespoints pt 7 ps 0.9 lt i+1 title columnheader(1), \
       for [i=0:nb-1] f index i using 3:7:(sprintf("%d", $2)) with labels offset char 0.2,char -0.8 \
         left font ",8" tc lt i+1 notitle, \
       for [k=1:words(tot)] f index (word(tot, k) + 0) using 3:(column(9) > 0 ? column(9) : NaN) \
         with linespoints dt 2 lw 2 pt 6 ps 1.1 lt (word(tot, k) + 1) notitle, \
       e1 * sqrt(c1 / x) with lines dt 3 lw 2 lc rgb "black" title "stat ∝ (CPU time)^{−1/2}", \
       NaN with linespoints dt 2 lw 2 pt 6 lc rgb "gray40" title "total, √(stat² + sys²)", \
       NaN with points pt 7 lc rgb "gray40" title "stat: sd of all runs / √R (R beside)"
  } else {
  plot for [i=0:nb-1] f index i using 3:7 with linespoints pt 7 ps 0.9 lt i+1 title columnheader(1), \
       for [i=0:nb-1] f index i using 3:7:(sprintf("%d", $2)) with labels offset char 0.2,char -0.8 \
         left font ",8" tc lt i+1 notitle, \
       e1 * sqrt(c1 / x) with lines dt 3 lw 2 lc rgb "black" title "stat ∝ (CPU time)^{−1/2}", \
       NaN with points pt 7 lc rgb "gray40" title "stat: sd of all runs / √R (R beside)"
  }
}
if (two) { unset multiplot }
