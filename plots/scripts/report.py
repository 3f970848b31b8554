#!/usr/bin/python3
"""plots/scripts/report.py: plots/out/index.html, one self-contained page of `make plots`.

usage: report.py OUT [--version V] [--config 'K=V ...'] [--db FIG=PATH ...] [--png NAME ...]
                 [-o FILE]

Every figure OUT/NAME.png (the --png names, in that order; else every PNG in OUT) is embedded as
a data: URI (the page needs no other file and no network; its SVG and PDF beside it are linked
by relative paths), with its caption: what it shows, what its error bars and bands are, its
units, and what was run, read from the run databases given with --db FIG=PATH (runs, N, area
fraction, alpha, a/d, seeds, cpd or time reached, haff version of the runs).  Tables I-II
(OUT/table1.tsv, OUT/table2.tsv) are rendered beside the values of Costantini et al. (2005).
The build's provenance: haff version, date (UTC), host, the parameters of plots/plots.mk.
A small inline script writes into the page, after loading, how many images loaded (their
naturalWidth > 0): #imgcheck, which tests/test_plots.c reads through headless Chromium.
Python 3 standard library only.
"""
import argparse
import base64
import configparser
import csv
import datetime
import html
import os
import socket
import sqlite3
import sys

# What each figure shows, its bars and bands, its units (the run summary is appended).
U_DIMER = "Units: d = m = T<sub>0</sub> = 1 (disk diameter, disk mass, initial temperature)."
U_RODS = "Units: rod mass m = 1, mean spacing 1 (ring length = N), scene time unit."
CAPTIONS = {
    "fig1": ("Fig. 1", "Snapshot of the final state: every disk drawn with diameter d, dimers that "
             "cross the box edge wrapped (both images drawn), coloured by the speed |V| of the "
             "dimer's centre of mass in units of √(T<sub>0</sub>/m). " + U_DIMER),
    "fig2": ("Fig. 2", "E/E(0) against x = (1 − α²)·cpd at a/d = 1, one colour per α; bands: the "
             "spread (± one standard deviation) over the runs of each α; lines: hard disks "
             "(α = 0.95, 0.9, the same N and η); dashed: exp(−x/3) (D<sub>e</sub> = 3). Inset: the "
             "same against ν<sub>0</sub><sup>eff</sup>t with Haff's law of the fitted "
             "D<sub>e</sub> (dashed) and a t<sup>−2</sup> guide. Lower panel: E/E(0) over exp(−x/3), "
             "where the bands and the differences between the α can be seen. " + U_DIMER),
    "fig3": ("Fig. 3", "(1 − α²)·cpd against ν<sub>0</sub><sup>eff</sup>t (log axis) with eq. (31) "
             "of the fitted D<sub>e</sub>; open symbols: groups that haff-fit --alpha-group flags on "
             "these very runs, the flag named in the key (at N = 900, α = 0.9 and 0.8 are past "
             "the HCS's critical size: inhomogeneous), shown for comparison. Points: mean over "
             "the runs. "
             + U_DIMER),
    "fig4": ("Fig. 4", "Two dimers at contact, a/d = 1: the allowed range |θ| ≤ θ<sub>max</sub> of "
             "the contact angle (Monte Carlo geometry, no statistics). Lengths in units of d."),
    "fig5": ("Fig. 5", "Distribution of the contact angle θ per block of collisions (α = 0.98, "
             "steps) and of the whole elastic run (α = 1, points with error bars: each bin's "
             "standard error; the blocks' typical error is written in the key); dashed: the "
             "uniform model. " + U_DIMER),
    "fig6": ("Fig. 6", "Distributions of the velocity components c = V<sub>x,y</sub>/v<sub>th</sub> "
             "and of c = ω/ω<sub>th</sub>, with v<sub>th</sub> the rms of one velocity component "
             "(= √(T<sub>tr</sub>/M)) and ω<sub>th</sub> the rms of ω (= √(T<sub>rot</sub>/I)) of "
             "the snapshot, per snapshot "
             "(cpd in the key); black: the pooled snapshots of many runs with Poisson error bars "
             "(√count), also on the snapshots' points. Bins of one snapshot with a single count are "
             "left out (the one-count floor is drawn). " + U_DIMER),
    "hcs": ("hcs", "State measures against cpd, each over its value for an uncorrelated gas: "
            "s<sub>⊥</sub> (shear), s<sub>∥</sub>, flow energy, cell-count variance, for a box "
            "below (left) and above (right) the HCS's critical size L<sub>c</sub> (the box edge "
            "beyond which the shear mode grows). Dashed: the threshold s<sub>⊥</sub> = 10 where the "
            "HCS window ends. One run each, no error bars. " + U_DIMER),
    "errcost": ("errcost", "Error of the ensemble mean ⟨D<sub>e</sub>⟩ over R runs against their "
                "total CPU time, one colour per run length (cpd); filled: standard error "
                "sd(all runs)/√R, the expected error of R runs; open: total error √(stat² + sys²); R is written beside each point. "
                "Points of R = 2 are left out: the standard deviation of two values is itself "
                "uncertain by ~70 %. Both panels share the y range."),
    "shapes": ("shapes", "Rigid clusters of disks: E/E<sub>0</sub> against (1 − α²)·cpd per shape; "
               "right: ⟨f⟩ = ⟨μ<sub>eff</sub>/m<sub>ref</sub>⟩ of the run's collisions (batch-means "
               "error) against the Monte Carlo collision model (standard error). "
               "m<sub>ref</sub>: the mass of the touching disk (docs/contract.md); asym: a dimer of "
               "a disk d = 1, m = 1 and a disk d = 0.5, m = 0.3, 0.8 d apart. The right panel shows "
               "engine − MC with the combined error. " + U_DIMER),
    "species": ("species", "Binary mixtures of smooth disks (equal sizes, light m = 1): each "
                "species' temperature over the mixture's, T<sub>i</sub>/T with T = x<sub>l</sub>"
                "T<sub>l</sub> + x<sub>h</sub>T<sub>h</sub>, averaged over each run's HCS window "
                "(<code>haff haff-fit --by-species</code>; error bars: standard error over the "
                "seeds), against Garzó and Dufty's homogeneous cooling state in the Maxwellian "
                "approximation for d = 2 (lines; docs/analysis.md). Right: run over theory − 1, "
                "the ±3 % band shaded. " + U_DIMER),
    "fmean": ("fmean", "⟨f⟩(a/d) and D<sub>e</sub>(a/d) of the three contact models (Monte Carlo, "
              "error bars: standard error), with Table I of the paper and haff's own fitted "
              "D<sub>e</sub> (table1.tsv, ± standard error over the runs). " + U_DIMER),
    "rods-energy": ("rods Fig. 1", "Kinetic energy per rod against t. No error bars (one run "
                    "each). " + U_RODS),
    "rods-collisions": ("rods Fig. 2", "(a) Total collisions against t with the ideal-gas "
                        "count and eq. (35); (b) the paper's inset: stochastic (solid) and "
                        "constant ε (dashed) until the constant model's inelastic collapse, "
                        "linear axes. One run each. " + U_RODS),
    "rods-damped": ("rods Figs. 9–10", "Damped bath: collisions (left axis) and kinetic energy "
                    "per rod (right axis) against t. One run. The late steps of the energy (the last one "
                    "two decades) are real: the energy sits in a few fast rods between the "
                    "clusters, and each step is one of them running into a cluster "
                    "(plots/README.md). " + U_RODS),
    "rods-damped50": ("rods Fig. 11", "50 damped rods: E<sub>kin</sub> ∝ t<sup>−2</sup>. One run. "
                      + U_RODS),
    "rods-density": ("rods Figs. 3–4", "Coarse-grained density over the mean N/L (100 bins) "
                     "in the (x, t) plane, linear and log time, one row per snapshot. One run. " + U_RODS),
    "rods-phase": ("rods Fig. 5", "Phase space (x, v) of every rod at two times. One run. "
                   + U_RODS),
    "rods-local": ("rods Fig. 6", "Local density and kinetic energy per rod along the ring at the "
                   "last snapshot. One run. " + U_RODS),
    "rods-veldist": ("rods Fig. 7", "Velocity histograms of all rods and of one cluster (rods "
                     "closer than 0.2 mean spacings), with "
                     "Poisson error bars (√count), against the Gaussians of the same variance. "
                     + U_RODS),
    "rods-gofr": ("rods Fig. 8", "Pair correlation g(x) of the ring, normalised by the mean "
                  "density N/L (uniform rods: 1; its mean over the whole ring is 1). The ring is "
                  "clustered: g ≈ 4 inside a cluster, a correlation hole of ≈ 0.5 next to it, "
                  "peaks at the distances between clusters (plots/README.md). " + U_RODS),
    "rods-collapse": ("rods collapse", "Fraction of constant-ε rings that collapse, against "
                      "McNamara–Young's N = −ln(1−ε)/(1−ε). Three seeds per point."),
}

