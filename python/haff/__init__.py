"""haff from Python: read a haff database into numpy arrays (or pandas DataFrames), and run or
resume scenes with the installed `haff` program.

Pure Python over the standard sqlite3 module and numpy; pandas is optional (as_frame=True).
docs/python.md has the examples and the measurements.

    import haff
    db = haff.open("study.db")
    db.runs()                                   # run_summary: one dict per run, typed
    db.params(3)                                # {"dimers.alpha": 0.95, ...}
    c = db.collisions(3, kinds=["dimer-dimer"], columns=["t", "f"])   # numpy structured array
    sp = db.sample_species(3)                   # t, species, e_tr, e_rot of every species
    for chunk in db.collisions(chunk=1_000_000): ...                   # memory-light
    for fr in db.frames(3): fr.t, fr.bodies["x"], fr.disks()["x"]      # decoded frames
    run = haff.run("scene.ini", "out.db", set={"dimers.alpha": 0.9})   # calls `haff run`
"""
import itertools
import math
import os
import re
import shutil
import sqlite3
import subprocess

import numpy as np

__all__ = ["open", "Database", "Frame", "HaffError", "run", "resume", "COLLISION_KINDS",
           "FRAME_DTYPE", "STATE_LABELS"]

#: collisions.kind, in the order of the codes of Database.collisions' "kind" field
COLLISION_KINDS = ("dimer-dimer", "dimer-disk", "disk-disk", "dimer-wall", "disk-wall",
                   "rod-rod", "body-body", "body-wall")

#: one body of a frames row (db/schema.sql): 36 bytes, little-endian
FRAME_DTYPE = np.dtype([("x", "<f8"), ("y", "<f8"), ("phi", "<f8"),
                        ("vx", "<f4"), ("vy", "<f4"), ("omega", "<f4")])

# the columns of the tables as numpy types; a nullable integer column reads NULL as -1, a REAL
# column NULL as NaN; text columns are given as (sql, dtype) below
_COLLISION_COLUMNS = {
    "seq": "i8", "t": "f8", "kind": "i1", "i": "i8", "j": "i8", "disk_i": "i4", "disk_j": "i4",
    "theta_i": "f8", "theta_j": "f8", "f": "f8", "de": "f8", "vn": "f8", "eps": "f8",
    "e_tr": "f8", "tb_i": "f8", "tb_j": "f8"}
_SAMPLE_COLUMNS = {
    "t": "f8", "collisions": "i8", "cpd": "f8", "e_tr": "f8", "e_rot": "f8", "e_tr_dimer": "f8",
    "e_rot_dimer": "f8", "e_tr_disk": "f8", "flow_frac": "f8", "flow_chaos": "f8",
    "count_var": "f8", "s_rho": "f8", "s_perp": "f8", "s_par": "f8"}
_STATE_COLUMNS = {
    "label": "U10", "t": "f8", "cpd": "f8", "body": "i8", "kind": "U5", "species": "i4",
    "x": "f8", "y": "f8", "phi": "f8", "vx": "f8", "vy": "f8", "omega": "f8"}


class HaffError(Exception):
    """A haff command that failed (its exit status and its message), or a database, run, label
    or argument that is not what was asked for.  status: the haff command's exit status (None
    when no command ran); run: the id of the run the command made or resumed, when one was made
    (e.g. an interrupted run), else None."""

    def __init__(self, message, status=None, run=None):
        super().__init__(message)
        self.status, self.run = status, run


#: states.label values (db/schema.sql)
STATE_LABELS = ("initial", "final", "checkpoint", "velocities")


def open(path):  # noqa: A001 (the module's verb, as in gsd.hoomd.open)
    """Opens the haff database at path for reading (it is never written); see Database."""
    return Database(path)


