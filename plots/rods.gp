# Rod paper Figs. 1, 2, 9, 10, 11 from `haff rods-energy` TSV (plots/rods.mk sets D and O).
# Writes O/rods-{energy,collisions,damped,damped50}.{png,svg,pdf}.  Units: rod mass m = 1, mean
# spacing 1 (ring length L = N), time in the scene's unit; E_kin per rod.
STYLE = system("dirname '".ARG0."'")."/style.gp"
load STYLE
stats D.'/rods-constant.energy.tsv' u 1:2 nooutput name 'C'
tc = C_max_x                         # where the constant model broke off (its collapse)
nrods = system("awk 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^N=/) print substr($i, 3) }' '".D."/rods-stochastic.energy.tsv'")
UNITS = "units: rod mass m = 1, mean spacing 1 (ring length L = N), the scene's time unit"
do for [ext in "png svg pdf"] {
  reset
  load STYLE
  set datafile separator whitespace
  set key autotitle columnhead
  # --- Fig. 1: kinetic energy ------------------------------------------------------------------
  eval term(O.'/rods-energy.'.ext, 820, 600)
  set output O.'/rods-energy.'.ext
  set logscale xy; set xlabel 't'; set ylabel 'E_{kin} per rod'
  set format y '10^{%L}'; set format x '10^{%L}'
  set title sprintf("Fig. 1: kinetic energy, %s rods and 50 rods \n%s", nrods, UNITS)
  set key top right spacing 1.15 font ",10"
  # the constant model (thick, dashed, drawn last) coincides with the stochastic one until it
  # collapses at t = tc
  plot D.'/rods-stochastic.energy.tsv' u 1:4 w l lt 1 lw 2 t 'stochastic ε', \
       D.'/rods-50.energy.tsv' u 1:4 w l lt 3 lw 1.2 t '50 rods (stochastic ε)', \
       D.'/rods-50.energy.tsv' u 1:($7/2) w l lt 4 lw 2 dt 4 t '50 rods: bath energy per mode / 2', \
       D.'/rods-50.energy.tsv' u 1:8 w l lc rgb 'black' lw 1.5 dt 2 t 'equipartition', \
       D.'/rods-constant.energy.tsv' u 1:4 w l lt 2 lw 3.5 dt (6,4) t sprintf('constant ε = γ (collapses at t = %.3g)', tc)
  # --- Fig. 2: collisions, and the paper's inset as panel (b) ---------------------------------
  eval term(O.'/rods-collisions.'.ext, 1150, 560)
  set output O.'/rods-collisions.'.ext
  set multiplot title sprintf("Fig. 2: collisions against t\n%s", UNITS)
  set lmargin at screen 0.07; set rmargin at screen 0.60; set tmargin at screen 0.84; set bmargin at screen 0.12
  set title '(a) total collisions; dotted: stationary ideal gas of the same N and E, dashed: eq. (35)'
  set ylabel 'collisions'
  set key top left spacing 1.1 font ",9"
  plot D.'/rods-stochastic.energy.tsv' u 1:2 w l lt 1 lw 2 t sprintf('%s rods, stochastic', nrods), \
       D.'/rods-stochastic.energy.tsv' u 1:9 w l dt 3 lt 1 lw 2 t sprintf('%s rods: ideal gas', nrods), \
       D.'/rods-stochastic.energy.tsv' u 1:10 w l dt 2 lt 1 lw 1.5 t sprintf('%s rods: eq. (35)', nrods), \
       D.'/rods-50.energy.tsv' u 1:($2*100) w l lt 3 lw 2 t '50 rods × 100', \
       D.'/rods-50.energy.tsv' u 1:($9*100) w l dt 3 lt 3 lw 2 t '50 rods × 100: ideal gas', \
       D.'/rods-50.energy.tsv' u 1:($10*100) w l dt 2 lt 3 lw 1.5 t '50 rods × 100: eq. (35)'
  set lmargin at screen 0.70; set rmargin at screen 0.98
  unset logscale; set format x '%g'; set format y '%g'
  set title sprintf("(b) the paper's inset, linear axes, to 1.5 t_c")
  set xlabel 't'; set ylabel 'collisions (thousands)'
  set xrange [0:1.5*tc]
  set yrange [0:*]
  set key at graph 0.03, graph 0.55 left top Left reverse font ",9"
  plot D.'/rods-stochastic.energy.tsv' u 1:($2/1000) w l lt 1 lw 2 t 'stochastic ε', \
       D.'/rods-constant.energy.tsv' u 1:($2/1000) w l lt 2 lw 2 dt 2 \
         t sprintf("constant ε: inelastic collapse, t_c = %.3g", tc)
  unset multiplot
  set autoscale xy
  set lmargin -1; set rmargin -1; set tmargin -1; set bmargin -1
  # --- Figs. 9-10: the damped ring, two y axes -------------------------------------------------
  eval term(O.'/rods-damped.'.ext, 820, 600)
  set output O.'/rods-damped.'.ext
  set logscale xy; set logscale y2
  set format y '10^{%L}'; set format x '10^{%L}'; set format y2 '10^{%L}'
  set xlabel 't'
  set title sprintf("Figs. 9–10: damped baths, ν = 0.01, %s rods \n%s", nrods, UNITS)
  set ylabel 'collisions (Fig. 9)' tc lt 1
  set y2label 'E_{kin} per rod (Fig. 10)' tc lt 2
  set ytics nomirror tc lt 1; set y2tics tc lt 2
  set key bottom right font ",10"
  # the last steps: E_kin sits in the few fast rods between clusters; each drop is one of them
  # running into a cluster (plots/README.md): not a data fault, a finite-N effect
  plot D.'/rods-damped.energy.tsv' u 1:2 w l lt 1 lw 2 axes x1y1 t 'collisions (left axis)', \
       '' u 1:4 w l lt 2 lw 2 axes x1y2 t 'E_{kin} per rod (right axis); steps: a fast rod joins a cluster'
  unset y2tics; unset y2label; unset logscale y2; set ytics mirror tc rgb 'black'; set ylabel tc rgb 'black'
  # --- Fig. 11 --------------------------------------------------------------------------------
  eval term(O.'/rods-damped50.'.ext, 820, 600)
  set output O.'/rods-damped50.'.ext
  set title sprintf("Fig. 11: 50 damped rods, E ∼ t^{−2}\n%s", UNITS)
  set ylabel 'E_{kin} per rod'
  set key inside top right
  plot D.'/rods-damped50.energy.tsv' u 1:4 w l lt 1 t 'E_{kin}', (x > 10 ? 100/x**2 : 1/0) w l lc rgb 'black' dt 2 t '100 t^{−2}'
  set output
}
