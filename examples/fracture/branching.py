#!/usr/bin/env python3
"""Dynamic crack branching in a glass plate (Ha & Bobaru 2010): runs in.branching.nosb and
in.branching.lps (branching.geometry) on one set-up, follows the crack from the notch tip over
time, finds whether and where it branches, prints one table, and with --pictures draws the
mid-plane damage at several times.

    python3 branching.py [--lmp ../../build/lmp] [--spacing 1|0.5] [--styles nosb lps]
        [--pair "peri/nosb keywords"] [--nosb-var NAME VALUE] [--lps-var NAME VALUE]
        [--sigma 12] [--t-end 46] [--every 1] [--step NS] [--times 16 26 36 46] [--out DIR]
        [--pictures] [--reuse]

Each style runs in --out (default frames/branching-<spacing>mm) with the decks copied there,
-var a (the spacing), -var dt (--step, default the deck's 25 ns per mm), -var sigma (--sigma,
MPa), -var t_end (--t-end, us), -var dump (every --every us), and for peri/nosb -var keys
(--pair, default none: the pair style's defaults) and the -var of --nosb-var, for peri/lps those
of --lps-var.

What is measured, per dump frame, in the reference configuration (the positions of the first
frame) of the mid-plane layer (tools/crack_path.py's mid_layer), on its particles with damage
above 0.4 connected by distances below 1.5 spacings (crack_path.components):
- the crack: the connected damaged sets with a particle within 2.5 spacings of the notch tip
  (x = 50 mm, y = 20 mm);
- tip x: the largest x of the crack; its speed, the slope of a least-squares line through
  tip x over the frames within --window us (default 2) either side;
- path: the largest distance along the crack from the notch tip (the shortest route through
  the crack's particles, steps below 1.5 spacings), and its speed the same way (for a branched
  crack, the speed along a branch);
- branches: per column of particles (one spacing of x) beyond the notch tip (x > 50 mm) the
  crack's particles split into runs of y with gaps of more than 1.5 spacings between them; the
  crack is branched from the first column of 2 horizons (6 columns) in a row that each hold
  two or more runs (branch x, the x of that column); the angle between the branches: between
  the lines fitted (least squares, y against x) through the centres of the topmost and the
  bottommost run of the columns with two or more runs up to 20 spacings beyond branch x;
- right edge: the first frame at which the crack reaches the last column (x > 100 mm - 1.5 a);
- off-path: the fraction of the mid-plane's particles with damage above 0.4 not on the crack.
The summary line per style: whether the crack branched, the time, branch x and angle of the
first frame in which it is branched, the largest speeds, the time it reaches the right edge,
the wall time of the run. --reuse measures the dumps already in --out without running LAMMPS.
Needs numpy (and matplotlib for the pictures: branching-<spacing>mm-<sigma>MPa.png in --out,
drawn by tools/render_particles.py, a row per style, a column per --times, in the current
configuration).
"""
import argparse
import heapq
import math
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(HERE))
import crack_path  # noqa: E402
import damage_maps  # noqa: E402
from dump_to_vtu import read_dump  # noqa: E402

TIP = (0.05, 0.02)
WIDTH = 0.1
FILES = ["branching.geometry", "branching.run", "in.branching.lps", "in.branching.nosb"]
THRESHOLD = 0.4
LINK = 1.5          # spacings: the damaged particles that touch
SEED = 2.5          # spacings from the notch tip: the sets that start there
PERSIST = 6         # columns (two horizons) that two branches must go on for
FIT = 20            # columns beyond branch x in the branches' angle fit


def step(args, a):
    """The time step (s): --step in ns, default the deck's 2.5e-5 a (25 ns at 1 mm)."""
    return args.step * 1e-9 if args.step else 2.5e-5 * a


