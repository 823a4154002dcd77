#!/usr/bin/env python3
"""Make a triangle-mesh sheet (a rectangle or a disc in the plane z = 0) as a Wavefront OBJ file.

    python3 tools/make_sheet.py rectangle 1.0 0.5 --spacing 0.05 -o sheet.obj
    python3 tools/make_sheet.py rectangle 1.0 0.5 --spacing 0.05 --pattern equilateral -o cloth.obj
    python3 tools/make_sheet.py disc 0.5 --spacing 0.02 --jitter 0.2 --seed 3 -o disc.obj
    python3 tools/make_sheet.py sphere 0.05 --spacing 0.01 -o ball.obj

The file holds `v x y z` and `f a b c` lines (1-based vertex indices), the form `read_mesh`
reads. The sheet is centred at the origin (--center X Y Z moves it) and every triangle is
listed counter-clockwise seen from +z, so its normal by the right-hand rule is +z. One line
on standard output sums the mesh up: vertices, faces, total area, shortest and longest edge,
smallest angle.

rectangle LX LY (--pattern alternate or right; equilateral below): a grid of
nx = round(LX/a) + 1 by ny = round(LY/a) + 1 vertices (a the --spacing; Python's round, halves
to even; at least one cell each way), so the spacings are dx = LX/(nx-1), dy = LY/(ny-1) and
the sheet has exactly the size asked for. Each cell is cut into two right triangles:
--pattern alternate (the default) flips the diagonal from cell to cell like a chequerboard, so
the diagonals criss-cross (a union-jack pattern: every other interior vertex joins 8 edges, the
rest 4) and no diagonal direction is preferred; --pattern right cuts every cell from its
lower-left to its upper-right corner.

--grade g (alternate and right, without --jitter): the same cells, each g^(1/(m-1)) times
the one before along x and along y (m cells that way), the last g times the first; the sheet
keeps its size. A graded mesh for the bending validation (examples/membranes).

--pattern equilateral: rows of vertices parallel to x, ny = round(LY/h) + 1 of them with
h = a sqrt(3)/2 (so dy = LY/(ny-1)), every odd row (counting from 0 at the bottom) shifted by
dx/2; nx = round(LX/a) + 1 and dx = LX/(nx-1) as above. An even row holds the nx vertices
x0 + i dx (x0 = -LX/2); an odd row holds nx + 1: its interior vertices at x0 + dx/2 + k dx and
its ends exactly on the left and right edges. Between two rows lie 2(nx-1) - 1 equilateral
triangles (every interior vertex joins 6 edges, along 0 and about +-60 degrees) and at each end
a right-angled half (legs dx/2 and dy), 2(nx-1) + 1 in all: with mx = nx-1, my = ny-1 cells,
(mx+1)(my+1) + floor((my+1)/2) vertices and (2mx+1) my triangles. Equilateral only up to the
rounding: with q = 2 dy / (sqrt(3) dx) (1 when a fits both ways), the full triangles have
base angles atan(sqrt(3) q) and apex 180 - 2 atan(sqrt(3) q) degrees, the halves 90,
atan(sqrt(3) q) and atan(1/(sqrt(3) q)); the smallest angle of the sheet is
min(atan(1/(sqrt(3) q)), atan(sqrt(3) q)) (30 degrees at q = 1, in a half). Since dx/a and
dy/h lie within 1/(2mx) and 1/(2my) of 1, mx, my >= 10 keep every full triangle's angles
within 5.1 degrees of 60 and the smallest angle within 2.6 degrees of 30. This is the pattern
for bending: the discrete-shells hinge energy is isotropic on equilateral triangles only (on
the right-triangle patterns it is 1.5 times stiffer about the diagonals).

disc R: the centre and n = round(R/a) rings (at least one), ring k at radius k h with h = R/n
(so the outer ring lies on the circle) holding 6k equally spaced vertices, the first at angle
0. Ring k-1 and ring k are joined sector by sector (six sectors of 60 degrees) in 6(2k-1)
triangles: 1 + 3n(n+1) vertices, 6n^2 triangles, the boundary the regular 6n-gon inscribed in
the circle. The triangles are equilateral around the centre; the worst are the near-right ones
along the six sector lines (legs h and about h pi/3): smallest angle above atan(3/pi) = 43.68
degrees, smallest altitude above 0.7232 h, both approached as n grows.

sphere R (a closed surface, not a sheet: an obstacle such as a ball): the geodesic sphere of
frequency n = round(1.0515 R/a) (at least 1; 1.0515 R is the edge of the icosahedron inscribed
in the sphere): each of the icosahedron's 20 faces cut into n^2 triangles by its barycentric
grid and every vertex projected radially onto the sphere, 10 n^2 + 2 vertices (12 with 5
triangles, the rest with 6), 20 n^2 triangles, each counter-clockwise seen from outside (its
normal points out of the ball). The projection stretches the middle of each big face most (by
up to 1/0.7947, the icosahedron's circumradius over its inradius): edges range over about 0.87
to 1.26 times 1.0515 R / n. --jitter is refused.

--jitter f (0 <= f < 0.3) makes the mesh irregular: with random.Random(--seed) every interior
vertex moves by an offset drawn uniformly from the ellipse of half-axes f sx, f sy
(rectangle: sx = min(a, dx), sy = min(a, dy); disc: sx = sy = min(a, h)), so never by more
than f a in any direction. Boundary vertices stay on the boundary: a rectangle's edge vertices
move along their edge by at most f sx (or f sy), its corners not at all; the disc's outer ring
moves along the circle by an arc of at most f sx. Why no triangle can invert: three points
that end up on one line all lie within the largest displacement d of that line, so the
triangle fitted in a strip of width 2d and its smallest altitude was at most 2d. The
rectangle's triangles, seen in units of (dx, dy), have smallest altitude 1/sqrt(2) = 0.707
(right triangles) or 2/sqrt(5) = 0.894 (the equilateral pattern's full triangles, (0, 0),
(1, 0), (1/2, 1) in these units) against offsets of at most f; the disc's have at least
0.7232 h against offsets of at most f h. So any f below 0.35 is safe. The equilateral
pattern's halves at the left and right edges (smallest altitude 1/sqrt(5) = 0.447 in these
units) are safe by another argument: two of their vertices stay on the edge line and in order
(dy apart, each moving by at most f dy along it), the third starts dx/2 from that line and
moves by at most f dx across it; twice the area is the product of the two distances,
(1/2 - f) dx (1 - 2f) dy at least, positive for any f < 1/2. The tool accepts f < 0.3 and
checks every triangle anyway.

Functions for scripts and tests (vertices as (x, y, z) tuples, faces as 0-based (i, j, k)):
rectangle(), disc(), sphere(), write_obj(), read_obj(), check_triangles(), mesh_stats().
"""
from __future__ import annotations

