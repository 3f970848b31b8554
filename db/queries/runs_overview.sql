-- One line per run: status, when, how long, how fast, how much was logged.
--
-- usage:  sqlite3 -header -column run.db < db/queries/runs_overview.sql
--         (or -cmd '.parameter set @run 3' for one run)
--
-- Columns: id, status, started, finished (ISO 8601 UTC), seed, version, events, wall_seconds,
-- events_per_s, bodies (in the initial state), collisions_logged, samples, last_cpd (cpd of the
-- newest sample), has_checkpoint, box_x, box_y, message (why a run ended when not 'done').
SELECT r.id, r.status, r.started, r.finished, r.seed, r.version, r.events, r.wall_seconds,
       CASE WHEN r.wall_seconds > 0 THEN r.events / r.wall_seconds END AS events_per_s,
       (SELECT count(*) FROM states AS s WHERE s.run = r.id AND s.label = 'initial') AS bodies,
       (SELECT count(*) FROM collisions AS c WHERE c.run = r.id) AS collisions_logged,
       (SELECT count(*) FROM samples AS s WHERE s.run = r.id) AS samples,
       (SELECT s.cpd FROM samples AS s WHERE s.run = r.id ORDER BY s.t DESC LIMIT 1) AS last_cpd,
       EXISTS (SELECT 1 FROM checkpoints AS k WHERE k.run = r.id) AS has_checkpoint,
       r.box_x, r.box_y, r.message
FROM runs AS r
WHERE r.id BETWEEN coalesce(@run, 0) AND coalesce(@run, 9223372036854775807)  -- a search by id
ORDER BY r.id;
