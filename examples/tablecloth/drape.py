#!/usr/bin/env python3
"""Drape of a tablecloth from a LAMMPS dump: drape coefficient and overhang profile.

    python3 drape.py cloth_ci.obj dump.ci.300 [--half 0.4] [--top 0.0] [--svg drape.svg]

Inputs: the cloth's mesh (the OBJ file read_mesh read, centred at the origin in z = 0: its
triangles and the reference positions of the vertices, vertex k being atom ID first-id + k) and
a `dump custom` text file with the columns id x y z (the last frame of the file is used), the
table's half-width (a square table centred on the z axis) and the height of its top.

Outputs (on standard output; --json writes the same numbers as one JSON object):
  * the drape coefficient, Cusick-style, (A_p - A_t) / (A_c - A_t): A_p the area of the
    cloth's projection on the plane of the table (the union of its projected triangles,
    overlapping folds counted once), A_t the table's area, A_c the cloth's (flat) area. 1 for
    a cloth that stays flat, 0 for one that hangs straight down from the table's edges.
    A_p comes from rasterizing the projected triangles on a square grid of cells of --res
    (default a quarter of the mean edge of the mesh; a cell counts when its centre lies in a
    triangle); the convex hull of the projected vertices gives a second value, which also
    counts the gaps between folds (an upper bound of the first);
  * the overhang profile: for each of the cloth's four sides (its boundary vertices, by their
    reference position), the drop below the table top, top - z, against the reference
    position s along the side (s from -L/2 to L/2), in --bins bins: mean over the four sides,
    smallest and largest;
  * --svg FILE: a picture, the projection seen from above (table, cloth triangles, cloth
    outline) next to the overhang profile of every side.
Python standard library only.
"""
from __future__ import annotations

import argparse
import json
import math
import sys