import argparse
import math
import random
import shlex
import sys

PATTERNS = ("alternate", "right", "equilateral")
MAX_JITTER = 0.3


def _require(ok: bool, message: str):
    if not ok:
        raise ValueError(message)


def _check_common(shape: str, a: float, jitter: float):
    _require(math.isfinite(a) and a > 0,
             f"make_sheet {shape}: --spacing a must be > 0 (got {a})")
    _require(0.0 <= jitter < MAX_JITTER,
             f"make_sheet {shape}: --jitter f must satisfy 0 <= f < {MAX_JITTER} (got {jitter})")


def _in_unit_disc(rng: random.Random) -> tuple[float, float]:
    """A point drawn uniformly from the unit disc (two draws of rng)."""
    r = math.sqrt(rng.random())
    t = 2.0 * math.pi * rng.random()
    return r * math.cos(t), r * math.sin(t)


def _placed(points, center):
    """Points (x, y) of the plane z = 0 as (x, y, z) moved by center; -0.0 printed as 0.0."""
    cx, cy, cz = (float(c) for c in center)
    return [(x + cx + 0.0, y + cy + 0.0, cz + 0.0) for x, y in points]


def rectangle(Lx: float, Ly: float, a: float, pattern: str = "alternate",
              jitter: float = 0.0, seed: int = 1, center=(0.0, 0.0, 0.0), grade: float = 1.0):
    """A rectangular sheet Lx (along x) by Ly (along y) centred at `center`.

    Inputs:  Lx, Ly > 0 the size; a > 0 the target spacing; pattern "alternate", "right" or
             "equilateral"; jitter f in [0, 0.3) and seed of the irregular version;
             center (x, y, z); grade g in [1, 4] (alternate and right only, no jitter): the
             cells grow geometrically along x and along y, the last g times the first.
    Outputs: (vertices, faces), row by row from the bottom (y = -Ly/2), x fastest within a row.
             alternate, right: mx = round(Lx/a), my = round(Ly/a) cells (at least 1),
             (mx+1)(my+1) vertices, 2 mx my counter-clockwise triangles (0-based).
             equilateral: mx = round(Lx/a), my = round(Ly/(a sqrt(3)/2)) (at least 1), even
             rows of mx+1 vertices, odd rows of mx+2 (shifted by dx/2, ends on the edges):
             (mx+1)(my+1) + (my+1)//2 vertices, (2mx+1) my counter-clockwise triangles.
    Raises ValueError on a bad argument or (never expected) an inverted triangle.
    """
    for name, value in (("width Lx", Lx), ("height Ly", Ly)):
        _require(math.isfinite(value) and value > 0,
                 f"make_sheet rectangle: {name} must be > 0 (got {value})")
    _check_common("rectangle", a, jitter)
    _require(pattern in PATTERNS, f"make_sheet rectangle: --pattern must be one of "
             f"{', '.join(PATTERNS)} (got '{pattern}')")
    _require(math.isfinite(grade) and 1.0 <= grade <= 4.0,
             f"make_sheet rectangle: --grade g must satisfy 1 <= g <= 4 (got {grade})")
    _require(grade == 1.0 or (pattern != "equilateral" and jitter == 0.0),
             "make_sheet rectangle: --grade goes with --pattern alternate or right and no "
             "--jitter")
    equilateral = pattern == "equilateral"
    row_height = a * math.sqrt(3.0) / 2.0 if equilateral else a
    mx, my = max(1, round(Lx / a)), max(1, round(Ly / row_height))
    # each row's vertices as fractions t of the width, x = Lx (t - 1/2): t = 0 and 1 give the
    # edges at -+Lx/2 exactly (as j/my - 1/2 gives -+Ly/2); shifted rows add the two ends
    grid = _graded(mx, grade)
    shifted = [0.0] + [(k + 0.5) / mx for k in range(mx)] + [1.0]
    rows = [shifted if equilateral and j % 2 else grid for j in range(my + 1)]
    start = [0]                                 # index of each row's first vertex
    for row in rows:
        start.append(start[-1] + len(row))
    heights = _graded(my, grade)
    points = [[Lx * (t - 0.5), Ly * (heights[j] - 0.5)] for j, row in enumerate(rows) for t in row]
    if jitter > 0:
        rng = random.Random(seed)
        sx, sy = jitter * min(a, Lx / mx), jitter * min(a, Ly / my)
        for j, row in enumerate(rows):
            for i, t in enumerate(row):
                p = points[start[j] + i]
                inner_x, inner_y = 0 < t < 1, 0 < j < my
                if inner_x and inner_y:
                    u, v = _in_unit_disc(rng)
                    p[0] += sx * u
                    p[1] += sy * v
                elif inner_x:                   # bottom or top edge: along x only
                    p[0] += sx * (2.0 * rng.random() - 1.0)
                elif inner_y:                   # left or right edge: along y only
                    p[1] += sy * (2.0 * rng.random() - 1.0)
    faces = []
    for j in range(my):
        if equilateral:
            faces += _equilateral_strip(start[j], start[j + 1], mx, j % 2 == 1)
            continue
        for i in range(mx):
            v00 = start[j] + i
            v10, v01, v11 = v00 + 1, v00 + mx + 1, v00 + mx + 2
            if pattern == "right" or (i + j) % 2 == 0:       # diagonal v00-v11
                faces += [(v00, v10, v11), (v00, v11, v01)]
            else:                                            # diagonal v10-v01
                faces += [(v00, v10, v01), (v10, v11, v01)]
    vertices = _placed(points, center)
    check_triangles(vertices, faces, f"rectangle {Lx} {Ly} --spacing {a} --pattern {pattern} "
                                     f"--jitter {jitter}")
    return vertices, faces


