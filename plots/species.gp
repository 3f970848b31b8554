# The temperature ratio of binary disk mixtures against the mass ratio: runs and Garzo-Dufty.
# usage: gnuplot -e "in='species.tsv'; alphas='0.7 0.8 0.95'; outbase='species'" plots/species.gp
#   in: one block per alpha (plots/species.mk): m_ratio alpha T_light T_light_err th_light
#       T_heavy T_heavy_err th_heavy (T_i/T, T = x_l T_l + x_h T_h, haff-fit --by-species)
#   writes outbase.png, .svg, .pdf (or out, one file of the extension it names: the tests)
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'species.tsv'
if (!exists("alphas")) alphas = '0.7 0.8 0.95'
if (!exists("n")) n = 300
if (!exists("eta")) eta = 0.02
if (!exists("seeds")) seeds = 4
if (!exists("outbase")) outbase = 'species'
na = words(alphas)
terms = exists("out") ? out[strlen(out)-2:] : "png svg pdf"
do for [t in terms] {
  file = exists("out") ? out : outbase.".".t
  eval term(file, 1200, 560)
  set output file
  set multiplot layout 1,2 title sprintf("Binary mixtures of smooth disks (d = 1, m_{light} = 1, " \
    . "T_0 = 1): %d + %d disks, area fraction %g, %d seeds per point; T = x_l T_l + x_h T_h\n" \
    . "points: runs, T_i/T over the HCS window ± standard error over the seeds; " \
    . "lines: Garzó–Dufty (Maxwellian approximation, d = 2)", n, n, eta, seeds) font ",11"
  set xlabel "m_{heavy} / m_{light}"
  set ylabel "T_i / T"
  set key top left spacing 1.1 font ",10"
  set xrange [0.8:5.2]
  set yrange [*:*]
  plot for [i=0:na-1] in index i using 1:6:7 with yerrorbars lt i+1 pt 7 ps 1 lw 1.5 \
         title sprintf("heavy, α = %s", word(alphas, i + 1)), \
       for [i=0:na-1] in index i using 1:3:4 with yerrorbars lt i+1 pt 6 ps 1 lw 1.5 \
         title sprintf("light, α = %s", word(alphas, i + 1)), \
       for [i=0:na-1] in index i using 1:8 with lines lt i+1 lw 1.5 notitle, \
       for [i=0:na-1] in index i using 1:5 with lines lt i+1 lw 1.5 dt 2 notitle, \
       1 with lines lw 1 lc rgb "black" dt 3 title "equipartition"
  set ylabel "T_{run} / T_{theory} − 1  (%)"
  set yrange [-4:4]
  set key off
  set label 1 "symbols as on the left (α shifted apart in x); shaded: ±3 %" at graph 0.03, graph 0.95 font ",10"
  set object 1 rect from graph 0, first -3 to graph 1, first 3 fc rgb "#eeeeee" behind
  plot for [i=0:na-1] in index i using ($1 + 0.1 * (i - 1) - 0.025):(100 * ($6 / $8 - 1)):(100 * $7 / $8) \
         with yerrorbars lt i+1 pt 7 ps 1 lw 1.5 notitle, \
       for [i=0:na-1] in index i using ($1 + 0.1 * (i - 1) + 0.025):(100 * ($3 / $5 - 1)):(100 * $4 / $5) \
         with yerrorbars lt i+1 pt 6 ps 1 lw 1.5 notitle, \
       0 with lines lw 1 lc rgb "black" notitle
  unset label 1
  unset object 1
  unset multiplot
}
