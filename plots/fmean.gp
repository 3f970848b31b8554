# <f>(a/d) and D_e(a/d) for the three contact models of `haff mc fmean`, 0 < a/d <= 3.
# usage: gnuplot -e "data='fmean.tsv'; outbase='plots/out/fmean'" plots/fmean.gp
#   data: the TSV of `haff mc fmean --scan A0:A1:STEP --model all`; writes outbase.png, .svg, .pdf
#   t1 (optional): this build's table1.tsv (`haff table1`): haff's own D_e, drawn in the lower
#   panel beside the paper's
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("data")) data = 'fmean.tsv'
if (!exists("outbase")) outbase = 'fmean'
if (!exists("t1")) t1 = ''
have_t1 = strlen(t1) > 0 && system("test -s '".t1."' && echo 1 || echo 0") eq "1"
set datafile separator "\t"
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

# haff's own D_e (a/d > 0, alpha < 1), shifted right by 0.03 to stay clear of the paper's crosses
t1x = have_t1 ? t1 : data
set xrange [0 : 3.05]
do for [t in "png svg pdf"] {
  eval term(outbase.".".t, 900, 900)
  set output outbase.".".t
  set multiplot layout 2,1 title "Orientation factor of dimer–dimer collisions (Costantini et al. 2005, eqs. 36–40)\nMonte Carlo: error bars one standard error; lengths in units of d"
  set lmargin 10
  set rmargin 3
  set ylabel "⟨f⟩"
  set xlabel ""
  set yrange [0.625:0.7]
  set key at graph 0.98, graph 0.02 right bottom Left reverse spacing 1.1 font ",10" opaque box lc rgb "gray80"
  plot data using (sel("heuristic", 2)):(sel("heuristic", 9)) with lines lw 2 lc rgb OI1 title "heuristic, quadrature", \
       data using (sel("heuristic", 2)):3:4 with yerrorbars pt 7 ps 0.5 lc rgb OI1 title "heuristic, MC", \
       data using (sel("exclusion", 2)):3:4 with yerrorlines pt 5 ps 0.5 lc rgb OI3 title "exclusion", \
       data using (sel("collision", 2)):3:4 with yerrorlines pt 9 ps 0.7 lc rgb OI2 title "collision", \
       '+' using (1):(0.64) every ::0::0 with points pt 3 ps 2.5 lw 2 lc rgb "black" title "paper: 0.64 at a = d"
  set ylabel "effective dimension D_e"
  set xlabel "a/d"
  set yrange [2.65:3.25]
  set key at graph 0.5, graph 0.02 center bottom Left reverse maxrows 4 spacing 1.05 font ",9" opaque box lc rgb "gray80"
  plot data using (sel("heuristic", 2)):5:6 with yerrorlines pt 7 ps 0.5 lc rgb OI1 title "D/⟨f⟩, heuristic (paper's)", \
       data using (sel("exclusion", 2)):5:6 with yerrorlines pt 5 ps 0.5 lc rgb OI3 title "D/⟨f⟩, exclusion", \
       data using (sel("collision", 2)):5:6 with yerrorlines pt 9 ps 0.7 lc rgb OI2 title "D/⟨f⟩, collision", \
       data using (sel("collision", 2)):13:14 with yerrorbars pt 6 ps 0.6 lc rgb "black" title "4E/⟨f v_n²⟩, collision (energy balance)", \
       3 with lines dt 2 lw 1.5 lc rgb "black" title "D + 1 = 3 (equipartition)", \
       $table using 1:3 with points pt 2 ps 1.3 lw 2 lc rgb OI4 title "paper, Table I (cooling fits, α = 0.85–0.99)", \
       t1x using (have_t1 && $2 > 0 && $3 == $3 ? $2 + 0.03 : NaN):3:4 with yerrorbars pt 13 ps 1.0 \
         lc rgb OI5 title (have_t1 ? "haff, Table I of this build (α < 1, ± s.e.)" : "")
  unset multiplot
  set output
}
