# Cooling of bodies of different shapes (issue 18) and their mean orientation factor.
# usage: gnuplot -e "in='shapes.tsv'; fin='shapes_f.tsv'; alpha=0.95; outbase='shapes'" plots/shapes.gp
#   in:  plots/shapes.c's blocks (shape cpd x E/E0 E_tr/E_rot), one per shape
#   fin: shape, engine <f>, its error, MC collision-model <f>, its error
#   writes outbase.png and outbase.svg (or out, one file of the extension it names: the tests)
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'shapes.tsv'
if (!exists("fin")) fin = 'shapes_f.tsv'
if (!exists("alpha")) alpha = 0.95
if (!exists("outbase")) outbase = 'shapes'
nshape = 6
terms = exists("out") ? out[strlen(out)-2:] : "png svg pdf"
do for [t in terms] {
  file = exists("out") ? out : outbase.".".t
  eval term(file, 1200, 560)
  set output file
  set multiplot layout 1,2 title sprintf("Rigid clusters of disks (d = m = T_0 = 1): cooling at α = %g and ⟨f⟩ " \
    . "= ⟨μ_{eff}/m_{ref}⟩, m_{ref} the mass of the touching disk (docs/contract.md)\n" \
    . "linear, bent (120°), triangle: trimers of touching disks; asym: disks d = 1, m = 1 and " \
    . "d = 0.5, m = 0.3, 0.8 d apart; one run of 500 bodies each", alpha) font ",11"
  set xlabel "x = (1 − α²) · cpd"
  set ylabel "E / E_0"
  set logscale y
  set format y "10^{%L}"
  set key bottom left spacing 1.1 font ",10"
  set xrange [*:*]
  set yrange [*:*]
  # the references over the data: black, dashed and dotted, thick enough to tell apart
  plot for [i=0:nshape-1] in index i using 3:4 every 4 with linespoints lt i+1 pi 8 lw 1.5 \
         title word("disk dimer linear bent triangle asym", i + 1), \
       exp(-x/2) with lines dt (8,6) lw 2.5 lc rgb "black" title "exp(−x/2): D_e = 2 (disks)", \
       exp(-x/3) with lines dt (1,4) lw 3.5 lc rgb "black" title "exp(−x/3): D_e = 3 (turning bodies)"
  unset logscale y
  set format y "%g"
  # right: the engine's <f> minus the Monte Carlo's, with the combined standard error (the bars
  # were invisible on the scale of <f> itself: 0.001-0.003); the values written above
  set xlabel "shape"
  set ylabel "⟨f⟩_{engine} − ⟨f⟩_{MC, collision model}"
  set yrange [-0.012 : 0.012]
  set key top left
  set xrange [-0.5 : nshape - 0.5]
  set xtics rotate by -30
  plot 0 with lines dt 2 lw 1.5 lc rgb "black" notitle, \
       fin using 0:($2 - $4):(sqrt($3**2 + $5**2)):xtic(1) with yerrorbars pt 7 ps 1.2 lw 2 lt 1 \
         title "engine − MC, ± combined standard error", \
       fin using 0:(-0.0105):(sprintf("⟨f⟩ =\n%.4f", $2)) with labels font ",9" notitle
  unset xtics
  set xtics
  unset multiplot
}