def geodesic(points, seeds, link):
    """Shortest distance from the seed points to every point through steps shorter than link."""
    cells = {}
    keys = np.floor(points / link).astype(int)
    for k, key in enumerate(map(tuple, keys)):
        cells.setdefault(key, []).append(k)
    dist = np.full(len(points), np.inf)
    heap = [(0.0, int(k)) for k in seeds]
    for _, k in heap:
        dist[k] = 0.0
    heapq.heapify(heap)
    while heap:
        d, k = heapq.heappop(heap)
        if d > dist[k]:
            continue
        cx, cy = keys[k]
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in cells.get((cx + dx, cy + dy), ()):
                    r = math.dist(points[j], points[k])
                    if r < link and d + r < dist[j]:
                        dist[j] = d + r
                        heapq.heappush(heap, (d + r, j))
    return dist


def runs(ys, gap):
    """The runs of sorted values ys split where consecutive values are more than gap apart."""
    ys = np.sort(ys)
    cuts = np.flatnonzero(np.diff(ys) > gap) + 1
    return np.split(ys, cuts)


def branches(crack, h):
    """(branch x or None, angle in degrees or nan, largest number of runs in a column) of the
    crack's particles (m x 2, x y), by the runs of y per column of particles."""
    if len(crack) == 0:
        return None, float("nan"), 0
    column = np.round((crack[:, 0] - 0.5 * h) / h).astype(int)
    first, last = column.min(), column.max()
    per = {c: runs(crack[column == c, 1], LINK * h) for c in range(first, last + 1)}
    count = {c: len(r) if len(r[0]) else 0 for c, r in per.items()}
    most = max(count.values())
    start = next((c for c in range(first, last - PERSIST + 2)
                  if all(count[k] >= 2 for k in range(c, c + PERSIST))), None)
    if start is None:
        return None, float("nan"), most
    split = [c for c in range(start, min(last, start + FIT) + 1) if count[c] >= 2]
    xs = [(c + 0.5) * h for c in split]
    top = [per[c][-1].mean() for c in split]
    bottom = [per[c][0].mean() for c in split]
    slope_top = np.polyfit(xs, top, 1)[0]
    slope_bottom = np.polyfit(xs, bottom, 1)[0]
    angle = math.degrees(math.atan(slope_top) - math.atan(slope_bottom))
    return (start + 0.5) * h, angle, most


def measure(dump, a, dt):
    """Per frame: {time (us), tip x (m), path (m), branch x (m) or None, angle, runs, right
    (reached the last column), off-path fraction}."""
    rows = []
    reference = None
    for timestep, columns, words in read_dump(dump):
        table = np.array(words, dtype=float).reshape(len(words), len(columns))
        ids = table[:, columns.index("id")].astype(int)
        if reference is None:
            reference = table[np.argsort(ids)][:, [columns.index(c) for c in "xyz"]]
            order = np.sort(ids)
            layer = crack_path.mid_layer(reference, 2, a)
            plane = reference[layer][:, :2]
        if not np.array_equal(np.sort(ids), order):
            raise ValueError(f"{dump}: step {timestep}: the particles differ from the first "
                             "frame's")
        damage = table[np.argsort(ids), columns.index("v_damage")]
        hot = np.flatnonzero(damage[layer] > THRESHOLD)
        row = {"time": timestep * dt * 1e6, "tip_x": float("nan"), "path": 0.0,
               "branch_x": None, "angle": float("nan"), "runs": 0, "right": False,
               "off_path": len(hot) / max(layer.sum(), 1)}
        if len(hot):
            points = plane[hot]
            label = crack_path.components(points, LINK * a)
            near = np.linalg.norm(points - np.array(TIP), axis=1) <= SEED * a
            on = np.isin(label, np.unique(label[near]))
            row["off_path"] = float((~on).sum() / layer.sum())
            if on.any():
                crack = points[on]
                row["tip_x"] = float(crack[:, 0].max())
                seeds = np.flatnonzero(np.linalg.norm(crack - np.array(TIP), axis=1)
                                       <= SEED * a)
                row["path"] = float(geodesic(crack, seeds, LINK * a).max())
                row["branch_x"], row["angle"], row["runs"] = branches(
                    crack[crack[:, 0] > TIP[0]], a)
                row["right"] = row["tip_x"] > WIDTH - LINK * a
        rows.append(row)
    return rows


