#!/usr/bin/env python3
"""Cracks from notch tips in a LAMMPS `dump custom` with positions and a damage column: per tip
whether a crack left it, its length, its angle to the notch and its width in particles, and how
much damage lies off the cracks.

    python3 tools/crack_path.py dump.kalthoff.lps --tip 0.075 0.05 --tip 0.125 0.05 \\
        --direction 0 1 --scale 1000 --unit mm

For every frame of the dump (or only the last, --last), on the positions of the dump's first
frame (the reference configuration, where an opened crack and flying fragments stay in place;
the positions of each frame with --current): the mid-plane layer (the particles
within half a spacing of the lattice plane nearest to the median of the coordinate along
--normal, default z) and, in it, the damaged particles (damage > --threshold, default 0.4).
Damaged particles closer than 1.5 spacings (a lattice's nearest and diagonal neighbours) are
connected; a tip's path is every connected set that has a damaged particle within --seed
spacings of the tip (default 2.5: the tips of a moving notch move). Per tip:
- crack: yes when some particle of the path lies --min-length spacings or more from the tip
  (default 6, two horizons of 3 spacings);
- length: the largest distance of a path particle from the tip;
- angle: between the notch direction (--direction, pointing from the notch's mouth to its
  tip) and the line fitted (total least squares) through the main branch: the path particles
  farther than --seed and at most --fit-length (default 20 spacings) from the tip that lie
  within 15 degrees, seen from the tip, of the direction holding the most of them (a path that
  forks or meets other damage is fitted along its main branch; once a frame of the file has a
  crack at the tip, later frames look for that direction within 30 degrees of the last one
  found, so a crack is followed, not replaced by damage that joins it later; dump often enough
  for that); the line is oriented away from the tip; 0 degrees is straight ahead, 90 square to
  the notch; dx dy: that direction as a unit vector;
- width: the median, over the main branch cut into pieces one spacing long along the line,
  of the number of its particles in a piece (a band w spacings wide holds about w per piece).
For the layer: off-path, the fraction of its particles that are damaged but on no tip's path
(diffuse damage, and cracks that did not start at a tip); d>0.1, the fraction with damage above
0.1; mean, the mean damage of the layer, and of all particles of the frame (mean all).
The spacing is --spacing or the median distance of a particle to its nearest neighbour.
Lengths are printed times --scale in --unit (default 1, the dump's units). Exit status 0, 1 when
a file cannot be read. Needs numpy; reads the dump with tools/dump_to_vtu.py's reader.
"""
import argparse
import sys
from collections import deque
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from dump_to_vtu import position_columns, read_dump  # noqa: E402

AXES = "xyz"


def spacing(points, samples=400):
    """Median distance to the nearest neighbour of up to `samples` evenly picked particles."""
    pick = points[np.linspace(0, len(points) - 1, min(samples, len(points))).astype(int)]
    d2 = ((pick[:, None, :] - points[None, :, :]) ** 2).sum(axis=2)
    d2[d2 == 0.0] = np.inf
    return float(np.sqrt(np.median(d2.min(axis=1))))


def mid_layer(points, normal, h):
    """Mask of the particles within h/2 of the lattice plane nearest to the median along
    `normal` (the plane of the particle nearest to the median)."""
    coord = points[:, normal]
    plane = coord[np.argmin(np.abs(coord - np.median(coord)))]
    return np.abs(coord - plane) <= 0.5 * h


def components(points, link):
    """Label per point of the sets connected by distances below `link` (2D points)."""
    cells = {}
    keys = np.floor(points / link).astype(int)
    for k, key in enumerate(map(tuple, keys)):
        cells.setdefault(key, []).append(k)
    label = np.full(len(points), -1)
    current = 0
    for start in range(len(points)):
        if label[start] >= 0:
            continue
        label[start] = current
        queue = deque([start])
        while queue:
            k = queue.popleft()
            cx, cy = keys[k]
            for dx in (-1, 0, 1):
                for dy in (-1, 0, 1):
                    for j in cells.get((cx + dx, cy + dy), ()):
                        if label[j] < 0 and ((points[j] - points[k]) ** 2).sum() < link * link:
                            label[j] = current
                            queue.append(j)
        current += 1
    return label


