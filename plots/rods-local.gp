# Rod paper Figs. 3-8 from the rods-stochastic run (plots/rods.mk sets D and O).
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 900,600 } else { set terminal svg size 900,600 }
  ext = fmt
  set output O.'/rods-density.'.ext
  set multiplot layout 1,2 title 'Figs. 3-4: coarse-grained density (100 bins)'
  set view map; set xlabel 'x'; set ylabel 't'; set palette gray negative; set cbrange [0:5]
  splot D.'/rods-stochastic.density.tsv' u 3:1:4 w pm3d notitle
  set logscale y; set ylabel 't (log)'
  splot D.'/rods-stochastic.density.tsv' u 3:1:4 w pm3d notitle
  unset multiplot; unset logscale; unset view; set autoscale cb
  set output O.'/rods-phase.'.ext
  set multiplot layout 1,2 title 'Fig. 5: phase space at two times'
  set xlabel 'x'; set ylabel 'v'
  plot D.'/rods-stochastic.phase1.tsv' u 2:3 w d t columnhead(1)
  plot D.'/rods-stochastic.phase2.tsv' u 2:3 w d notitle
  unset multiplot
  set output O.'/rods-local.'.ext
  set title 'Fig. 6: local kinetic energy and density (last snapshot)'
  set xlabel 'x'; set ylabel 'rho'; set y2label 'E_{local}'; set y2tics; set ytics nomirror
  plot D.'/rods-stochastic.local.tsv' u 3:4 w l t 'density', '' u 3:5 axes x1y2 w l dt 2 t 'kinetic energy'
  unset y2tics; unset y2label; set ytics mirror
  set output O.'/rods-veldist.'.ext
  set title 'Fig. 7: velocities sqrt(m) v of all rods and of one cluster'
  set xlabel 'sqrt(m) v'; set ylabel 'p'
  plot D.'/rods-stochastic.veldist.tsv' u 1:2 w p pt 6 t 'all', '' u 1:3 w p pt 8 t 'cluster', \
       '' u 1:4 w l t 'Gaussian (all)', '' u 1:5 w l t 'Gaussian (cluster)'
  set output O.'/rods-gofr.'.ext
  set title 'Fig. 8: pair correlation g(x)'
  set xlabel 'x'; set ylabel 'g(x)'
  plot D.'/rods-stochastic.gofr.tsv' u 1:2 w l notitle
  unset title
}
