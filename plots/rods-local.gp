# Rod paper Figs. 3-8 from the rods-stochastic run (plots/rods.mk sets D and O).
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 900,600 } else { set terminal svg size 900,600 }
  ext = fmt
  # at most six x ticks whatever the ring's length, as 2k 4k ... (250 smeared 40 labels at 10^4
  # rods)
  stats D.'/rods-stochastic.density.tsv' u 3 nooutput name 'X'
  xt = 10**floor(log10(X_max)); xt = X_max/xt > 5 ? (X_max/(2*xt) > 5 ? 5*xt : 2*xt) : xt
  set output O.'/rods-density.'.ext
  set multiplot layout 1,2 title 'Figs. 3-4: coarse-grained density (100 bins)'
  set view map scale 1; set xlabel 'x'; set ylabel 't' rotate by 90; set xtics xt; set format x '%.0s%c'
  set palette gray negative; set cbrange [0:5]; set lmargin 9; set rmargin 9
  splot D.'/rods-stochastic.density.tsv' u 3:1:4 w pm3d notitle
  set logscale y; set format y '10^{%L}'; set cblabel 'rods per unit length' offset 1.5
  splot D.'/rods-stochastic.density.tsv' u 3:1:4 w pm3d notitle
  unset multiplot; unset logscale; unset view; set autoscale cb; unset cblabel; set xtics autofreq
  set format x '% h'
  set format y '% h'; unset lmargin; unset rmargin
  set output O.'/rods-phase.'.ext
  set multiplot layout 1,2 title 'Fig. 5: phase space (x, v) of every rod at two times'
  set xlabel 'x'; set ylabel 'v'; set xtics xt; set mxtics 5; set format x '%.0s%c'
  # each panel's time is the first line of its TSV ("# t = ..."); both share the v range
  stats D.'/rods-stochastic.phase1.tsv' u 3 nooutput name 'P1'
  stats D.'/rods-stochastic.phase2.tsv' u 3 nooutput name 'P2'
  set yrange [(P1_min < P2_min ? P1_min : P2_min):(P1_max > P2_max ? P1_max : P2_max)]
  set title system("head -1 '".D."/rods-stochastic.phase1.tsv' | awk '{ printf \"t = %.5g\", $4 }'")
  plot D.'/rods-stochastic.phase1.tsv' u 2:3 w d notitle
  set title system("head -1 '".D."/rods-stochastic.phase2.tsv' | awk '{ printf \"t = %.5g\", $4 }'")
  plot D.'/rods-stochastic.phase2.tsv' u 2:3 w d notitle
  unset multiplot; unset title; set autoscale y; set xtics autofreq; unset mxtics
  set format x '% h'
  set output O.'/rods-local.'.ext
  set title 'Fig. 6: local kinetic energy and density (last snapshot)'
  set xlabel 'x'; set ylabel 'rho'; set y2label 'E_{local}'; set y2tics; set ytics nomirror
  plot D.'/rods-stochastic.local.tsv' u 3:4 w l t 'density', '' u 3:5 axes x1y2 w l dt 2 t 'kinetic energy'
  unset y2tics; unset y2label; set ytics mirror
  set output O.'/rods-veldist.'.ext
  set title 'Fig. 7: velocities sqrt(m) v of all rods and of one cluster'
  set xlabel 'sqrt(m) v'; set ylabel 'p'
  set key below
  plot D.'/rods-stochastic.veldist.tsv' u 1:2 w p pt 6 t 'all', '' u 1:3 w p pt 8 t 'cluster', \
       '' u 1:4 w l t 'Gaussian (all)', '' u 1:5 w l t 'Gaussian (cluster)'
  set key default
  set output O.'/rods-gofr.'.ext
  set title 'Fig. 8: pair correlation g(x)'
  set xlabel 'x'; set ylabel 'g(x)'
  plot D.'/rods-stochastic.gofr.tsv' u 1:2 w l notitle
  unset title
}
