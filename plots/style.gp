# plots/style.gp: the one style of every figure of `make plots` (loaded first by each plots/*.gp:
# `load 'plots/style.gp'`), so that a new figure gets it by default.
#
#   fonts     DejaVu Sans (has α θ ν ⟨⟩ ⊥ ∥ …: symbols are written as UTF-8 in every key and label)
#   lines     lw 2 for data lines, 1.5 for reference lines; points ps 0.8
#   palette   Okabe & Ito (2008), "Color Universal Design": distinct for the common forms of
#             colour blindness; linetypes 1-8 also differ in point type (filled circle, square,
#             diamond, triangle, ...) and, from 5 on, in dash pattern, so that curves stay
#             distinct in greyscale.  Yellow (#F0E442) is left out: too light on white.
#   terminals by the output file's extension: .png (pngcairo, screens), .svg, .pdf (pdfcairo,
#             papers).  A script sets its size in pixels and calls
#               eval term(out, W, H)
#             (pdf: the same aspect, W/100 x H/100 inches at the same font size).
#   units     every figure says its units (d = m = T0 = 1 for the dimer/disk figures; rods: the
#             ring's length unit, rod mass m = 1, t in the scene's time unit); U_DIMER and U_RODS
#             are the strings the scripts put in their titles.
set encoding utf8
FONT = "DejaVu Sans"
term(o, w, h) = (o[strlen(o)-3:] eq ".svg") ? \
  sprintf("set terminal svg size %d,%d dynamic enhanced font '%s,12' linewidth 1.2 background rgb 'white'", w, h, FONT) : \
  (o[strlen(o)-3:] eq ".pdf") ? \
  sprintf("set terminal pdfcairo size %.2fin,%.2fin enhanced font '%s,9' linewidth 1.2", w / 100.0, h / 100.0, FONT) : \
  sprintf("set terminal pngcairo size %d,%d enhanced font '%s,11' linewidth 1.2", w, h, FONT)
# Okabe-Ito, in the order most distinct first (blue, vermillion, bluish green, reddish purple,
# orange, sky blue, black, grey)
OI1 = "#0072B2"; OI2 = "#D55E00"; OI3 = "#009E73"; OI4 = "#CC79A7"
OI5 = "#E69F00"; OI6 = "#56B4E9"; OI7 = "#000000"; OI8 = "#777777"
set linetype 1 lc rgb OI1 lw 2 pt 7  ps 0.8 dt 1
set linetype 2 lc rgb OI2 lw 2 pt 5  ps 0.8 dt 1
set linetype 3 lc rgb OI3 lw 2 pt 9  ps 0.9 dt 1
set linetype 4 lc rgb OI4 lw 2 pt 13 ps 0.9 dt 1
set linetype 5 lc rgb OI5 lw 2 pt 11 ps 0.9 dt 4
set linetype 6 lc rgb OI6 lw 2 pt 6  ps 0.8 dt 5
set linetype 7 lc rgb OI7 lw 2 pt 4  ps 0.8 dt 1
set linetype 8 lc rgb OI8 lw 2 pt 8  ps 0.8 dt 3
set linetype cycle 8
# a sequential palette for colour maps that is monotone in lightness (viridis-like: dark blue to
# yellow), readable in greyscale
set palette defined (0 "#30123b", 0.15 "#3e4a89", 0.35 "#26828e", 0.55 "#35b779", 0.8 "#b5de2b", 1 "#fde725")
set style fill solid 1.0 noborder   # bands: fs transparent solid 0.25 where drawn
set grid lc rgb "#e0e0e0" lw 1
set border lw 1.2
set tics out nomirror
set key samplen 2.5 spacing 1.15
set datafile missing NaN
U_DIMER = "units: d = m = T_0 = 1 (d disk diameter, m disk mass, T_0 initial temperature)"
U_RODS = "units: rod mass m = 1, ring length L = N (mean spacing 1), scene time unit"
