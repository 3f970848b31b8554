# Fig. 4 of Costantini et al. (2005), redrawn for any a/d: two dimers at contact and the allowed
# range |theta| <= theta_max of the contact angle (DESIGN.md convention: theta from the outward
# axis A2 -> A1 to the contact normal A1 -> B1).
# usage: gnuplot -e "data='fig4.dat'; a=1.0; outbase='plots/out/fig4'" plots/fig4.gp
#   data: the output of `haff mc fmean --a A --fig4-data` (lengths in units of d)
#   a: the same a/d (for the title); writes outbase.png, outbase.svg and outbase.pdf
load system("dirname '".ARG0."'")."/style.gp"
if (!exists("data")) data = 'fig4.dat'
if (!exists("a")) a = 1.0
if (!exists("outbase")) outbase = 'fig4'
tm = (a < 2.0) ? pi - acos(a / 2.0) : pi
tmdeg = tm * 180.0 / pi
th = 0.55 * tm

set size ratio -1
unset key
unset border
unset tics
set xrange [-a - 1.2 : 2.6 + a]
set yrange [-2.0 : 2.1 + a]
set title sprintf("Two dimers at contact, a/d = %.3g: allowed |θ| ≤ θ_{max} = π − arccos(a/2d) = %.4g°\nlengths in units of the disk diameter d", a, tmdeg)
set label 1 "A_1" at 0.08, -0.18 center front
set label 2 "A_2" at -a, -0.18 center front
set label 3 sprintf("allowed contact normals\n|θ| ≤ %.1f°", tmdeg) at 1.75, -1.1 left front
# left of and above the ghost circle of B_1 at +theta_max, with an arrow to it (not over it)
set label 4 "B_1 at θ = ±θ_{max}\n(touches A_2)" at -a - 1.15, sin(tm) + 1.05 left front
set arrow 2 from -a - 0.6, sin(tm) + 0.75 to cos(tm) - 0.45 * cos(pi / 4), sin(tm) + 0.45 * sin(pi / 4) \
    head size 0.08,20 lw 1 lc rgb "#333333" front
set label 5 "θ" at 0.5 * cos(0.5 * th), 0.5 * sin(0.5 * th) center front
set label 6 "B_1" at cos(th) + 0.12, sin(th) - 0.15 center front
set label 7 "outward axis" at 1.65, 0.12 left front
set arrow 1 from 0, 0 to 1.6, 0 nohead dt 3 lw 1.5 lc rgb "#333333" front
set style arrow 1 head filled size 0.12,20 lw 2 lc rgb "black"

unset grid
do for [t in "png svg pdf"] {
  eval term(outbase.".".t, 900, 760)
  set output outbase.".".t
  plot data index 3 using 1:2:3:4:5 with circles lc rgb "#cdebc2" fs solid 1.0 noborder, \
       data index 2 using 1:2:3 with circles lc rgb "#666666" dt 2 lw 1.5 fs empty, \
       data index 0 using 1:2:3 with circles lc rgb "#7fa7d9" fs solid 0.9 border lc rgb "black", \
       data index 1 using 1:2:3 with circles lc rgb "#e5a36b" fs solid 0.9 border lc rgb "black", \
       data index 4 using 1:2:3:4 with vectors arrowstyle 1, \
       '+' using (0):(0):(0.35):(0):(th * 180 / pi) every ::0::0 with circles lc rgb "black" lw 1.5 fs empty
  set output
}
