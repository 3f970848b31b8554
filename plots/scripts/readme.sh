#!/usr/bin/env bash
# plots/scripts/readme.sh OUT DATA CONFIG HAFF > OUT/README.md
# plots/README.md followed by the numbers of this build: parameters, Tables I-II, where the
# homogeneity detector cut the fits, <f> from the runs beside the Monte Carlo models, the
# error-against-cost table and the velocity statistics of Fig. 6.
set -eu
out=$1 data=$2 config=$3 haff=$4
cat plots/README.md
tsv2md() { # TSV with a header row -> Markdown table
  awk -F '\t' 'NR == 1 { h = "|"; s = "|"; for (i = 1; i <= NF; i++) { h = h " " $i " |"; s = s "---|" }
                         print h; print s; next }
               NF > 0 && $1 !~ /^#/ { r = "|"; for (i = 1; i <= NF; i++) r = r " " $i " |"; print r }' "$@"; }
echo
echo "## This build"
echo
echo "Made $(date -u '+%Y-%m-%d %H:%M UTC') by \`$("$haff" --version)\`."
echo "Parameters (plots/plots.mk): \`$config\`."
echo
echo "### Table I (\`table1.tsv\`): D_e and ν0_eff/ν0, mean ± standard error over the runs"
echo
echo "ν0 is eq. (29) in haff's convention: the bodies' number density, σ = d, the body mass (2m"
echo "for a dimer), g(η) at the reference disks' η = πnd²/4, and the translational temperature at the"
echo "window's start averaged over its samples. ν0_eff/ν_kt divides by the low-density theory of"
echo "rotating dimers (\`haff mc rate\`: 1.643, 2.090, 2.608 at a/d = 0.5, 1, 1.5) times"
echo "g(area fraction)/g(η); it is 1 where runs and theory agree (docs/mc-rate.md). The paper's"
echo "1.07–1.50 trend in a/d is reproduced by no convention (docs/analysis.md, \"ν0\")."
echo
echo "Each row's box: its N bodies at the area fraction shown, 0.7 L_c (0.5 L_c at α < 0.9, and α = 0.9 a/d = 1.5) of the"
echo "HCS or at most NDIM (\"Boxes of the tables\" above; \`make -f plots/plots.mk tables-boxes\`)."
echo
cat "$out/table1.md"
echo
echo "### Inside the HCS's validity? Every (α, a/d) group (\`data/fits-groups.tsv\`)"
echo
echo "D_e ± stat ± sys on each run's HCS window (cpd), the window's mean s_perp (the shear modes'"
echo "energy over molecular chaos), the flag and the runs rejected as near-collapse outliers; Tables"
echo "I and II leave the flagged groups out (docs/analysis.md, \"Errors of D_e\", \"Outlier runs\")."
echo
# (an empty cell, a value missing or not measured, prints — and not awk's 0)
awk -F '\t' 'function v(f, x) { return x == "" ? "—" : sprintf(f, x) }
             NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
                       print "| species | α | a/d | N | runs | D_e | ± stat | ± sys | window (cpd) | s_perp | flag | rejected |"
                       print "|---|---|---|---|---|---|---|---|---|---|---|---|"; next }
             { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s–%s | %s | %s | %s |\n", $c["species"],
                      $c["alpha"], $c["a_over_d"], $c["n"], $c["runs"], v("%.4f", $c["D_e"]),
                      v("%.2g", $c["D_e_err"]), v("%.2g", $c["D_e_sys"]), v("%.0f", $c["cpd_start"]),
                      v("%.0f", $c["cpd_end"]), v("%.3g", $c["s_perp"]), $c["flag"], $c["rejected"] }' \
  "$data/fits-groups.tsv"
