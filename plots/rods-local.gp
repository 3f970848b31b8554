# Rod paper Figs. 3-8 from the rods-stochastic run (plots/rods.mk sets D and O).
# Writes O/rods-{density,phase,local,veldist,gofr}.{png,svg,pdf}.  Units: rod mass m = 1, mean
# spacing 1 (ring length L = N), the scene's time unit.
STYLE = system("dirname '".ARG0."'")."/style.gp"
UNITS = "units: rod mass m = 1, mean spacing 1 (ring length L = N), the scene's time unit"
nrods = system("awk 'NR > 1 && $3 > m { m = $3 } END { print m + 5 }' '".D."/rods-stochastic.density.tsv'")
do for [ext in "png svg pdf"] {
  reset
  load STYLE
  set datafile separator whitespace
  # at most six x ticks whatever the ring's length, as 2k 4k ... (250 smeared 40 labels at 10^4
  # rods)
  stats D.'/rods-stochastic.density.tsv' u 3 nooutput name 'X'
  xt = 10**floor(log10(X_max)); xt = X_max/xt > 5 ? (X_max/(2*xt) > 5 ? 5*xt : 2*xt) : xt
  # --- Figs. 3-4: density in the (x, t) plane, linear and log time ---------------------------
  eval term(O.'/rods-density.'.ext, 1200, 600)
  set output O.'/rods-density.'.ext
  set multiplot title sprintf("Figs. 3–4: coarse-grained density of the %d rods (100 bins), one row per snapshot\n%s", \
    int(nrods), UNITS)
  set view map scale 1; set xlabel 'x'; set ylabel 't' rotate by 90; set xtics xt; set format x '%.0s%c'
  set palette defined (0 "white", 0.25 "#9ecae1", 0.5 "#3182bd", 0.75 "#08306b", 1 "black")
  set cbrange [0:5]; set cblabel 'density / mean density N/L' offset 0.5
  unset grid
  set tmargin at screen 0.86; set bmargin at screen 0.12
  set lmargin at screen 0.07; set rmargin at screen 0.40
  set title '(a) linear time'
  splot D.'/rods-stochastic.density.tsv' u 3:1:4 w pm3d notitle
  set lmargin at screen 0.55; set rmargin at screen 0.88
  set title '(b) log time'
  set logscale y; set format y '10^{%L}'
  splot D.'/rods-stochastic.density.tsv' u 3:1:4 w pm3d notitle
  unset multiplot; unset logscale; unset view; set autoscale cb; unset cblabel; set xtics autofreq
  set lmargin -1; set rmargin -1; set tmargin -1; set bmargin -1
  set format x '% h'
  set format y '% h'
  set grid
  # --- Fig. 5: phase space ---------------------------------------------------------------------
  eval term(O.'/rods-phase.'.ext, 1000, 560)
  set output O.'/rods-phase.'.ext
  set multiplot layout 1,2 title "Fig. 5: phase space (x, v) of every rod at two times\n".UNITS
  set xlabel 'x'; set ylabel 'v'; set xtics xt; set mxtics 5; set format x '%.0s%c'
  # each panel's time is the first line of its TSV ("# t = ..."); both share the v range
  stats D.'/rods-stochastic.phase1.tsv' u 3 nooutput name 'P1'
  stats D.'/rods-stochastic.phase2.tsv' u 3 nooutput name 'P2'
  set yrange [(P1_min < P2_min ? P1_min : P2_min):(P1_max > P2_max ? P1_max : P2_max)]
  set title system("head -1 '".D."/rods-stochastic.phase1.tsv' | awk '{ printf \"t = %.5g\", $4 }'")
  plot D.'/rods-stochastic.phase1.tsv' u 2:3 w d lc rgb 'black' notitle
  set title system("head -1 '".D."/rods-stochastic.phase2.tsv' | awk '{ printf \"t = %.5g\", $4 }'")
  plot D.'/rods-stochastic.phase2.tsv' u 2:3 w d lc rgb 'black' notitle
  unset multiplot; unset title; set autoscale y; set xtics autofreq; unset mxtics
  set format x '% h'
  # --- Fig. 6: local density and energy at the last snapshot ---------------------------------
  tl = system("awk 'NR == 2 { print $1 }' '".D."/rods-stochastic.local.tsv'")
  eval term(O.'/rods-local.'.ext, 900, 560)
  set output O.'/rods-local.'.ext
  set title sprintf("Fig. 6: local density and kinetic energy along the ring at t = %s (last snapshot)\n%s", tl, UNITS)
  set xlabel 'x'
  set ylabel 'ρ: rods per bin / mean (dimensionless)' tc lt 1
  set y2label 'E_{local}: kinetic energy per rod in the bin (m v²/2)' tc lt 2
  set y2tics tc lt 2; set ytics nomirror tc lt 1; set logscale y2; set format y2 '10^{%L}'
  set key top right
  plot D.'/rods-stochastic.local.tsv' u 3:4 w l lt 1 lw 2 t 'density ρ (left)', \
       '' u 3:($5 > 0 ? $5 : NaN) axes x1y2 w l lt 2 lw 1.5 dt 2 t 'kinetic energy E_{local} (right)'
  unset y2tics; unset y2label; unset logscale y2; set ytics mirror tc rgb 'black'; set ylabel tc rgb 'black'
  # --- Fig. 7: velocity histograms -----------------------------------------------------------
  vd = D.'/rods-stochastic.veldist.tsv'
  vh1 = system("head -1 '".vd."' | sed 's/^# //'")
  ma = real(system("awk 'NR == 2 { print $4 + 0 }' '".vd."'")); sa = real(system("awk 'NR == 2 { print $6 + 0 }' '".vd."'"))
  mc = real(system("awk 'NR == 2 { print $9 + 0 }' '".vd."'")); sc = real(system("awk 'NR == 2 { print $11 + 0 }' '".vd."'"))
  ncl = real(system("head -1 '".vd."' | awk '{ for (i = 1; i <= NF; i++) if ($i == \"rods\") print $(i - 1) }'"))
  stats vd u 1 nooutput name 'W'
  dw = (W_max - W_min) / (W_records - 1)
  # counts: p * n * dw (n = N rods for all, ncl for the cluster); Poisson error sqrt(count)
  eval term(O.'/rods-veldist.'.ext, 900, 600)
  set output O.'/rods-veldist.'.ext
  set title sprintf("Fig. 7: velocities √m v of all rods and of one cluster, error bars √count\n%s\n%s", vh1, UNITS) font ",10"
  set xlabel '√m v'; set ylabel 'p(√m v)'
  set samples 500
  set yrange [0:*]
  set key top right
  g(x, m, s) = exp(-(x - m)**2 / (2 * s * s)) / (s * sqrt(2 * pi))
  plot vd u 1:($2 > 0 ? $2 : NaN):($2 / sqrt($2 * nrods * dw)) w yerrorbars pt 6 lt 1 t sprintf('all %d rods', int(nrods)), \
       '' u 1:($3 > 0 ? $3 : NaN):($3 / sqrt($3 * ncl * dw)) w yerrorbars pt 5 lt 2 t sprintf('cluster of %d rods', int(ncl)), \
       g(x, ma, sa) w l lt 1 lw 1.5 t 'Gaussian (all)', g(x, mc, sc) w l lt 2 lw 1.5 dt 2 t 'Gaussian (cluster)'
  set autoscale y
  # --- Fig. 8: pair correlation ----------------------------------------------------------------
  tg = system("head -1 '".D."/rods-stochastic.gofr.tsv' | awk '{ print $4 }'")
  eval term(O.'/rods-gofr.'.ext, 900, 560)
  set output O.'/rods-gofr.'.ext
  set title sprintf("Fig. 8: pair correlation g(x), %d rods at t = %s; g normalised by the mean density N/L\n" \
    . "(g = 1 for uniform rods; its mean over the whole ring is 1). %s", int(nrods), tg, UNITS) font ",10"
  set xlabel 'x (ring distance)'; set ylabel 'g(x)'
  set key top right
  plot D.'/rods-stochastic.gofr.tsv' u 1:2 w l lt 1 lw 1.5 t 'g(x)', 1 w l lc rgb 'black' dt 2 t 'uniform: g = 1'
  set output
}