# Costantini et al. (2005), Tables I and II (shared/papers): (a/d, alpha) -> values
PAPER_T1 = {  # D_e, nu0_eff/nu0
    (0.5, 0.99): (3.003, 1.07), (0.5, 0.98): (3.013, 1.08), (0.5, 0.95): (3.028, 1.08),
    (0.5, 0.90): (3.079, 1.11), (0.5, 0.85): (3.109, 1.13),
    (1.0, 0.99): (2.987, 1.26), (1.0, 0.98): (3.014, 1.25), (1.0, 0.95): (3.038, 1.28),
    (1.0, 0.90): (3.086, 1.32), (1.0, 0.85): (3.041, 1.31),
    (1.5, 0.99): (3.004, 1.45), (1.5, 0.98): (3.031, 1.47), (1.5, 0.95): (3.059, 1.50),
    (1.5, 0.90): (3.050, 1.48), (1.5, 0.85): (3.102, 1.50),
    (0.0, None): (1.998, None),  # hard disks (the paper's check, at area fraction 5.7e-4)
}
PAPER_T2 = {  # a0, da0, a1, da1 (99 % intervals)
    (0.5, 1.0): (1.999, 1e-3, -2.86e-6, 1.2e-6), (0.5, 0.98): (2.014, 1e-3, -2.82e-5, 3.5e-6),
    (0.5, 0.95): (1.994, 2e-3, 6.83e-5, 1.0e-5), (0.5, 0.85): (2.056, 2e-3, 2.17e-4, 1.5e-5),
    (1.0, 1.0): (2.001, 1e-3, 1.35e-5, 2.1e-6), (1.0, 0.98): (1.989, 1e-3, 4.84e-5, 3.1e-6),
    (1.0, 0.95): (2.046, 1e-3, -2.50e-4, 8.6e-6), (1.0, 0.85): (2.064, 2e-3, -4.78e-5, 1.7e-5),
    (1.5, 1.0): (1.987, 1e-3, 3.22e-5, 2.0e-6), (1.5, 0.98): (2.025, 1e-3, -5.38e-5, 3.3e-6),
    (1.5, 0.95): (2.036, 2e-3, -1.13e-4, 9.2e-6), (1.5, 0.85): (2.075, 2e-3, 2.06e-4, 1.6e-5),
}