echo
echo "### Table II (\`table2.tsv\`): K = E_tr/E_rot = a0 + a1 τ, 99 % intervals"
echo
cat "$out/table2.md"
echo
echo "### Where the fits stopped (homogeneity detector, \`data/fits.tsv\` per run)"
echo
echo "Per (α, a/d): runs, how many the detector cut, the cpd where the fit ended (mean, min,"
echo "max over the runs; a run not cut is fitted to its end) and the mean run length in cpd."
echo
awk -F '\t' 'NR == 1 { next }
  { k = $2 "\t" $3 "\t" $4; if (!(k in n)) { ord[++m] = k; lo[k] = 1e300; hi[k] = -1 }
    n[k]++; det[k] += $6; s[k] += $8; if ($8 < lo[k]) lo[k] = $8; if ($8 > hi[k]) hi[k] = $8 }
  END { print "| species | α | a/d | runs | cut | cpd_end mean | min | max |"
        print "|---|---|---|---|---|---|---|---|"
        for (i = 1; i <= m; i++) { k = ord[i]; split(k, f, "\t")
          printf "| %s | %s | %s | %d | %d | %.1f | %.1f | %.1f |\n", f[1], f[2], f[3], n[k], det[k],
                 s[k] / n[k], lo[k], hi[k] } }' "$data/fits.tsv"
echo
echo "Long runs that go on until the detector cuts them (α = LONG_ALPHA, a = d, LONG_CPD cpd;"
echo "\`data/long-fits.tsv\`): detected = 1 where it cut, cpd_end where; D_e fitted up to there."
echo
tsv2md "$data/long-fits.tsv"
echo
echo "### a/d near 2 (\`data/gap.tsv\`, \`data/gap-fits.tsv\`): the fate of each run"
echo
tsv2md "$data/gap.tsv"
echo
echo "Fits of eq. (31) to those runs (\`haff haff-fit\`; a failed fit shows empty cells, its reason below):"
echo
tsv2md "$data/gap-fits.tsv"
echo
sed 's/^/    /' "$data/gap-fits.err"
echo
echo "### ⟨f⟩ from the collision logs beside the Monte Carlo models (\`fmean_vs_engine.tsv\`)"
echo
tsv2md "$out/fmean_vs_engine.tsv"
echo
echo "### Error of D_e against CPU time (\`data/errcost.tsv\`, \`errcost.png\`)"
echo
for f in errcost errcost-stable; do
  [ -f "$data/$f.tsv" ] || continue
  echo "\`data/$f.tsv\`:"
  echo
  awk -F '\t' 'BEGIN { print "| stop_cpd | runs | CPU s | ⟨D_e⟩ | standard error | fit ended at cpd | sd(all)/√R | sys | total |"
                       print "|---|---|---|---|---|---|---|---|---|" }
               NF > 1 && $1 ~ /^[0-9.]+$/ { printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9 }' \
    "$data/$f.tsv"
  echo
done
echo
echo "### Fig. 6: velocity statistics per snapshot (\`data/veldist_stats.tsv\`)"
echo
tsv2md "$data/veldist_stats.tsv"
if [ -f "$data/species.tsv" ]; then
  echo
  echo "### Binary disk mixtures: T_i/T against the mass ratio (\`data/species.tsv\`, \`species.png\`)"
  echo
  echo "Runs (\`haff haff-fit --by-species\`, ± standard error over the seeds) against Garzó–Dufty's"
  echo "Maxwellian approximation for d = 2 (docs/analysis.md, \"Mixtures: the temperature ratio\")."
  echo
  awk -F '\t' 'BEGIN { print "| m_h/m_l | α | T_light/T | theory | T_heavy/T | theory | T_h/T_l | theory |"
                       print "|---|---|---|---|---|---|---|---|" }
               NF == 8 && $1 ~ /^[0-9.]+$/ { printf "| %s | %s | %.4f ± %.4f | %.4f | %.4f ± %.4f | %.4f | %.4f | %.4f |\n",
                 $1, $2, $3, $4, $5, $6, $7, $8, $6 / $3, $8 / $5 }' "$data/species.tsv"
fi
