"""Tests of the Python module haff (python/haff), with Debian's /usr/bin/python3 (unittest).

usage: HAFF_BIN=bin/haff /usr/bin/python3 python/tests/test_haff.py [-v] [TestCase...]
tests/test_python.c runs each TestCase under `make test`.  The module under test is the source
tree's (python/, put first on sys.path), the haff program $HAFF_BIN.

TestStudy builds a study as a user would: four dimer runs (alpha 0.8, 0.95 x a 0.5, 1; 50
dimers at area fraction 0.1 to 10 cpd, every collision logged, frames every 2 cpd) made by
`haff sweep` (a study, merged into its study.db), and a mixture of dimers, disks and triangles
with frames, merged with `haff merge` into one; then checks the module against docs/sql.md's own SQL (<f>, D_e =
2/<f> and K = E_tr/E_rot, to 1e-12 relative: the sums are the same numbers added in another
order) and the decoded frames against `haff export xyz` (every disk's position and velocity,
exactly: the export prints the shortest form that reads back as the same double).
TestStudy also reads sample_species, frames by negative index, and checks that bad run ids,
labels and None are HaffErrors.  TestRunResume interrupts a run with SIGINT and resumes it with
haff.resume (the id of the run resumed, not the newest; resume(all=True) the ids resumed;
nothing to resume an error), and checks that haff.run gives the id of its own run when another
process adds one meanwhile, and of a run that collapsed.  TestErrors: a file that is not
SQLite, a haff program that is missing, a bad scene.
"""
import math
import os
import re
import signal
import sqlite3
import subprocess
import sys
import tempfile
import threading
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "python"))

import numpy as np  # noqa: E402

import haff  # noqa: E402

HAFF = os.environ.get("HAFF_BIN") or os.path.join(ROOT, "bin", "haff")

DIMERS = """[system]
area_fraction = 0.1
seed = 1
[dimers]
count = 50
alpha = 0.9
a = 1
[run]
stop_cpd = 10
[log]
collisions = all
samples_every = 0.5
frames_every = 2
"""

MIXTURE = """[system]
box = 30 30
seed = 5
[dimers]
count = 10
a = 0.6
[disks]
count = 10
sigma = 0.8
mass = 0.5
[species tri]
count = 10
shape = triangle
[walls]
sides = bottom top
[run]
stop_cpd = 4
[log]
collisions = all
samples_every = 0.5
frames_every = 1
"""

# rods that collapse at once (tests/test_sweep.c's): haff run's exit 1
COLLAPSE = """[system]
seed = 1998
[rods]
count = 1000
gamma = 0.8
nmod = 1000
model = constant
[run]
stop_time = 1e4
[log]
collisions = none
"""

# dimers for ~3 s on an idle machine (one stopped by SIGINT after 0.8 s, past its set-up, is
# interrupted with a checkpoint and can be resumed)
SLOW = """[system]
area_fraction = 0.2
seed = 4
[dimers]
count = 1000
[run]
stop_cpd = 2000
[log]
collisions = none
"""


def sql_of(question):
    """The ```sql block of question N of docs/sql.md."""
    with open(os.path.join(ROOT, "docs", "sql.md")) as f:
        text = f.read()
    m = re.search(r"^### %d\. .*?```sql\n(.*?)```" % question, text, re.M | re.S)
    return m.group(1)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def close(a, b, rel=1e-12):
    return abs(a - b) <= rel * max(abs(a), abs(b))