class Database:
    """A haff database, read-only (PRAGMA query_only).  Every reader takes run=None for every
    run (the rows then carry a "run" field) or one run id; as_frame=True gives a pandas
    DataFrame instead of a numpy structured array."""

    def __init__(self, path):
        if not os.path.isfile(path):
            raise HaffError("%s: no such database file" % path)
        self.path = path
        self.con = sqlite3.connect(path)
        try:
            self.con.execute("PRAGMA query_only = 1")
            names = {r[0] for r in self.con.execute(
                "SELECT name FROM sqlite_master WHERE type IN ('table', 'view')")}
        except sqlite3.DatabaseError as e:
            self.con.close()
            raise HaffError("%s: not an SQLite database (%s)" % (path, e)) from None
        if "runs" not in names:
            self.con.close()
            raise HaffError("%s: not a haff database (no runs table)" % path)
        self._tables = names
        self._columns = {}

    def close(self):
        self.con.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ---- helpers --------------------------------------------------------------------------
    def _has(self, table, column):
        if table not in self._columns:
            self._columns[table] = {r[1] for r in self.con.execute(
                "PRAGMA table_info(%s)" % table)}
        return column in self._columns[table]

    def _spec(self, table, spec):
        """spec and, after it, the file's columns of table that spec lacks (a column added to
        the table later, e.g. one of db/hd_db.h's HD_COLLISION_COLUMNS): INTEGER as i8 (NULL
        -1), REAL as f8 (NULL NaN), other types as text."""
        out = dict(spec)
        for r in self.con.execute("PRAGMA table_info(%s)" % table):
            if r[1] not in out and r[1] != "run":
                t = (r[2] or "").upper()
                out[r[1]] = "i8" if t.startswith("INT") else "f8" if t.startswith("REAL") else "U64"
        return out

    def _select(self, table, columns, spec):
        """SQL expressions and dtype for columns of table (a missing column reads NULL)."""
        exprs, fields = [], []
        for c in columns:
            if c not in spec:
                raise HaffError("%s has no column %r (has: %s)" % (table, c, ", ".join(spec)))
            t = spec[c]
            e = c if self._has(table, c) else "NULL"
            if c == "kind" and table == "collisions":
                e = "CASE kind %s ELSE -1 END" % " ".join(
                    "WHEN '%s' THEN %d" % (k, n) for n, k in enumerate(COLLISION_KINDS))
            elif t[0] in "iu":
                e = "ifnull(%s, -1)" % e
            elif t[0] == "U":
                e = "ifnull(%s, '')" % e
            exprs.append(e)
            fields.append((c, t))
        return exprs, np.dtype(fields)

    def _run(self, run):
        """run as an int, the id of a run of the file; HaffError otherwise (None too)."""
        if isinstance(run, bool) or not isinstance(run, (int, np.integer)):
            raise HaffError("%s: a run id is an integer, not %r" % (self.path, run))
        run = int(run)
        if self.con.execute("SELECT 1 FROM runs WHERE id = ?", (run,)).fetchone() is None:
            ids = self.run_ids()
            raise HaffError("%s: there is no run %d (runs: %s)" % (
                self.path, run, ", ".join(map(str, ids)) if ids else "none"))
        return run

    def _runs_where(self, run):
        if run is None:
            return "", ()
        return " WHERE run = ?", (self._run(run),)

    def _array(self, sql, args, dtype, count=None):
        cur = self.con.execute(sql, args)
        return np.fromiter(cur, dtype=dtype, count=-1 if count is None else count)

    @staticmethod
    def _frame(a, as_frame, categorical=None):
        if not as_frame:
            return a
        import pandas as pd
        df = pd.DataFrame(a)
        for col, cats in (categorical or {}).items():
            if col in df:
                df[col] = pd.Categorical.from_codes(df[col].astype("int64").clip(-1), cats)
        return df

    def _count(self, table, run):
        where, args = self._runs_where(run)
        return self.con.execute("SELECT count(*) FROM %s%s" % (table, where), args).fetchone()[0]

    # ---- runs and parameters --------------------------------------------------------------
    def run_ids(self):
        """The ids of the runs, oldest first."""
        return [r[0] for r in self.con.execute("SELECT id FROM runs ORDER BY id")]

    def runs(self, as_frame=False):
        """The run_summary view (db/README.md): one dict per run with typed columns (run,
        species, n, ..., alpha, a_over_d, ..., status, events, cpd_reached, t_reached), plus
        "params", the run's scene keys (Database.params).  as_frame: a DataFrame (no params)."""
        if as_frame:
            import pandas as pd
            return pd.read_sql("SELECT * FROM run_summary ORDER BY run", self.con)
        cur = self.con.execute("SELECT * FROM run_summary ORDER BY run")
        names = [d[0] for d in cur.description]
        out = [dict(zip(names, row)) for row in cur]
        params = self.params()
        for r in out:
            r["params"] = params.get(r["run"], {})
        return out

    def params(self, run=None):
        """The scene keys of a run as {"section.key": value}, value a float when the key is a
        number (the params view's num), else its text; run=None: {run: {...}} for every run."""
        where, args = self._runs_where(run)
        out = {}
        for r, sec, key, value, num in self.con.execute(
                "SELECT run, section, key, value, num FROM params%s" % where, args):
            out.setdefault(r, {})["%s.%s" % (sec, key)] = value if num is None else num
        return out.get(self._run(run), {}) if run is not None else out

    def species(self, run):
        """The species table of a run: one dict per species (idx, name, count, mass, inertia,
        disks: [(x, y, d, m), ...] in the body frame about the centre of mass); [] for rods and
        files made before schema version 3."""
        run = self._run(run)
        if "species" not in self._tables:
            return []
        out = []
        for idx, name, disks, count, mass, inertia in self.con.execute(
                "SELECT idx, name, disks, count, mass, inertia FROM species WHERE run = ? "
                "ORDER BY idx", (run,)):
            d = [tuple(float(v) for v in p.split()) for p in disks.split(";") if p.strip()]
            out.append({"idx": idx, "name": name, "count": count, "mass": mass,
                        "inertia": inertia, "disks": d})
        return out

    # ---- rows -----------------------------------------------------------------------------
    def collisions(self, run=None, kinds=None, columns=None, chunk=None, as_frame=False):
        """The collisions of a run (or of every run, with a "run" field), in (run, seq) order,
        as a numpy structured array: seq, t, kind (a code: COLLISION_KINDS[kind]; a DataFrame
        has it as a Categorical), i, j, disk_i, disk_j (-1 for NULL), theta_i, theta_j, f, de,
        vn, eps, e_tr, tb_i, tb_j (NaN for NULL), then any column the file has besides (a later
        one: INTEGER as i8, -1 for NULL, REAL as f8).  kinds: only these kinds (names); columns:
        only these fields.  chunk=N: an iterator over arrays (or DataFrames) of at most N rows,
        for files larger than memory.  Reads ~3x faster than pandas.read_sql (docs/python.md)."""
        spec = self._spec("collisions", _COLLISION_COLUMNS)
        cols = list(columns or spec)
        if run is None and "run" not in cols:
            cols = ["run"] + cols
        spec["run"] = "i8"
        exprs, dtype = self._select("collisions", cols, spec)
        where, args = self._runs_where(run)
        if kinds:
            kinds = [kinds] if isinstance(kinds, str) else list(kinds)
            bad = [k for k in kinds if k not in COLLISION_KINDS]
            if bad:
                raise HaffError("unknown collision kind %s (kinds: %s)" %
                                (", ".join(bad), ", ".join(COLLISION_KINDS)))
            where += (" AND " if where else " WHERE ") + "kind IN (%s)" % ",".join("?" * len(kinds))
            args += tuple(kinds)
        sql = "SELECT %s FROM collisions%s ORDER BY %s" % (
            ", ".join(exprs), where, "seq" if run is not None else "run, seq")
        cats = {"kind": list(COLLISION_KINDS)}
        if chunk:
            return self._chunks(sql, args, dtype, int(chunk), as_frame, cats)
        return self._frame(self._array(sql, args, dtype), as_frame, cats)

    def _chunks(self, sql, args, dtype, n, as_frame, cats):
        cur = self.con.cursor()
        cur.execute(sql, args)
        while True:
            a = np.fromiter(itertools.islice(cur, n), dtype=dtype)
            if len(a) == 0:
                return
            yield self._frame(a, as_frame, cats)

    def samples(self, run=None, columns=None, as_frame=False):
        """The samples of a run (or every run, with "run") in time order: t, collisions, cpd,
        e_tr, e_rot, the per-species columns and the state measures (NaN for NULL)."""
        cols = list(columns or _SAMPLE_COLUMNS)
        if run is None and "run" not in cols:
            cols = ["run"] + cols
        exprs, dtype = self._select("samples", cols, dict(_SAMPLE_COLUMNS, run="i8"))
        where, args = self._runs_where(run)
        sql = "SELECT %s FROM samples%s ORDER BY %s" % (", ".join(exprs), where,
                                                         "t" if run is not None else "run, t")
        return self._frame(self._array(sql, args, dtype), as_frame)

    def states(self, run=None, label=None, as_frame=False):
        """The states rows of a run (or every run, with "run"), by (label, t, body): label, t,
        cpd, body, kind, species (species.idx; -1 for rods and rows written before schema
        version 4), x, y, phi, vx, vy, omega.  label: only 'initial', 'final', 'checkpoint' or
        'velocities' (STATE_LABELS), or a list of them; another label is a HaffError."""
        cols = list(_STATE_COLUMNS)
        if run is None:
            cols = ["run"] + cols
        exprs, dtype = self._select("states", cols, dict(_STATE_COLUMNS, run="i8"))
        where, args = self._runs_where(run)
        if label is not None:
            labels = [label] if isinstance(label, str) else list(label)
            bad = [x for x in labels if x not in STATE_LABELS]
            if bad or not labels:
                raise HaffError("unknown states label %s (labels: %s)" % (
                    ", ".join(map(repr, bad)) or "(none given)", ", ".join(STATE_LABELS)))
            where += (" AND " if where else " WHERE ") + "label IN (%s)" % ",".join(
                "?" * len(labels))
            args += tuple(labels)
        sql = "SELECT %s FROM states%s ORDER BY %s" % (
            ", ".join(exprs), where, ("" if run is not None else "run, ") + "label, t, body")
        return self._frame(self._array(sql, args, dtype), as_frame)

    def sample_species(self, run=None, as_frame=False):
        """The per-species samples of a run (or every run, with "run"), the table sample_species
        (docs/sql.md), by (t, species): t, species (species.idx, as in Database.species), e_tr,
        e_rot (per body of the species; NaN for NULL); every species of a mixture, named
        species too.  Empty for a file made before schema version 3."""
        cols = ["t", "species", "e_tr", "e_rot"]
        if run is None:
            cols = ["run"] + cols
        where, args = self._runs_where(run)
        spec = {"run": "i8", "t": "f8", "species": "i4", "e_tr": "f8", "e_rot": "f8"}
        if "sample_species" not in self._tables:
            return self._frame(np.zeros(0, np.dtype([(c, spec[c]) for c in cols])), as_frame)
        exprs, dtype = self._select("sample_species", cols, spec)
        sql = "SELECT %s FROM sample_species%s ORDER BY %s" % (
            ", ".join(exprs), where, ("" if run is not None else "run, ") + "t, species")
        return self._frame(self._array(sql, args, dtype), as_frame)

    # ---- frames ---------------------------------------------------------------------------
    def frame_count(self, run):
        """The number of frames of a run."""
        run = self._run(run)
        if "frames" not in self._tables:
            return 0
        return self.con.execute("SELECT count(*) FROM frames WHERE run = ?",
                                (run,)).fetchone()[0]

    def _bodies(self, run):
        """kind and species of every body of a run, from its initial states (the frames' rule);
        species from the species counts when the file has no states.species."""
        st = self.states(run, label="initial")
        if len(st) == 0:
            raise HaffError("%s: run %d has no initial states" % (self.path, run))
        t0 = st["t"].min()
        st = st[st["t"] == t0]
        st = st[np.argsort(st["body"], kind="stable")]
        species = st["species"].copy()
        if np.all(species < 0) and st["kind"][0] != "rod":
            first = 0
            for sp in self.species(run):
                species[(st["body"] >= first) & (st["body"] < first + sp["count"])] = sp["idx"]
                first += sp["count"]
        return st["kind"], species

    def frames(self, run, start=0, stop=None):
        """Iterates over the frames of a run in time order, one Frame at a time (one frames row
        in memory): Frame.index, t, cpd, bodies (FRAME_DTYPE: x, y, phi float64; vx, vy, omega
        float32 as stored), kind and species of each body, and Frame.disks().  start, stop: the
        frames start to stop - 1, as a Python slice (negative: counted from the end)."""
        run = self._run(run)  # checked now, not at the first next()
        return self._frames(run, start, stop)

    def _frames(self, run, start, stop):
        if "frames" not in self._tables:
            return
        start, stop, _ = slice(start, stop).indices(self.frame_count(run))
        if start >= stop:
            return
        kind, species = self._bodies(run)
        shapes = _shapes(self.species(run))
        cur = self.con.execute(
            "SELECT t, cpd, n, data FROM frames WHERE run = ? ORDER BY t, rowid LIMIT ? OFFSET ?",
            (run, stop - start, start))
        for k, (t, cpd, n, data) in enumerate(cur, start):
            if n != len(kind) or len(data) != n * FRAME_DTYPE.itemsize:
                raise HaffError("%s: run %d: frame %d holds %d bodies, the initial states %d" %
                                (self.path, run, k, n, len(kind)))
            yield Frame(k, t, cpd, np.frombuffer(data, dtype=FRAME_DTYPE), kind, species,
                        shapes)

    def frame(self, run, index):
        """Frame number index (0-based, time order; negative: from the end, -1 the last) of a
        run; HaffError when there is no such frame."""
        run = self._run(run)
        n = self.frame_count(run)
        k = int(index)
        if k < -n or k >= n:
            raise HaffError("%s: run %d has no frame %d (it has %d)" % (self.path, run, k, n))
        for f in self.frames(run, k % n, k % n + 1):
            return f
        raise HaffError("%s: run %d has no frame %d" % (self.path, run, k))


