#!/usr/bin/python3
"""Reads a `haff export gsd` file with Debian's real GSD reader (python3-gsd, gsd.hoomd) and checks
every frame against the run's database, recomputed here independently of haff's C code.

usage: gsd_check.py FILE.gsd RUN.db RUN_ID
Checks that gsd.hoomd.open returns one frame per stored state snapshot and frames row (the
order of `haff export xyz`), and in each: step, dimensions 2, the box (Lx, Ly, 0: float32 of the
stored box; a ring of rods: its length and 1), the types (the species by idx, then NAME_disk for
each species of more than one disk), and for every particle its typeid, body id (a body of more
than one disk: its centre with body = its own tag, then its disks with body = the centre's tag;
-1 for a single disk or a rod), mass, diameter, moment of inertia, position and image (HOOMD's
box centred on 0), orientation q = (cos phi/2, 0, 0, sin phi/2), velocity and angmom
p = 2 q (0, 0, 0, I omega); the log values haff/time, cpd, label and the exact doubles
haff/position, velocity, phi, omega.  Every comparison is exact: the float32 fields against the
float32 of the double computed here, the doubles bit for bit (a disk's position and velocity
use the engine's formula, glibc's sin and cos, which equal its sincos).
The pure-Python reader gsd.pygsd (its own parser of the file layer) must read the same frames.
Prints one line per failed check and "N passed, M failed"; exit 1 on a failure.
"""
import math
import sqlite3
import struct
import sys

import gsd.hoomd
import gsd.pygsd
import numpy as np

from check_tally import check, done


