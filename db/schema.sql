-- haff database schema (SQLite).  One file holds many runs.  This file is compiled into
-- bin/haff and applied with CREATE ... IF NOT EXISTS on every open; DESIGN.md fixes the
-- column names that users rely on, the rest are additions documented here.
PRAGMA journal_mode = WAL;

-- One row per run.  status: running, done, interrupted, collapsed, failed.
-- A process killed with -9 leaves 'running'; `haff resume` accepts it.
CREATE TABLE IF NOT EXISTS runs (
  id           INTEGER PRIMARY KEY,
  scene        TEXT NOT NULL,      -- canonical INI of the effective scene (file + --set)
  seed         INTEGER NOT NULL,
  status       TEXT NOT NULL CHECK (status IN ('running','done','interrupted','collapsed','failed')),
  started      TEXT NOT NULL,      -- ISO 8601 UTC
  finished     TEXT,               -- ISO 8601 UTC, NULL while running
  version      TEXT NOT NULL,      -- haff version that made the run
  events       INTEGER NOT NULL DEFAULT 0,   -- events processed (collisions + cell crossings)
  wall_seconds REAL NOT NULL DEFAULT 0,      -- wall-clock time spent, over all resumes
  message      TEXT,               -- why the run ended when not 'done' (collapse details, error)
  box_x        REAL,               -- box edges Lx, Ly (hd_db_run_box), for export and analysis
  box_y        REAL
);

-- One row per logged collision.  kind: dimer-dimer, dimer-disk, disk-disk, dimer-wall,
-- disk-wall, rod-rod.  Bodies are 0-based indices; j < 0 is a wall (-1 left, -2 right,
-- -3 bottom, -4 top).  theta_* follow DESIGN.md (NULL for disks and walls).
-- f: orientation factor mu_eff/m (eq. 36 for dimer-dimer, 1/2 for equal disks).
-- de: kinetic energy after minus before.  vn: normal relative velocity before (< 0).
-- Rod runs fill eps, e_tr, tb_i, tb_j and leave the 2D columns NULL.
CREATE TABLE IF NOT EXISTS collisions (
  run     INTEGER NOT NULL REFERENCES runs(id),
  seq     INTEGER NOT NULL,   -- 1, 2, ... within the run (all collisions count, logged or not)
  t       REAL NOT NULL,
  kind    TEXT NOT NULL,
  i       INTEGER NOT NULL,
  j       INTEGER NOT NULL,
  disk_i  INTEGER,
  disk_j  INTEGER,
  theta_i REAL,
  theta_j REAL,
  f       REAL,
  de      REAL,
  vn      REAL,
  eps     REAL,               -- rods: coefficient of restitution drawn
  e_tr    REAL,               -- rods: translational energy of the relative motion
  tb_i    REAL,               -- rods: bath temperatures after the collision
  tb_j    REAL
);

-- Energies per body every [log] samples_every cpd.  cpd = 2 * pair collisions / N.
-- e_tr, e_rot: mean translational and rotational kinetic energy per body (all species);
-- per-species columns for mixtures.  Rods: e_rot is the bath energy per rod.
CREATE TABLE IF NOT EXISTS samples (
  run        INTEGER NOT NULL REFERENCES runs(id),
  t          REAL NOT NULL,
  collisions INTEGER NOT NULL,
  cpd        REAL NOT NULL,
  e_tr       REAL NOT NULL,
  e_rot      REAL NOT NULL,
  e_tr_dimer REAL, e_rot_dimer REAL, e_tr_disk REAL  -- per species, NULL when absent
);

-- Body states: label 'initial', 'final', 'checkpoint', 'velocities' (at [log] velocities_at).
CREATE TABLE IF NOT EXISTS states (
  run   INTEGER NOT NULL REFERENCES runs(id),
  label TEXT NOT NULL,
  t     REAL NOT NULL,
  cpd   REAL,
  body  INTEGER NOT NULL,
  kind  TEXT NOT NULL,        -- 'dimer', 'disk' or 'rod'
  x REAL, y REAL, phi REAL, vx REAL, vy REAL, omega REAL
);

-- Exact engine state for `haff resume` (opaque, bit-exact); only the newest per run is kept.
CREATE TABLE IF NOT EXISTS checkpoints (
  run   INTEGER NOT NULL REFERENCES runs(id),
  seq   INTEGER NOT NULL,     -- collisions logged up to here
  t     REAL NOT NULL,
  blob  BLOB NOT NULL
);
