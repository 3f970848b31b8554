#!/usr/bin/python3
"""Reads a `haff export xyz` file with ASE (Debian's python3-ase, 3.22) and checks every frame
against the run's database, recomputed here independently of haff's C code.

usage: ase_check.py FILE.xyz RUN.db RUN_ID
Checks, for every frame that ase.io.read(FILE, index=':') returns (and that it returns one per
stored state snapshot and frames row): the cell (Lx, Ly, 1), pbc (F along walls and z), the
masses, positions and velocities (get_velocities(): momenta / masses) of every disk, the
orientation phi of every body, the bond length of every dimer, and the species of every disk
(issue 28): its species_name is its body's species (states.species -> species.name; 'rod' for
rods), and each species has an element symbol of its own.  Tolerances: positions and
bonds 1e-12 of the box (17 significant digits; the old %.10g export was off by ~1e-9),
velocities 1e-12 of the largest speed for states, 1e-6 for frames (stored as float32).
Prints one line per failed check and a final line "N passed, M failed"; exit 1 on a failure.
"""
import math
import sqlite3
import struct
import sys

import ase.io

from check_tally import check, done


def scene_keys(text):
    """[section] key -> value from the run's canonical scene text."""
    keys, sec = {}, ""
    for line in text.splitlines():
        line = line.split(";")[0].strip()
        if line.startswith("["):
            sec = line.strip("[]")
        elif "=" in line:
            k, v = line.split("=", 1)
            keys[sec + "." + k.strip()] = v.strip()
    return keys


def disks_of(kind, x, y, phi, vx, vy, om, keys, body, shape=None):
    """(species mass, [(px, py, vx, vy)]) of a body: DESIGN.md's dimer geometry; a body of a
    named species (shape: its species.disks, "x y d m; ...") is its disks, rotated by phi."""
    if kind == "body":
        c, s = math.cos(phi), math.sin(phi)
        out, mass = [], None
        for part in shape.split(";"):
            ox, oy, _, m = (float(v) for v in part.split())
            rx, ry = c * ox - s * oy, s * ox + c * oy
            out.append((x + rx, y + ry, vx - om * ry, vy + om * rx))
            mass = m if mass is None else mass
        return mass, out
    if kind == "dimer":
        h = 0.5 * float(keys.get("dimers.a", 1))
        m = float(keys.get("dimers.m", 1))
        c, s = math.cos(phi), math.sin(phi)
        return m, [(x - h * c, y - h * s, vx + h * om * s, vy - h * om * c),
                   (x + h * c, y + h * s, vx - h * om * s, vy + h * om * c)]
    if kind == "rod":
        g = float(keys.get("rods.gamma", 0.8))
        return (1 + 1 / g if body % 2 else 1 + g), [(x, 0.0, vx, 0.0)]
    return float(keys.get("disks.mass", 1)), [(x, y, vx, vy)]


