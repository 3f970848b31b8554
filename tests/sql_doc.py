"""Runs the ten questions of docs/sql.md on the study database that tests/test_sql.c makes, and
checks them: the SQL (run by the sqlite3 shell) and the pandas answer (Debian's python3-pandas)
must agree row by row, and each answer must be right for the study's design (below).

usage: /usr/bin/python3 tests/sql_doc.py STUDY.db docs/sql.md     exit 0 when every check holds

The study (made by tests/test_sql.c): runs 1-8 are 50 dimers at area fraction 0.1, stop_cpd 10,
every collision logged, alpha in (0.8, 0.95) x a in (0.5, 1) x seed in (1, 2) in that order
(seed fastest); run 9 is 60 disks, alpha 0.9, at 0.1; run 10 a mixture of 10 dimers (a = 0.5,
alpha 0.9) and 10 disks (sigma 0.8, alpha 0.85) in a 20 x 15 box, stop_cpd 3, every 3rd
collision logged."""
import json
import math
import re
import sqlite3
import subprocess
import sys

import pandas as pd

DB, DOC = sys.argv[1], sys.argv[2]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def close(a, b, rel=1e-9, tiny=1e-12):
    if a is None or b is None or (isinstance(a, float) and math.isnan(a)) or (
            isinstance(b, float) and math.isnan(b)):
        na = a is None or (isinstance(a, float) and math.isnan(a))
        nb = b is None or (isinstance(b, float) and math.isnan(b))
        return na and nb
    if isinstance(a, str) or isinstance(b, str):
        return a == b
    return abs(a - b) <= rel * max(abs(a), abs(b)) + tiny


# ---- the questions: "### N. title", then a ```sql block and a ```python block ----------------
text = open(DOC).read()
questions = {}
for m in re.finditer(r"^### (\d+)\. (.*?)$(.*?)(?=^### |\Z)", text, re.M | re.S):
    body = m.group(3)
    sql = re.search(r"```sql\n(.*?)```", body, re.S)
    py = re.search(r"```python\n(.*?)```", body, re.S)
    questions[int(m.group(1))] = (m.group(2), sql and sql.group(1), py and py.group(1))
check(sorted(questions) == list(range(1, 11)), f"docs/sql.md has questions {sorted(questions)}")

con = sqlite3.connect(DB)
answers = {}
for k, (title, sql, py) in sorted(questions.items()):
    if not sql or not py:
        check(False, f"Q{k}: needs a sql and a python block")
        continue
    out = subprocess.run(["sqlite3", "-json", DB], input=sql, capture_output=True, text=True)
    if out.returncode or out.stderr:
        check(False, f"Q{k}: sqlite3: {out.stderr.strip()}")
        continue
    rows = json.loads(out.stdout) if out.stdout.strip() else []
    env = {"pd": pd, "con": con}
    try:
        exec(py, env)
    except Exception as e:  # a block that fails is a failed check, with its message
        check(False, f"Q{k}: pandas block: {type(e).__name__}: {e}")
        continue
    df = env.get("df")
    if not isinstance(df, pd.DataFrame):
        check(False, f"Q{k}: pandas block leaves no DataFrame df")
        continue
    cols = list(rows[0].keys()) if rows else list(df.columns)
    check(list(df.columns) == cols, f"Q{k}: columns: sql {cols}, pandas {list(df.columns)}")
    check(len(df) == len(rows), f"Q{k}: rows: sql {len(rows)}, pandas {len(df)}")
    prow = [dict(zip(df.columns, (None if v is None else (v.item() if hasattr(v, "item") else v)
                                   for v in r))) for r in df.itertuples(index=False)]
    for i, (a, b) in enumerate(zip(rows, prow)):
        for c in cols:
            if c in b and not close(a.get(c), b[c]):
                check(False, f"Q{k} row {i} {c}: sql {a.get(c)!r}, pandas {b[c]!r}")
    answers[k] = rows

# ---- the answers against the study's design ------------------------------------------------
design = [(al, a, s) for al in (0.8, 0.95) for a in (0.5, 1.0) for s in (1, 2)]


