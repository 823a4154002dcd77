#!/usr/bin/env python3
"""Render a frame of a mesh dump (dump nosb/mesh: .vtp, .vtu or .obj) as a shaded surface.

    python3 tools/render_mesh.py frames/cloth.300.vtp -o cloth.png
    python3 tools/render_mesh.py frames/cloth.300.vtp --field c_s[4] --label "von Mises (Pa)"
    python3 tools/render_mesh.py frames/cloth.300.obj --elev 20 --azim -60 --zoom 1.3

Every triangle is one flat polygon (matplotlib's Poly3DCollection, drawn back to front) whose
colour is the base colour, or the colour map's colour of the field averaged over its three
vertices, times Lambert shading: ambient + (1 - ambient) |n . l| with n the triangle's unit
normal and l the light direction (both sides of a cloth lit alike). The light is given in the
camera's frame (right, up, towards the viewer), so it stays where it is when the camera moves.
Each polygon's edge is drawn in its own colour and without antialiasing: neither the background
nor blended edges show along the seams between triangles (no moire on flat regions). Needs numpy and matplotlib only (the files are
read here: the ASCII VTK XML that dump nosb/mesh writes, and OBJ v and f lines).
"""
import argparse
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np


def read_vtk(path):
    """Points (n x 3), triangles (m x 3, 0-based) and point arrays {name: values} of an ASCII
    .vtp or .vtu file."""
    root = ET.parse(path).getroot()
    piece = root.find(f"{root.get('type')}/Piece")
    if piece is None:
        raise ValueError(f"{path}: no {root.get('type')} piece")

    def values(node):
        if node.get("format", "ascii") != "ascii":
            raise ValueError(f"{path}: only ASCII arrays are read")
        return np.array(node.text.split(), dtype=float)

    points = values(piece.find("Points/DataArray")).reshape(-1, 3)
    cells = piece.find("Polys") if piece.find("Polys") is not None else piece.find("Cells")
    arrays = {a.get("Name"): values(a) for a in cells}
    offsets = arrays["offsets"].astype(int)
    if np.any(np.diff(np.concatenate([[0], offsets])) != 3):
        raise ValueError(f"{path}: cells other than triangles")
    triangles = arrays["connectivity"].astype(int).reshape(-1, 3)
    data = piece.find("PointData")
    fields = {a.get("Name"): values(a) for a in data} if data is not None else {}
    return points, triangles, fields


def read_obj(path):
    """Points and triangles (polygons split into fans) of an OBJ file; no fields."""
    points, triangles = [], []
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "v":
            points.append([float(w) for w in words[1:4]])
        elif words[0] == "f":
            idx = [int(w.split("/")[0]) for w in words[1:]]
            idx = [i - 1 if i > 0 else len(points) + i for i in idx]
            triangles += [[idx[0], idx[k], idx[k + 1]] for k in range(1, len(idx) - 1)]
    return np.array(points, float), np.array(triangles, int).reshape(-1, 3), {}


def read_mesh(path):
    suffix = Path(path).suffix
    if suffix in (".vtp", ".vtu"):
        return read_vtk(path)
    if suffix == ".obj":
        return read_obj(path)
    raise ValueError(f"{path}: not a .vtp, .vtu or .obj file")


def camera_frame(elev, azim):
    """Unit vectors (right, up, towards the viewer) of matplotlib's camera at elev, azim
    (degrees)."""
    e, a = np.radians(elev), np.radians(azim)
    toward = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    right = np.array([-np.sin(a), np.cos(a), 0.0])
    return right, np.cross(toward, right), toward


def lambert(points, triangles, light, ambient):
    """ambient + (1 - ambient) |n . l| per triangle (l a unit vector)."""
    tri = points[triangles]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(n, axis=1)
    n = n / np.where(length > 0, length, 1.0)[:, None]
    return ambient + (1.0 - ambient) * np.abs(n @ light)


def render(points, triangles, fields, args):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors as mcolors
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    right, up, toward = camera_frame(args.elev, args.azim)
    light = args.light[0] * right + args.light[1] * up + args.light[2] * toward
    light /= np.linalg.norm(light)
    shade = lambert(points, triangles, light, args.ambient)

    mappable = None
    if args.field:
        if args.field not in fields:
            raise ValueError(f"no field {args.field} in the file (fields: "
                             f"{', '.join(fields) or 'none'})")
        per_face = fields[args.field][triangles].mean(axis=1)
        lo, hi = args.range if args.range else (per_face.min(), per_face.max())
        norm = mcolors.Normalize(lo, hi if hi > lo else lo + 1.0)
        cmap = plt.get_cmap(args.cmap)
        base = cmap(norm(per_face))[:, :3]
        mappable = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    else:
        base = np.tile(mcolors.to_rgb(args.color), (len(triangles), 1))
    rgb = np.clip(base * shade[:, None], 0.0, 1.0)

    fig = plt.figure(figsize=args.size, dpi=args.dpi)
    ax = fig.add_subplot(projection="3d")
    faces = Poly3DCollection(points[triangles], facecolors=rgb, edgecolors=rgb,
                             linewidths=0.3, antialiased=False)
    ax.add_collection3d(faces)
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, half = (lo + hi) / 2, max(hi - lo) / 2
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1), zoom=args.zoom)
    ax.view_init(elev=args.elev, azim=args.azim)
    ax.set_axis_off()
    if args.title:
        ax.set_title(args.title)
    if mappable is not None:
        fig.colorbar(mappable, ax=ax, shrink=0.6, label=args.label or args.field)
    fig.savefig(args.output, bbox_inches="tight", facecolor="white")
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("file", help="a .vtp, .vtu or .obj frame")
    ap.add_argument("-o", "--output", help="picture (.png, .svg, .pdf; default FILE.png)")
    ap.add_argument("--elev", type=float, default=25.0, help="camera elevation (degrees)")
    ap.add_argument("--azim", type=float, default=-60.0, help="camera azimuth (degrees)")
    ap.add_argument("--zoom", type=float, default=1.0, help="> 1 brings the mesh closer")
    ap.add_argument("--light", type=float, nargs=3, default=(0.4, 0.7, 1.0),
                    metavar=("RIGHT", "UP", "TOWARD"),
                    help="light direction in the camera's frame")
    ap.add_argument("--ambient", type=float, default=0.35, help="light without direction (0-1)")
    ap.add_argument("--color", default="#dcc08f", help="surface colour without --field")
    ap.add_argument("--field", help="colour by this point array of a .vtp/.vtu file")
    ap.add_argument("--cmap", default="viridis", help="colour map of --field")
    ap.add_argument("--range", type=float, nargs=2, metavar=("LO", "HI"),
                    help="field values at the ends of the colour map (default: min, max)")
    ap.add_argument("--label", help="colour bar label (default: the field's name)")
    ap.add_argument("--title", help="title above the picture")
    ap.add_argument("--size", type=float, nargs=2, default=(6.0, 5.0), metavar=("W", "H"),
                    help="figure size (inches)")
    ap.add_argument("--dpi", type=int, default=150)
    args = ap.parse_args(argv)
    args.output = args.output or str(Path(args.file).with_suffix(".png"))
    try:
        points, triangles, fields = read_mesh(args.file)
        if len(triangles) == 0:
            raise ValueError(f"{args.file}: no triangles")
        render(points, triangles, fields, args)
    except (ValueError, OSError, ET.ParseError) as e:
        print(f"render_mesh.py: {e}", file=sys.stderr)
        return 1
    print(f"render_mesh.py: {args.output} ({len(triangles)} triangles)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