def _graded(m: int, g: float):
    """The m + 1 fractions 0 = t_0 < ... < t_m = 1 of cells that grow by the same factor from one
    to the next, the last g times the first (t_k = k/m when g = 1 or m = 1)."""
    if g == 1.0 or m == 1:
        return [k / m for k in range(m + 1)]
    r = g ** (1.0 / (m - 1))
    return [0.0] + [(r ** k - 1.0) / (r ** m - 1.0) for k in range(1, m)] + [1.0]


def _equilateral_strip(lower: int, upper: int, mx: int, lower_shifted: bool):
    """The 2mx + 1 counter-clockwise triangles between two rows of the equilateral pattern.

    Inputs:  lower, upper the index of each row's first vertex; mx the cells across; which row
             is the shifted one (mx + 2 vertices s_0..s_mx+1; the other, u_0..u_mx, has mx + 1).
    Outputs: the triangles from left to right: the half at the left edge, then alternately
             one with a side on the unshifted row and one with a side on the shifted row, the
             half at the right edge.
    """
    if not lower_shifted:                       # u below, s above
        u, s = (lambda i: lower + i), (lambda k: upper + k)
        faces = [(u(0), s(1), s(0))]
        for i in range(mx):
            faces.append((u(i), u(i + 1), s(i + 1)))
            if i < mx - 1:
                faces.append((u(i + 1), s(i + 2), s(i + 1)))
        faces.append((u(mx), s(mx + 1), s(mx)))
    else:                                       # s below, u above
        s, u = (lambda k: lower + k), (lambda i: upper + i)
        faces = [(s(0), s(1), u(0))]
        for i in range(mx):
            faces.append((s(i + 1), u(i + 1), u(i)))
            if i < mx - 1:
                faces.append((s(i + 1), s(i + 2), u(i + 1)))
        faces.append((s(mx), s(mx + 1), u(mx)))
    return faces