E = html.escape


def ranges(nums):
    """'1-8, 11' from [1..8, 11]."""
    nums = sorted(set(nums))
    out, i = [], 0
    while i < len(nums):
        j = i
        while j + 1 < len(nums) and nums[j + 1] == nums[j] + 1:
            j += 1
        out.append(str(nums[i]) if i == j else "%d–%d" % (nums[i], nums[j]))
        i = j + 1
    return ", ".join(out)


def fmt_set(vals, f="%g"):
    vals = sorted(set(v for v in vals if v is not None))
    if not vals:
        return None
    return ", ".join(f % v for v in vals)


def span(vals, f="%.4g"):
    vals = [v for v in vals if v is not None]
    if not vals:
        return None
    lo, hi = min(vals), max(vals)
    return f % lo if lo == hi else (f + "–" + f) % (lo, hi)


def run_summary(paths):
    """What was run, from the runs of the databases: one line of text, or None."""
    runs = []
    for p in paths:
        if not os.path.exists(p):
            continue
        try:
            con = sqlite3.connect("file:%s?mode=ro" % p, uri=True)
            rows = con.execute("SELECT scene, seed, status, cpd, version FROM runs").fetchall()
            tmax = {}
            try:
                tmax = dict(con.execute("SELECT run, max(t) FROM samples GROUP BY run")
                            .fetchall())
            except sqlite3.Error:
                pass
            ids = [r[0] for r in con.execute("SELECT id FROM runs").fetchall()]
            con.close()
        except sqlite3.Error as e:
            print("report.py: %s: %s" % (p, e), file=sys.stderr)
            continue
        for rid, (scene, seed, status, cpd, version) in zip(ids, rows):
            cp = configparser.ConfigParser(interpolation=None, strict=False,
                                           inline_comment_prefixes=(";",))
            try:
                cp.read_string(scene)
            except configparser.Error:
                cp = None
            runs.append((cp, seed, status, cpd, version, tmax.get(rid)))
    if not runs:
        return None

    def key(sec, k):
        out = []
        for r in runs:
            cp = r[0]
            if cp is not None and cp.has_option(sec, k):
                try:
                    out.append(float(cp.get(sec, k).split()[0]))
                except ValueError:
                    pass
        return out

    parts = ["%d run%s" % (len(runs), "" if len(runs) == 1 else "s")]
    for sec, name in (("dimers", "dimers"), ("disks", "disks"), ("rods", "rods")):
        n = fmt_set(key(sec, "count"), "%d")
        if n:
            parts.append("N = %s %s" % (n, name))
    sp = [r[0] for r in runs if r[0] is not None]
    spec = sorted(set(s[8:] for cp in sp for s in cp.sections() if s.startswith("species ")))
    if spec:
        parts.append("species " + ", ".join(spec))
    eta = fmt_set(key("system", "area_fraction"))
    if eta:
        parts.append("area fraction η = " + eta)
    al = fmt_set(key("dimers", "alpha") + key("disks", "alpha") +
                 [v for s in spec for v in key("species " + s, "alpha")])
    if al:
        parts.append("α = " + al)
    a = fmt_set(key("dimers", "a"))
    if a:
        parts.append("a/d = " + a)
    g = fmt_set(key("rods", "gamma"))
    if g:
        parts.append("γ = " + g)
    c = span([r[3] for r in runs])
    if c:
        parts.append("cpd reached " + c)
    t = span([r[5] for r in runs])
    if t and key("rods", "count"):
        parts.append("t reached " + t)
    parts.append("seeds " + ranges([r[1] for r in runs]))
    st = {}
    for r in runs:
        st[r[2]] = st.get(r[2], 0) + 1
    parts.append("status " + ", ".join("%s %d" % kv for kv in sorted(st.items())))
    v = fmt_set([r[4] for r in runs], "%s")
    if v:
        parts.append("haff " + v)
    return "; ".join(parts) + "."


