# Rod paper Figs. 1, 2, 9, 10, 11 from `haff rods-energy` TSV (plots/rods.mk sets D and O).
# Keys sit outside the data (below the plot) where the curves fill the frame.
stats D.'/rods-constant.energy.tsv' u 1:2 nooutput name 'C'
tc = C_max_x                         # where the constant model broke off (its collapse)
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 800,600 } else { set terminal svg size 800,600 }
  ext = fmt
  set key autotitle columnhead
  set output O.'/rods-energy.'.ext
  set logscale xy; set xlabel 't'; set ylabel 'E_{kin} per rod'
  set format y '10^{%L}'; set format x '10^{%L}'
  set title 'Fig. 1: kinetic energy (the constant model breaks off at its collapse)'
  set key below
  plot D.'/rods-stochastic.energy.tsv' u 1:4 w l t 'stochastic', \
       D.'/rods-constant.energy.tsv' u 1:4 w l t 'constant eps = gamma', \
       D.'/rods-50.energy.tsv' u 1:4 w l t '50 rods', \
       D.'/rods-50.energy.tsv' u 1:($7/2) w l dt 4 t '50 rods: bath energy per mode / 2', \
       D.'/rods-50.energy.tsv' u 1:8 w l dt 2 t 'equipartition'
  set output O.'/rods-collisions.'.ext
  set title 'Fig. 2: collisions; dotted: stationary count (ideal gas), dashed: eq. (35)'
  set ylabel 'collisions'
  set multiplot
  plot D.'/rods-stochastic.energy.tsv' u 1:2 w l lc 1 t 'stochastic', \
       D.'/rods-stochastic.energy.tsv' u 1:9 w l dt 3 lc 1 t 'stationary, same N (ideal gas)', \
       D.'/rods-stochastic.energy.tsv' u 1:10 w l dt 2 lc 1 t 'same N, eq. (35)', \
       D.'/rods-50.energy.tsv' u 1:($2*100) w l lc 3 t '50 rods x 100', \
       D.'/rods-50.energy.tsv' u 1:($9*100) w l dt 3 lc 3 t '50 rods x 100: ideal gas', \
       D.'/rods-50.energy.tsv' u 1:($10*100) w l dt 2 lc 3 t '50 rods x 100: eq. (35)'
  # the paper's inset: deterministic (dashed) against stochastic (solid) up to the collapse,
  # linear axes, in the empty lower right
  set origin 0.55,0.27; set size 0.42,0.34; unset title; unset logscale; unset key
  set format x '%g'; set format y '%.1s%c'; set xlabel ''; set ylabel ''
  set xrange [0:1.5*tc]; set xtics font ',8'; set ytics font ',8'
  set object 1 rect from graph 0,0 to graph 1,1 behind fc rgb 'white' fs solid noborder
  plot D.'/rods-stochastic.energy.tsv' u 1:2 w l lc 1 notitle, \
       D.'/rods-constant.energy.tsv' u 1:2 w l dt 2 lc 2 notitle
  unset object 1; unset multiplot; set origin 0,0; set size 1,1; set autoscale x
  set xtics font ''; set ytics font ''; set key below autotitle columnhead
  set logscale xy; set format y '10^{%L}'; set format x '10^{%L}'; set xlabel 't'
  set output O.'/rods-damped.'.ext
  set title 'Figs. 9-10: damped baths (nu = 0.01)'
  set ylabel 'collisions, E_{kin} per rod'
  plot D.'/rods-damped.energy.tsv' u 1:2 w l t 'collisions (Fig. 9)', '' u 1:4 w l t 'E_{kin} per rod (Fig. 10)'
  set output O.'/rods-damped50.'.ext
  set title 'Fig. 11: 50 damped rods, E ∼ t^{−2}'
  set ylabel 'E_{kin} per rod'
  set key inside top right
  plot D.'/rods-damped50.energy.tsv' u 1:4 w l t 'E_{kin}', (x > 10 ? 100/x**2 : 1/0) w l dt 2 t '100 t^{−2}'
  unset title; unset logscale
}