def _shapes(species):
    """The engine's shapes of the species rows (hd_shape_cluster, with its fast paths): the
    disks recentred on the centre of mass; a symmetric pair of equal disks is a dimer (half
    bond h: the engine's formulas differ in the order of a product); a lone disk a disk."""
    out = {}
    for sp in species:
        d = sp["disks"]
        mass = cx = cy = 0.0
        for x, y, _, m in d:
            mass += m
            cx += m * x
            cy += m * y
        cx /= mass
        cy /= mass
        o = [(x - cx, y - cy, dd, m) for x, y, dd, m in d]
        tag = "cluster"
        if len(o) == 1:
            tag = "disk"
        elif len(o) == 2 and o[0][2] == o[1][2] and o[0][3] == o[1][3] and o[0][1] == 0.0 and \
                o[1][1] == 0.0 and o[0][0] == -o[1][0] and o[0][0] <= 0:
            tag = "dimer"
            o = [(0.5 * (o[1][0] - o[0][0]) * s, 0.0, dd, m) for s, (_, _, dd, m) in
                 zip((-1.0, 1.0), o)]
        out[sp["idx"]] = (tag, o, sp["name"])
    return out


DISK_DTYPE = np.dtype([("body", "i8"), ("species", "i4"), ("x", "f8"), ("y", "f8"),
                       ("vx", "f8"), ("vy", "f8"), ("mass", "f8"), ("diameter", "f8")])