def read_tsv(path):
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader((l for l in f if not l.startswith("#")), delimiter="\t"))


def num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return float("nan")


def pm(v, e, f="%.4f"):
    """'v ± e' with f, or '—' for a value that is not a number (no fit: elastic runs)."""
    if v != v:
        return "—"
    return (f + " ± " + f) % (v, e) if e == e else f % v


def table1_html(rows):
    h = ["<table><caption>Table I: D<sub>e</sub> and ν<sub>0</sub><sup>eff</sup>/ν<sub>0</sub> "
         "(haff: mean ± standard error over the runs, ± systematic; paper: Costantini et al. "
         "2005, Table I; d = m = T<sub>0</sub> = 1; a/d = 0: hard disks)</caption>",
         "<tr><th>a/d</th><th>α</th><th>runs</th><th>D<sub>e</sub> (haff)</th>"
         "<th>D<sub>e</sub> (paper)</th><th>ν<sub>0</sub><sup>eff</sup>/ν<sub>0</sub> (haff)</th>"
         "<th>ν<sub>0</sub><sup>eff</sup>/ν<sub>0</sub> (paper)</th><th>flag</th></tr>"]
    seen = set()
    for r in rows or []:
        ad, al = num(r["a_over_d"]), num(r["alpha"])
        p = PAPER_T1.get((round(ad, 3), round(al, 3))) or (PAPER_T1.get((0.0, None))
                                                          if ad == 0 else None)
        seen.add((round(ad, 3), round(al, 3)))
        de = pm(num(r["D_e"]), num(r["D_e_err"]))
        if de != "—":  # a systematic error not measured is empty: "—", never nan
            sys = num(r["D_e_sys"])
            de += " ± %.4f" % sys if sys == sys else " ± —"
        h.append("<tr><td>%g</td><td>%g</td><td>%s</td><td>%s</td><td>%s</td>"
                 "<td>%s</td><td>%s</td><td>%s</td></tr>" % (
                     ad, al, E(r["runs"]), de,
                     "%.3f" % p[0] if p else "—", pm(num(r["ratio"]), num(r["ratio_err"]), "%.3f"),
                     "%.2f" % p[1] if p and p[1] else "—", E(r.get("flag", ""))))
    for (ad, al), p in sorted((k, v) for k, v in PAPER_T1.items() if k[1] is not None):
        if (ad, al) not in seen:
            h.append("<tr class='missing'><td>%g</td><td>%g</td><td>0</td><td>— (not in this "
                     "build's table: flagged or not run)</td><td>%.3f</td><td>—</td><td>%.2f</td><td></td></tr>"
                     % (ad, al, p[0], p[1]))
    h.append("</table>")
    return "\n".join(h)


