-- Mean orientation factor <f> of the dimer-dimer collisions of each run, with its standard
-- error, and the effective dimension D_e = D / <f> (D = 2) of Costantini et al. 2005, sec. 5
-- (their estimate for a = d: <f> = 0.64, D_e = 3.12).
--
-- usage:  sqlite3 -header -column run.db < db/queries/mean_f_per_run.sql          (every run)
--         sqlite3 -header -column run.db -cmd '.parameter set @run 1' < db/queries/mean_f_per_run.sql
--
-- Columns: run, n (dimer-dimer collisions with an f), mean_f, sd_f (sample standard deviation,
-- n - 1), stderr_f = sd_f / sqrt(n), d_e = 2 / mean_f.
-- The standard error treats the collisions as independent; successive collisions of a body are
-- correlated, so read it as a lower bound (compare blocks with angle_histogram_per_block.sql).
-- Needs SQLite's math functions (sqrt), built into the sqlite3 shell since 3.35.
-- (run IN (SELECT id FROM runs ...), not "@run IS NULL OR run = @run", which SQLite answers
-- with a SCAN of every row even when @run is set: this form searches the index run by run.)
WITH
  d AS (SELECT run, f FROM collisions
        WHERE kind = 'dimer-dimer' AND f IS NOT NULL
          AND run IN (SELECT id FROM runs WHERE @run IS NULL OR id = @run)),
  m AS (SELECT run, count(*) AS n, avg(f) AS mean_f FROM d GROUP BY run),
  v AS (SELECT d.run, sum((d.f - m.mean_f) * (d.f - m.mean_f)) AS ss
        FROM d JOIN m ON m.run = d.run GROUP BY d.run)
SELECT m.run, m.n, m.mean_f,
       CASE WHEN m.n > 1 THEN sqrt(v.ss / (m.n - 1)) END AS sd_f,
       CASE WHEN m.n > 1 THEN sqrt(v.ss / (m.n - 1) / m.n) END AS stderr_f,
       2.0 / m.mean_f AS d_e
FROM m JOIN v ON v.run = m.run
ORDER BY m.run;
