-- haff database schema (SQLite).  One file holds many runs.  This file is compiled into
-- bin/haff and applied with CREATE ... IF NOT EXISTS on every open; DESIGN.md fixes the
-- column names that users rely on, the rest are additions documented here.
--
-- Schema version (PRAGMA user_version), set by every writer that opens the file
-- (HD_DB_SCHEMA_VERSION, db/README.md):
--   0  files made before versions were kept;
--   2  adds runs.cpd, the provenance and frames tables, the state measures of samples and the
--      views params and run_summary.  A version-0 file opened for writing is brought to 2 in
--      one transaction (hd_db.c, schema_apply: ALTER TABLE ... ADD COLUMN for the columns of
--      added_columns[], old rows NULL; the rest IF NOT EXISTS); readers take a missing column
--      as NULL.
--   3  adds the species and sample_species tables (issue 18: species of any shape, named in
--      the scene), and the collision kinds body-body, body-wall and the states kind body.
--      New tables only: a file of version 0 or 2 is brought to 3 by creating them.
--   4  adds how each run was made (issue 28): runs.git_commit, git_dirty, compiler, cflags,
--      command and sweep_point (added to older files' runs with ALTER TABLE, old rows NULL),
--      and the view run_species; run_summary gives named species (issue 18) their label.
--      Also states.species (each body's species.idx; issue 28): ALTER TABLE ... ADD COLUMN,
--      old rows NULL (their species still follows from the body number and species.count).
--   5  stores per-species energies in one form, sample_species (issue 29): the species-independent
--      columns of a sample are the table sample_rows, and samples is a view of it with the
--      columns e_tr_dimer, e_rot_dimer, e_tr_disk made from sample_species (the same columns, in
--      the same order, as version 4's table samples: queries of samples read as before).  A file
--      of version 0 to 4 opened for writing is brought to 5 in one transaction (hd_db.c,
--      hd_db_samples_convert): its table samples is copied to sample_rows, each value of its columns
--      e_tr_dimer, e_rot_dimer, e_tr_disk that sample_species lacks becomes a sample_species row
--      (species 0 the dimers, 1 the disks with e_rot 0: files before version 3 had no
--      sample_species), the table is dropped and the view made.  Readers read files of every
--      version: samples is a table up to version 4 and a view from 5, with the same columns.
-- The views params, run_summary and run_species are made again by a writer whenever the file's
-- differ from the ones below (hd_db.c, views_stale), without a new version: a fix of a view
-- (run_summary's area_fraction of one species in a box given, review 14) reaches old files.
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
  box_y        REAL,
  cpd          REAL,               -- collisions per particle reached (updated with events at
                                   -- every commit while the run goes; schema version 2)
  -- The run's homogeneous cooling state window (schema version 2; NULL while it goes, with
  -- fewer than 3 samples, and in files from before): stored when the run ends (done, collapsed,
  -- interrupted; again at the end of a resume) from all its samples, with the default
  -- detection (hd_hcs_window_find; docs/analysis.md, "The stored HCS window").
  hcs_cpd_start   REAL,            -- first sample's cpd in the window (after the transient)
  hcs_cpd_end     REAL,            -- last sample's cpd in the window
  hcs_end         TEXT,            -- what ended the HCS: 'none' (the run's end), 's_perp' (the
                                   -- state measures; the window may end earlier where the
                                   -- rate detector did), 'rate' (rate/sqrt(E) alone)
  hcs_s_perp      REAL,            -- mean s_perp over the state measures' window (NULL without)
  hcs_flow_excess REAL,            -- mean flow_frac - flow_chaos there
  -- How the run was made (schema version 4; NULL in runs made before).  The build's are
  -- compiled in (the Makefile, engine/core/hd_build.h) and printed by `haff -V`.  A run's
  -- identity is (scene, seed, git_commit): `haff merge` refuses a run whose identity OUT has
  -- (a NULL commit counts as 'unknown'), `haff run` one whose scene and seed DB has (--force).
  git_commit   TEXT,               -- the commit haff was built from (git rev-parse HEAD), or
                                   -- 'unknown' (built outside git, e.g. from a tarball)
  git_dirty    INTEGER,            -- 1: the build's tree differed from the commit, 0: it did
                                   -- not, NULL: unknown
  compiler     TEXT,               -- e.g. 'cc (Debian 12.2.0-14) 12.2.0'
  cflags       TEXT,               -- the flags of the build (-O2 ...)
  command      TEXT,               -- the command line that began the run, shell-quoted
  sweep_point  TEXT                -- 'DIR point K: SETS' for a point of `haff sweep` (DIR the
                                   -- study's folder, SETS its --set overrides), else NULL
);

-- Where each run was made, and where it was merged from (schema version 2).  One row per run,
-- written when the run begins (source NULL) and carried over, with source and source_run set,
-- by `haff merge`; a run merged twice keeps its first source.  A run made by an older haff has
-- no row here.
CREATE TABLE IF NOT EXISTS provenance (
  run        INTEGER PRIMARY KEY REFERENCES runs(id),
  host       TEXT,      -- host name of the machine that began the run
  slurm_job  TEXT,      -- $SLURM_ARRAY_JOB_ID (else $SLURM_JOB_ID) when run under Slurm
  slurm_task TEXT,      -- $SLURM_ARRAY_TASK_ID when run as a task of a job array
  source     TEXT,      -- the database file it was merged from (absolute path), NULL if made here
  source_run INTEGER,   -- its id there
  merged     TEXT       -- ISO 8601 UTC of the merge
);

-- One row per logged collision.  kind: dimer-dimer, dimer-disk, disk-disk, dimer-wall,
-- disk-wall, rod-rod; body-body and body-wall (schema version 3) when a body of a named
-- species takes part (i is the body of the lower species index; a body's species follows
-- from its number: dimers, disks, then each species of the species table in idx order).
-- Bodies are 0-based indices; j < 0 is a wall (-1 left, -2 right,
-- -3 bottom, -4 top).  theta_* follow DESIGN.md (NULL for disks and walls; for a cluster, the
-- angle from its centre of mass -> contacting disk axis to the normal, NULL for a disk at the
-- centre of mass).  disk_i, disk_j: the touching disks (0 .. disks - 1).
-- f: orientation factor mu_eff/m (eq. 36 for dimer-dimer, 1/2 for equal disks).
-- de: kinetic energy after minus before.  vn: normal relative velocity before (< 0).
-- Rod runs fill eps, e_tr, tb_i, tb_j and leave the 2D columns NULL.
CREATE TABLE IF NOT EXISTS collisions (
  run     INTEGER NOT NULL REFERENCES runs(id),
  seq     INTEGER NOT NULL,   -- 1, 2, ... within the run (all collisions count, logged or not)
  t       REAL NOT NULL,      -- time
  kind    TEXT NOT NULL,      -- collision kind (the list above)
  i       INTEGER NOT NULL,   -- body (0-based)
  j       INTEGER NOT NULL,   -- body, or -1 - wall for a wall
  disk_i  INTEGER,            -- the touching disk of i (0 for a disk)
  disk_j  INTEGER,            -- the touching disk of j (-1 for a wall)
  theta_i REAL,               -- contact angle of i (NULL when not defined)
  theta_j REAL,               -- contact angle of j
  f       REAL,               -- orientation factor mu_eff/m
  de      REAL,               -- kinetic energy after minus before
  vn      REAL,               -- normal relative velocity before (< 0)
  eps     REAL,               -- rods: coefficient of restitution drawn
  e_tr    REAL,               -- rods: translational energy of the relative motion
  tb_i    REAL,               -- rods: bath temperature of i after the collision
  tb_j    REAL                -- rods: bath temperature of j after the collision
);

-- Energies per body every [log] samples_every cpd.  cpd = 2 * pair collisions / N.
-- e_tr, e_rot: mean translational and rotational kinetic energy per body (all species; each
-- species' own: sample_species).  Rods: e_rot is the bath energy per rod.  Read it as the view
-- samples (below), which every version of the file has; haff writes this table (schema
-- version 5; the table samples of older files, with the per-species columns, before).
CREATE TABLE IF NOT EXISTS sample_rows (
  run        INTEGER NOT NULL REFERENCES runs(id),
  t          REAL NOT NULL,
  collisions INTEGER NOT NULL,
  cpd        REAL NOT NULL,
  e_tr       REAL NOT NULL,
  e_rot      REAL NOT NULL,
  -- State measures (schema version 2; NULL for rods and in runs logged before them), each with
  -- its value for an uncorrelated gas: docs/analysis.md, "State measures".
  flow_frac  REAL,  -- energy of the momentum field on a 4 x 4 grid / translational energy
  flow_chaos REAL,  -- flow_frac's value for independent velocities (about 16/N)
  count_var  REAL,  -- variance / mean of the counts in the 4 x 4 cells (Poisson: 1)
  s_rho      REAL,  -- density structure factor at the 4 smallest wave vectors (~S(0))
  s_perp     REAL,  -- transverse (shear) momentum structure factor there (uncorrelated: 1)
  s_par      REAL   -- longitudinal momentum structure factor there (uncorrelated: 1)
);

-- The species of a 2D run (schema version 3), one row per species that has bodies: idx is the
-- engine's species index ([dimers] 0, [disks] 1, each [species NAME] section 2, 3, ... in
-- scene order), name 'dimer', 'disk' or NAME; disks: the body's disks as "x y d m" separated
-- by "; " (centre in the body frame relative to the centre of mass, diameter, mass; numbers
-- that read back exactly); mass and inertia: the body's total mass and moment of inertia about
-- its centre of mass (the disks as point masses: I = sum m |x|^2).
CREATE TABLE IF NOT EXISTS species (
  run     INTEGER NOT NULL REFERENCES runs(id),
  idx     INTEGER NOT NULL,
  name    TEXT NOT NULL,
  disks   TEXT NOT NULL,
  count   INTEGER NOT NULL,
  mass    REAL NOT NULL,
  inertia REAL NOT NULL
);
CREATE INDEX IF NOT EXISTS species_run ON species(run, idx);

-- Energies per body of each species with every sample (schema version 3): one row per
-- species that has bodies, at the samples row's t.  The one place per-species values are stored
-- (schema version 5; up to 4 the table samples also had them as columns for dimer-disk mixtures).
CREATE TABLE IF NOT EXISTS sample_species (
  run     INTEGER NOT NULL REFERENCES runs(id),
  t       REAL NOT NULL,
  species INTEGER NOT NULL,  -- species.idx
  e_tr    REAL NOT NULL,     -- translational kinetic energy per body of the species
  e_rot   REAL NOT NULL      -- rotational kinetic energy per body of the species
);
CREATE INDEX IF NOT EXISTS sample_species_run ON sample_species(run, t);

-- samples: one row per sample, the columns of sample_rows and, after e_rot, the per-species
-- columns of a mixture of [dimers] and [disks] as version 4's table had them, from
-- sample_species: e_tr_dimer, e_rot_dimer (species 0) and e_tr_disk (species 1) when the run
-- has both at that t, else NULL (one species, named species only, rods).  The columns users and
-- DESIGN.md rely on (run, t, collisions, cpd, e_tr, e_rot) are sample_rows' own; a query that
-- does not ask for the per-species columns reads sample_rows alone (SQLite flattens the view).
CREATE VIEW IF NOT EXISTS samples AS
SELECT run, t, collisions, cpd, e_tr, e_rot,
       CASE WHEN EXISTS (SELECT 1 FROM sample_species AS k WHERE k.run = sample_rows.run
                           AND k.t = sample_rows.t AND k.species = 1)
            THEN (SELECT d.e_tr FROM sample_species AS d WHERE d.run = sample_rows.run
                    AND d.t = sample_rows.t AND d.species = 0) END AS e_tr_dimer,
       CASE WHEN EXISTS (SELECT 1 FROM sample_species AS k WHERE k.run = sample_rows.run
                           AND k.t = sample_rows.t AND k.species = 1)
            THEN (SELECT d.e_rot FROM sample_species AS d WHERE d.run = sample_rows.run
                    AND d.t = sample_rows.t AND d.species = 0) END AS e_rot_dimer,
       CASE WHEN EXISTS (SELECT 1 FROM sample_species AS d WHERE d.run = sample_rows.run
                           AND d.t = sample_rows.t AND d.species = 0)
            THEN (SELECT k.e_tr FROM sample_species AS k WHERE k.run = sample_rows.run
                    AND k.t = sample_rows.t AND k.species = 1) END AS e_tr_disk,
       flow_frac, flow_chaos, count_var, s_rho, s_perp, s_par
FROM sample_rows;

-- Body states: label 'initial', 'final', 'checkpoint', 'velocities' (at [log] velocities_at).
-- 'checkpoint' is where an interrupted or collapsed run stopped; `haff resume` removes it.
CREATE TABLE IF NOT EXISTS states (
  run   INTEGER NOT NULL REFERENCES runs(id),
  label TEXT NOT NULL,
  t     REAL NOT NULL,
  cpd   REAL,
  body  INTEGER NOT NULL,
  kind  TEXT NOT NULL,        -- 'dimer', 'disk', 'rod' or 'body' (a named species: version 3)
  x REAL, y REAL, phi REAL, vx REAL, vy REAL, omega REAL,
  species INTEGER             -- the body's species: species.idx of the run (0 dimer, 1 disk,
                              -- 2.. each [species NAME]; its name: JOIN species ON species.run
                              -- = states.run AND species.idx = states.species); NULL for rods
                              -- and in rows written before schema version 4
);

-- Trajectory frames ([log] frames_every / frames_every_time): one row per frame, the bodies
-- packed in one BLOB in body order (0 .. n-1), 36 bytes each, little-endian: x, y, phi as
-- float64 (positions exact, as in states), then vx, vy, omega as float32 (7 digits: enough
-- to colour a movie by speed).  Rods: x, 0, 0, v, 0, bath temperature.  The kinds and species
-- of the bodies are those of the run's 'initial' states (states.kind, states.species).  36 bytes per body against ~107 for a states
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

-- Tabulated p_beta(eps) of the rod paper (`haff mc eps --tabulate`, db/hd_epsdb.c): inverse
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

-- ---- parameters as data (schema version 2; docs/sql.md) ----------------------------------------
-- params: one row per key of each run's canonical scene text (runs.scene, made by
-- engine/scene/hd_scene.c: "[section]" lines, then "key = value" lines; ";" lines are comments).
-- value is the text after "=", num its number when it is one (always REAL, so that a / b
-- never divides integers; NULL for text
-- such as "every 10", "left right" or a list).  A view: it always agrees with runs.scene, in
-- merged files too, and needs no filling.  E.g. SELECT run FROM params WHERE section = 'dimers'
-- AND key = 'alpha' AND num = 0.9.
CREATE VIEW IF NOT EXISTS params AS
WITH RECURSIVE split(run, section, line, rest) AS (
  SELECT id, '', NULL, replace(scene, char(13), '') || char(10) FROM runs
  UNION ALL
  SELECT run,
         CASE WHEN substr(rest, 1, 1) = '['
              THEN substr(rest, 2, instr(substr(rest, 1, instr(rest, char(10)) - 1), ']') - 2)
              ELSE section END,
         substr(rest, 1, instr(rest, char(10)) - 1),
         substr(rest, instr(rest, char(10)) + 1)
  FROM split WHERE rest <> ''),
kv(run, section, key, value) AS (
  SELECT run, section, trim(substr(line, 1, instr(line, '=') - 1)),
         trim(substr(line, instr(line, '=') + 1))
  FROM split
  WHERE line NOT LIKE '[%' AND line NOT LIKE ';%' AND instr(line, '=') > 0)
SELECT run, section, key, value,
       CASE WHEN value GLOB '*[0-9]*' AND value NOT GLOB '*[^0-9eE.+-]*'
            THEN CAST(value AS REAL) END AS num
FROM kv;

-- run_summary: one row per run with its parameters as typed columns.
--   species        'dimers', 'disks', 'mixture' (dimers and disks) or 'rods'; for a run with
--                  bodies of a [species NAME] section (schema version 3): 'shapes:' and the
--                  species that have bodies, in species order (dimers, disks, then each NAME),
--                  joined by '+', e.g. 'shapes:dimers+tri+asym': the label of the analyses
--                  (`haff haff-fit`), which add '+walls' where this view has the column walls
--   n              bodies (n_dimers + n_disks + those of every [species NAME], or n_rods)
--   area_fraction  as given, or the bodies' area over the box's (the dimer's area is two disks
--                  of diameter d at distance a, less their overlap); NULL for rods, and for a
--                  run with named species whose box was given (their areas: run_species)
--   alpha          restitution of the dimers (of the disks when there are no dimers); NULL for
--                  rods, whose restitution is eps (model = constant) or drawn (stochastic); with
--                  named species, the restitution of every pair of species that have bodies
--                  (their own alpha and the alpha_OTHER between them) when it is one value, else
--                  NULL (the analyses then fit no single alpha); each species': run_species
--   a_over_d       dimers' a/d (NULL without dimers)
--   cpd_reached    cpd of the newest sample; t_reached its time
-- and the runs columns seed, status, version, started, finished, events, wall_seconds and
-- (schema version 4) git_commit, git_dirty.
-- Needs SQLite's math functions (sqrt, acos: the sqlite3 shell and Debian's library have them).
CREATE VIEW IF NOT EXISTS run_summary AS
WITH pp AS (SELECT run, section, key, value, num FROM params),
p AS (
  SELECT run,
         max(CASE WHEN section = 'system' AND key = 'area_fraction' THEN num END) AS area_fraction,
         max(CASE WHEN section = 'system' AND key = 'box' THEN value END) AS box,
         CAST(max(CASE WHEN section = 'dimers' AND key = 'count' THEN num END) AS INTEGER)
           AS n_dimers,
         max(CASE WHEN section = 'dimers' AND key = 'd' THEN num END) AS d,
         max(CASE WHEN section = 'dimers' AND key = 'a' THEN num END) AS a,
         max(CASE WHEN section = 'dimers' AND key = 'alpha' THEN num END) AS alpha_dimer,
         CAST(max(CASE WHEN section = 'disks' AND key = 'count' THEN num END) AS INTEGER)
           AS n_disks,
         max(CASE WHEN section = 'disks' AND key = 'sigma' THEN num END) AS sigma,
         max(CASE WHEN section = 'disks' AND key = 'alpha' THEN num END) AS alpha_disk,
         CAST(sum(CASE WHEN section LIKE 'species %' AND key = 'count' AND num > 0 THEN num END)
           AS INTEGER) AS n_named,
         max(CASE WHEN section = 'walls' AND key = 'sides' THEN value END) AS walls,
         max(CASE WHEN section = 'walls' AND key = 'alpha' THEN num END) AS alpha_wall,
         CAST(max(CASE WHEN section = 'rods' AND key = 'count' THEN num END) AS INTEGER)
           AS n_rods,
         max(CASE WHEN section = 'rods' AND key = 'model' THEN value END) AS rod_model,
         max(CASE WHEN section = 'rods' AND key = 'eps' THEN num END) AS eps,
         max(CASE WHEN section = 'rods' AND key = 'gamma' THEN num END) AS gamma
  FROM pp GROUP BY run),
