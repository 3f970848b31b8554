#!/usr/bin/env bash
# plots/scripts/fmean_engine.sh HAFF DB MC_SAMPLES > fmean_vs_engine.tsv
# <f> of the dimer-dimer collisions of every run in DB (`haff angles --fmean`: mean of the
# logged f, batch-means standard error) beside the three Monte Carlo models of
# `haff mc fmean --model all` at the same a/d (issue 4).
# Columns: source a_over_d alpha f_mean f_err D_over_f n
#   source: engine-run-ID or heuristic / exclusion / collision; D_over_f = 2/<f>;
#   n: collisions (engine) or Monte Carlo samples; alpha: NaN for the models.
set -eu
haff=$1 db=$2 samples=$3
printf 'source\ta_over_d\talpha\tf_mean\tf_err\tD_over_f\tn\n'
runs=$("$haff" haff-fit "$db" --no-detect | awk -F '\t' 'NR > 1 { print $1, $3, $4 }')
while read -r id alpha ad; do
  "$haff" angles "$db" --run "$id" --fmean | awk -F '\t' -v id="$id" -v al="$alpha" -v ad="$ad" \
    'NR == 2 { printf "engine-run-%s\t%s\t%s\t%.6f\t%.2g\t%.5f\t%s\n", id, ad, al, $3, $4, 2 / $3, $2 }'
done <<< "$runs"
for ad in $(awk '{ print $3 }' <<< "$runs" | sort -g -u); do
  "$haff" mc fmean --a "$ad" --model all --samples "$samples" --seed 1 |
    awk -F '\t' 'NR > 1 { printf "%s\t%s\tNaN\t%.6f\t%.2g\t%.5f\t%s\n", $1, $2, $3, $4, $5, $7 }'
done