def same(a, b):
    """Arrays equal bit for bit (NaN equal to NaN)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and \
        np.array_equal(a.view(np.uint8), b.view(np.uint8))


def main():
    path, dbpath, run = sys.argv[1], sys.argv[2], int(sys.argv[3])
    db = sqlite3.connect(dbpath)
    scene, lx, ly = db.execute("SELECT scene, box_x, box_y FROM runs WHERE id = ?",
                               (run,)).fetchone()
    rods = "[rods]" in scene
    if rods:
        ly = 1.0
    # species: name, disks (x y d m), count, mass, inertia, in idx order
    species = db.execute("SELECT idx, name, disks, count, mass, inertia FROM species WHERE run = ? "
                         "ORDER BY idx", (run,)).fetchall()
    shapes = [[tuple(float(v) for v in p.split()) for p in disks.split(";")]
              for _, _, disks, _, _, _ in species]
    first, at = [], 0
    for s in species:
        first.append(at)
        at += s[3]
    gamma = 0.8
    for line in scene.splitlines():
        if line.replace(" ", "").startswith("gamma="):
            gamma = float(line.split("=")[1].split(";")[0])

    def species_of(body):
        k = 0
        while k + 1 < len(first) and body >= first[k + 1]:
            k += 1
        return k

    rigid = [len(sh) > 1 for sh in shapes]
    want_types = ["rod"] if rods else [s[1] for s in species] + \
        [s[1] + "_disk" for s, r in zip(species, rigid) if r]

    order = {"initial": 0, "frames": 1, "velocities": 2, "checkpoint": 3, "final": 4}
    snaps = []
    for label, t, cpd in db.execute("SELECT label, t, max(cpd) FROM states WHERE run = ? "
                                    "GROUP BY label, t", (run,)):
        rows = db.execute("SELECT body, x, y, phi, vx, vy, omega FROM states WHERE run = ? "
                          "AND label = ? AND t = ? ORDER BY body", (run, label, t)).fetchall()
        rows = [tuple(0.0 if v is None else v for v in r) for r in rows]  # NULL reads as 0
        snaps.append((t, order[label], 0, label, cpd, rows))
    for rowid, t, cpd, n, data in db.execute("SELECT rowid, t, cpd, n, data FROM frames "
                                             "WHERE run = ?", (run,)):
        # x y phi as float64, vx vy omega as float32 (read as the doubles they are)
        rows = [(i,) + struct.unpack_from("<3d3f", data, 36 * i) for i in range(n)]
        snaps.append((t, order["frames"], rowid, "frames", cpd, rows))
    snaps.sort(key=lambda s: s[:3])

    traj = gsd.hoomd.open(path, "rb")
    check(len(traj) == len(snaps), "%d frames read, %d stored" % (len(traj), len(snaps)))
    f32 = np.float32
    for k, (frame, (t, lab, _, label, cpd, rows)) in enumerate(zip(traj, snaps)):
        where = "frame %d (%s t=%r)" % (k, label, t)
        check(frame.configuration.step == k and frame.configuration.dimensions == 2,
              where + ": step, dimensions")
        check(same(frame.configuration.box, np.array([lx, ly, 0, 0, 0, 0], dtype=f32)),
              where + ": box %s" % frame.configuration.box)
        check(list(frame.particles.types) == want_types,
              where + ": types %s, want %s" % (frame.particles.types, want_types))
        log = frame.log
        check(same(log["haff/time"], np.array([t])) and
              same(log["haff/cpd"], np.array([math.nan if cpd is None else cpd])) and
              same(log["haff/label"], np.array([lab], dtype=np.uint8)),
              where + ": log time, cpd, label")
        # the particles, computed here: centres and single bodies first, then the disks
        P = {key: [] for key in ("typeid", "mass", "diam", "body", "moi", "x", "v", "phi",
                                 "omega", "lz")}
        disks = {key: [] for key in P}

        def add(d, typeid, mass, diam, body, moi, x, y, vx, vy, phi, om, lz):
            d["typeid"].append(typeid)
            d["mass"].append(mass)
            d["diam"].append(diam)
            d["body"].append(body)
            d["moi"].append((0.0, 0.0, moi))
            d["x"].append((x, y, 0.0))
            d["v"].append((vx, vy, 0.0))
            d["phi"].append(phi)
            d["omega"].append(om)
            d["lz"].append(lz)

        ndisk_types = 0
        disk_type = {}
        for s, r in enumerate(rigid):
            if r:
                disk_type[s] = len(species) + ndisk_types
                ndisk_types += 1
        for body, x, y, phi, vx, vy, om in rows:
            if rods:
                m = 1 + 1 / gamma if body % 2 else 1 + gamma
                add(P, 0, m, 1.0, -1, 0.0, x, 0.0, vx, 0.0, 0.0, om, 0.0)
                continue
            s = species_of(body)
            sh = shapes[s]
            sn, cs = math.sin(phi), math.cos(phi)

            def disk(j):
                """The engine's shape of a species row (hd_shape_cluster with its fast paths:
                recentred on the centre of mass; a symmetric pair of equal disks is a dimer of
                half bond h, a single disk a disk) and its disk j (hd_kin_disk_pos, _vel)."""
                mass = 0.0
                cx = cy = 0.0
                for ox, oy, d, m in sh:
                    mass += m
                    cx += m * ox
                    cy += m * oy
                cx /= mass
                cy /= mass
                o = [(ox - cx, oy - cy, d, m) for ox, oy, d, m in sh]
                ox, oy, d, m = o[j]
                if len(o) == 1:
                    return x, y, vx, vy, d, m
                if len(o) == 2 and o[0][2] == o[1][2] and o[0][3] == o[1][3] and \
                        o[0][1] == 0.0 and o[1][1] == 0.0 and o[0][0] == -o[1][0] and o[0][0] <= 0:
                    h = 0.5 * (o[1][0] - o[0][0]) * (1.0 if j else -1.0)
                    hw = h * om
                    return x + h * cs, y + h * sn, vx - hw * sn, vy + hw * cs, d, m
                return (x + (ox * cs - oy * sn), y + (ox * sn + oy * cs),
                        vx - om * (ox * sn + oy * cs), vy + om * (ox * cs - oy * sn), d, m)
            if not rigid[s]:
                px, py, dvx, dvy, d, m = disk(0)
                add(P, s, m, d, -1, 0.0, px, py, dvx, dvy, phi, om, 0.0)
                continue
            inertia, mass = species[s][5], species[s][4]
            add(P, s, mass, 0.0, body, inertia, x, y, vx, vy, phi, om, inertia * om)
            for j in range(len(sh)):
                px, py, dvx, dvy, d, m = disk(j)
                add(disks, disk_type[s], m, d, body, 0.0, px, py, dvx, dvy, phi, om, 0.0)
        for key in P:
            P[key] += disks[key]
        n = len(P["mass"])
        p = frame.particles
        check(p.N == n, where + ": N %d, want %d" % (p.N, n))
        if p.N != n:
            continue
        x = np.array(P["x"])
        box = np.array([lx, ly, 1.0])
        image = np.floor(x / box)
        pos = (x - image * box - 0.5 * box).astype(f32)
        image[:, 2] = 0
        pos[:, 2] = 0
        if rods:
            pos[:, 1] = 0
            image[:, 1] = 0
        phi = np.array(P["phi"])
        half = [(math.cos(0.5 * a), math.sin(0.5 * a)) for a in phi]
        q = np.array([(c, 0, 0, s) for c, s in half], dtype=f32)
        lz = np.array(P["lz"])
        angmom = np.array([(-2 * s * l, 0, 0, 2 * c * l) for (c, s), l in zip(half, lz)],
                          dtype=f32)
        for name, got, want in [
                ("typeid", p.typeid, np.array(P["typeid"], dtype=np.uint32)),
                ("body", p.body, np.array(P["body"], dtype=np.int32)),
                ("mass", p.mass, np.array(P["mass"], dtype=f32)),
                ("diameter", p.diameter, np.array(P["diam"], dtype=f32)),
                ("moment_inertia", p.moment_inertia, np.array(P["moi"], dtype=f32)),
                ("position", p.position, pos),
                ("image", p.image, image.astype(np.int32)),
                ("orientation", p.orientation, q),
                ("velocity", p.velocity, np.array(P["v"], dtype=f32)),
                ("angmom", p.angmom, angmom),
                ("log haff/position", log["haff/position"], x),
                ("log haff/velocity", log["haff/velocity"], np.array(P["v"])),
                ("log haff/phi", log["haff/phi"], phi),
                ("log haff/omega", log["haff/omega"], np.array(P["omega"]))]:
            got = np.asarray(got)
            ok = same(got.reshape(want.shape) if got.size == want.size else got, want)
            check(ok, where + ": %s differs (%d of %d)" % (
                name, int(np.sum(got.reshape(want.shape) != want)) if got.size == want.size
                else -1, want.size))
        # the types' names hold every body's species: the rigid bodies' disks carry its id
        if not rods:
            check(all(p.body[i] == i or p.body[i] == -1 for i in range(len(rows))),
                  where + ": a body's own particle is its tag")
    # the pure-Python reader of the same package (its own parser of the file layer) agrees
    with open(path, "rb") as fh:
        py = gsd.hoomd.HOOMDTrajectory(gsd.pygsd.GSDFile(fh))
        check(len(py) == len(traj), "pygsd: %d frames" % len(py))
        for k in (0, len(py) - 1):
            check(same(py[k].particles.position, traj[k].particles.position) and
                  same(py[k].log["haff/position"], traj[k].log["haff/position"]),
                  "pygsd: frame %d differs" % k)
    done()


if __name__ == "__main__":
    main()
