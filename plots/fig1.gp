# Fig. 1 of Costantini et al. (2005): a snapshot of the dimer gas, every disk drawn as a circle
# of diameter d, coloured by the speed |V| of its dimer's centre of mass; a disk over the box's
# edge is drawn at both of its periodic images (fig1data.sh writes them).
# Input: `plots/scripts/fig1data.sh DB > in` (first line '# box Lx Ly cpd C t T N n', then
# x y r speed).
# usage: gnuplot -e "in='fig1.tsv'; out='fig1.png'[; title='...']" plots/fig1.gp  (.png .svg .pdf)
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'fig1.tsv'
if (!exists("out")) out = 'fig1.png'
if (!exists("title")) title = ''
eval term(out, 760, 760)
set output out
set datafile separator "\t"
set datafile commentschars "#"
# the box edges and the state's cpd and time from the first line
box = system(sprintf("head -n 1 '%s'", in))
Lx = real(word(box, 3))
Ly = real(word(box, 4))
cpd = words(box) >= 6 ? word(box, 6) : "?"
tt = words(box) >= 8 ? sprintf("%.4g", real(word(box, 8))) : "?"
set size ratio -1
set xrange [0:Lx]
set yrange [0:Ly]
set xlabel "x / d"
set ylabel "y / d"
set title title.sprintf("\nstate at cpd = %s (t = %s d√(m/T_0)); d = m = T_0 = 1", cpd, tt)
set cblabel "|V| / √(T_0/m)  (dimer centre of mass)"
set cbrange [0:*]
unset grid
set tics in
unset key
# plasma without its light end: every speed visible on white, lightness rising with |V|
set palette defined (0 "#0d0887", 0.35 "#7e03a8", 0.7 "#cc4778", 1 "#f89540")
set style fill solid 1.0
plot in using 1:2:3:4 with circles lc palette fs solid 1.0 noborder
