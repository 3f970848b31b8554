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
-- 'checkpoint' is where an interrupted or collapsed run stopped; `haff resume` removes it.
CREATE TABLE IF NOT EXISTS states (
  run   INTEGER NOT NULL REFERENCES runs(id),
  label TEXT NOT NULL,
  t     REAL NOT NULL,
  cpd   REAL,
  body  INTEGER NOT NULL,
  kind  TEXT NOT NULL,        -- 'dimer', 'disk' or 'rod'
  x REAL, y REAL, phi REAL, vx REAL, vy REAL, omega REAL
);

-- Trajectory frames ([log] frames_every / frames_every_time): one row per frame, the bodies
-- packed in one BLOB in body order (0 .. n-1), 36 bytes each, little-endian: x, y, phi as
-- float64 (positions exact, as in states), then vx, vy, omega as float32 (7 digits: enough
-- to colour a movie by speed).  Rods: x, 0, 0, v, 0, bath temperature.  The kinds of the
-- bodies are those of the run's 'initial' states.  36 bytes per body against ~107 for a states
-- row with its index (measured in db/README.md).  `haff export xyz` and `haff movie` read them.
CREATE TABLE IF NOT EXISTS frames (
  run   INTEGER NOT NULL REFERENCES runs(id),
  t     REAL NOT NULL,
  cpd   REAL NOT NULL,
  n     INTEGER NOT NULL,     -- bodies in the frame
  data  BLOB NOT NULL         -- n * 36 bytes
);
CREATE INDEX IF NOT EXISTS frames_run_t ON frames(run, t);

-- Exact engine state for `haff resume` (opaque, bit-exact); only the newest per run is kept,
-- and none once the run is done or collapsed (it cannot be resumed).
CREATE TABLE IF NOT EXISTS checkpoints (
  run   INTEGER NOT NULL REFERENCES runs(id),
  seq   INTEGER NOT NULL,     -- collisions (pair and wall, logged or not) up to here
  t     REAL NOT NULL,
  blob  BLOB NOT NULL
);

-- Tabulated p_beta(eps) of the rod paper (`haff mc eps --tabulate`, mc/eps_table.c): inverse
-- CDFs Q_k(u_j) on a logarithmic beta grid for one length ratio; docs/mc-eps.md.
CREATE TABLE IF NOT EXISTS eps_tables (
  id         INTEGER PRIMARY KEY,
  gamma      REAL NOT NULL,     -- length ratio l1/l2 as requested
  gamma_eff  REAL NOT NULL,     -- canonical ratio N1/N2 <= 1 actually simulated
  nbeta      INTEGER NOT NULL,  -- beta nodes, beta_k = beta_min (beta_max/beta_min)^(k/(nbeta-1))
  nu         INTEGER NOT NULL,  -- quantiles per node, u_j = j/(nu-1)
  beta_min   REAL NOT NULL,
  beta_max   REAL NOT NULL,
  samples    INTEGER NOT NULL,  -- direct samples per node
  step       REAL NOT NULL,     -- grid step of the direct sampler (at beta >= 1)
  adapt      INTEGER NOT NULL,  -- its step reduction at small beta
  richardson INTEGER NOT NULL,  -- 1 if per-path Richardson extrapolation was used
  seed       INTEGER NOT NULL,
  seconds    REAL NOT NULL,     -- build time
  created    TEXT NOT NULL      -- ISO 8601 UTC
);
CREATE TABLE IF NOT EXISTS eps_table_points (
  tab   INTEGER NOT NULL REFERENCES eps_tables(id),
  k     INTEGER NOT NULL,       -- beta node
  beta  REAL NOT NULL,
  j     INTEGER NOT NULL,       -- quantile index
  u     REAL NOT NULL,          -- j/(nu-1)
  eps   REAL NOT NULL           -- Q_k(u_j)
);