def mix_area_fraction():  # 10 dimers d = 1, a = 0.5 and 10 disks sigma 0.8 in 20 x 15
    r, a = 0.5, 0.5
    lens = 2 * r * r * math.acos(a / (2 * r)) - a / 2 * math.sqrt(4 * r * r - a * a)
    return (10 * (2 * math.pi * r * r - lens) + 10 * math.pi * 0.8 ** 2 / 4) / (20 * 15)


def q(sql, *args):
    return con.execute(sql, args).fetchall()


if 1 in answers:
    r = answers[1]
    check(len(r) == 10, f"Q1: {len(r)} runs, want 10")
    for i, (al, a, s) in enumerate(design[:len(r)]):
        x = r[i]
        check(x["species"] == "dimers" and x["n"] == 50 and close(x["alpha"], al)
              and close(x["a_over_d"], a) and x["seed"] == s and x["status"] == "done"
              and close(x["area_fraction"], 0.1) and x["cpd_reached"] >= 10,
              f"Q1: run {i + 1} is {x}, want dimers 50 alpha {al} a/d {a} seed {s} done")
    if len(r) == 10:
        check(r[8]["species"] == "disks" and r[8]["n"] == 60 and close(r[8]["alpha"], 0.9)
              and r[8]["a_over_d"] is None, f"Q1: run 9 is {r[8]}")
        check(r[9]["species"] == "mixture" and r[9]["n"] == 20
              and close(r[9]["area_fraction"], mix_area_fraction(), 1e-12),
              f"Q1: run 10 is {r[9]}, want a mixture of 20 at {mix_area_fraction()}")
if 2 in answers:
    got = [(x["alpha"], x["a_over_d"], x["runs"], x["done"]) for x in answers[2]]
    want = [(0.8, 0.5, 2, 2), (0.8, 1.0, 2, 2), (0.95, 0.5, 2, 2), (0.95, 1.0, 2, 2)]
    check(got == want, f"Q2: {got}, want {want}")
if 3 in answers:
    # recomputed here from the raw rows, without SQL's avg or pandas
    per_run = {}
    for run, f in q("SELECT run, f FROM collisions WHERE kind = 'dimer-dimer' AND f IS NOT NULL"):
        per_run.setdefault(run, []).append(f)
    groups = {}
    for run, fs in per_run.items():
        key = (design[run - 1][0], design[run - 1][1]) if run <= 8 else (0.9, 0.5)
        groups.setdefault(key, []).append(sum(fs) / len(fs))
    check(len(answers[3]) == len(groups), f"Q3: {len(answers[3])} groups, want {len(groups)}")
    for x in answers[3]:
        ms = groups.get((x["alpha"], x["a_over_d"]), [])
        mean = sum(ms) / len(ms) if ms else None
        check(x["runs"] == len(ms) and close(x["mean_f"], mean, 1e-12),
              f"Q3: {x}, want {len(ms)} runs, mean {mean}")
        if len(ms) > 1:
            se = math.sqrt(sum((m - mean) ** 2 for m in ms) / (len(ms) - 1) / len(ms))
            check(close(x["stderr_f"], se, 1e-9), f"Q3: stderr {x['stderr_f']}, want {se}")
        # f = mu_eff/m lies in [1/2, 1] for every dimer-dimer collision (eq. 36)
        check(0.5 <= x["mean_f"] <= 1, f"Q3: mean_f {x['mean_f']} outside [1/2, 1]")
        # a = d: the paper's <f> = 0.64; two runs of ~250 dimer-dimer collisions (sd of f
        # about 0.13) give a standard error near 0.006: 0.03 is 5 of them
        if x["a_over_d"] == 1:
            check(abs(x["mean_f"] - 0.64) < 0.03, f"Q3: a = d: <f> = {x['mean_f']}, not 0.64")