def speeds(times, values, window):
    """The slope (m/s) of a least-squares line through the (time us, value m) pairs within
    window us of each time; nan where fewer than 3 pairs with a value."""
    t = np.asarray(times)
    v = np.asarray(values, dtype=float)
    out = []
    for now in t:
        pick = (np.abs(t - now) <= window + 1e-9) & np.isfinite(v)
        out.append(np.polyfit(t[pick] * 1e-6, v[pick], 1)[0] if pick.sum() >= 3 else np.nan)
    return out


def run(args, style, out, a):
    """Run one deck in out; (dump file, wall seconds)."""
    dt = step(args, a)
    every = max(1, round(args.every * 1e-6 / dt))
    cmd = [args.lmp, "-in", f"in.branching.{style}", "-var", "a", f"{a:g}", "-var", "dt",
           f"{dt:g}", "-var", "t_end", f"{args.t_end * 1e-6:g}", "-var", "dump", str(every),
           "-var", "sigma", f"{args.sigma * 1e6:g}", "-log", f"log.{style}", "-screen", "none"]
    if style == "nosb" and args.pair:
        cmd += ["-var", "keys", args.pair]
    for var, value in args.nosb_var if style == "nosb" else args.lps_var:
        cmd += ["-var", var, value]
    start = time.time()
    proc = subprocess.run(cmd, cwd=out, capture_output=True, text=True)
    wall = time.time() - start
    if proc.returncode:
        log = out / f"log.{style}"
        tail = log.read_text().splitlines()[-5:] if log.exists() else []
        sys.exit(f"branching.py: {' '.join(cmd)} failed (exit {proc.returncode}):\n"
                 + "\n".join(tail) + proc.stderr[-500:])
    return out / f"dump.branching.{style}", wall


def summary(rows):
    """{branched, branch_x and angle at the first frame with branches (None, nan without), time
    of that frame (us), the largest tip-x and path speed (m/s), the time (us) the crack reaches
    the right edge (None if it does not)}."""
    first = next((r for r in rows if r["branch_x"] is not None), None)
    speeds_x = [r["v_x"] for r in rows if np.isfinite(r["v_x"])]
    speeds_path = [r["v_path"] for r in rows if np.isfinite(r["v_path"])]
    return {"branched": first is not None, "branch_x": first["branch_x"] if first else None,
            "angle": first["angle"] if first else float("nan"),
            "branch_time": first["time"] if first else None,
            "v_x": max(speeds_x, default=float("nan")),
            "v_path": max(speeds_path, default=float("nan")),
            "right": next((r["time"] for r in rows if r["right"]), None)}


