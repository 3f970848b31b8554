# Cooling of bodies of different shapes (issue 18) and their mean orientation factor.
# usage: gnuplot -e "in='shapes.tsv'; fin='shapes_f.tsv'; alpha=0.95; outbase='shapes'" plots/shapes.gp
#   in:  plots/shapes.c's blocks (shape cpd x E/E0 E_tr/E_rot), one per shape
#   fin: shape, engine <f>, its error, MC collision-model <f>, its error
#   writes outbase.png and outbase.svg (or out, one file of the extension it names: the tests)
if (!exists("in")) in = 'shapes.tsv'
if (!exists("fin")) fin = 'shapes_f.tsv'
if (!exists("alpha")) alpha = 0.95
if (!exists("outbase")) outbase = 'shapes'
set encoding utf8
set datafile missing NaN
set grid lc rgb "#dddddd"
nshape = 6
terms = exists("out") ? (out[strlen(out)-2:] eq "svg" ? "svg" : "png") : "png svg"
do for [t in terms] {
  file = exists("out") ? out : outbase.".".t
  if (t eq "png") { set terminal png size 1200,520 font ",11" }
  if (t eq "svg") { set terminal svg size 1200,520 dynamic font "Helvetica,13" }
  set output file
  set multiplot layout 1,2 title sprintf("Rigid clusters of disks: cooling at α = %g and <f>", alpha)
  set xlabel "(1 − α²) cpd"
  set ylabel "E / E_0"
  set logscale y
  set key bottom left
  plot for [i=0:nshape-1] in index i using 3:4 with lines lw 2 \
         title word("disk dimer linear bent triangle asym", i + 1), \
       exp(-x/2) with lines dt 2 lc rgb "black" title "exp(−x/2): D_e = 2", \
       exp(-x/3) with lines dt 3 lc rgb "black" title "exp(−x/3): D_e = 3"
  unset logscale y
  set xlabel "shape"
  set ylabel "<f> = <μ_{eff} / m_{ref}> over collisions"
  set yrange [0.4 : 1.15]
  set key top left
  set xrange [-0.5 : nshape - 0.5]
  set xtics rotate by -30
  plot fin using ($0 - 0.1):2:3:xtic(1) with yerrorbars pt 7 title "engine (the runs at left)", \
       fin using ($0 + 0.1):4:5 with yerrorbars pt 6 title "MC, collision model"
  unset xtics
  set xtics
  unset multiplot
}
