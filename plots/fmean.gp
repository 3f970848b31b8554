# <f>(a/d) and D_e(a/d) for the three contact models of `haff mc fmean`, 0 < a/d <= 3.
# usage: gnuplot -e "data='fmean.tsv'; outbase='plots/out/fmean'" plots/fmean.gp
#   data: the TSV of `haff mc fmean --scan A0:A1:STEP --model all`; writes outbase.png, .svg
if (!exists("data")) data = 'fmean.tsv'
if (!exists("outbase")) outbase = 'fmean'
set encoding utf8
set datafile separator "\t"
set datafile missing NaN
sel(m, col) = (strcol(1) eq m) ? column(col) : NaN

# Table I of the paper: D_e fitted from cooling runs (a/d, alpha, D_e)
$table << EOD
0.5	0.99	3.003
0.5	0.98	3.013
0.5	0.95	3.028
0.5	0.90	3.079
0.5	0.85	3.109
1.0	0.99	2.987
1.0	0.98	3.014
1.0	0.95	3.038
1.0	0.90	3.086
1.0	0.85	3.041
1.5	0.99	3.004
1.5	0.98	3.031
1.5	0.95	3.059
1.5	0.90	3.050
1.5	0.85	3.102
EOD

set xrange [0 : 3.05]
set grid lc rgb "#dddddd"
set key outside right top vertical Left reverse samplen 2 width -4
do for [t in "png svg"] {
  if (t eq "png") { set terminal png size 1100,900 font ",11"; set output outbase.".png" }
  if (t eq "svg") { set terminal svg size 1100,900 dynamic font "Helvetica,13"; set output outbase.".svg" }
  set multiplot layout 2,1 title "Orientation factor of dimer–dimer collisions (Costantini et al. 2005, eq. 36–40)"
  # the same left and right edges for both panels (their keys, outside, differ in width)
  set lmargin at screen 0.08
  set rmargin at screen 0.60
  set ylabel "<f>"
  set xlabel ""
  set yrange [*:*]
  plot data using (sel("heuristic", 2)):(sel("heuristic", 9)) with lines lw 2 lc rgb "#1f77b4" title "heuristic, quadrature", \
       data using (sel("heuristic", 2)):3:4 with yerrorbars pt 7 ps 0.6 lc rgb "#1f77b4" title "heuristic, MC", \
       data using (sel("exclusion", 2)):3:4 with yerrorlines pt 5 ps 0.6 lc rgb "#2ca02c" title "exclusion", \
       data using (sel("collision", 2)):3:4 with yerrorlines pt 9 ps 0.8 lc rgb "#d62728" title "collision", \
       '+' using (1):(0.64) every ::0::0 with points pt 3 ps 2.5 lw 2 lc rgb "black" title "paper: 0.64 at a = d"
  set ylabel "effective dimension D_e"
  set xlabel "a/d"
  set yrange [2.7:3.25]
  plot data using (sel("heuristic", 2)):5:6 with yerrorlines pt 7 ps 0.6 lc rgb "#1f77b4" title "D/<f>, heuristic (paper's)", \
       data using (sel("exclusion", 2)):5:6 with yerrorlines pt 5 ps 0.6 lc rgb "#2ca02c" title "D/<f>, exclusion", \
       data using (sel("collision", 2)):5:6 with yerrorlines pt 9 ps 0.8 lc rgb "#d62728" title "D/<f>, collision", \
       data using (sel("collision", 2)):13:14 with yerrorbars pt 6 ps 0.7 lc rgb "black" title "4E/<f v_n^2>, collision (energy balance)", \
       3 with lines dt 2 lw 2 lc rgb "black" title "D + 1 = 3 (consistent, equipartition)", \
       $table using 1:3 with points pt 2 ps 1.2 lw 2 lc rgb "#9467bd" title "paper, Table I (cooling fits, α = 0.85–0.99)"
  unset multiplot
  unset lmargin
  unset rmargin
  set output
}