-- the species sections that have bodies, with the name alpha_NAME gives them, in the runs
-- with bodies of a named species (the others need none of what follows)
present AS (
  SELECT run, section,
         CASE WHEN section LIKE 'species %' THEN substr(section, 9) ELSE section END AS name
  FROM pp WHERE key = 'count' AND num > 0
    AND (section IN ('dimers', 'disks') OR section LIKE 'species %')
    AND run IN (SELECT run FROM p WHERE n_named > 0)),
-- the restitution of every pair of them that a key sets: each one's own alpha, alpha_OTHER of a
-- named species with OTHER present, [disks] alpha_dimer with dimers present (a pair that no key
-- sets takes the smaller own alpha, which is among these: it moves neither end of the range)
pair AS (
  SELECT x.run, x.num AS al FROM pp AS x JOIN present AS s ON s.run = x.run AND s.section = x.section
  WHERE x.key = 'alpha'
  UNION ALL
  SELECT x.run, x.num FROM pp AS x
    JOIN present AS s ON s.run = x.run AND s.section = x.section AND s.section LIKE 'species %'
    JOIN present AS o ON o.run = x.run AND x.key = 'alpha_' || o.name AND o.section <> s.section
  UNION ALL
  SELECT x.run, x.num FROM pp AS x
    JOIN present AS o ON o.run = x.run AND o.section = 'dimers'
  WHERE x.section = 'disks' AND x.key = 'alpha_dimer'
    AND EXISTS (SELECT 1 FROM present AS s WHERE s.run = x.run AND s.section = 'disks')),
