#!/usr/bin/python3
"""plots/scripts/energy_band.py DB [LABEL] > band.tsv: Fig. 2's mean and spread over the runs.

For each alpha of the runs in DB (a merged database of runs of one body kind and a/d), the runs'
E/E(0) (E = e_tr + e_rot per body, E(0) each run's first sample) at their common samples (the
k-th sample of every run: samples are taken every 0.5 cpd in all of them), as one block per alpha
(two blank lines between blocks; gnuplot `index`):
  header line:  LABEL α = A (R runs)       (the key's title, columnheader(1))
  columns:      x = (1 - alpha^2) cpd (mean over the runs), mean E/E0, sd of E/E0 over the runs,
                standard error sd/sqrt(R), runs
Rows end where the shortest run ends.  Python 3 standard library only.
"""
import configparser
import math
import sqlite3
import sys


def main():
    if len(sys.argv) not in (2, 3):
        print("usage: energy_band.py DB [LABEL] > band.tsv", file=sys.stderr)
        return 2
    db, label = sys.argv[1], (sys.argv[2] + " " if len(sys.argv) == 3 else "")
    con = sqlite3.connect("file:%s?mode=ro" % db, uri=True)
    groups = {}
    for rid, scene in con.execute("SELECT id, scene FROM runs ORDER BY id"):
        cp = configparser.ConfigParser(interpolation=None, strict=False,
                                       inline_comment_prefixes=(";",))
        cp.read_string(scene)
        alpha = None
        for sec in ("dimers", "disks"):
            if cp.has_option(sec, "count") and int(float(cp.get(sec, "count"))) > 0:
                alpha = float(cp.get(sec, "alpha", fallback="1"))
                break
        if alpha is None:
            continue
        rows = con.execute("SELECT cpd, e_tr + e_rot FROM samples WHERE run = ? ORDER BY t",
                           (rid,)).fetchall()
        if rows and rows[0][1] > 0:
            groups.setdefault(alpha, []).append([(c, e / rows[0][1]) for c, e in rows])
    first = True
    for alpha in sorted(groups, reverse=True):
        runs = groups[alpha]
        r = len(runs)
        n = min(len(x) for x in runs)
        if not first:
            sys.stdout.write("\n\n")
        first = False
        print("%sα = %g (%d runs)\tmean\tsd\tsem\truns" % (label, alpha, r))
        for k in range(n):
            x = sum(run[k][0] for run in runs) / r * (1 - alpha * alpha)
            v = [run[k][1] for run in runs]
            m = sum(v) / r
            sd = math.sqrt(sum((y - m) ** 2 for y in v) / (r - 1)) if r > 1 else float("nan")
            print("%.6g\t%.6g\t%.4g\t%.4g\t%d" % (x, m, sd, sd / math.sqrt(r), r))
    return 0


if __name__ == "__main__":
    sys.exit(main())