def analyse(dump, a, dt, window):
    """measure() of a dump with the speeds v_x and v_path (m/s) added to each frame."""
    rows = measure(dump, a, dt)
    times = [r["time"] for r in rows]
    tip = [r["tip_x"] for r in rows]
    path = [r["path"] if r["path"] > 0 else np.nan for r in rows]
    for r, vx, vp in zip(rows, speeds(times, tip, window), speeds(times, path, window)):
        r["v_x"], r["v_path"] = vx, vp
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=str(ROOT / "build" / "lmp"), help="LAMMPS with the plugin")
    ap.add_argument("--spacing", type=float, default=1.0, help="lattice spacing in mm")
    ap.add_argument("--styles", nargs="+", default=["nosb", "lps"], choices=["lps", "nosb"])
    ap.add_argument("--pair", default="", help="keywords for peri/nosb's pair_coeff (-var keys)")
    ap.add_argument("--nosb-var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a -var for the peri/nosb run only (repeat)")
    ap.add_argument("--lps-var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a -var for the peri/lps run only (repeat)")
    ap.add_argument("--sigma", type=float, default=12.0, help="the tension (MPa)")
    ap.add_argument("--t-end", type=float, default=46.0, help="simulated time (us)")
    ap.add_argument("--every", type=float, default=1.0, help="dump interval (us)")
    ap.add_argument("--window", type=float, default=2.0,
                    help="half width (us) of the speed's least-squares window")
    ap.add_argument("--step", type=float, help="time step in ns (default 25 per mm of spacing)")
    ap.add_argument("--times", type=float, nargs="+", default=[16.0, 26.0, 36.0, 46.0],
                    help="times (us) of the pictures")
    ap.add_argument("--out", help="the working folder (default frames/branching-<spacing>mm)")
    ap.add_argument("--pictures", action="store_true", help="draw the damage maps")
    ap.add_argument("--reuse", action="store_true",
                    help="measure the dumps already in --out instead of running the decks")
    args = ap.parse_args(argv)
    args.lmp = str(Path(args.lmp).resolve())
    a = args.spacing * 1e-3
    dt = step(args, a)
    out = Path(args.out) if args.out else HERE / "frames" / f"branching-{args.spacing:g}mm"
    out.mkdir(parents=True, exist_ok=True)
    for name in FILES:
        shutil.copy(HERE / name, out / name)
    results = {}
    for style in args.styles:
        if args.reuse:
            dump, wall = out / f"dump.branching.{style}", float("nan")
        else:
            dump, wall = run(args, style, out, a)
        results[style] = (dump, wall, analyse(dump, a, dt, args.window))
    print(f"Dynamic crack branching plate, spacing {args.spacing:g} mm, step {dt * 1e9:g} ns, "
          f"sigma {args.sigma:g} MPa, peri/nosb keywords: {args.pair or '(the deck default)'}")
    print(f"{'style':>5s} {'t (us)':>6s} {'tip x':>6s} {'path':>6s} {'v x':>6s} {'v path':>6s} "
          f"{'runs':>4s} {'branch x':>8s} {'angle':>6s} {'off-path':>8s}")
    for style in args.styles:
        for r in results[style][2]:
            bx = f"{r['branch_x'] * 1e3:8.1f}" if r["branch_x"] is not None else f"{'-':>8s}"
            print(f"{style:>5s} {r['time']:6.1f} {r['tip_x'] * 1e3:6.1f} {r['path'] * 1e3:6.1f} "
                  f"{r['v_x']:6.0f} {r['v_path']:6.0f} {r['runs']:4d} {bx} {r['angle']:6.1f} "
                  f"{r['off_path']:8.4f}")
    print(f"{'style':>5s} {'branched':>8s} {'at (us)':>7s} {'branch x':>8s} {'angle':>6s} "
          f"{'v x max':>7s} {'v path max':>10s} {'right edge (us)':>15s} {'wall (s)':>8s}")
    for style in args.styles:
        dump, wall, rows = results[style]
        s = summary(rows)
        nan = float("nan")
        print(f"{style:>5s} {'yes' if s['branched'] else 'no':>8s} "
              f"{s['branch_time'] if s['branched'] else nan:7.1f} "
              f"{s['branch_x'] * 1e3 if s['branched'] else nan:8.1f} {s['angle']:6.1f} "
              f"{s['v_x']:7.0f} {s['v_path']:10.0f} "
              f"{s['right'] if s['right'] is not None else nan:15.1f} {wall:8.0f}")
    if args.pictures:
        picture = damage_maps.draw([(f"peri/{s}", results[s][0]) for s in args.styles],
                                   args.times, dt, a, (-0.002, 0.102, -0.002, 0.042), (3.0, 1.5),
                                   out / f"branching-{args.spacing:g}mm-{args.sigma:g}MPa.png")
        print(f"pictures: {picture}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