def disc(R: float, a: float, jitter: float = 0.0, seed: int = 1, center=(0.0, 0.0, 0.0)):
    """A disc of radius R centred at `center`, triangulated ring to ring.

    Inputs:  R > 0 the radius; a > 0 the target spacing; jitter f in [0, 0.3) and seed of the
             irregular version; center (x, y, z).
    Outputs: (vertices, faces): the centre, then ring k = 1..n (n = round(R/a), at least 1) of
             6k vertices counter-clockwise from angle 0, 1 + 3n(n+1) vertices in all; 6n^2
             counter-clockwise triangles (0-based).
    Raises ValueError on a bad argument or (never expected) an inverted triangle.
    """
    _require(math.isfinite(R) and R > 0, f"make_sheet disc: radius R must be > 0 (got {R})")
    _check_common("disc", a, jitter)
    n = max(1, round(R / a))
    s = jitter * min(a, R / n)
    rng = random.Random(seed)
    points = [(0.0, 0.0)]
    start = [0]                                 # index of each ring's first vertex
    for k in range(1, n + 1):
        start.append(len(points))
        r = R * k / n                           # exactly R on the outer ring
        for m in range(6 * k):
            t = 2.0 * math.pi * m / (6 * k)
            if k == n and s > 0:                # the outer ring slides along the circle
                t += s / R * (2.0 * rng.random() - 1.0)
            points.append((r * math.cos(t), r * math.sin(t)))
    if s > 0:
        for v in range(start[n]):               # the centre and the inner rings
            u, w = _in_unit_disc(rng)
            points[v] = (points[v][0] + s * u, points[v][1] + s * w)
    faces = []
    for k in range(1, n + 1):
        n_in, n_out = 6 * (k - 1), 6 * k

        def inner(i):
            return start[k - 1] + (i % n_in if k > 1 else 0)

        def outer(j):
            return start[k] + j % n_out

        for sector in range(6):
            i0, j0 = sector * (k - 1), sector * k
            # k triangles with an outer edge, k-1 with an inner edge, interleaved
            for p in range(k):
                faces.append((inner(i0 + p), outer(j0 + p), outer(j0 + p + 1)))
                if p < k - 1:
                    faces.append((inner(i0 + p), outer(j0 + p + 1), inner(i0 + p + 1)))
    vertices = _placed(points, center)
    check_triangles(vertices, faces, f"disc {R} --spacing {a} --jitter {jitter}")
    return vertices, faces


