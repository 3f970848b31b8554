#!/usr/bin/env bash
# plots/scripts/errcost.sh HAFF STOP_CPD:DB... > errcost.tsv
# Error of D_e against the CPU time spent (issue 5).  Each DB holds the runs (same alpha, a/d,
# different seeds) of one run length STOP_CPD, made by run.sh (table plots_runs has each run's
# CPU seconds).  For R = 4, 8, 16, ... up to all the runs (and all of them), the first R runs
# (in seed order) give the ensemble mean of the per-run fits of eq. (31) (`haff haff-fit`,
# homogeneous part only) and its standard error sd/sqrt(R); cpu_seconds is the CPU time of those
# R runs.  Columns: stop_cpd runs cpu_seconds D_e D_e_err cpd_fit_end D_e_err_all D_e_sys D_e_total
# (cpd_fit_end: mean over the R runs of the cpd where the fit stopped: the run's end, or the
# end of homogeneous cooling found by the detector; D_e_err_all: sd of all the runs / sqrt(R);
# D_e_sys: the group's systematic error from `haff-fit --alpha-group` over all the runs of that
# length, D_e_total = sqrt(D_e_err_all^2 + D_e_sys^2), the error that covers the truth: issue 15).
# R = 2 is left out (issue 26): the sd of two values is itself uncertain by ~70 % (it came out as
# 1.3e-4 for two runs that happened to agree); D_e_err_all, the sd of all the runs over sqrt(R),
# is the expected error of R runs, well estimated at every R, and what errcost.gp draws.
set -eu
haff=$1
shift
first=1
for arg in "$@"; do
  L=${arg%%:*} db=${arg#*:}
  [ $first = 1 ] || printf '\n\n'
  first=0
  printf 'runs to %s cpd\truns\tcpu_seconds\tD_e\tD_e_err\tcpd_fit_end\tD_e_err_all\tD_e_sys\t' "$L"
  printf 'D_e_total\n'
  sys=$("$haff" haff-fit "$db" --alpha-group 2>/dev/null |
    awk -F '\t' 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "D_e_sys") c = i; next }
                  { print $c; exit }')
  # per run: run, D_e, cpd_end (haff-fit's columns found by name, as D_e_sys above)
  fits=$("$haff" haff-fit "$db" | awk -F '\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i
                                                         if (!c["run"] || !c["D_e"] || !c["cpd_end"]) {
                                                           print "errcost: haff-fit has no run, D_e or cpd_end column" > "/dev/stderr"; exit 1 }
                                                         next }
                                                { print $c["run"] "\t" $c["D_e"] "\t" $c["cpd_end"] }')
  cpu=$(sqlite3 -separator $'\t' "$db" "SELECT run, cpu_seconds FROM plots_runs ORDER BY run")
  join -t $'\t' <(sort -k1,1 <<< "$fits") <(sort -k1,1 <<< "$cpu") | sort -n -k1,1 |
    awk -F '\t' -v L="$L" -v sys="${sys:-}" '
      { n++; de[n] = $2; ce[n] = $3; cpu[n] = $4 }
      function sd(R,   i, s, ss, m) {
        s = ss = 0
        for (i = 1; i <= R; i++) s += de[i]
        m = s / R
        for (i = 1; i <= R; i++) ss += (de[i] - m) ^ 2
        return sqrt(ss / (R - 1))
      }
      function row(R,   i, s, c, e) {
        s = c = e = 0
        for (i = 1; i <= R; i++) { s += de[i]; c += cpu[i]; e += ce[i] }
        e1 = sd(R) / sqrt(R)
        # sys empty: not measured (the group flagged short: its windows too short for eq. 31)
        printf "%s\t%d\t%.4g\t%.6g\t%.4g\t%.4g\t%.4g\t%s\t%s\n", L, R, c, s / R, e1, e / R,
               sd(n) / sqrt(R), sys == "" ? "" : sprintf("%.4g", sys),
               sys == "" ? "" : sprintf("%.4g", sqrt(sd(n) * sd(n) / R + sys * sys))
      }
      END { for (R = 4; R < n; R *= 2) row(R); if (n >= 2) row(n) }'
done
