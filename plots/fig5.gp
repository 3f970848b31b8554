# Fig. 5 of Costantini et al. (2005): distribution of the contact angle theta (between r12 and
# r13), one curve per block of collisions; optionally a second run (e.g. alpha = 1) as bullets;
# the uniform model on |theta| <= pi - acos(a/2d) (2 pi/3 for a = d) dashed.  Every distribution
# is drawn as a histogram (steps: a bin that straddles theta_max is a step, not a ramp); error
# bars (each bin's standard error) on the elastic run's points only, the blocks' typical error
# written in the key (their bars overlapped into an unreadable band).
# Input: `haff angles DB --run ID -o in` (and the same for in2).
# Optional fm: plots/scripts/fmean_engine.sh output; its rows at a/d = ad are written in a box
# (<f> of each run's log beside the three Monte Carlo models).
# usage: gnuplot -e "in='angles.tsv'; out='fig5.png'[; in2='angles_elastic.tsv'; ad=1; fm='f.tsv']" plots/fig5.gp
if (!exists("in")) in = 'angles.tsv'
if (!exists("out")) out = 'fig5.png'
if (!exists("ad")) ad = 1.0
load system("dirname '".ARG0."'")."/style.gp"
eval term(out, 820, 600)
set output out
set datafile separator "\t"
stats in using 4 nooutput
nb = STATS_blocks
# the blocks' typical (mean over the populated bins) standard error
stats in using ($5 > 0 ? $6 : NaN) nooutput
berr = STATS_mean
tmax = ad < 2 ? pi - acos(ad / 2.0) : pi
uniform(x) = abs(x) <= tmax ? 1.0 / (2 * tmax) : 0
set samples 1000
set xlabel "contact angle θ (rad)"
set ylabel "P(θ) (1/rad)"
set title sprintf("Contact angles of dimer–dimer collisions, a/d = %g: steps, the inelastic run per block\nof collisions; points, the elastic run (d = m = T_0 = 1)", ad)
set xrange [-pi:pi]
set yrange [0:*]
set key top right font ",10" spacing 1.05
if (nb > 6) { set key outside right top font ",9" } # many blocks: beside the plot, not over it
if (exists("fm")) {
  ftxt = system(sprintf("awk -F'\t' 'NR > 1 && $2 + 0 == %g { n = $1; if (n ~ /^engine/) n = sprintf(\"run, α = %%s\", $3); printf \"%%s: ⟨f⟩ = %%.4f ± %%.1g\\n\", n, $4, $5 }' '%s'", ad, fm))
  set label 1 ftxt at graph 0.02, graph 0.95 left front font ",9"
  set yrange [0:*]
  set offsets 0, 0, graph 0.35, 0
}
# the blocks as histograms; the elastic run with its standard errors
if (exists("in2")) {
  plot for [i=0:nb-1] in index i using 4:5 with histeps lw 1.5 lt i+1 title columnheader(1), \
       NaN with lines lc rgb "white" title sprintf("(typical block error ±%.3f, not drawn)", berr), \
       in2 index 0 using 4:5:6 with yerrorbars pt 7 ps 0.8 lw 1.2 lc rgb "black" title "elastic (α = 1), ± s.e.", \
       uniform(x) with lines dt 2 lw 2 lc rgb "gray40" title "uniform on |θ| < θ_{max}"
} else {
  plot for [i=0:nb-1] in index i using 4:5 with histeps lw 1.5 lt i+1 title columnheader(1), \
       for [i=0:nb-1] in index i using 4:5:6 with yerrorbars pt 0 lt i+1 notitle, \
       uniform(x) with lines dt 2 lw 2 lc rgb "gray40" title "uniform on |θ| < θ_{max}"
}