def sphere(R: float, a: float, center=(0.0, 0.0, 0.0)):
    """A geodesic sphere of radius R centred at `center` (an icosahedron subdivided n times).

    Inputs:  R > 0 the radius; a > 0 the target spacing; center (x, y, z).
    Outputs: (vertices, faces): n = round(1.0515 R / a) (at least 1); 10 n^2 + 2 vertices on
             the sphere (the icosahedron's 12 corners first), 20 n^2 triangles (0-based), each
             counter-clockwise seen from outside.
    Raises ValueError on a bad argument or (never expected) a triangle facing inwards.
    """
    _require(math.isfinite(R) and R > 0, f"make_sheet sphere: radius R must be > 0 (got {R})")
    _check_common("sphere", a, 0.0)
    g = (1.0 + math.sqrt(5.0)) / 2.0            # the icosahedron (0, +-1, +-g) and its cycles
    corners = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
               (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    big = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
           (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
           (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    edge = 2.0 / math.sqrt(g * g + 1.0)         # 1.0515: the edge of the unit icosahedron
    n = max(1, round(edge * R / a))
    points, index = [], {}

    def vertex(weights):
        """The index of the grid point sum_c (w_c / n) corner_c, keyed by its nonzero weights
        (so a point on a shared edge or corner is made once)."""
        key = tuple(sorted((c, w) for c, w in weights if w > 0))
        if key not in index:
            p = [sum(w * corners[c][k] for c, w in key) / n for k in range(3)]
            r = math.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2)
            index[key] = len(points)
            points.append(tuple(R * q / r for q in p))
        return index[key]

    for c in range(12):
        vertex([(c, n)])
    faces = []
    for A, B, C in big:
        def at(i, j):                           # i steps towards B, j towards C
            return vertex([(A, n - i - j), (B, i), (C, j)])

        for i in range(n):
            for j in range(n - i):
                faces.append((at(i, j), at(i + 1, j), at(i, j + 1)))
                if i + j < n - 1:
                    faces.append((at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)))
    for f, (i, j, k) in enumerate(faces):       # outward: (q - p) x (r - p) . p > 0
        p, q, r = points[i], points[j], points[k]
        outward = sum(u * v for u, v in zip(_cross(_sub(q, p), _sub(r, p)), p))
        _require(outward > 0, f"make_sheet sphere {R} --spacing {a}: triangle {f} (vertices "
                              f"{i} {j} {k}) faces inwards")
    cx, cy, cz = (float(c) for c in center)
    vertices = [(x + cx + 0.0, y + cy + 0.0, z + cz + 0.0) for x, y, z in points]
    return vertices, faces


def check_triangles(vertices, faces, what: str = "mesh"):
    """Raise ValueError naming the first triangle that is inverted or degenerate seen from +z.

    Inputs:  vertices (x, y, z); faces (i, j, k) 0-based; what names the mesh in the message.
    A triangle counts as degenerate when twice its signed area in the xy plane is at most
    1e-12 times its longest edge squared (a smallest angle below about 1e-10 degrees).
    """
    for f, (i, j, k) in enumerate(faces):
        p, q, r = vertices[i], vertices[j], vertices[k]
        ux, uy, vx, vy = q[0] - p[0], q[1] - p[1], r[0] - p[0], r[1] - p[1]
        twice_area = ux * vy - uy * vx
        longest = max(ux * ux + uy * uy, vx * vx + vy * vy,
                      (r[0] - q[0]) ** 2 + (r[1] - q[1]) ** 2)
        if not twice_area > 1e-12 * longest:
            raise ValueError(f"make_sheet {what}: triangle {f} (vertices {i} {j} {k}) is "
                             f"{'inverted' if twice_area < 0 else 'degenerate'} (signed area "
                             f"{0.5 * twice_area:.3g}); every triangle must turn "
                             f"counter-clockwise seen from +z")


def _cross(u, v):
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def _sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def _angle(u, v):
    """Angle between vectors u and v in degrees (atan2: accurate near 0 and 180)."""
    return math.degrees(math.atan2(math.hypot(*_cross(u, v)), sum(a * b for a, b in zip(u, v))))


def mesh_stats(vertices, faces) -> dict:
    """Sizes and quality of a triangle mesh.

    Inputs:  vertices (x, y, z); faces (i, j, k) 0-based.
    Outputs: dict with vertices, faces, edges (distinct), boundary_edges (in one face only),
             area (sum of the triangles' areas), min_edge, max_edge (lengths), min_angle,
             max_angle (degrees, over every corner of every triangle).
    """
    edge_faces = {}
    areas, angles = [], []
    for i, j, k in faces:
        p, q, r = vertices[i], vertices[j], vertices[k]
        areas.append(0.5 * math.hypot(*_cross(_sub(q, p), _sub(r, p))))
        angles += [_angle(_sub(q, p), _sub(r, p)), _angle(_sub(r, q), _sub(p, q)),
                   _angle(_sub(p, r), _sub(q, r))]
        for e in ((i, j), (j, k), (k, i)):
            key = (min(e), max(e))
            edge_faces[key] = edge_faces.get(key, 0) + 1
    lengths = [math.dist(vertices[i], vertices[j]) for i, j in edge_faces]
    return {"vertices": len(vertices), "faces": len(faces), "edges": len(edge_faces),
            "boundary_edges": sum(1 for c in edge_faces.values() if c == 1),
            "area": math.fsum(areas),
            "min_edge": min(lengths, default=0.0), "max_edge": max(lengths, default=0.0),
            "min_angle": min(angles, default=0.0), "max_angle": max(angles, default=0.0)}


def write_obj(path, vertices, faces, header_lines=()):
    """Write a Wavefront OBJ file.

    Inputs:  path; vertices (x, y, z); faces (i, j, k) 0-based (written 1-based);
             header_lines written first as comments ("# " added where missing).
    Coordinates are written with repr(), which reads back to the same float.
    """
    with open(path, "w") as out:
        for line in header_lines:
            out.write((line if line.startswith("#") else "# " + line) + "\n")
        for x, y, z in vertices:
            out.write(f"v {float(x)!r} {float(y)!r} {float(z)!r}\n")
        for face in faces:
            out.write("f " + " ".join(str(i + 1) for i in face) + "\n")


def read_obj(path):
    """Read the triangles of a Wavefront OBJ file.

    Inputs:  path of a file with `v x y z [w]` lines and `f` lines whose entries are `a`,
             `a/t`, `a/t/n` or `a//n` (a the vertex: 1-based, or negative counting back from
             the last vertex read so far); a face of more than three vertices is cut into a
             fan (a0 a1 a2), (a0 a2 a3), ...; every other line (vt, vn, o, g, s, usemtl,
             comments) is ignored; a line ending in a backslash continues on the next.
    Outputs: (vertices as (x, y, z) tuples, faces as 0-based (i, j, k) tuples).
    Raises ValueError naming the file, the line and the bad entry.
    """
    vertices, faces, pending = [], [], []       # pending: (index, where, token)
    with open(path) as src:
        lines = src.read().splitlines()
    joined, first = "", 0
    for number, text in enumerate(lines, 1):
        if not joined:
            first = number                      # where a continued line starts
        if text.endswith("\\"):
            joined += text[:-1] + " "
            continue
        text, joined = joined + text, ""
        words = text.split("#", 1)[0].split()
        if not words:
            continue
        where = f"read_obj {path} line {first}"
        if words[0] == "v":
            bad = f"{where}: a vertex needs three numbers x y z (got '{text.strip()}')"
            _require(len(words) >= 4, bad)
            try:
                vertices.append(tuple(float(w) for w in words[1:4]))
            except ValueError:
                raise ValueError(bad) from None
        elif words[0] == "f":
            _require(len(words) >= 4, f"{where}: a face needs at least three vertices "
                                      f"(got '{text.strip()}')")
            corners = []
            for token in words[1:]:
                try:
                    index = int(token.split("/", 1)[0])
                except ValueError:
                    raise ValueError(f"{where}: face entry '{token}' is not a vertex index "
                                     f"(a, a/t, a/t/n or a//n with a an integer)") from None
                _require(index != 0, f"{where}: face entry '{token}': vertex indices start "
                                     f"at 1 (or count back from -1)")
                if index < 0:
                    _require(-index <= len(vertices),
                             f"{where}: face entry '{token}' counts back past the first "
                             f"vertex ({len(vertices)} read so far)")
                    index += len(vertices)
                else:
                    index -= 1
                    pending.append((index, where, token))
                corners.append(index)
            faces += [(corners[0], corners[m], corners[m + 1])
                      for m in range(1, len(corners) - 1)]
    for index, where, token in pending:         # positive indices may point ahead
        _require(index < len(vertices), f"{where}: face entry '{token}' names a vertex "
                                        f"beyond the last one ({len(vertices)} in the file)")
    return vertices, faces


def summary(path, vertices, faces) -> str:
    """The one line printed after writing a sheet."""
    s = mesh_stats(vertices, faces)
    return (f"{path}: {s['vertices']} vertices, {s['faces']} faces, area {s['area']:.10g}, "
            f"edges {s['min_edge']:.6g} to {s['max_edge']:.6g}, "
            f"smallest angle {s['min_angle']:.4g} deg")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--spacing", type=float, required=True, metavar="a",
                        help="target edge length")
    common.add_argument("--jitter", type=float, default=0.0, metavar="f",
                        help=f"random offsets of at most f*a, 0 <= f < {MAX_JITTER} "
                             "(default 0: regular)")
    common.add_argument("--seed", type=int, default=1, help="seed of --jitter (default 1)")
    common.add_argument("--center", type=float, nargs=3, default=(0.0, 0.0, 0.0),
                        metavar=("X", "Y", "Z"), help="centre of the sheet (default 0 0 0)")
    common.add_argument("-o", "--output", required=True, metavar="FILE",
                        help="the OBJ file to write")
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    shapes = ap.add_subparsers(dest="shape", required=True, metavar="{rectangle,disc,sphere}")
    rect = shapes.add_parser("rectangle", parents=[common], help="LX by LY rectangle")
    rect.add_argument("Lx", type=float, metavar="LX", help="width along x")
    rect.add_argument("Ly", type=float, metavar="LY", help="height along y")
    rect.add_argument("--grade", type=float, default=1.0, metavar="g",
                      help="cells growing geometrically along x and y, the last g times the "
                           "first, 1 <= g <= 4 (alternate and right, no --jitter; default 1)")
    rect.add_argument("--pattern", choices=PATTERNS, default="alternate",
                      help="right triangles with diagonals criss-crossing (alternate, "
                           "default) or all one way (right), or equilateral triangles in rows "
                           "of height a sqrt(3)/2 (equilateral: isotropic bending)")
    circle = shapes.add_parser("disc", parents=[common], help="disc of radius R")
    circle.add_argument("R", type=float, help="radius")
    ball = shapes.add_parser("sphere", parents=[common], help="geodesic sphere of radius R "
                             "(a closed surface: an obstacle)")
    ball.add_argument("R", type=float, help="radius")
    args = ap.parse_args(argv)
    try:
        if args.shape == "rectangle":
            vertices, faces = rectangle(args.Lx, args.Ly, args.spacing, args.pattern,
                                        args.jitter, args.seed, args.center, args.grade)
        elif args.shape == "disc":
            vertices, faces = disc(args.R, args.spacing, args.jitter, args.seed, args.center)
        else:
            _require(args.jitter == 0, f"make_sheet sphere: --jitter is not available for a "
                                       f"sphere (got {args.jitter})")
            vertices, faces = sphere(args.R, args.spacing, args.center)
    except ValueError as err:                   # the message names the shape and option
        print(err, file=sys.stderr)
        return 2
    header = ["made by tools/make_sheet.py " + " ".join(shlex.quote(a) for a in argv),
              f"vertices {len(vertices)} faces {len(faces)}"]
    write_obj(args.output, vertices, faces, header)
    print(summary(args.output, vertices, faces))
    return 0


if __name__ == "__main__":
    sys.exit(main())