def read_obj(path):
    """Vertices [(x, y, z)] and triangles [(i, j, k)] (0-based) of an OBJ file (v and f lines;
    polygons as fans, as read_mesh reads them)."""
    verts, tris = [], []
    with open(path) as fh:
        for line in fh:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append(tuple(float(c) for c in w[1:4]))
            elif w[0] == "f":
                idx = [int(t.split("/")[0]) for t in w[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


def read_dump(path):
    """{atom id: (x, y, z)} of the last frame of a dump custom text file with id x y z."""
    frames, cols, atoms, mode = [], None, None, None
    with open(path) as fh:
        for line in fh:
            if line.startswith("ITEM:"):
                mode = line.split()[1]
                if mode == "ATOMS":
                    cols = line.split()[2:]
                    atoms = {}
                    frames.append(atoms)
                continue
            if mode == "ATOMS":
                w = line.split()
                rec = dict(zip(cols, w))
                atoms[int(rec["id"])] = (float(rec["x"]), float(rec["y"]), float(rec["z"]))
    if not frames:
        sys.exit(f"drape.py: {path}: no ITEM: ATOMS section (expected a dump custom file "
                 "with the columns id x y z)")
    return frames[-1]


def cross2(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def hull_area(points):
    """Area of the convex hull of 2d points (monotone chain)."""
    pts = sorted(set(points))
    if len(pts) < 3:
        return 0.0
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross2(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross2(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    hull = lower[:-1] + upper[:-1]
    return 0.5 * abs(sum(hull[i][0] * hull[i - 1][1] - hull[i - 1][0] * hull[i][1]
                         for i in range(len(hull))))


def raster_area(points, tris, res):
    """Area of the union of the 2d triangles (cells of side res whose centre lies in one)."""
    cells = set()
    for i, j, k in tris:
        a, b, c = points[i], points[j], points[k]
        det = cross2(a, b, c)
        if det == 0.0:
            continue
        x0 = math.floor(min(a[0], b[0], c[0]) / res - 0.5)
        x1 = math.ceil(max(a[0], b[0], c[0]) / res - 0.5)
        y0 = math.floor(min(a[1], b[1], c[1]) / res - 0.5)
        y1 = math.ceil(max(a[1], b[1], c[1]) / res - 0.5)
        for ix in range(x0, x1 + 1):
            px = (ix + 0.5) * res
            for iy in range(y0, y1 + 1):
                if (ix, iy) in cells:
                    continue
                p = (px, (iy + 0.5) * res)
                u, v, w = cross2(b, c, p) / det, cross2(c, a, p) / det, cross2(a, b, p) / det
                if u >= 0.0 and v >= 0.0 and w >= 0.0:
                    cells.add((ix, iy))
    return len(cells) * res * res


def boundary_vertices(tris):
    """Vertices on the mesh's boundary (ends of the edges that belong to one triangle)."""
    count = {}
    for t in tris:
        for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(e), max(e))
            count[key] = count.get(key, 0) + 1
    out = set()
    for (i, j), n in count.items():
        if n == 1:
            out.update((i, j))
    return out


def sides(ref, boundary):
    """The boundary vertices of a rectangular cloth by side: {'x+': [(s, vertex)], ...},
    s the reference coordinate along the side; a corner belongs to both its sides."""
    xs = [ref[v][0] for v in boundary]
    ys = [ref[v][1] for v in boundary]
    tol = 1e-6 * max(max(xs) - min(xs), max(ys) - min(ys))
    out = {"x-": [], "x+": [], "y-": [], "y+": []}
    for v in boundary:
        x, y = ref[v][0], ref[v][1]
        if abs(x - min(xs)) < tol:
            out["x-"].append((y, v))
        if abs(x - max(xs)) < tol:
            out["x+"].append((y, v))
        if abs(y - min(ys)) < tol:
            out["y-"].append((x, v))
        if abs(y - max(ys)) < tol:
            out["y+"].append((x, v))
    for key in out:
        out[key].sort()
    return out


def drape(obj, dump, half, top, first_id=1, res=None, bins=12):
    """Everything the script reports, as a dict (see the module's docstring)."""
    ref, tris = read_obj(obj)
    atoms = read_dump(dump)
    missing = [k for k in range(len(ref)) if first_id + k not in atoms]
    if missing:
        sys.exit(f"drape.py: {dump} has no atom ID {first_id + missing[0]} (vertex "
                 f"{missing[0] + 1} of {obj}); {len(missing)} vertices missing (is --first-id "
                 f"{first_id} right?)")
    cur = [atoms[first_id + k] for k in range(len(ref))]
    area_cloth = sum(0.5 * abs(cross2(ref[i], ref[j], ref[k])) for i, j, k in tris)
    edges = [math.dist(ref[t[a]], ref[t[(a + 1) % 3]]) for t in tris for a in range(3)]
    mean_edge = sum(edges) / len(edges)
    res = res or mean_edge / 4.0
    flat = [(p[0], p[1]) for p in cur]
    area_proj = raster_area(flat, tris, res)
    area_hull = hull_area(flat)
    area_table = (2.0 * half) ** 2
    span = area_cloth - area_table
    profile = {}
    by_side = sides(ref, boundary_vertices(tris))
    for key, verts in by_side.items():
        profile[key] = [(s, top - cur[v][2]) for s, v in verts]
    lo = min(s for key in profile for s, _ in profile[key])
    hi = max(s for key in profile for s, _ in profile[key])
    table = []
    for b in range(bins):
        s0, s1 = lo + (hi - lo) * b / bins, lo + (hi - lo) * (b + 1) / bins
        drops = [d for key in profile for s, d in profile[key]
                 if s0 <= s < s1 or (b == bins - 1 and s == s1)]
        if drops:
            table.append({"s": 0.5 * (s0 + s1), "mean": sum(drops) / len(drops),
                          "min": min(drops), "max": max(drops), "n": len(drops)})
    return {
        "vertices": len(ref), "triangles": len(tris), "mean_edge": mean_edge, "res": res,
        "area_cloth": area_cloth, "area_table": area_table, "area_projected": area_proj,
        "area_hull": area_hull,
        "drape_coefficient": (area_proj - area_table) / span,
        "drape_coefficient_hull": (area_hull - area_table) / span,
        "drop_min": min(top - p[2] for p in cur), "drop_max": max(top - p[2] for p in cur),
        "profile": table, "sides": profile, "_flat": flat, "_tris": tris,
        "_outline": {k: [flat[v] for _, v in vs] for k, vs in by_side.items()},
    }


def write_svg(path, r, half, title):
    """Top view (table, projected triangles, outline) and overhang profiles, side by side."""
    size, pad = 360.0, 20.0
    ext = max(max(abs(c) for p in r["_flat"] for c in p), half) * 1.05
    sc = (size / 2 - pad) / ext

    def tx(p):
        return (size / 2 + p[0] * sc, size / 2 - p[1] * sc)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * size:.0f}" '
           f'height="{size + 30:.0f}" font-family="sans-serif" font-size="12">',
           f'<rect width="{2 * size:.0f}" height="{size + 30:.0f}" fill="white"/>',
           f'<text x="10" y="{size + 20:.0f}">{title}</text>']
    a, b = tx((-half, half)), tx((half, -half))
    out.append(f'<rect x="{a[0]:.1f}" y="{a[1]:.1f}" width="{b[0] - a[0]:.1f}" '
               f'height="{b[1] - a[1]:.1f}" fill="#d9c7a0"/>')
    pts = [tx(p) for p in r["_flat"]]
    out.append('<g fill="#4a78c2" fill-opacity="0.25" stroke="none">')
    for i, j, k in r["_tris"]:
        out.append(f'<path d="M{pts[i][0]:.1f} {pts[i][1]:.1f}L{pts[j][0]:.1f} '
                   f'{pts[j][1]:.1f}L{pts[k][0]:.1f} {pts[k][1]:.1f}Z"/>')
    out.append("</g>")
    for key, poly in r["_outline"].items():
        d = "M" + "L".join(f"{tx(p)[0]:.1f} {tx(p)[1]:.1f}" for p in poly)
        out.append(f'<path d="{d}" fill="none" stroke="#1b3d73" stroke-width="1.5"/>')
    # the profile panel: drop below the table top (down) against s
    x0, y0, w, h = size + 50, pad, size - 70, size - 2 * pad
    smax = max(abs(s) for k in r["sides"] for s, _ in r["sides"][k]) or 1.0
    dmax = max(max(d for k in r["sides"] for _, d in r["sides"][k]), 1e-3) * 1.05
    out.append(f'<rect x="{x0}" y="{y0}" width="{w}" height="{h}" fill="none" stroke="black"/>')
    out.append(f'<text x="{x0}" y="{y0 - 5}">drop below table top, 0 to {dmax:.3g} m, '
               f'against s (-{smax:.2g} to {smax:.2g} m)</text>')
    colours = {"x-": "#c0392b", "x+": "#27ae60", "y-": "#8e44ad", "y+": "#e67e22"}
    for key, prof in r["sides"].items():
        d = "M" + "L".join(f"{x0 + (s + smax) / (2 * smax) * w:.1f} {y0 + dd / dmax * h:.1f}"
                           for s, dd in prof)
        out.append(f'<path d="{d}" fill="none" stroke="{colours[key]}" stroke-width="1.2"/>')
    out.append("</svg>")
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("obj", help="the cloth's mesh (OBJ) as read by read_mesh")
    ap.add_argument("dump", help="dump custom file with id x y z (its last frame is used)")
    ap.add_argument("--half", type=float, default=0.4, help="table half-width (m), 0.4")
    ap.add_argument("--top", type=float, default=0.0, help="height of the table top (m), 0")
    ap.add_argument("--first-id", type=int, default=1, help="atom ID of the mesh's vertex 1")
    ap.add_argument("--res", type=float, default=None, help="raster cell (m), mean edge / 4")
    ap.add_argument("--bins", type=int, default=12, help="bins of the overhang profile, 12")
    ap.add_argument("--svg", help="write a picture (top view and overhang profiles)")
    ap.add_argument("--json", action="store_true", help="print the results as JSON")
    args = ap.parse_args(argv)
    if args.half <= 0.0:
        ap.error(f"--half {args.half}: the table's half-width must be > 0")
    r = drape(args.obj, args.dump, args.half, args.top, args.first_id, args.res, args.bins)
    if r["area_cloth"] <= r["area_table"]:
        sys.exit(f"drape.py: the cloth ({r['area_cloth']:.4g} m^2) is not larger than the "
                 f"table ({r['area_table']:.4g} m^2): no drape coefficient")
    if args.svg:
        write_svg(args.svg, r, args.half,
                  f"{args.dump}: drape coefficient {r['drape_coefficient']:.3f}")
    if args.json:
        print(json.dumps({k: v for k, v in r.items() if not k.startswith("_")}, indent=1))
        return
    print(f"{args.dump}: {r['vertices']} vertices, {r['triangles']} triangles")
    print(f"areas (m^2): cloth {r['area_cloth']:.6g}, table {r['area_table']:.6g}, projected "
          f"{r['area_projected']:.6g} (cells of {r['res']:.3g} m), convex hull "
          f"{r['area_hull']:.6g}")
    print(f"drape coefficient {r['drape_coefficient']:.4f} (convex hull: "
          f"{r['drape_coefficient_hull']:.4f})")
    print(f"drop below the table top: {r['drop_min']:.4g} to {r['drop_max']:.4g} m")
    print("overhang profile of the sides (drop below the table top, m):")
    print(f"{'s (m)':>9} {'mean':>9} {'min':>9} {'max':>9}")
    for row in r["profile"]:
        print(f"{row['s']:9.4f} {row['mean']:9.4f} {row['min']:9.4f} {row['max']:9.4f}")


if __name__ == "__main__":
    main()