class Frame:
    """One decoded frames row: index (0-based, time order), t, cpd, bodies (a FRAME_DTYPE array
    of the n bodies in body order), kind (each body's states.kind) and species (species.idx;
    -1 for rods)."""

    def __init__(self, index, t, cpd, bodies, kind, species, shapes):
        self.index, self.t, self.cpd, self.bodies = index, t, cpd, bodies
        self.kind, self.species, self._shapes = kind, species, shapes

    def __repr__(self):
        return "Frame(index=%d, t=%r, cpd=%r, n=%d)" % (self.index, self.t, self.cpd,
                                                        len(self.bodies))

    def species_names(self):
        """The species name of every body ('rod' for rods)."""
        names = {k: v[2] for k, v in self._shapes.items()}
        return np.array([names.get(s, "rod") for s in self.species])

    def disks(self):
        """Every disk of every body in body order (a dimer gives its two), with the engine's
        formulas (hd_kin_disk_pos, hd_kin_disk_vel): body, species, x, y, vx, vy (rotation
        included), mass, diameter.  The same numbers as `haff export xyz --label frames`, to the
        last digit.  A rod is one disk of diameter 1 (its mass is NaN here: see the scene)."""
        out = []
        b = self.bodies
        for i in range(len(b)):
            x, y, phi = float(b["x"][i]), float(b["y"][i]), float(b["phi"][i])
            vx, vy, om = float(b["vx"][i]), float(b["vy"][i]), float(b["omega"][i])
            s = int(self.species[i])
            if s not in self._shapes:
                out.append((i, s, x, y, vx, vy, math.nan, 1.0))
                continue
            tag, o, _ = self._shapes[s]
            if tag == "disk":
                out.append((i, s, x, y, vx, vy, o[0][3], o[0][2]))
                continue
            sn, cs = math.sin(phi), math.cos(phi)
            for ox, oy, d, m in o:
                if tag == "dimer":
                    hw = ox * om
                    out.append((i, s, x + ox * cs, y + ox * sn, vx - hw * sn, vy + hw * cs, m, d))
                else:
                    out.append((i, s, x + (ox * cs - oy * sn), y + (ox * sn + oy * cs),
                                vx - om * (ox * sn + oy * cs), vy + om * (ox * cs - oy * sn),
                                m, d))
        return np.array(out, dtype=DISK_DTYPE)