if 4 in answers:
    e = {(x["alpha"], x["a_over_d"]): x["e_over_e0"] for x in answers[4]}
    check(len(e) == 4 and all(x["runs"] == 2 for x in answers[4]), f"Q4: {answers[4]}")
    for a in (0.5, 1.0):
        lo, hi = e.get((0.8, a), 1), e.get((0.95, a), 0)
        # Haff: ln E/E0 ~ -(1 - alpha^2) cpd / D_e with D_e in [2, 5]: at cpd 5, alpha 0.8
        # gives 0.41-0.70, alpha 0.95 0.78-0.91; the two ranges do not overlap
        check(0 < lo < hi < 1, f"Q4: a/d {a}: E/E0 {lo} (alpha 0.8) not below {hi} (0.95)")
        check(math.exp(-0.36 * 5 / 2) - 0.05 < lo < math.exp(-0.36 * 5 / 5) + 0.05,
              f"Q4: a/d {a}, alpha 0.8: E/E0 = {lo}, want exp(-0.36 * 5 / D_e), D_e in [2, 5]")
        check(math.exp(-0.0975 * 5 / 2) - 0.05 < hi < math.exp(-0.0975 * 5 / 5) + 0.05,
              f"Q4: a/d {a}, alpha 0.95: E/E0 = {hi}, want exp(-0.0975 * 5 / D_e)")
if 5 in answers:
    check([x["run"] for x in answers[5]] == list(range(1, 9)), f"Q5: runs {answers[5]}")
    for x in answers[5]:
        check(x["cpd"] >= 10 and 0 < x["k"] < 100, f"Q5: {x}")
if 6 in answers:
    got = [(x["section"], x["key"], x["n_values"], x["vals"]) for x in answers[6]]
    want = [("dimers", "a", 2, "0.5,1"), ("dimers", "alpha", 2, "0.8,0.95"),
            ("system", "seed", 2, "1,2")]
    check(got == want, f"Q6: {got}, want {want}")
if 7 in answers:
    check([x["run"] for x in answers[7]] == list(range(1, 10)),
          f"Q7: runs {[x['run'] for x in answers[7]]}, want 1-9 (run 10 logs every 3rd)")
    for x in answers[7]:
        check(x["de_samples"] < 0 and close(x["de_samples"], x["de_collisions"], 1e-9),
              f"Q7: energy lost by collisions {x['de_collisions']} != by samples "
              f"{x['de_samples']} in run {x['run']}")
if 8 in answers:
    check([x["run"] for x in answers[8]] == [7, 8], f"Q8: {answers[8]}, want runs 7 and 8")
if 9 in answers:
    got = {x["species"]: x["runs"] for x in answers[9]}
    # the mixture's dimers and disks count with their own species, not pooled as "mixture"
    check(got == {"dimers": 9, "disks": 2}, f"Q9: {answers[9]}, want dimers in 9 runs, disks in 2")
    # a2 per species from the bodies' kind (not their species column), run by run
    a2 = {}
    for run, kind, v2, v4 in q("SELECT run, kind, avg(vx * vx + vy * vy), "
                               "avg((vx * vx + vy * vy) * (vx * vx + vy * vy)) FROM states "
                               "WHERE label = 'final' GROUP BY run, kind"):
        a2.setdefault(kind + "s", []).append(v4 / (2 * v2 * v2) - 1)
    for x in answers[9]:
        runs = a2.get(x["species"], [math.nan])
        want = sum(runs) / len(runs)
        check(close(x["a2"], want, 1e-9), f"Q9: a2 = {x['a2']} for {x['species']}, want {want}")
        check(abs(x["a2"]) < 0.5, f"Q9: a2 = {x['a2']} for {x['species']}")
if 10 in answers:
    n = q("SELECT count(*) FROM samples WHERE run <= 8")[0][0]
    check(len(answers[10]) == n, f"Q10: {len(answers[10])} rows, want {n} samples")
    first = {}
    for x in answers[10]:
        first.setdefault(x["run"], x)
        check(x["x"] >= 0 and 0 < x["e_over_e0"] <= 1 + 1e-12, f"Q10: {x}")
    check(all(close(x["e_over_e0"], 1.0) and x["x"] == 0 for x in first.values()),
          "Q10: each run's first row is not x = 0, E/E0 = 1")

for f in failures:
    print("FAIL", f)
print(f"sql_doc: {len(questions)} questions, {len(failures)} failed checks")
sys.exit(1 if failures else 0)
