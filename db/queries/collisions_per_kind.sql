-- Logged collisions per kind and run: how many, what fraction, and their energy loss.
--
-- usage:  sqlite3 -header -column run.db < db/queries/collisions_per_kind.sql        (every run)
--         sqlite3 -header -column run.db -cmd '.parameter set @run 1' < db/queries/collisions_per_kind.sql
--
-- Columns: run, kind (dimer-dimer, dimer-disk, disk-disk, dimer-wall, disk-wall, rod-rod),
-- n, fraction (of the run's logged collisions), mean_de and total_de (kinetic energy after minus
-- before, <= 0), mean_f (orientation factor; NULL where the kind has none).
-- With [log] collisions = every N these count the logged rows, not all collisions.
-- (run IN (SELECT id FROM runs ...), not "@run IS NULL OR run = @run", which SQLite answers
-- with a SCAN of every row even when @run is set: this form searches the index run by run.)
SELECT run, kind,
       count(*) AS n,
       count(*) * 1.0 / sum(count(*)) OVER (PARTITION BY run) AS fraction,
       avg(de) AS mean_de,
       sum(de) AS total_de,
       avg(f) AS mean_f
FROM collisions
WHERE run IN (SELECT id FROM runs WHERE @run IS NULL OR id = @run)
GROUP BY run, kind
ORDER BY run, kind;