# ---- running haff ---------------------------------------------------------------------------
def _haff(haff):
    exe = haff or os.environ.get("HAFF_BIN") or shutil.which("haff")
    if not exe:
        raise HaffError("the haff program is not found (install it, put it on PATH, or give "
                        "haff= or $HAFF_BIN)")
    return str(exe)


def _call(args):
    """Runs args; the CompletedProcess (any exit status); HaffError when it cannot start."""
    try:
        return subprocess.run(args, capture_output=True, text=True)
    except OSError as e:
        raise HaffError("%s: cannot run the haff program: %s (give haff= or $HAFF_BIN)" %
                        (args[0], e.strerror or e)) from None


def _failed(args, p, run=None):
    return HaffError("haff %s: exit %d: %s" % (args[1],
                                          p.returncode, (p.stderr or p.stdout).strip()),
                     status=p.returncode, run=run)


def _query(db, sql, args=()):
    """The rows of sql on database file db (read-only); [] when db is no haff database yet."""
    if not os.path.isfile(str(db)):
        return []
    try:
        con = sqlite3.connect(str(db), timeout=30)
    except sqlite3.Error:
        return []
    try:
        con.execute("PRAGMA query_only = 1")
        return con.execute(sql, args).fetchall()
    except sqlite3.Error:
        return []
    finally:
        con.close()