def fit_direction(points, tip):
    """Unit direction of the total-least-squares line through points, oriented away from tip."""
    centre = points.mean(axis=0)
    _, _, vt = np.linalg.svd(points - centre, full_matrices=False)
    direction = vt[0]
    if np.dot(centre - tip, direction) < 0:
        direction = -direction
    return direction


def turn(a, b):
    """Signed angle in degrees from 2D direction(s) b to a (counterclockwise positive)."""
    return np.degrees(np.arctan2(b[0] * a[..., 1] - b[1] * a[..., 0], a @ b))


def main_branch(points, tip, notch, half_window=15.0, previous=None):
    """The points within half_window degrees (seen from tip) of the direction that holds the
    most of them (of the directions within 2 half_window of `previous` when given): one branch
    of a path that forks or meets other damage."""
    if len(points) == 0:
        return points
    angle = turn(points - tip, notch)
    centres = np.arange(-180.0, 180.0, 1.0)
    if previous is not None:
        ahead = turn(np.asarray(previous, dtype=float), notch)
        centres = centres[np.abs((centres - ahead + 180.0) % 360.0 - 180.0) <= 2 * half_window]
    off = np.abs((angle[None, :] - centres[:, None] + 180.0) % 360.0 - 180.0)
    best = centres[np.argmax((off <= half_window).sum(axis=1))]
    return points[np.abs((angle - best + 180.0) % 360.0 - 180.0) <= half_window]


def analyse(points, damage, tips, direction, normal=2, h=None, threshold=0.4, seed=2.5,
            min_length=6.0, fit_length=20.0, previous=None):
    """(per-tip dicts, layer dict) for one frame; points n x 3, damage n, tips k x 2 in the
    layer's two in-plane coordinates, direction the notch direction in those coordinates; seed,
    min_length and fit_length in spacings; previous: per tip the crack direction found in an
    earlier frame, or None (the branch is then looked for within 30 degrees of it)."""
    points = np.asarray(points, dtype=float)
    damage = np.asarray(damage, dtype=float)
    h = h or spacing(points)
    layer = mid_layer(points, normal, h)
    u, v = [k for k in range(3) if k != normal]
    plane = points[layer][:, [u, v]]
    dlayer = damage[layer]
    hot = np.flatnonzero(dlayer > threshold)
    label = components(plane[hot], 1.5 * h) if len(hot) else np.array([], dtype=int)
    notch = np.asarray(direction, dtype=float)
    notch = notch / np.linalg.norm(notch)
    on_path = np.zeros(len(hot), dtype=bool)
    results = []
    for k, tip in enumerate(np.asarray(tips, dtype=float).reshape(-1, 2)):
        dist = np.linalg.norm(plane[hot] - tip, axis=1) if len(hot) else np.array([])
        seeds = set(label[dist <= seed * h])
        path = np.isin(label, list(seeds)) if seeds else np.zeros(len(hot), dtype=bool)
        on_path |= path
        row = {"tip": tuple(tip), "crack": False, "length": 0.0, "angle": float("nan"),
               "dir": (float("nan"), float("nan")), "width": 0.0, "particles": int(path.sum())}
        if path.any():
            row["length"] = float(dist[path].max())
            row["crack"] = row["length"] >= min_length * h
            near = main_branch(plane[hot][path & (dist > seed * h) & (dist <= fit_length * h)],
                               tip, notch, previous=previous[k] if previous else None)
            if len(near) >= 3:
                line = fit_direction(near, tip)
                row["dir"] = (float(line[0]), float(line[1]))
                row["angle"] = float(np.degrees(np.arccos(np.clip(np.dot(line, notch), -1, 1))))
                s = (near - tip) @ line
                counts = np.bincount(np.floor(np.maximum(s, 0.0) / h).astype(int))
                row["width"] = float(np.median(counts[counts > 0]))
        results.append(row)
    stats = {"layer": int(layer.sum()), "spacing": h,
             "off_path": float((~on_path).sum() / max(len(dlayer), 1)),
             "touched": float((dlayer > 0.1).mean()) if len(dlayer) else 0.0,
             "mean_layer": float(dlayer.mean()) if len(dlayer) else 0.0,
             "mean_all": float(damage.mean()) if len(damage) else 0.0}
    return results, stats


