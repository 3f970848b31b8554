# Collapse map of the constant-eps ring against McNamara and Young (plots/rods.mk sets D, O).
# Filled grey level = collapsed fraction; every (N, eps) gets a black ring, so 0 shows as an
# open circle on the white background.
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 700,520 } else { set terminal svg size 700,520 }
  set output O.'/rods-collapse.'.fmt
  set title 'constant eps: fraction of rings that collapse; line: N = -ln(1-eps)/(1-eps)'
  set xlabel 'eps'; set ylabel 'N'; set logscale y; set xrange [0.25:1]; set yrange [2:1000]
  set cbrange [0:1]; set palette defined (0 'white', 1 'black'); set cblabel 'collapsed fraction'
  set key top left
  plot D.'/rods-collapse.tsv' u 2:1:5 w p pt 7 ps 2 lc palette notitle, \
       '' u 2:1 w p pt 6 ps 2 lc rgb 'black' t 'rings run (open: none collapsed)', \
       -log(1-x)/(1-x) w l lw 2 t 'McNamara-Young'
  unset logscale
}