def main():
    path, dbpath, run = sys.argv[1], sys.argv[2], int(sys.argv[3])
    db = sqlite3.connect(dbpath)
    scene, lx, ly = db.execute("SELECT scene, box_x, box_y FROM runs WHERE id = ?",
                               (run,)).fetchone()
    keys = scene_keys(scene)
    sides = keys.get("walls.sides", "")
    rods = "rods.count" in keys
    want_pbc = [not ("left" in sides or "right" in sides),
                not ("bottom" in sides or "top" in sides or rods), False]
    if rods:
        ly = 1.0
    # the expected frames, in the export's order
    order = {"initial": 0, "frames": 1, "velocities": 2, "checkpoint": 3, "final": 4}
    snaps = []
    for label, t in db.execute("SELECT DISTINCT label, t FROM states WHERE run = ?", (run,)):
        rows = db.execute("SELECT body, kind, x, y, phi, vx, vy, omega FROM states WHERE run = ? "
                          "AND label = ? AND t = ? ORDER BY body", (run, label, t)).fetchall()
        snaps.append((t, order[label], 0, label, rows, 1e-12))
    kinds = [k for (k,) in db.execute("SELECT kind FROM states WHERE run = ? AND label = "
                                      "'initial' ORDER BY body", (run,))]
    # each body's species name and shape: states.species (schema version 4) -> species
    spname, spshape = {}, {}
    has_species = db.execute("SELECT count(*) FROM sqlite_master WHERE name = 'species'"
                             ).fetchone()[0]
    if has_species:
        for idx, name, disks in db.execute("SELECT idx, name, disks FROM species WHERE run = ?",
                                           (run,)):
            spname[idx], spshape[idx] = name, disks
    # a file from before schema version 4 has no states.species: the species follows from the
    # body number (bodies are numbered species by species in idx order), else from the kind
    cols = [c[1] for c in db.execute("PRAGMA table_info(states)")]
    first, at = {}, 0
    if has_species:
        for idx, count in db.execute("SELECT idx, count FROM species WHERE run = ? ORDER BY idx",
                                     (run,)):
            first[idx], at = (at, at + count), at + count
    body_species = {}
    for body, kind, sp in db.execute("SELECT body, kind, %s FROM states WHERE run = ? AND "
                                     "label = 'initial' ORDER BY body"
                                     % ("species" if "species" in cols else "NULL"), (run,)):
        if sp is None and kind != "rod":
            sp = next((k for k, (lo, hi) in first.items() if lo <= body < hi),
                      0 if kind == "dimer" else 1)
        body_species[body] = ("rod" if kind == "rod" else spname[sp] if sp in spname
                              else ("dimer", "disk")[sp],
                              spshape.get(sp))
    # a database from before the frames table has none
    has_frames = db.execute("SELECT count(*) FROM sqlite_master "
                            "WHERE name = 'frames'").fetchone()[0]
    sql = ("SELECT rowid, t, n, data FROM frames WHERE run = ?" if has_frames
           else "SELECT 1, 2, 3, 4 WHERE ? AND 0")
    for rowid, t, n, data in db.execute(sql, (run,)):
        rows = []
        for i in range(n):
            x, y, phi, vx, vy, om = struct.unpack_from("<3d3f", data, 36 * i)
            rows.append((i, kinds[i], x, y, phi, vx, vy, om))
        snaps.append((t, order["frames"], rowid, "frames", rows, 1e-6))
    snaps.sort(key=lambda s: s[:3])

    frames = ase.io.read(path, index=":")
    check(len(frames) == len(snaps), "%d frames read, %d stored" % (len(frames), len(snaps)))
    box = max(lx, ly)
    for f, (t, _, _, label, rows, vtol) in zip(frames, snaps):
        where = "frame %s t=%r" % (label, t)
        check(f.info.get("Label") == label and f.info.get("Time") == t, where + ": Time, Label")
        cell = f.get_cell()
        check(abs(cell[0][0] - lx) == 0 and abs(cell[1][1] - ly) == 0 and cell[2][2] == 1,
              where + ": cell %s" % cell.lengths())
        check(list(f.get_pbc()) == want_pbc, where + ": pbc %s" % f.get_pbc())
        pos, vel, mass = f.get_positions(), f.get_velocities(), f.get_masses()
        phis = f.arrays.get("phi")
        want = []
        for body, kind, x, y, phi, vx, vy, om in rows:
            name, shape = body_species[body]
            m, disks = disks_of(kind, x, y, phi or 0.0, vx, vy or 0.0, om or 0.0, keys, body,
                                shape)
            turns = kind == "dimer" or (kind == "body" and len(disks) > 1)
            for k, d in enumerate(disks):
                if kind == "body":  # the disk's own mass
                    m = float(shape.split(";")[k].split()[3])
                want.append((body, m, d, phi if turns else 0.0, name))
        check(len(f) == len(want), where + ": %d disks, want %d" % (len(f), len(want)))
        if len(f) != len(want):
            continue
        vmax = max(1e-300, max(math.hypot(d[2], d[3]) for _, _, d, _, _ in want))
        bad_p = bad_v = bad_m = bad_phi = bad_sp = 0
        names = f.arrays.get("species_name")
        symbols = f.get_chemical_symbols()
        element = {}
        for i, (body, m, (px, py, dvx, dvy), phi, name) in enumerate(want):
            bad_sp += names is None or names[i] != name or element.setdefault(name, symbols[i]) \
                != symbols[i]
            bad_p += abs(pos[i][0] - px) > 1e-12 * box or abs(pos[i][1] - py) > 1e-12 * box \
                or pos[i][2] != 0
            bad_v += abs(vel[i][0] - dvx) > vtol * vmax or abs(vel[i][1] - dvy) > vtol * vmax
            bad_m += mass[i] != m
            bad_phi += phis is None or phis[i] != phi
        check(bad_p == 0, where + ": %d positions off" % bad_p)
        check(bad_v == 0, where + ": %d velocities off" % bad_v)
        check(bad_m == 0, where + ": %d masses off" % bad_m)
        check(bad_phi == 0, where + ": %d orientations off" % bad_phi)
        check(bad_sp == 0 and len(set(element.values())) == len(element),
              where + ": %d species names off, elements %s" % (bad_sp, element))
        # the bond of every dimer from the file's own numbers
        a = float(keys.get("dimers.a", 1))
        worst = 0.0
        for i in range(len(want) - 1):
            if want[i][0] == want[i + 1][0] and f.get_chemical_symbols()[i] == "N":
                worst = max(worst, abs(math.dist(pos[i], pos[i + 1]) - a))
        check(worst <= 1e-12 * box, where + ": bond off by %.3g" % worst)
    done()


if __name__ == "__main__":
    main()
