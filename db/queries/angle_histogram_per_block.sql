-- Histogram of the contact angle theta_i, 36 bins over (-pi, pi], per block of collisions.
--
-- usage:  sqlite3 -header -column run.db -cmd '.parameter set @run 1' \
--                 < db/queries/angle_histogram_per_block.sql
--   @run    the run (unset: every run)
--   @block  collisions per block [10000]; block b holds seq in [b*@block + 1, (b+1)*@block]
--           (e.g. -cmd '.parameter set @block 1000')
--
-- Only collisions that have a theta_i enter (dimer-dimer, dimer-disk, dimer-wall: i is the
-- dimer).  Bin k in 0..35 is (-pi + k w, -pi + (k+1) w] with w = 2 pi / 36, i.e.
-- k = 35 - floor((pi - theta) / w).  Every bin of every block is listed, empty ones with n = 0.
-- Columns: run, block, bin, theta_lo, theta_hi, n (collisions in the bin), n_block (in the
-- block), density = n / (n_block w) (a probability density: it integrates to 1).
-- Paper (Costantini et al. 2005, Fig. 5): for a = d the density is nearly flat, 1/(4 pi/3),
-- on |theta| <= 2 pi/3 and 0 outside.
-- (run IN (SELECT id FROM runs ...), not "@run IS NULL OR run = @run", which SQLite answers
-- with a SCAN of every row even when @run is set: this form searches the index run by run.)
WITH RECURSIVE
  bins(k) AS (SELECT 0 UNION ALL SELECT k + 1 FROM bins WHERE k < 35),
  c AS (
    SELECT run,
           (seq - 1) / CAST(coalesce(@block, 10000) AS INTEGER) AS block,
           max(0, min(35, 35 - CAST((3.141592653589793 - theta_i) / (6.283185307179586 / 36)
                                    AS INTEGER))) AS k
    FROM collisions
    WHERE theta_i IS NOT NULL
      AND run IN (SELECT id FROM runs WHERE @run IS NULL OR id = @run)),
  blocks AS (SELECT run, block, count(*) AS n_block FROM c GROUP BY run, block),
  counts AS (SELECT run, block, k, count(*) AS n FROM c GROUP BY run, block, k)
SELECT b.run, b.block, bins.k AS bin,
       -3.141592653589793 + bins.k * (6.283185307179586 / 36) AS theta_lo,
       -3.141592653589793 + (bins.k + 1) * (6.283185307179586 / 36) AS theta_hi,
       coalesce(counts.n, 0) AS n,
       b.n_block,
       coalesce(counts.n, 0) / (b.n_block * (6.283185307179586 / 36)) AS density
FROM blocks AS b
  CROSS JOIN bins
  LEFT JOIN counts ON counts.run = b.run AND counts.block = b.block AND counts.k = bins.k
ORDER BY b.run, b.block, bins.k;
