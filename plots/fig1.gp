# Fig. 1 of Costantini et al. (2005): a snapshot of the dimer gas, every disk drawn as a circle
# of diameter d, coloured by the speed |V| of its dimer's centre of mass.
# Input: `plots/scripts/fig1data.sh DB > in` (first line '# box Lx Ly', then x y r speed).
# usage: gnuplot -e "in='fig1.tsv'; out='fig1.png'[; title='...']" plots/fig1.gp   (.png or .svg)
if (!exists("in")) in = 'fig1.tsv'
if (!exists("out")) out = 'fig1.png'
if (!exists("title")) title = ''
if (out[strlen(out)-3:] eq ".svg") { set terminal svg size 760,700 enhanced font "Helvetica,14" } \
else { set terminal pngcairo size 760,700 enhanced font "DejaVu Sans,11" }
set output out
set encoding utf8
set datafile separator "\t"
set datafile commentschars "#"
# the box edges from the first line
box = system(sprintf("head -n 1 '%s'", in))
Lx = real(word(box, 3))
Ly = real(word(box, 4))
set size ratio -1
set xrange [0:Lx]
set yrange [0:Ly]
set xlabel "x / d"
set ylabel "y / d"
set title title
set cblabel "|V| (centre of mass)"
set palette defined (0 "#2c7bb6", 1 "#abd9e9", 2 "#fdae61", 3 "#d7191c")
unset key
plot in using 1:2:3:4 with circles lc palette fs solid 0.85 border lc rgb "black"
