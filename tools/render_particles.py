#!/usr/bin/env python3
"""Picture of a slice of particles from LAMMPS `dump custom` files, coloured by a column: a
damage or stress map of a solid, several runs side by side.

    python3 tools/render_particles.py dump.atoms --column c_s[1] -o damage.png
    python3 tools/render_particles.py dump.nosb dump.lps --column v_damage --slice z \\
        --labels peri/nosb peri/lps --range 0 1 -o damage.png

Of each file the last frame is drawn (or the frame at the timestep that --steps gives for it):
the particles within half a --thickness of the plane AXIS = --at (default: the median of the
particles' coordinates along AXIS; thickness default: the spacing, the median distance of a
particle to its nearest neighbour, so that one lattice plane is taken), as squares of that size
in the plane's two other coordinates, coloured by the column on one colour scale for all files
(--range, default the smallest and largest value in the slices), in --window (default: around
every particle of the slices); one picture per file, in --rows rows. Prints per file how many
particles are in the slice and the column's range there.
Pictures are W x H inches at --dpi (default 8 x 4.5 at 100: 800 x 450 pixels). Needs numpy and
matplotlib; reads the dumps with tools/dump_to_vtu.py's reader.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from dump_to_vtu import position_columns, read_dump  # noqa: E402

AXES = "xyz"


def last_frame(path, column, step=None):
    """(positions n x 3, values n, step) of the last frame of a dump file, or of the frame at
    timestep `step`."""
    frames = read_dump(path)
    if step is not None:
        frames = [f for f in frames if f[0] == step]
        if not frames:
            raise ValueError(f"{path}: no frame at step {step}")
    step, columns, rows = frames[-1]
    if column not in columns:
        raise ValueError(f"{path}: no column {column} (columns: {' '.join(columns)})")
    table = np.array(rows, dtype=float).reshape(len(rows), len(columns))
    return table[:, position_columns(columns)], table[:, columns.index(column)], step


def spacing(points):
    """The median distance of a particle to its nearest neighbour (the lattice constant of a
    lattice, whatever fragments flew off)."""
    nearest = []
    for start in range(0, len(points), 512):
        chunk = points[start:start + 512]
        d2 = ((chunk[:, None, :] - points[None, :, :]) ** 2).sum(axis=2)
        d2[np.arange(len(chunk)), start + np.arange(len(chunk))] = np.inf
        nearest.append(d2.min(axis=1))
    return float(np.sqrt(np.median(np.concatenate(nearest))))


def in_slice(points, axis, at, thickness):
    return np.abs(points[:, axis] - at) <= 0.5 * thickness


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dumps", nargs="+", help="dump custom files (x y z and the column)")
    ap.add_argument("--column", required=True, help="the colouring column (c_s[1], v_damage, ...)")
    ap.add_argument("--slice", default="z", choices=list(AXES), help="the axis normal to the "
                    "slice (default z)")
    ap.add_argument("--at", type=float, help="the slice's position along the axis")
    ap.add_argument("--thickness", type=float, help="the slice's thickness")
    ap.add_argument("--window", type=float, nargs=4, metavar=("ULO", "UHI", "VLO", "VHI"),
                    help="the region of the plane shown, in its two coordinates (x y for a z "
                    "slice; default: all particles of the slices)")
    ap.add_argument("--steps", type=int, nargs="+", help="a timestep per file: the frame drawn "
                    "(default: the last)")
    ap.add_argument("--rows", type=int, default=1, help="the pictures in this many rows")
    ap.add_argument("--labels", nargs="+", help="a title per file (default: the file names)")
    ap.add_argument("--range", type=float, nargs=2, metavar=("LO", "HI"),
                    help="column values at the ends of the colour map")
    ap.add_argument("--cmap", default="inferno", help="colour map")
    ap.add_argument("--label", help="colour bar label (default: the column's name)")
    ap.add_argument("--title", help="title above the pictures")
    ap.add_argument("--size", type=float, nargs=2, default=(8.0, 4.5), metavar=("W", "H"))
    ap.add_argument("--dpi", type=int, default=100)
    ap.add_argument("-o", "--output", default="slice.png", help="the picture (.png, .svg, .pdf)")
    args = ap.parse_args(argv)
    labels = args.labels or [Path(d).name for d in args.dumps]
    if len(labels) != len(args.dumps):
        print("render_particles.py: --labels needs one label per dump file", file=sys.stderr)
        return 1
    if args.steps and len(args.steps) != len(args.dumps):
        print("render_particles.py: --steps needs one step per dump file", file=sys.stderr)
        return 1
    steps = args.steps or [None] * len(args.dumps)
    try:
        frames = [last_frame(d, args.column, n) for d, n in zip(args.dumps, steps)]
    except (ValueError, OSError) as e:
        print(f"render_particles.py: {e}", file=sys.stderr)
        return 1
    axis = AXES.index(args.slice)
    u, v = [k for k in range(3) if k != axis]
    slices = []
    for path, (points, values, step) in zip(args.dumps, frames):
        width = args.thickness or spacing(points)
        at = args.at if args.at is not None else float(np.median(points[:, axis]))
        keep = in_slice(points, axis, at, width)
        if not keep.any():
            print(f"render_particles.py: {path}: no particle within {width / 2:g} of "
                  f"{args.slice} = {at:g}", file=sys.stderr)
            return 1
        slices.append((points[keep], values[keep], width, step))

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import Normalize

    lo, hi = args.range or (min(s[1].min() for s in slices), max(s[1].max() for s in slices))
    norm = Normalize(lo, hi if hi > lo else lo + 1.0)
    cmap = plt.get_cmap(args.cmap)
    rows = max(1, min(args.rows, len(slices)))
    cols = -(-len(slices) // rows)
    fig, grid = plt.subplots(rows, cols, figsize=args.size, dpi=args.dpi, squeeze=False)
    axes = grid.reshape(1, -1)
    for ax in axes[0][len(slices):]:
        ax.set_visible(False)
    every = np.concatenate([s[0] for s in slices])
    pad = max(s[2] for s in slices)
    limits = ([args.window[:2], args.window[2:]] if args.window else
              [(every[:, k].min() - pad, every[:, k].max() + pad) for k in (u, v)])
    for ax, label, (points, values, width, step) in zip(axes[0], labels, slices):
        # one square of the slice's thickness (the spacing) per particle, centred on it
        h = 0.5 * width
        corners = np.array([[-h, -h], [h, -h], [h, h], [-h, h]])
        squares = points[:, [u, v]][:, None, :] + corners[None, :, :]
        ax.add_collection(PolyCollection(squares, facecolors=cmap(norm(values)),
                                         edgecolors="none"))
        ax.set_xlim(*limits[0])
        ax.set_ylim(*limits[1])
        ax.set_aspect("equal")
        ax.set_xlabel(AXES[u])
        ax.set_ylabel(AXES[v])
        ax.set_title(f"{label}, step {step}")
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=list(axes[0]), shrink=0.8,
                 label=args.label or args.column)
    if args.title:
        fig.suptitle(args.title)
    fig.savefig(args.output, facecolor="white")
    plt.close(fig)
    for path, (points, values, width, step) in zip(args.dumps, slices):
        print(f"render_particles.py: {path}: step {step}, {len(values)} particles in the slice, "
              f"{args.column} from {values.min():g} to {values.max():g}")
    print(f"render_particles.py: {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
