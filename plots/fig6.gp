# Fig. 6 of Costantini et al. (2005): a) translational (each component) and b) rotational
# velocity distributions scaled by the snapshot's thermal velocity, one colour per snapshot (cpd),
# against the Gaussian (dashed).  v_th: the rms of one component of the centre-of-mass velocity
# (about its mean) = √(T_tr/M); ω_th: the rms of ω = √(T_rot/I), so that a Maxwellian is the
# standard normal.  Error bars: Poisson, √count of each bin.  Bins of a single snapshot with
# fewer than 2 counts are left out (their one-count floor is drawn, dotted); the pooled
# snapshots of many runs (black squares) reach the tails.
# Input: `haff veldist DB --run ID -o in`; optional pool: `haff veldist DB --pool -o pool`.
# usage: gnuplot -e "in='veldist.tsv'; out='fig6.png'[; pool='veldist_pool.tsv'; nbody=900]" plots/fig6.gp
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("in")) in = 'veldist.tsv'
if (!exists("out")) out = 'fig6.png'
eval term(out, 1200, 600)
set output out
set datafile separator "\t"
stats in using 3 nooutput
nb = STATS_blocks
stats in index 0 using 3 nooutput
dc = (STATS_max - STATS_min) / (STATS_records - 1)   # bin width
# one count of a snapshot: the smallest non-zero density of any snapshot
stats in using ($4 > 0 ? $4 : NaN) nooutput
one = STATS_min
cnt(p) = p / one
ok(p) = p > 0 && cnt(p) > 1.5
haspool = exists("pool")
if (!haspool) pool = in
# the pool's count per bin: p * n * dc (n: column 8, the values pooled); its plot elements
# (macros: none without a pool)
pc(p) = p * column(8) * dc
POOLA = !haspool ? "" : ", pool index 0 using 3:($4 > 0 ? $4 : NaN):($4 / sqrt(pc($4))) " \
  . "with yerrorbars pt 5 ps 1.0 lc rgb 'black' title columnheader(1), pool index 0 using " \
  . "3:($5 > 0 ? $5 : NaN):($5 / sqrt(pc($5))) with yerrorbars pt 4 ps 1.0 lc rgb 'black' notitle"
POOLB = !haspool ? "" : ", pool index 0 using 3:($6 > 0 ? $6 : NaN):($6 / sqrt(pc($6))) " \
  . "with yerrorbars pt 5 ps 1.0 lc rgb 'black' notitle"
if (!exists("what")) what = "900 dimers, a = d, α = 0.9"
set multiplot title "Scaled velocity distributions, ".what." (d = m = T_0 = 1)\n" \
  . "v_{th} = rms of V_x, V_y = √(T_{tr}/M);  ω_{th} = rms of ω = √(T_{rot}/I);  error bars √count" font ",11"
set logscale y
set yrange [1e-6:1]
set xrange [-5:5]
set format y "10^{%L}"
# panels a and b, then the key alone in a column at the right
set tmargin at screen 0.84
set bmargin at screen 0.11
set lmargin at screen 0.06
set rmargin at screen 0.355
set key at screen 0.72, screen 0.84 left top Left reverse font ",10" spacing 1.15 samplen 2
set xlabel "c = V_{x,y} / v_{th}"
set ylabel "P(c)"
set title "a) translational"
plot one with lines dt 3 lw 1 lc rgb "gray50" title "one count in a snapshot", \
     for [i=0:nb-1] in index i using 3:(ok($4) ? $4 : NaN):(sqrt(cnt($4)) * one) \
       with yerrorbars pt 7 ps 0.6 lt i+1 title columnheader(1), \
     for [i=0:nb-1] in index i using 3:(ok($5) ? $5 : NaN):(sqrt(cnt($5)) * one) \
       with yerrorbars pt 6 ps 0.6 lt i+1 notitle, \
     in index 0 using 3:7 with lines dt 2 lw 2 lc rgb "black" title "Gaussian", \
     NaN with points pt 7 ps 0.8 lc rgb "gray40" title "filled: V_x", \
     NaN with points pt 6 ps 0.8 lc rgb "gray40" title "open: V_y" @POOLA
set xlabel "c = ω / ω_{th}"
set title "b) rotational"
unset ylabel
unset key
set lmargin at screen 0.41
set rmargin at screen 0.705
plot one with lines dt 3 lw 1 lc rgb "gray50" notitle, \
     for [i=0:nb-1] in index i using 3:(ok($6) ? $6 : NaN):(sqrt(cnt($6)) * one) \
       with yerrorbars pt 7 ps 0.6 lt i+1 notitle, \
     in index 0 using 3:7 with lines dt 2 lw 2 lc rgb "black" notitle @POOLB
unset multiplot