class TestStudy(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="haff-py-")
        d = cls.tmp.name
        cls.scene = os.path.join(d, "dimers.ini")
        write(cls.scene, DIMERS)
        write(os.path.join(d, "mix.ini"), MIXTURE)
        # a real study: `haff sweep` over (alpha, a/d), merged by the sweep into its study.db,
        # then merged once more with a mixture run (issue 28: a sweep's merged database)
        write(os.path.join(d, "study.ini"),
              "[sweep]\nscene = dimers.ini\nseeds = 1\n[axes]\n"
              "dimers.alpha = 0.8 0.95\ndimers.a = 0.5 1\n")
        subprocess.run([HAFF, "sweep", os.path.join(d, "study.ini"), "-o",
                        os.path.join(d, "study"), "--jobs", "2", "--progress", "0"],
                       check=True, capture_output=True)
        haff.run(os.path.join(d, "mix.ini"), os.path.join(d, "b.db"), haff=HAFF)
        cls.path = os.path.join(d, "all.db")
        subprocess.run([HAFF, "merge", cls.path, os.path.join(d, "study", "study.db"),
                        os.path.join(d, "b.db")], check=True, capture_output=True)
        cls.db = haff.open(cls.path)

    @classmethod
    def tearDownClass(cls):
        cls.db.close()
        cls.tmp.cleanup()

    def test_runs_typed(self):
        runs = self.db.runs()
        self.assertEqual([r["run"] for r in runs], [1, 2, 3, 4, 5])
        self.assertEqual([(r["alpha"], r["a_over_d"]) for r in runs[:4]],
                         [(0.8, 0.5), (0.8, 1.0), (0.95, 0.5), (0.95, 1.0)])
        p = runs[0]["params"]
        self.assertEqual(p["dimers.count"], 50.0)
        self.assertIsInstance(p["dimers.alpha"], float)
        self.assertEqual(p["log.collisions"], "all")
        self.assertEqual(self.db.params(5)["species tri.count"], 10.0)
        self.assertEqual([s["name"] for s in self.db.species(5)], ["dimer", "disk", "tri"])
        df = self.db.runs(as_frame=True)
        self.assertEqual(list(df.run), [1, 2, 3, 4, 5])

    def test_mean_f_and_d_e_as_docs_sql(self):
        """Question 3 of docs/sql.md (<f> per (alpha, a/d)) against the module's arrays."""
        con = sqlite3.connect(self.path)
        want = con.execute(sql_of(3)).fetchall()
        con.close()
        runs = {r["run"]: (r["alpha"], r["a_over_d"]) for r in self.db.runs()}
        per_run = {}
        for run in runs:
            c = self.db.collisions(run, kinds="dimer-dimer", columns=["f"])
            f = c["f"][~np.isnan(c["f"])]
            if len(f):
                per_run[run] = math.fsum(f) / len(f)
        groups = {}
        for run, f in per_run.items():
            groups.setdefault(runs[run], []).append(f)
        got = sorted(groups.items())
        self.assertEqual(len(got), len(want))
        for (key, fs), (alpha, aod, n, mean_f, _) in zip(got, want):
            self.assertEqual(key, (alpha, aod))
            self.assertEqual(len(fs), n)
            self.assertTrue(close(sum(fs) / len(fs), mean_f), (key, sum(fs) / len(fs), mean_f))
            self.assertTrue(close(2 / (sum(fs) / len(fs)), 2 / mean_f))  # D_e = 2/<f>
        self.assertTrue(0.5 < want[-1][3] < 0.8)  # the paper's <f> = 0.64 for a = d

    def test_k_as_docs_sql(self):
        """Question 5 of docs/sql.md (K = E_tr/E_rot at the end of each dimer run)."""
        con = sqlite3.connect(self.path)
        want = con.execute(sql_of(5)).fetchall()
        con.close()
        self.assertEqual([w[0] for w in want], [1, 2, 3, 4])
        s = self.db.samples()
        for run, _, _, cpd, k in want:
            last = s[s["run"] == run][-1]
            self.assertEqual(last["cpd"], cpd)
            self.assertEqual(last["e_tr"] / last["e_rot"], k)

    def test_collisions_whole_chunked_frame(self):
        c = self.db.collisions()
        con = sqlite3.connect(self.path)
        n, sum_de, nwall = con.execute(
            "SELECT count(*), sum(de), sum(kind = 'dimer-wall') FROM collisions").fetchone()
        con.close()
        self.assertEqual(len(c), n)
        self.assertTrue(close(math.fsum(c["de"]), sum_de, 1e-9))
        self.assertEqual(int(np.sum(c["kind"] == haff.COLLISION_KINDS.index("dimer-wall"))), nwall)
        parts = list(self.db.collisions(chunk=200))
        self.assertTrue(all(len(p) <= 200 for p in parts) and len(parts) > 2, len(parts))
        self.assertTrue(np.array_equal(np.concatenate(parts)[["run", "seq"]], c[["run", "seq"]]))
        df = self.db.collisions(2, as_frame=True)
        self.assertEqual(set(df.kind.astype(str)), {"dimer-dimer"})
        self.assertTrue(np.array_equal(df.t.to_numpy(), c[c["run"] == 2]["t"]))
        with self.assertRaises(haff.HaffError):
            self.db.collisions(1, kinds=["dimer-dimmer"])

    def test_frames_match_export_xyz(self):
        """Every disk of every frame decoded by the module equals `haff export xyz --label
        frames`, to the last digit; the species names too."""
        for run in (2, 5):
            xyz = subprocess.run([HAFF, "export", "xyz", self.path, "--run", str(run), "--label",
                                  "frames"], check=True, capture_output=True, text=True).stdout
            lines = xyz.splitlines()
            frames = list(self.db.frames(run))
            self.assertEqual(len(frames), self.db.frame_count(run))
            self.assertGreaterEqual(len(frames), 4)
            at = 0
            for fr in frames:
                n = int(lines[at])
                head = lines[at + 1]
                rows = [ln.split() for ln in lines[at + 2:at + 2 + n]]
                at += 2 + n
                self.assertEqual(float(re.search(r"Time=(\S+)", head).group(1)), fr.t)
                d = fr.disks()
                self.assertEqual(len(d), n)
                names = fr.species_names()[d["body"]]
                for k, r in enumerate(rows):
                    self.assertEqual(tuple(float(v) for v in (r[1], r[2], r[4], r[5])),
                                     (d["x"][k], d["y"][k], d["vx"][k], d["vy"][k]),
                                     "run %d frame %d disk %d" % (run, fr.index, k))
                    self.assertEqual(int(r[12]), d["body"][k])
                    self.assertEqual(r[-1], names[k])
                    self.assertEqual(float(r[7]), d["mass"][k])
            self.assertEqual(at, len(lines))

    def test_frame_negative_index(self):
        """db.frame(run, -1) is the last frame (Python's indexing), never frame 0 labelled -1;
        past either end a HaffError (review 14b, finding 4)."""
        n = self.db.frame_count(5)
        frames = list(self.db.frames(5))
        last = self.db.frame(5, -1)
        self.assertEqual((last.index, last.t), (n - 1, frames[-1].t))
        self.assertNotEqual(frames[0].t, last.t)
        self.assertEqual(self.db.frame(5, -n).t, frames[0].t)
        self.assertEqual([f.t for f in self.db.frames(5, -2)], [f.t for f in frames[-2:]])
        self.assertEqual([f.index for f in self.db.frames(5, 1, -1)], list(range(1, n - 1)))
        for k in (n, -n - 1):
            with self.assertRaises(haff.HaffError):
                self.db.frame(5, k)

    def test_sample_species(self):
        """db.sample_species(run): the table sample_species, every species of the mixture
        (review 14b, finding 6)."""
        con = sqlite3.connect(self.path)
        want = con.execute("SELECT t, species, e_tr, e_rot FROM sample_species WHERE run = 5 "
                           "ORDER BY t, species").fetchall()
        allrows = con.execute("SELECT count(*) FROM sample_species").fetchone()[0]
        con.close()
        ss = self.db.sample_species(5)
        self.assertGreater(len(want), 3)
        self.assertEqual(list(ss.dtype.names), ["t", "species", "e_tr", "e_rot"])
        self.assertEqual([tuple(r) for r in ss.tolist()], want)
        self.assertEqual(set(ss["species"]), {s["idx"] for s in self.db.species(5)})
        self.assertTrue(np.all(ss["e_tr"] > 0))
        every = self.db.sample_species()
        self.assertEqual(len(every), allrows)
        self.assertEqual(every.dtype.names[0], "run")
        df = self.db.sample_species(5, as_frame=True)
        self.assertEqual(list(df.columns), ["t", "species", "e_tr", "e_rot"])
        self.assertTrue(np.array_equal(df.e_tr.to_numpy(), ss["e_tr"]))

    def test_bad_arguments(self):
        """Every documented error is a HaffError: unknown run ids, None, unknown labels; a list
        of labels is read (review 14b, finding 8)."""
        for call in (lambda: self.db.collisions(99), lambda: self.db.params(99),
                     lambda: self.db.species(99), lambda: self.db.states(99),
                     lambda: self.db.samples(99), lambda: self.db.sample_species(99),
                     lambda: self.db.frame_count(99), lambda: self.db.frames(99),
                     lambda: self.db.frame(99, 0), lambda: self.db.frames(None),
                     lambda: self.db.species(None), lambda: self.db.frame(None, 0),
                     lambda: self.db.frame_count(None),
                     lambda: self.db.states(2, label="finall"),
                     lambda: self.db.states(2, label=["initial", "finall"])):
            with self.assertRaises(haff.HaffError):
                call()
        both = self.db.states(2, label=["initial", "final"])
        self.assertEqual(set(both["label"]), {"initial", "final"})
        self.assertEqual(len(both), len(self.db.states(2, label="initial")) +
                         len(self.db.states(2, label="final")))

    def test_states_species(self):
        st = self.db.states(5, label="initial")
        sp = {s["idx"]: s for s in self.db.species(5)}
        first = 0
        for idx in sorted(sp):
            sel = (st["body"] >= first) & (st["body"] < first + sp[idx]["count"])
            self.assertTrue(np.all(st["species"][sel] == idx))
            first += sp[idx]["count"]
        self.assertEqual(first, len(st))