pr AS (SELECT run, min(al) AS alpha_lo, max(al) AS alpha_hi FROM pair GROUP BY run),
-- the label: the present species' names in species order, which is their order in runs.scene
-- (dimers, disks, then each [species NAME] as written), joined by '+'
lab AS (
  SELECT DISTINCT s.run, 'shapes:' || group_concat(s.name, '+') OVER (
           PARTITION BY s.run ORDER BY instr(r.scene, '[' || s.section || ']')
           ROWS BETWEEN UNBOUNDED PRECEDING AND UNBOUNDED FOLLOWING) AS label
  FROM present AS s JOIN runs AS r ON r.id = s.run),
q AS (
  SELECT r.*, p.*, pr.alpha_lo, pr.alpha_hi, lab.label,
         coalesce(p.n_dimers, 0) AS nd, coalesce(p.n_disks, 0) AS ns,
         coalesce(p.n_named, 0) AS nn,
         coalesce(r.box_x, CAST(substr(p.box, 1, instr(p.box, ' ') - 1) AS REAL)) AS lx,
         coalesce(r.box_y, CAST(substr(p.box, instr(p.box, ' ') + 1) AS REAL)) AS ly
  FROM runs AS r LEFT JOIN p ON p.run = r.id LEFT JOIN pr ON pr.run = r.id
    LEFT JOIN lab ON lab.run = r.id)