def _quote(word):
    """A word of a command line as haff stores it in runs.command (cli/cmd_run.c,
    command_line): as is when made of [A-Za-z0-9._/-+=:,@%], else single-quoted."""
    if word and all(c.isascii() and (c.isalnum() or c in "._/-+=:,@%") for c in word):
        return word
    return "'" + word.replace("'", "'\\''") + "'"


def _status(db, run):
    rows = _query(db, "SELECT status FROM runs WHERE id = ?", (run,))
    return rows[0][0] if rows else None


def run(scene, db, set=None, seed=None, haff=None):  # noqa: A002 (haff's own option name)
    """Runs the scene file `scene` into database `db` with the installed haff (`haff run SCENE
    -o DB --quiet [--set S.K=V]... [--seed N]`) and returns the new run's id, that of a run that
    collapsed too (a collapse is a result: runs.status 'collapsed', runs.message).  set: a dict
    {"section.key": value} or a list of "section.key=value".  HaffError on failure (the exit
    status and haff's message; .run the run's id when one was made, e.g. an interrupted run).

    The id is that of the one run, newer than those before the call, whose runs.command is this
    call's command line: right when other processes write to db too (haff refuses a second run
    of the same scene and seed, so no other process makes a run with that command line)."""
    args = [_haff(haff), "run", str(scene), "-o", str(db), "--quiet"]
    items = set.items() if isinstance(set, dict) else [s.split("=", 1) for s in (set or [])]
    for k, v in items:
        args += ["--set", "%s=%s" % (k, v)]
    if seed is not None:
        args += ["--seed", str(int(seed))]
    before = (_query(db, "SELECT max(id) FROM runs") or [(None,)])[0][0] or 0
    p = _call(args)
    tail = " " + " ".join(_quote(a) for a in args[1:])
    ids = [r[0] for r in _query(db, "SELECT id, command FROM runs WHERE id > ? ORDER BY id",
                                (before,))
           if r[1] is not None and (r[1] == tail[1:] or r[1].endswith(tail))]
    if len(ids) > 1:
        raise HaffError("%s: runs %s all have this command line: which one is this call's is "
                        "not known" % (db, ", ".join(map(str, ids))), status=p.returncode)
    new = ids[0] if ids else None
    if p.returncode == 1 and new is not None and _status(db, new) == "collapsed":
        return new
    if p.returncode != 0:
        raise _failed(args, p, new)
    if new is None:
        raise HaffError("%s: haff run ended well but its run is not found (a haff that does not "
                        "store runs.command?)" % db, status=0)
    return new