class TestRunResume(unittest.TestCase):
    def test_interrupt_and_resume(self):
        with tempfile.TemporaryDirectory(prefix="haff-py-") as d:
            scene = os.path.join(d, "long.ini")
            write(scene, "[system]\narea_fraction = 0.2\nseed = 4\n[dimers]\ncount = 1000\n"
                  "[run]\nstop_cpd = 2000\n[log]\ncollisions = none\n")
            out = os.path.join(d, "r.db")
            p = subprocess.Popen([HAFF, "run", scene, "-o", out, "--quiet"])
            for _ in range(600):  # until it has committed events (a commit every second)
                time.sleep(0.1)
                try:
                    con = sqlite3.connect(out)
                    ev = con.execute("SELECT max(events) FROM runs").fetchone()[0]
                    con.close()
                except sqlite3.Error:
                    ev = None
                if ev or p.poll() is not None:
                    break
            p.send_signal(signal.SIGINT)
            self.assertEqual(p.wait(), 1)  # interrupted
            db = haff.open(out)
            self.assertEqual(db.runs()[0]["status"], "interrupted")
            db.close()
            # a newer run that is done: resume() resumes run 1 and says so (review 14b: it
            # returned max(id), 2)
            short = os.path.join(d, "short.ini")
            write(short, "[system]\narea_fraction = 0.2\nseed = 4\n[dimers]\ncount = 20\n"
                  "[run]\nstop_cpd = 2\n[log]\ncollisions = none\n")
            self.assertEqual(haff.run(short, out, haff=HAFF), 2)
            self.assertEqual(haff.resume(out, haff=HAFF), 1)
            db = haff.open(out)
            status, cpd = db.con.execute("SELECT status, cpd FROM runs").fetchone()
            self.assertEqual(status, "done")
            self.assertGreaterEqual(cpd, 2000)
            db.close()
            with self.assertRaises(haff.HaffError) as e:  # a done run cannot be resumed
                haff.resume(out, run=1, haff=HAFF)
            self.assertIn("exit 2", str(e.exception))
            for every in (False, True):  # nothing left to resume: an error, not a run id
                with self.assertRaises(haff.HaffError):
                    haff.resume(out, all=every, haff=HAFF)

    def test_resume_all(self):
        """resume(all=True) gives the ids it resumed."""
        with tempfile.TemporaryDirectory(prefix="haff-py-") as d:
            out = os.path.join(d, "a.db")
            slow = os.path.join(d, "slow.ini")
            write(slow, SLOW)
            for seed in (1, 2):
                subprocess.run(["timeout", "-s", "INT", "0.8", HAFF, "run", slow, "-o", out,
                                "--quiet", "--seed", str(seed)], capture_output=True)
            st = dict(sqlite3.connect(out).execute("SELECT id, status FROM runs").fetchall())
            self.assertEqual(st, {1: "interrupted", 2: "interrupted"})
            self.assertEqual(haff.resume(out, all=True, haff=HAFF), [1, 2])

    def test_collapse_is_a_result(self):
        """A run that collapses (haff run's exit 1) gives its id, as resume of one does."""
        with tempfile.TemporaryDirectory(prefix="haff-py-") as d:
            scene = os.path.join(d, "rc.ini")
            write(scene, COLLAPSE)
            out = os.path.join(d, "c.db")
            self.assertEqual(haff.run(scene, out, haff=HAFF), 1)
            self.assertEqual(haff.run(scene, out, seed=7, haff=HAFF), 2)
            db = haff.open(out)
            self.assertEqual([r["status"] for r in db.runs()], ["collapsed", "collapsed"])
            db.close()

    def test_run_id_with_another_writer(self):
        """haff.run's id is its own run's when another process adds a run to the same database
        while it runs (review 14b: it was max(id), the other's)."""
        with tempfile.TemporaryDirectory(prefix="haff-py-") as d:
            slow = os.path.join(d, "slow.ini")
            write(slow, SLOW)
            quick = os.path.join(d, "quick.ini")
            write(quick, "[system]\narea_fraction = 0.2\nseed = 5\n[dimers]\ncount = 20\n"
                  "[run]\nstop_cpd = 2\n[log]\ncollisions = none\n")
            out = os.path.join(d, "w.db")
            got = []
            th = threading.Thread(target=lambda: got.append(haff.run(slow, out, haff=HAFF)))
            th.start()
            for _ in range(600):  # until the slow run has its row
                time.sleep(0.05)
                rows = []
                try:
                    con = sqlite3.connect(out)
                    rows = con.execute("SELECT id FROM runs").fetchall()
                    con.close()
                except sqlite3.Error:
                    pass
                if rows or not th.is_alive():
                    break
            other = subprocess.run([HAFF, "run", quick, "-o", out, "--quiet"])
            th.join()
            self.assertEqual(other.returncode, 0)
            con = sqlite3.connect(out)
            ids = dict(con.execute("SELECT seed, id FROM runs").fetchall())
            finished = con.execute("SELECT id FROM runs ORDER BY finished").fetchall()
            con.close()
            self.assertEqual(finished[0][0], ids[5])  # the other run ended first
            self.assertEqual(got, [ids[4]])