SELECT id AS run,
       CASE WHEN n_rods > 0 THEN 'rods'
            WHEN nn > 0 THEN label
            WHEN nd > 0 AND ns > 0 THEN 'mixture'
            WHEN nd > 0 THEN 'dimers' WHEN ns > 0 THEN 'disks' END AS species,
       CASE WHEN n_rods > 0 THEN n_rods ELSE nd + ns + nn END AS n,
       n_dimers, n_disks, n_rods,
       CASE WHEN n_rods > 0 THEN NULL
            WHEN area_fraction IS NOT NULL THEN area_fraction
            WHEN nn > 0 THEN NULL
            -- each kind's area only when it has bodies: an absent section's d, a or sigma
            -- is NULL, and 0 * NULL would make the sum NULL
            ELSE ((CASE WHEN nd = 0 THEN 0
                        WHEN a >= d THEN nd * pi() * d * d / 2.0
                        ELSE nd * (pi() * d * d / 2.0
                                   - (d * d / 2.0 * acos(a / d) - a / 2.0 * sqrt(d * d - a * a)))
                   END)
                  + (CASE WHEN ns = 0 THEN 0 ELSE ns * pi() * sigma * sigma / 4.0 END))
                 / (lx * ly) END AS area_fraction,
       lx AS box_x, ly AS box_y,
       CASE WHEN n_rods > 0 THEN NULL
            WHEN nn > 0 THEN CASE WHEN alpha_hi - alpha_lo <= 1e-12 THEN alpha_hi END
            WHEN nd > 0 THEN alpha_dimer WHEN ns > 0 THEN alpha_disk END AS alpha,
       CASE WHEN ns > 0 THEN alpha_disk END AS alpha_disk,
       alpha_wall, walls,
       CASE WHEN nd > 0 THEN a / d END AS a_over_d,
       CASE WHEN nd > 0 THEN d END AS d, CASE WHEN nd > 0 THEN a END AS a,
       CASE WHEN ns > 0 THEN sigma END AS sigma,
       rod_model, eps, gamma,
       seed, status, version, started, finished, events, wall_seconds, git_commit, git_dirty,
       (SELECT s.cpd FROM samples AS s WHERE s.run = q.id ORDER BY s.t DESC LIMIT 1) AS cpd_reached,
       (SELECT max(s.t) FROM samples AS s WHERE s.run = q.id) AS t_reached