def table2_html(rows):
    h = ["<table><caption>Table II: K = E<sub>tr</sub>/E<sub>rot</sub> = a<sub>0</sub> + "
         "a<sub>1</sub>τ (haff: estimate with its 99 % interval; paper: a ± Δa, 99 %, Table II)"
         "</caption>",
         "<tr><th>a/d</th><th>α</th><th>a<sub>0</sub> (haff)</th><th>a<sub>0</sub> (paper)</th>"
         "<th>a<sub>1</sub> (haff)</th><th>a<sub>1</sub> (paper)</th></tr>"]
    for r in rows or []:
        ad, al = num(r["a_over_d"]), num(r["alpha"])
        p = PAPER_T2.get((round(ad, 3), round(al, 3)))
        h.append("<tr><td>%g</td><td>%g</td><td>%.4f [%.4f, %.4f]</td><td>%s</td>"
                 "<td>%.3g [%.3g, %.3g]</td><td>%s</td></tr>" % (
                     ad, al, num(r["a0"]), num(r["a0_lo"]), num(r["a0_hi"]),
                     "%.3f ± %.0e" % (p[0], p[1]) if p else "—",
                     num(r["a1"]), num(r["a1_lo"]), num(r["a1_hi"]),
                     "%.3g ± %.2g" % (p[2], p[3]) if p else "—"))
    h.append("</table>")
    return "\n".join(h)


def main():
    ap = argparse.ArgumentParser(description="plots/out/index.html")
    ap.add_argument("out")
    ap.add_argument("--version", default="")
    ap.add_argument("--config", default="")
    ap.add_argument("--db", action="append", default=[], help="FIG=PATH")
    ap.add_argument("--png", action="append", default=[], help="figure names, in page order")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    if a.version.startswith("haff "):
        a.version = a.version[5:]
    dbs = {}
    for d in a.db:
        fig, _, path = d.partition("=")
        dbs.setdefault(fig, []).append(path)
    names = a.png or sorted(f[:-4] for f in os.listdir(a.out) if f.endswith(".png"))
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")
    h = ["<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>",
         "<meta name='viewport' content='width=device-width'>",
         "<title>haff: figures and tables of make plots</title>",
         "<style>body{font-family:'DejaVu Sans',sans-serif;max-width:1250px;margin:1em auto;"
         "padding:0 1em;color:#111}figure{margin:2em 0;border-top:1px solid #ccc;padding-top:1em}"
         "figure img{max-width:100%;height:auto;display:block}figcaption{font-size:0.92em;"
         "margin-top:0.5em}table{border-collapse:collapse;margin:1em 0;font-size:0.9em}"
         "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}caption{text-align:left;"
         "font-weight:bold;padding:4px 0}tr.missing td{color:#888}.tables{display:flex;"
         "flex-wrap:wrap;gap:2em}code{font-size:0.95em}</style>",
         "</head><body>", "<h1>haff: the papers' figures and tables (<code>make plots</code>)</h1>",
         "<p id='provenance'>Built with haff %s on %s, host %s. Parameters of plots/plots.mk: "
         "<code>%s</code>. What each figure shows and how: plots/README.md.</p>"
         % (E(a.version), now, E(socket.gethostname()), E(a.config)),
         "<p id='imgcheck'>(images not checked: scripts off)</p>",
         "<h2>Tables</h2><div class='tables'>",
         table1_html(read_tsv(os.path.join(a.out, "table1.tsv"))),
         table2_html(read_tsv(os.path.join(a.out, "table2.tsv"))), "</div>", "<h2>Figures</h2>"]
    for n in names:
        png = os.path.join(a.out, n + ".png")
        if not os.path.exists(png):
            print("report.py: %s: missing" % png, file=sys.stderr)
            return 1
        with open(png, "rb") as f:
            uri = "data:image/png;base64," + base64.b64encode(f.read()).decode("ascii")
        title, cap = CAPTIONS.get(n, (n, ""))
        runs = run_summary(dbs.get(n, []))
        links = " ".join("<a href='%s.%s'>%s</a>" % (E(n), e, e.upper()) for e in ("svg", "pdf")
                         if os.path.exists(os.path.join(a.out, n + "." + e)))
        h.append("<figure id='%s'><img src='%s' alt='%s'><figcaption><b>%s</b> (%s.png%s). %s%s"
                 "</figcaption></figure>" % (
                     E(n), uri, E(title), E(title), E(n), "; " + links if links else "", cap,
                     " <i>Run:</i> " + E(runs) if runs else ""))
    h.append("<script>window.addEventListener('load',function(){var im=document.images,k=0;"
             "for(var i=0;i<im.length;i++)if(im[i].complete&&im[i].naturalWidth>0)k++;"
             "var p=document.getElementById('imgcheck');p.setAttribute('data-loaded',k);"
             "p.setAttribute('data-total',im.length);p.textContent=k+' of '+im.length+"
             "' images loaded';});</script>")
    h.append("</body></html>")
    text = "\n".join(h) + "\n"
    if a.output:
        tmp = a.output + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, a.output)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