def frames(path, column, current=False):
    """[(step, positions n x 3, damage n)] of a dump file; the positions of the first frame
    (matched by the id column) unless current."""
    out = []
    reference = None
    for step, columns, rows in read_dump(path):
        if column not in columns:
            raise ValueError(f"{path}: no column {column} (columns: {' '.join(columns)})")
        table = np.array(rows, dtype=float).reshape(len(rows), len(columns))
        points = table[:, position_columns(columns)]
        if not current:
            if "id" not in columns:
                raise ValueError(f"{path}: no id column to match the first frame's positions")
            ids = table[:, columns.index("id")].astype(int)
            if reference is None:
                reference = dict(zip(ids, points))
            missing = [i for i in ids if i not in reference]
            if missing:
                raise ValueError(f"{path}: step {step}: {len(missing)} ids not in the first "
                                 "frame")
            points = np.array([reference[i] for i in ids])
        out.append((step, points, table[:, columns.index(column)]))
    return out


def table(rows, scale=1.0, unit=""):
    """The printed table: one line per (label, step, tip)."""
    unit = f" ({unit})" if unit else ""
    lines = [f"{'run':>12s} {'step':>7s} {'tip':>3s} {'crack':>5s} {'length' + unit:>12s} "
             f"{'angle':>6s} {'dx':>6s} {'dy':>6s} {'width':>5s} {'off-path':>8s} "
             f"{'d>0.1':>6s} {'mean':>6s} {'mean all':>8s}"]
    for label, step, tips, stats in rows:
        for k, tip in enumerate(tips, 1):
            lines.append(
                f"{label:>12s} {step:7d} {k:3d} {'yes' if tip['crack'] else 'no':>5s} "
                f"{tip['length'] * scale:12.4g} {tip['angle']:6.1f} {tip['dir'][0]:6.2f} "
                f"{tip['dir'][1]:6.2f} {tip['width']:5.1f} {stats['off_path']:8.4f} "
                f"{stats['touched']:6.3f} {stats['mean_layer']:6.3f} {stats['mean_all']:8.4f}")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dumps", nargs="+", help="dump custom files (x y z and the damage column)")
    ap.add_argument("--column", default="v_damage", help="the damage column (default v_damage)")
    ap.add_argument("--tip", type=float, nargs=2, action="append", required=True,
                    metavar=("U", "V"), help="a notch tip in the layer's coordinates (repeat)")
    ap.add_argument("--direction", type=float, nargs=2, default=(0.0, 1.0), metavar=("DU", "DV"),
                    help="the notch direction, mouth to tip (default 0 1)")
    ap.add_argument("--normal", default="z", choices=list(AXES), help="the layer's normal")
    ap.add_argument("--spacing", type=float, help="the lattice spacing (default: measured)")
    ap.add_argument("--threshold", type=float, default=0.4)
    ap.add_argument("--seed", type=float, default=2.5, help="spacings from a tip (default 2.5)")
    ap.add_argument("--min-length", type=float, default=6.0, help="spacings (default 6)")
    ap.add_argument("--fit-length", type=float, default=20.0, help="spacings (default 20)")
    ap.add_argument("--last", action="store_true", help="only the last frame of each file")
    ap.add_argument("--current", action="store_true",
                    help="the positions of each frame (default: those of the first frame)")
    ap.add_argument("--labels", nargs="+", help="a name per file (default: the file names)")
    ap.add_argument("--scale", type=float, default=1.0, help="length factor for the table")
    ap.add_argument("--unit", default="", help="the unit of the scaled lengths")
    args = ap.parse_args(argv)
    labels = args.labels or [Path(d).name for d in args.dumps]
    if len(labels) != len(args.dumps):
        print("crack_path.py: --labels needs one label per dump file", file=sys.stderr)
        return 1
    rows = []
    for path, label in zip(args.dumps, labels):
        try:
            series = frames(path, args.column, args.current)
        except (ValueError, OSError) as e:
            print(f"crack_path.py: {e}", file=sys.stderr)
            return 1
        previous = [None] * len(args.tip)
        for step, points, damage in series[-1:] if args.last else series:
            tips, stats = analyse(points, damage, args.tip, args.direction,
                                  AXES.index(args.normal), args.spacing, args.threshold,
                                  args.seed, args.min_length, args.fit_length, previous)
            previous = [t["dir"] if t["crack"] else p for t, p in zip(tips, previous)]
            rows.append((label, step, tips, stats))
    print(table(rows, args.scale, args.unit))
    return 0


if __name__ == "__main__":
    sys.exit(main())
