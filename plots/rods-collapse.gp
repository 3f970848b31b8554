# Collapse map of the constant-eps ring against McNamara and Young (plots/rods.mk sets D, O).
# Filled grey level = collapsed fraction; every (N, eps) gets a black ring, so 0 shows as an
# open circle on the white background.
load system("dirname '".ARG0."'")."/style.gp"
do for [fmt in "png svg pdf"] {
  eval term(O.'/rods-collapse.'.fmt, 760, 560)
  set output O.'/rods-collapse.'.fmt
  set title "constant ε: fraction of rings of N rods that collapse (3 seeds, 1000 cpd each)\nline: McNamara–Young N = −ln(1 − ε)/(1 − ε)"
  set xlabel 'ε'; set ylabel 'N'; set logscale y; set xrange [0.25:1]; set yrange [2:1000]
  set cbrange [0:1]; set palette defined (0 'white', 1 'black'); set cblabel 'collapsed fraction'
  set key top left
  plot D.'/rods-collapse.tsv' u 2:1:5 w p pt 7 ps 2 lc palette notitle, \
       '' u 2:1 w p pt 6 ps 2 lc rgb 'black' t 'rings run (open: none collapsed)', \
       -log(1-x)/(1-x) w l lw 2 lt 2 t 'McNamara–Young'
  unset logscale
  set output
}