class TestErrors(unittest.TestCase):
    def test_bad_input(self):
        with tempfile.TemporaryDirectory(prefix="haff-py-") as d:
            with self.assertRaises(haff.HaffError):
                haff.open(os.path.join(d, "none.db"))
            other = os.path.join(d, "other.db")
            con = sqlite3.connect(other)
            con.execute("CREATE TABLE t (x)")
            con.close()
            with self.assertRaises(haff.HaffError) as e:
                haff.open(other)
            self.assertIn("not a haff database", str(e.exception))
            junk = os.path.join(d, "junk.db")  # not SQLite
            write(junk, "this is not a database\n" * 100)
            with self.assertRaises(haff.HaffError) as e:
                haff.open(junk)
            self.assertIn("not an SQLite database", str(e.exception))
            with self.assertRaises(haff.HaffError):
                haff.run(os.path.join(d, "any.ini"), os.path.join(d, "y.db"),
                         haff=os.path.join(d, "no-haff"))
            scene = os.path.join(d, "bad.ini")
            write(scene, "[dimers]\ncount = 10\nalpha = 1.5\n")
            with self.assertRaises(haff.HaffError) as e:
                haff.run(scene, os.path.join(d, "x.db"), haff=HAFF)
            self.assertIn("alpha", str(e.exception))
            self.assertIn("exit 2", str(e.exception))


if __name__ == "__main__":
    unittest.main()