# hd_db_find_resumable's (db/hd_db.c) choice of a run to resume, oldest first
_RESUMABLE = ("SELECT id FROM runs WHERE status IN ('running', 'interrupted', 'failed') AND "
              "(EXISTS (SELECT 1 FROM checkpoints c WHERE c.run = runs.id) OR status = "
              "'running') ORDER BY id")


def resume(db, run=None, all=False, haff=None):  # noqa: A002
    """Resumes an interrupted, killed or failed run of `db` (`haff resume DB --run ID --quiet`):
    run=ID that run; else the newest resumable run (haff's rule, hd_db_find_resumable), chosen
    here and passed as --run.  Returns the id of the run resumed (also when it collapsed: a
    result, as for run()).  all=True: every resumable run in turn (`haff resume DB --all`),
    returns the list of the ids resumed, oldest first.  HaffError on failure (.run the run's id),
    e.g. a run that is done (exit 2), and when there is nothing to resume."""
    exe = _haff(haff)
    if all:
        if run is not None:
            raise HaffError("resume: run= and all=True: give one")
        # not --quiet: haff says "haff resume: run N done, in DB" for each run it resumed
        args = [exe, "resume", str(db), "--all", "--progress", "0"]
        p = _call(args)
        done = [int(m) for m in re.findall(r"^haff resume: run (\d+) done, in ", p.stderr, re.M)]
        if p.returncode != 0:
            raise _failed(args, p, done[-1] if done else None)
        if not done:
            raise HaffError("%s: no run to resume (%s)" % (db, p.stderr.strip() or "none"),
                            status=0)
        return done
    if run is None:
        ids = [r[0] for r in _query(db, _RESUMABLE)]
        if not ids:
            args = [exe, "resume", str(db), "--quiet"]  # haff's own message for this file
            p = _call(args)
            if p.returncode != 0:
                raise _failed(args, p)
            raise HaffError("%s: no run to resume" % db, status=p.returncode)
        run = ids[-1]
    if isinstance(run, bool) or not isinstance(run, (int, np.integer)):
        raise HaffError("resume: a run id is an integer, not %r" % (run,))
    run = int(run)
    args = [exe, "resume", str(db), "--quiet", "--run", str(run)]
    p = _call(args)
    if p.returncode == 1 and _status(db, run) == "collapsed":
        return run
    if p.returncode != 0:
        raise _failed(args, p, run if _status(db, run) is not None else None)
    return run
