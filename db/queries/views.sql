-- Views for interactive work.  Create them once in a database:
--     sqlite3 run.db < db/queries/views.sql
-- (they are dropped and recreated, so running it again picks up changes).  They read every
-- run: filter with WHERE run = ...
--
-- v_dimer_collisions   dimer-dimer collisions with cos^2 of both contact angles and f from
--                      eq. 36, f_eq36 = 1 / (2 - (cos^2 theta_i + cos^2 theta_j) / 2), next to
--                      the logged f (they agree to rounding).
-- v_wall_collisions    body-wall collisions with the wall's name (j = -1 left, -2 right,
--                      -3 bottom, -4 top).
-- v_energy             samples with T_tr, T_rot, E = T_tr + T_rot/2 and K = E_tr / E_rot
--                      (eq. 34-35 of Costantini et al. 2005; see energy_vs_cpd.sql).
-- v_runs               runs with events per second and the number of logged collisions.
DROP VIEW IF EXISTS v_dimer_collisions;
CREATE VIEW v_dimer_collisions AS
SELECT run, seq, t, i, j, disk_i, disk_j, theta_i, theta_j, f, de, vn,
       cos(theta_i) * cos(theta_i) AS cos2_i,
       cos(theta_j) * cos(theta_j) AS cos2_j,
       1.0 / (2.0 - (cos(theta_i) * cos(theta_i) + cos(theta_j) * cos(theta_j)) / 2.0) AS f_eq36
FROM collisions
WHERE kind = 'dimer-dimer';

DROP VIEW IF EXISTS v_wall_collisions;
CREATE VIEW v_wall_collisions AS
SELECT run, seq, t, kind, i, disk_i, theta_i, de, vn,
       CASE j WHEN -1 THEN 'left' WHEN -2 THEN 'right' WHEN -3 THEN 'bottom' WHEN -4 THEN 'top'
       END AS wall
FROM collisions
WHERE kind IN ('dimer-wall', 'disk-wall');

DROP VIEW IF EXISTS v_energy;
CREATE VIEW v_energy AS
SELECT run, t, collisions, cpd, e_tr, e_rot,
       e_tr AS t_tr, 2 * e_rot AS t_rot, e_tr + e_rot AS e,
       CASE WHEN e_rot > 0 THEN e_tr / e_rot END AS k
FROM samples;

DROP VIEW IF EXISTS v_runs;
CREATE VIEW v_runs AS
SELECT r.id, r.status, r.started, r.finished, r.seed, r.events, r.wall_seconds,
       CASE WHEN r.wall_seconds > 0 THEN r.events / r.wall_seconds END AS events_per_s,
       (SELECT count(*) FROM collisions AS c WHERE c.run = r.id) AS collisions_logged,
       r.message
FROM runs AS r;