FROM q;

-- run_species (schema version 4): one row per species of a run that has bodies, from the
-- species table and the scene: run; idx (species.idx: 0 [dimers], 1 [disks], 2, 3, ... each
-- [species NAME] in scene order; 0 for rods); species, the name the analyses' labels use
-- ('dimers', 'disks', NAME, 'rods'); n its bodies; alpha the restitution of its own pairs
-- (NULL for rods); shape the scene's short form ('triangle 1', 'linear 3 1'; 'dimer A' for
-- [dimers] of a = A, 'disk' for [disks]; NULL for a species given by its disks); disks, mass,
-- inertia as in species (NULL for rods).  A run from before schema version 3 (no species rows)
-- gets its rows from the scene: its dimers, disks or rods.
CREATE VIEW IF NOT EXISTS run_species AS
WITH pp AS (SELECT run, section, key, value, num FROM params
            WHERE key IN ('alpha', 'shape', 'a', 'count')),
sec AS (
  SELECT s.run, s.idx, s.name, s.disks, s.count, s.mass, s.inertia,
         CASE s.name WHEN 'dimer' THEN 'dimers' WHEN 'disk' THEN 'disks'
                     ELSE 'species ' || s.name END AS section
  FROM species AS s WHERE s.count > 0)
SELECT sec.run, sec.idx,
       CASE WHEN sec.section LIKE 'species %' THEN sec.name ELSE sec.section END AS species,
       sec.count AS n,
       (SELECT x.num FROM pp AS x WHERE x.run = sec.run AND x.section = sec.section
          AND x.key = 'alpha') AS alpha,
       CASE sec.section
         WHEN 'dimers' THEN 'dimer ' || (SELECT x.value FROM pp AS x WHERE x.run = sec.run
                                           AND x.section = 'dimers' AND x.key = 'a')
         WHEN 'disks' THEN 'disk'
         ELSE (SELECT x.value FROM pp AS x WHERE x.run = sec.run AND x.section = sec.section
                 AND x.key = 'shape') END AS shape,
       sec.disks, sec.mass, sec.inertia
FROM sec
UNION ALL
SELECT x.run, CASE x.section WHEN 'disks' THEN 1 ELSE 0 END, x.section,
       CAST(x.num AS INTEGER),
       (SELECT y.num FROM pp AS y WHERE y.run = x.run AND y.section = x.section
          AND y.key = 'alpha' AND x.section <> 'rods'),
       CASE x.section
         WHEN 'dimers' THEN 'dimer ' || (SELECT y.value FROM pp AS y WHERE y.run = x.run
                                           AND y.section = 'dimers' AND y.key = 'a')
         WHEN 'disks' THEN 'disk' END,
       NULL, NULL, NULL
FROM pp AS x
WHERE x.key = 'count' AND x.num > 0 AND x.section IN ('dimers', 'disks', 'rods')
  AND NOT EXISTS (SELECT 1 FROM species AS s WHERE s.run = x.run);
