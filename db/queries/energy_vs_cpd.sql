-- Energy decay against collisions per particle (cpd), from the samples table.
--
-- usage:  sqlite3 -csv -header run.db -cmd '.parameter set @run 1' < db/queries/energy_vs_cpd.sql > e.csv
--   @run  the run (unset: every run)
--
-- Columns: run, t, collisions, cpd, e_tr, e_rot (per body, as logged), and in the notation of
-- Costantini et al. 2005 (eq. 34-35, energies per dimer, k_B = 1):
--   t_tr = e_tr          (two translational degrees of freedom: T_tr = <E_tr>)
--   t_rot = 2 e_rot      (one rotational degree of freedom: T_rot = 2 <E_rot>)
--   e = e_tr + e_rot     (= T_tr + T_rot / 2)
--   e_over_e0            e divided by the first sample's e of the run
--   k = e_tr / e_rot     (K of the paper; NULL when e_rot = 0, e.g. pure disks)
-- Note: e_tr is the kinetic energy of the centre-of-mass velocities as logged (eq. 34 subtracts
-- the mean velocity, which is zero for a periodic gas started at rest in the mean).
-- (run IN (SELECT id FROM runs ...), not "@run IS NULL OR run = @run", which SQLite answers
-- with a SCAN of every row even when @run is set: this form searches the index run by run.)
SELECT run, t, collisions, cpd, e_tr, e_rot,
       e_tr AS t_tr,
       2 * e_rot AS t_rot,
       e_tr + e_rot AS e,
       (e_tr + e_rot) / first_value(e_tr + e_rot) OVER (PARTITION BY run ORDER BY t) AS e_over_e0,
       CASE WHEN e_rot > 0 THEN e_tr / e_rot END AS k
FROM samples
WHERE run IN (SELECT id FROM runs WHERE @run IS NULL OR id = @run)
ORDER BY run, t;
