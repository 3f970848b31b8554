# Rod paper Figs. 1, 2, 9, 10, 11 from `haff rods-energy` TSV (plots/rods.mk sets D and O).
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 800,560 } else { set terminal svg size 800,560 }
  ext = fmt
  set key autotitle columnhead
  set output O.'/rods-energy.'.ext
  set logscale xy; set xlabel 't'; set ylabel 'E_{kin} per rod'
  set format y '10^{%L}'; set format x '10^{%L}'
  set title 'Fig. 1: kinetic energy (the constant model breaks off at its collapse)'
  plot D.'/rods-stochastic.energy.tsv' u 1:4 w l t 'stochastic', \
       D.'/rods-constant.energy.tsv' u 1:4 w l t 'constant eps = gamma', \
       D.'/rods-50.energy.tsv' u 1:4 w l t '50 rods', \
       D.'/rods-50.energy.tsv' u 1:($7/2) w l dt 4 t '50 rods: bath energy per mode / 2', \
       D.'/rods-50.energy.tsv' u 1:8 w l dt 2 t 'equipartition'
  set output O.'/rods-collisions.'.ext
  set title 'Fig. 2: collisions (dotted: stationary count, ideal gas and eq. 35)'
  set ylabel 'collisions'
  plot D.'/rods-stochastic.energy.tsv' u 1:2 w l t 'stochastic', \
       D.'/rods-constant.energy.tsv' u 1:2 w l t 'constant', \
       D.'/rods-50.energy.tsv' u 1:2 w l t '50 rods', \
       D.'/rods-50.energy.tsv' u 1:9 w l dt 3 t '50 rods: ideal gas', \
       D.'/rods-50.energy.tsv' u 1:10 w l dt 2 t '50 rods: eq. (35)'
  set output O.'/rods-damped.'.ext
  set title 'Figs. 9-10: damped baths (nu = 0.01)'
  set ylabel 'collisions, E_{kin} per rod'
  plot D.'/rods-damped.energy.tsv' u 1:2 w l t 'collisions', '' u 1:4 w l t 'E_{kin}'
  set output O.'/rods-damped50.'.ext
  set title 'Fig. 11: 50 damped rods, E ~ t^{-2}'
  set ylabel 'E_{kin} per rod'
  plot D.'/rods-damped50.energy.tsv' u 1:4 w l t 'E_{kin}', (x > 10 ? 100/x**2 : 1/0) w l dt 2 t 't^{-2}'
  unset title; unset logscale
}
