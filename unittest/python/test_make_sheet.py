"""tools/make_sheet.py: sizes, topology (one consistently oriented disc-like sheet), +z normals,
exact areas, bounds on the jitter and on the triangles' angles, determinism, the OBJ writer and
reader, and the command line. Needs neither LAMMPS nor build/lmp."""
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parents[2] / "tools" / "make_sheet.py"
sys.path.insert(0, str(TOOL.parent))
import make_sheet as ms  # noqa: E402


@pytest.fixture(scope="session", autouse=True)
def lmp_built():
    """Overrides conftest's check that build/lmp exists: nothing here runs LAMMPS."""
    yield


# (Lx, Ly, a, pattern): square and oblong cells, and a sheet thinner than half the spacing
# (one cell across); equilateral with an even (6, 8) and odd (7, 1) number of rows of triangles
RECTANGLES = [(1.0, 0.5, 0.1, "alternate"), (1.0, 0.5, 0.1, "right"),
              (0.7, 0.3, 0.045, "alternate"), (0.7, 0.3, 0.045, "right"),
              (0.2, 0.04, 0.1, "alternate"),
              (1.0, 0.5, 0.1, "equilateral"), (0.7, 0.3, 0.045, "equilateral"),
              (0.5, 0.6, 0.1, "equilateral"), (0.2, 0.04, 0.1, "equilateral")]
DISCS = [(0.5, 0.05), (1.0, 0.3), (0.1, 0.5)]      # (R, a): n = 10, 3 and 1 (the minimum)
JITTERS = [0.0, 0.1, 0.29]


def cells(length, a):
    return max(1, round(length / a))


def rect_cells(Lx, Ly, a, pattern):
    """(mx, my): cells across and rows of cells (rows of height a sqrt(3)/2 if equilateral)."""
    return cells(Lx, a), cells(Ly, a * math.sqrt(3) / 2 if pattern == "equilateral" else a)


def rect_counts(mx, my, pattern):
    """(vertices, faces, boundary edges) of a rectangle of mx by my cells."""
    if pattern == "equilateral":    # odd rows have one vertex more; a top odd row one edge more
        return (mx + 1) * (my + 1) + (my + 1) // 2, (2 * mx + 1) * my, 2 * (mx + my) + my % 2
    return (mx + 1) * (my + 1), 2 * mx * my, 2 * (mx + my)


def halves(vertices, faces, Lx):
    """The faces with two vertices on one of the edges x = -+Lx/2, as (face, the two on the
    edge, the other one): in the equilateral pattern, its right-angled halves."""
    out = []
    for face in faces:
        for edge in (-Lx / 2, Lx / 2):
            on = [i for i in face if vertices[i][0] == edge]
            if len(on) == 2:
                out.append((face, on, next(i for i in face if i not in on)))
    return out


def twice_area(vertices, face):
    """The z component of (q - p) x (r - p): twice the signed area seen from +z."""
    p, q, r = (vertices[i] for i in face)
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def corner_angles(vertices, face):
    p, q, r = (vertices[i] for i in face)
    out = []
    for a, b, c in ((p, q, r), (q, r, p), (r, p, q)):
        u, v = (b[0] - a[0], b[1] - a[1]), (c[0] - a[0], c[1] - a[1])
        out.append(math.atan2(abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]))
    return out


def sides(vertices, face):
    p, q, r = (vertices[i] for i in face)
    return math.dist(p, q), math.dist(q, r), math.dist(r, p)


def smallest_altitude(vertices, face):
    return abs(twice_area(vertices, face)) / max(sides(vertices, face))


def check_sheet(vertices, faces, boundary_edges):
    """One sheet with one boundary loop, every triangle counter-clockwise seen from +z."""
    directed = {}
    for f, (i, j, k) in enumerate(faces):
        assert len({i, j, k}) == 3
        for e in ((i, j), (j, k), (k, i)):
            assert e not in directed, f"edge {e} twice in one direction: inconsistent orientation"
            directed[e] = f
    undirected = {(min(e), max(e)) for e in directed}
    # every edge is in one triangle (boundary) or two that run through it in opposite senses
    boundary = [e for e in directed if (e[1], e[0]) not in directed]
    assert len(boundary) == boundary_edges
    assert len(vertices) - len(undirected) + len(faces) == 1      # Euler characteristic
    # the boundary edges form one closed loop through distinct vertices
    following = dict(boundary)
    assert len(following) == len(boundary)
    v, steps = boundary[0][0], 0
    while True:
        v, steps = following[v], steps + 1
        if v == boundary[0][0]:
            break
    assert steps == len(boundary)
    for face in faces:                          # normal +z: in-plane components vanish
        p, q, r = (vertices[i] for i in face)
        assert p[2] == q[2] == r[2]
        assert twice_area(vertices, face) > 0
    assert {i for face in faces for i in face} == set(range(len(vertices)))
    return boundary


def angle_bound(regular, face, d):
    """A lower bound on the smallest angle of `face` once every vertex has moved by at most d.

    Two bounds, the larger taken. (1) Each side vector changes by at most 2d, so its direction
    turns by at most asin(2d/|side|): each corner angle moves by at most the sum over its two
    sides. (2) A triangle's smallest altitude h is its least width, which moving the vertices
    by d lowers by at most 2d, and its longest side L grows by at most 2d; the smallest angle
    satisfies sin(angle) >= 2 area / L^2 = h / L.
    """
    def turn(side):
        return math.asin(2 * d / side) if 2 * d < side else math.pi

    points = [regular[i] for i in face]
    turned = []
    for c, angle in enumerate(corner_angles(regular, face)):      # the corner at points[c]
        p, q, r = points[c], points[(c + 1) % 3], points[(c + 2) % 3]
        turned.append(angle - turn(math.dist(p, q)) - turn(math.dist(p, r)))
    h, longest = smallest_altitude(regular, face), max(sides(regular, face))
    width = math.asin((h - 2 * d) / (longest + 2 * d)) if h > 2 * d else 0.0
    return max(min(turned), width)


# ---------------------------------------------------------------- rectangle


@pytest.mark.parametrize("jitter", JITTERS)
@pytest.mark.parametrize("Lx, Ly, a, pattern", RECTANGLES)
def test_rectangle(Lx, Ly, a, pattern, jitter):
    mx, my = rect_cells(Lx, Ly, a, pattern)
    n_vertices, n_faces, n_boundary = rect_counts(mx, my, pattern)
    vertices, faces = ms.rectangle(Lx, Ly, a, pattern, jitter, seed=7)
    assert len(vertices) == n_vertices
    assert len(faces) == n_faces
    check_sheet(vertices, faces, n_boundary)
    area = math.fsum(0.5 * twice_area(vertices, f) for f in faces)
    assert abs(area - Lx * Ly) <= 1e-12 * Lx * Ly
    assert ms.mesh_stats(vertices, faces)["area"] == pytest.approx(Lx * Ly, rel=1e-12, abs=0)

    regular, same_faces = ms.rectangle(Lx, Ly, a, pattern)
    assert same_faces == faces
    dx, dy = Lx / mx, Ly / my
    if jitter == 0:
        assert vertices == regular
        assert all(v[0] in (-Lx / 2, Lx / 2) or v[1] in (-Ly / 2, Ly / 2)
                   for v in vertices[:mx + 1] + vertices[-mx - 1:])
        if pattern == "equilateral":    # the halves' legs dx/2, dy; the full ones' base angle
            smallest = math.degrees(min(math.atan(dx / (2 * dy)), math.atan(2 * dy / dx)))
        else:   # right triangles with legs dx and dy: the smallest angle is atan(short/long)
            smallest = math.degrees(math.atan(min(dx, dy) / max(dx, dy)))
        assert ms.mesh_stats(vertices, faces)["min_angle"] == pytest.approx(smallest, rel=1e-9)
        return
    sx, sy = jitter * min(a, dx), jitter * min(a, dy)
    moved = 0
    for (x, y, _), (x0, y0, _) in zip(vertices, regular):
        on_x_edge, on_y_edge = abs(x0) == Lx / 2, abs(y0) == Ly / 2
        if on_x_edge:
            assert x == x0                                      # stays on its edge
        if on_y_edge:
            assert y == y0
        # the offset is drawn from the ellipse of half-axes sx, sy: never more than f a
        assert ((x - x0) / sx) ** 2 + ((y - y0) / sy) ** 2 <= 1 + 1e-9
        assert abs(x - x0) <= jitter * a * (1 + 1e-12) and abs(y - y0) <= jitter * a * (1 + 1e-12)
        moved += (x, y) != (x0, y0)
        if not (on_x_edge or on_y_edge):                        # inside: both ways
            assert x != x0 and y != y0
    assert moved == len(vertices) - 4 if len(vertices) > 4 else moved == 0
    d = jitter * max(min(a, dx), min(a, dy))
    for face in faces:
        assert min(corner_angles(vertices, face)) >= angle_bound(regular, face, d) - 1e-12
    if pattern != "equilateral":
        return
    least = (0.5 - jitter) * dx * (1 - 2 * jitter) * dy     # the docstring's bound
    for face, _, _ in halves(regular, faces, Lx):
        assert twice_area(vertices, face) >= least * (1 - 1e-12)


@pytest.mark.parametrize("Lx, Ly, a, pattern", RECTANGLES)
def test_rectangle_jitter_below_03_cannot_invert(Lx, Ly, a, pattern):
    """The documented guarantee for every seed: seen in units of (dx, dy) the offsets are at
    most f long, and three vertices that end up on one line lie in a strip of width 2f, so a
    triangle whose smallest altitude (its least width) exceeds 2 x 0.3 cannot flip. The
    equilateral pattern's halves are narrower (1/sqrt(5)) but keep two vertices on an edge
    line, dy apart, and their third dx/2 from it: offsets below 1/2 cannot flip them."""
    mx, my = rect_cells(Lx, Ly, a, pattern)
    vertices, faces = ms.rectangle(Lx, Ly, a, pattern)
    unit = [(x / (Lx / mx), y / (Ly / my), 0.0) for x, y, _ in vertices]
    half = []                                   # the equilateral pattern's halves
    if pattern == "equilateral":
        half = halves(vertices, faces, Lx)
        assert len(half) == 2 * my
    for face, on, other in half:
        assert abs(unit[on[0]][1] - unit[on[1]][1]) == pytest.approx(1.0, rel=1e-12)
        assert abs(abs(unit[other][0]) - mx / 2) == pytest.approx(0.5, rel=1e-12)
        assert smallest_altitude(unit, face) == pytest.approx(1 / math.sqrt(5), rel=1e-12)
    full = [f for f in faces if f not in {h[0] for h in half}]
    assert min(smallest_altitude(unit, f) for f in full) > 2 * ms.MAX_JITTER
    if pattern == "equilateral":
        assert min(smallest_altitude(unit, f) for f in full) == pytest.approx(2 / math.sqrt(5))
    for seed in range(1, 6):
        ms.rectangle(Lx, Ly, a, pattern, 0.299, seed)          # checks every triangle


def test_rectangle_patterns():
    """alternate: the diagonals criss-cross (vertex degrees 8 and 4 alternating inside);
    right: every diagonal from lower left to upper right (inside, every vertex has 6 edges)."""
    def degrees(faces, nx, ny):
        edges = {(min(e), max(e)) for i, j, k in faces for e in ((i, j), (j, k), (k, i))}
        count = [0] * (nx * ny)
        for i, j in edges:
            count[i] += 1
            count[j] += 1
        return [count[j * nx + i] for j in range(1, ny - 1) for i in range(1, nx - 1)]

    _, alternate = ms.rectangle(1.0, 1.0, 0.25, "alternate")
    _, right = ms.rectangle(1.0, 1.0, 0.25, "right")
    assert sorted(set(degrees(alternate, 5, 5))) == [4, 8]
    assert degrees(alternate, 5, 5) == [8, 4, 8, 4, 8, 4, 8, 4, 8]
    assert set(degrees(right, 5, 5)) == {6}
    # the two diagonal directions in equal numbers (on an even grid) or all one way
    vertices, _ = ms.rectangle(1.0, 1.0, 0.25)

    def diagonals(faces):
        up = down = 0
        for face in faces:
            for i, j in ((face[0], face[1]), (face[1], face[2]), (face[2], face[0])):
                (x0, y0, _), (x1, y1, _) = vertices[i], vertices[j]
                if x0 != x1 and y0 != y1:
                    up += (x1 - x0) * (y1 - y0) > 0
                    down += (x1 - x0) * (y1 - y0) < 0
        return up, down

    assert diagonals(alternate) == (16, 16)
    assert diagonals(right) == (32, 0)


@pytest.mark.parametrize("rows", [8, 7])
def test_rectangle_equilateral_when_a_fits(rows):
    """Lx = 8a, Ly = rows x a sqrt(3)/2: every full triangle equilateral with side a, every
    half right-angled with legs a/2 and a sqrt(3)/2 (30-60-90); rows alternate between 9
    vertices at x0 + i a and 10 (x0 + a/2 + k a inside, the ends on the edges); inside, every
    vertex joins 6 edges; the edges run along 0, 60 and 120 degrees, mx my of them along
    each diagonal."""
    a = 0.125
    h = a * math.sqrt(3) / 2
    Lx, Ly = 8 * a, rows * h
    vertices, faces = ms.rectangle(Lx, Ly, a, "equilateral")
    assert rect_cells(Lx, Ly, a, "equilateral") == (8, rows)
    x0, i = -Lx / 2, 0
    for j in range(rows + 1):
        xs = ([x0 + k * a for k in range(9)] if j % 2 == 0
              else [x0] + [x0 + a / 2 + k * a for k in range(8)] + [Lx / 2])
        for x in xs:
            assert vertices[i][0] == pytest.approx(x, abs=1e-15)
            assert vertices[i][1] == pytest.approx(-Ly / 2 + j * h, abs=1e-15)
            i += 1
        assert vertices[i - len(xs)][0] == -Lx / 2 and vertices[i - 1][0] == Lx / 2
    assert i == len(vertices)
    half = {h[0] for h in halves(vertices, faces, Lx)}
    assert len(half) == 2 * rows
    for face in faces:
        angles = sorted(math.degrees(t) for t in corner_angles(vertices, face))
        if face in half:
            assert sorted(sides(vertices, face)) == pytest.approx([a / 2, h, a], rel=1e-12)
            assert angles == pytest.approx([30, 60, 90], abs=1e-9)
        else:
            assert sides(vertices, face) == pytest.approx((a, a, a), rel=1e-12)
            assert angles == pytest.approx([60, 60, 60], abs=1e-9)
    assert ms.mesh_stats(vertices, faces)["min_angle"] == pytest.approx(30.0, abs=1e-9)

    edges = {(min(e), max(e)) for i, j, k in faces for e in ((i, j), (j, k), (k, i))}
    degree = [0] * len(vertices)
    directions = {}
    for p, q in edges:
        degree[p] += 1
        degree[q] += 1
        (x1, y1, _), (x2, y2, _) = vertices[p], vertices[q]
        t = round(math.degrees(math.atan2(y2 - y1, x2 - x1)) % 180, 6)
        directions[t] = directions.get(t, 0) + 1
    inside = [v for v, (x, y, _) in enumerate(vertices) if abs(x) < Lx / 2 and abs(y) < Ly / 2]
    assert inside and {degree[v] for v in inside} == {6}
    assert sorted(directions) == [0.0, 60.0, 90.0, 120.0]
    assert directions[60.0] == directions[120.0] == 8 * rows
    assert directions[90.0] == 2 * rows                     # the left and right edges only


@pytest.mark.parametrize("Lx_cells, Ly_rows", [(9.5001, 10.4999), (10.4999, 9.5001)])
def test_rectangle_equilateral_rounding_bound(Lx_cells, Ly_rows):
    """When a does not fit: 10 cells each way, one way stretched and the other squeezed by
    almost 5%, the worst the docstring allows for mx, my >= 10. The smallest angle is
    min(atan(1/(sqrt(3) q)), atan(sqrt(3) q)) with q = 2 dy / (sqrt(3) dx), within 2.6 degrees
    of 30, and the full triangles' angles stay within 5.1 degrees of 60."""
    a = 1.0
    h = a * math.sqrt(3) / 2
    Lx, Ly = Lx_cells * a, Ly_rows * h
    assert rect_cells(Lx, Ly, a, "equilateral") == (10, 10)
    vertices, faces = ms.rectangle(Lx, Ly, a, "equilateral")
    dx, dy = Lx / 10, Ly / 10
    q = 2 * dy / (math.sqrt(3) * dx)
    assert abs(q - 1) > 0.09                                # near the extremes
    smallest = ms.mesh_stats(vertices, faces)["min_angle"]
    assert smallest == pytest.approx(math.degrees(min(math.atan(1 / (math.sqrt(3) * q)),
                                                      math.atan(math.sqrt(3) * q))), rel=1e-9)
    assert abs(smallest - 30) < 2.6
    half = {h[0] for h in halves(vertices, faces, Lx)}
    for face in faces:
        angles = [math.degrees(t) for t in corner_angles(vertices, face)]
        if face not in half:
            assert max(abs(t - 60) for t in angles) < 5.1


# ---------------------------------------------------------------- disc


@pytest.mark.parametrize("jitter", JITTERS)
@pytest.mark.parametrize("R, a", DISCS)
def test_disc(R, a, jitter):
    n = cells(R, a)
    vertices, faces = ms.disc(R, a, jitter, seed=7)
    assert len(vertices) == 1 + 3 * n * (n + 1)
    assert len(faces) == 6 * n * n
    boundary = check_sheet(vertices, faces, 6 * n)
    outer = set(range(len(vertices) - 6 * n, len(vertices)))
    assert {i for e in boundary for i in e} == outer
    for i in outer:                                             # on the circle
        assert abs(math.hypot(*vertices[i][:2]) - R) <= 1e-15 * R
    area = math.fsum(0.5 * twice_area(vertices, f) for f in faces)
    # the outer ring's polygon: (1/2) R^2 sum of sin(angle between neighbours)
    angles = sorted(math.atan2(vertices[i][1], vertices[i][0]) for i in outer)
    gaps = [b - a for a, b in zip(angles, angles[1:] + [angles[0] + 2 * math.pi])]
    polygon = 0.5 * R * R * math.fsum(math.sin(g) for g in gaps)
    assert abs(area - polygon) <= 1e-12 * polygon
    regular_polygon = 0.5 * 6 * n * R * R * math.sin(2 * math.pi / (6 * n))
    assert polygon <= regular_polygon * (1 + 1e-12)     # the regular one is the largest

    regular, same_faces = ms.disc(R, a)
    assert same_faces == faces
    h = R / n
    if jitter == 0:
        assert vertices == regular
        assert abs(area - regular_polygon) <= 1e-12 * regular_polygon
        smallest = ms.mesh_stats(vertices, faces)["min_angle"]
        if n == 1:
            assert smallest == pytest.approx(60.0, abs=1e-9)
        else:   # the near-right triangles along the sector lines: legs h and h pi/3
            assert math.degrees(math.atan(3 / math.pi)) < smallest < 48.0
        return
    s = jitter * min(a, h)
    for i, ((x, y, _), (x0, y0, _)) in enumerate(zip(vertices, regular)):
        assert math.dist((x, y), (x0, y0)) <= s * (1 + 1e-12)
        if i in outer:                                          # an arc of at most s
            turn = math.atan2(x0 * y - y0 * x, x0 * x + y0 * y)
            assert abs(turn) * R <= s * (1 + 1e-12)
        assert (x, y) != (x0, y0)
    for face in faces:
        assert min(corner_angles(vertices, face)) >= angle_bound(regular, face, s) - 1e-12


@pytest.mark.parametrize("n", [1, 2, 3, 5, 12, 40])
def test_disc_jitter_below_03_cannot_invert(n):
    """The documented guarantee: every triangle of the regular disc is wider than 2 x 0.3 h
    (smallest altitude above 0.7232 h, the limit of the sector lines' near-right triangles),
    so offsets of at most 0.3 h cannot flip one."""
    vertices, faces = ms.disc(float(n), 1.0)
    assert min(smallest_altitude(vertices, f) for f in faces) > 0.7232
    for seed in range(1, 4):
        ms.disc(float(n), 1.0, 0.299, seed)


# ---------------------------------------------------------------- sphere


@pytest.mark.parametrize("R, a, n", [(1.0, 2.0, 1), (0.05, 0.01, 5), (2.0, 0.3, 7)])
def test_sphere(R, a, n):
    """A closed, consistently oriented surface of genus 0 on the sphere, facing outwards, with
    the documented counts; its area tends to 4 pi R^2 from below as n grows."""
    center = (0.5, -1.0, 2.0)
    vertices, faces = ms.sphere(R, a, center=center)
    assert len(vertices) == 10 * n * n + 2 and len(faces) == 20 * n * n
    directed = set()
    for i, j, k in faces:
        assert len({i, j, k}) == 3
        for e in ((i, j), (j, k), (k, i)):
            assert e not in directed
            directed.add(e)
    assert all((j, i) in directed for i, j in directed)         # closed: no boundary edge
    assert len(vertices) - len(directed) // 2 + len(faces) == 2  # Euler characteristic
    for p in vertices:
        assert math.dist(p, center) == pytest.approx(R, rel=1e-14)
    valence = {}
    for face in faces:
        for i in face:
            valence[i] = valence.get(i, 0) + 1
        p, q, r = (vertices[i] for i in face)
        normal = ms._cross(ms._sub(q, p), ms._sub(r, p))
        middle = [(p[k] + q[k] + r[k]) / 3 - center[k] for k in range(3)]
        assert sum(u * v for u, v in zip(normal, middle)) > 0      # outwards
    assert sorted(valence.values()) == [5] * 12 + [6] * (len(vertices) - 12)
    s = ms.mesh_stats(vertices, faces)
    assert s["boundary_edges"] == 0
    assert s["area"] < 4 * math.pi * R * R
    if n >= 5:
        assert s["area"] > 0.98 * 4 * math.pi * R * R
    # the projection stretches the middle of each big face most: by up to 1/0.7947 (the
    # icosahedron's inradius over its circumradius); edges near its corners stay near 0.87
    edge = 1.0515 * R / n
    assert 0.85 * edge < s["min_edge"] <= s["max_edge"] < 1.2584 * edge


def test_sphere_command_line(tmp_path):
    out = tmp_path / "ball.obj"
    run = run_tool("sphere", "0.05", "--spacing", "0.01", "--center", "0", "0", "-0.05",
                   "-o", str(out))
    assert run.returncode == 0, run.stderr
    assert ms.read_obj(out) == ms.sphere(0.05, 0.01, center=(0, 0, -0.05))
    assert "# vertices 252 faces 500" in out.read_text()
    bad = run_tool("sphere", "0.05", "--spacing", "0.01", "--jitter", "0.1", "-o", str(out))
    assert bad.returncode == 2 and "--jitter is not available for a sphere" in bad.stderr


# ---------------------------------------------------------------- shared


def test_center_moves_the_sheet():
    for make, args in ((ms.rectangle, (1.0, 0.5, 0.1, "alternate", 0.2, 3)),
                       (ms.rectangle, (1.0, 0.5, 0.1, "equilateral", 0.2, 3)),
                       (ms.disc, (0.5, 0.1, 0.2, 3))):
        at_origin, faces = make(*args)
        moved, moved_faces = make(*args, center=(1.5, -2.0, 0.25))
        assert moved_faces == faces
        for (x, y, z), (x0, y0, z0) in zip(moved, at_origin):
            assert (z0, z) == (0.0, 0.25)
            assert x == pytest.approx(x0 + 1.5, abs=1e-15) and y == pytest.approx(y0 - 2, abs=1e-15)


def test_the_seed_decides_the_jitter():
    assert ms.rectangle(1, 1, 0.1, "right", 0.2, 5) == ms.rectangle(1, 1, 0.1, "right", 0.2, 5)
    assert ms.disc(1, 0.1, 0.2, 5) == ms.disc(1, 0.1, 0.2, 5)
    assert ms.rectangle(1, 1, 0.1, "right", 0.2, 5) != ms.rectangle(1, 1, 0.1, "right", 0.2, 6)
    equilateral = ms.rectangle(1, 1, 0.1, "equilateral", 0.2, 5)
    assert equilateral == ms.rectangle(1, 1, 0.1, "equilateral", 0.2, 5)
    assert equilateral[0] != ms.rectangle(1, 1, 0.1, "equilateral", 0.2, 6)[0]
    assert ms.disc(1, 0.1, 0.2, 5)[0] != ms.disc(1, 0.1, 0.2, 6)[0]
    assert ms.disc(1, 0.1, 0.2)[0] == ms.disc(1, 0.1, 0.2, 1)[0]              # default seed 1


@pytest.mark.parametrize("call, words", [
    (lambda: ms.rectangle(0, 1, 0.1), ["rectangle", "Lx", "0"]),
    (lambda: ms.rectangle(1, float("nan"), 0.1), ["rectangle", "Ly", "nan"]),
    (lambda: ms.rectangle(1, 1, -0.1), ["--spacing", "-0.1", "> 0"]),
    (lambda: ms.rectangle(1, 1, 0.1, "left"), ["--pattern", "left",
                                                "alternate, right, equilateral"]),
    (lambda: ms.disc(1, 0.1, 0.3), ["disc", "--jitter", "0.3", "0 <= f < 0.3"]),
    (lambda: ms.disc(1, 0.1, -0.01), ["--jitter", "-0.01"]),
    (lambda: ms.disc(-1, 0.1), ["disc", "radius", "-1"]),
])
def test_bad_arguments_are_named(call, words):
    with pytest.raises(ValueError) as err:
        call()
    for word in words:
        assert word in str(err.value)


def test_check_triangles_finds_inverted_and_degenerate_triangles():
    vertices, faces = ms.rectangle(1.0, 1.0, 0.5)
    ms.check_triangles(vertices, faces)
    flipped = list(faces)
    flipped[5] = (faces[5][1], faces[5][0], faces[5][2])
    with pytest.raises(ValueError, match=r"triangle 5 .*inverted"):
        ms.check_triangles(vertices, flipped)
    flat = vertices + [(2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (4.0, 1e-13, 0.0)]
    with pytest.raises(ValueError, match=r"triangle 8 \(vertices 9 10 11\) is degenerate"):
        ms.check_triangles(flat, faces + [(9, 10, 11)])


def test_mesh_stats_of_known_triangles():
    s = ms.mesh_stats([(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 0, 3)], [(0, 1, 2), (0, 3, 1)])
    assert (s["vertices"], s["faces"], s["edges"], s["boundary_edges"]) == (4, 2, 5, 4)
    assert s["area"] == pytest.approx(2.0 + 3.0)
    assert (s["min_edge"], s["max_edge"]) == (2.0, pytest.approx(math.sqrt(13)))
    assert s["min_angle"] == pytest.approx(math.degrees(math.atan(2 / 3)))
    assert s["max_angle"] == pytest.approx(90.0)


# ---------------------------------------------------------------- OBJ files


def test_write_and_read_back(tmp_path):
    for vertices, faces in (ms.rectangle(1.0, 0.5, 0.1, "alternate", 0.25, 2),
                            ms.disc(0.3, 0.1, 0.2, 9, center=(1e3, -1e-3, 7.0))):
        path = tmp_path / "sheet.obj"
        ms.write_obj(path, vertices, faces, ["first line", "# second line"])
        lines = path.read_text().splitlines()
        assert lines[:2] == ["# first line", "# second line"]
        assert sum(ln.startswith("v ") for ln in lines) == len(vertices)
        assert sum(ln.startswith("f ") for ln in lines) == len(faces)
        assert ms.read_obj(path) == (vertices, faces)           # every float exactly


def test_read_obj_polygons_texture_normal_and_negative_indices(tmp_path):
    path = tmp_path / "mixed.obj"
    path.write_text("\n".join([
        "# a quad, a pentagon and a triangle with every kind of face entry",
        "mtllib sheet.mtl",
        "o sheet",
        "v 0 0 0", "v 1 0 0", "v 1 1 0", "v 0 1 0 1.0",       # a w coordinate: ignored
        "vt 0 0", "vt 1 0", "vn 0 0 1",
        "g front",
        "usemtl cloth",
        "s off",
        "f 1/1/1 2/2/1 3/2/1 4/1/1",
        "v 2 0 0  # a comment after a vertex",
        "v 2 1 0",
        "f -5//1 -2//1 -1//1 3//1 \\",
        "  -3/1",
        "f 6/1 5 -4",
        "l 1 2",
        ""]))
    vertices, faces = ms.read_obj(path)
    assert vertices == [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0),
                        (2.0, 0.0, 0.0), (2.0, 1.0, 0.0)]
    assert faces == [(0, 1, 2), (0, 2, 3),                      # the quad as a fan
                     (1, 4, 5), (1, 5, 2), (1, 2, 3),           # the pentagon, -5 = vertex 2
                     (5, 4, 2)]


@pytest.mark.parametrize("text, words", [
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", ["line 4", "'0'", "start at 1"]),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", ["line 4", "'4'", "beyond the last", "3 in"]),
    ("v 0 0 0\nv 1 0 0\nf -3 1 2\nv 0 1 0\n", ["line 3", "'-3'", "counts back", "2 read"]),
    ("v 0 0 0\nv 1 0 0\nf 1 2\n", ["line 3", "at least three vertices"]),
    ("v 0 0\n", ["line 1", "three numbers"]),
    ("v 0 0 zero\n", ["line 1", "three numbers", "zero"]),
    ("v 0 0 0\nf a/1 1 1\n", ["line 2", "'a/1'", "not a vertex index"]),
])
def test_read_obj_names_the_bad_entry(tmp_path, text, words):
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(ValueError) as err:
        ms.read_obj(path)
    for word in words + [str(path)]:
        assert word in str(err.value)


# ---------------------------------------------------------------- command line


def run_tool(*args):
    # the timeout guards against a hang only
    return subprocess.run([str(TOOL), *args], capture_output=True, text=True, timeout=600)


def test_command_line_writes_the_sheet(tmp_path):
    assert os.access(TOOL, os.X_OK)
    out = tmp_path / "disc.obj"
    run = run_tool("disc", "0.5", "--spacing", "0.1", "--jitter", "0.2", "--seed", "3",
                   "--center", "0", "0", "1", "-o", str(out))
    assert run.returncode == 0, run.stderr
    lines = out.read_text().splitlines()
    assert lines[0] == (f"# made by tools/make_sheet.py disc 0.5 --spacing 0.1 --jitter 0.2 "
                        f"--seed 3 --center 0 0 1 -o {out}")
    assert lines[1] == "# vertices 91 faces 150"
    vertices, faces = ms.read_obj(out)
    assert (vertices, faces) == ms.disc(0.5, 0.1, 0.2, 3, center=(0, 0, 1))
    s = ms.mesh_stats(vertices, faces)
    assert run.stdout.strip() == ms.summary(str(out), vertices, faces)
    assert run.stdout.startswith(f"{out}: 91 vertices, 150 faces, area {s['area']:.10g}, ")
    assert f"smallest angle {s['min_angle']:.4g} deg" in run.stdout

    out = tmp_path / "sheet.obj"
    run = run_tool("rectangle", "2", "1", "--spacing", "0.25", "--pattern", "right",
                   "-o", str(out))
    assert run.returncode == 0, run.stderr
    assert ms.read_obj(out) == ms.rectangle(2.0, 1.0, 0.25, "right")
    assert "# vertices 45 faces 64" in out.read_text()
    assert ", area 2, edges 0.25 to 0.353553, smallest angle 45 deg" in run.stdout

    # 8 cells across, 6 rows of height 0.25 sqrt(3)/2: 9 x 7 + 3 vertices, 17 x 6 triangles
    run = run_tool("rectangle", "2", str(6 * 0.25 * math.sqrt(3) / 2), "--spacing", "0.25",
                   "--pattern", "equilateral", "--center", "1", "0", "0", "-o", str(out))
    assert run.returncode == 0, run.stderr
    assert ms.read_obj(out) == ms.rectangle(2.0, 6 * 0.25 * math.sqrt(3) / 2, 0.25,
                                            "equilateral", center=(1, 0, 0))
    assert "# vertices 66 faces 102" in out.read_text()
    assert ", edges 0.125 to 0.25, smallest angle 30 deg" in run.stdout


@pytest.mark.parametrize("args, words", [
    (["disc", "1", "--spacing", "0.1", "--jitter", "0.3"], ["--jitter", "0.3", "0 <= f < 0.3"]),
    (["rectangle", "1", "0", "--spacing", "0.1"], ["rectangle", "Ly", "0"]),
    (["rectangle", "1", "1", "--spacing", "0.1", "--pattern", "left"], ["--pattern", "left"]),
    (["rectangle", "1", "1", "--spacing", "0.1", "--pattern", "equilateral", "--jitter", "0.3"],
     ["--jitter", "0.3"]),
    (["disc", "1"], ["--spacing", "required"]),
])
def test_command_line_refuses_bad_values(tmp_path, args, words):
    out = tmp_path / "never.obj"
    run = run_tool(*args, "-o", str(out))
    assert run.returncode == 2
    for word in words:
        assert word in run.stderr
    assert not out.exists()


@pytest.mark.parametrize("pattern", ["alternate", "right"])
@pytest.mark.parametrize("g", [1.0, 2.0, 4.0])
def test_rectangle_grade(pattern, g):
    """--grade g: the grid's columns and rows grow by one factor, the last cell g times the
    first both ways, the sheet keeps its size and area, and the triangles keep the topology."""
    Lx, Ly, a = 0.3, 0.2, 0.01
    vertices, faces = ms.rectangle(Lx, Ly, a, pattern, grade=g)
    mx, my = rect_cells(Lx, Ly, a, pattern)
    assert (len(vertices), len(faces)) == rect_counts(mx, my, pattern)[:2]
    xs = [vertices[i][0] for i in range(mx + 1)]
    ys = [vertices[j * (mx + 1)][1] for j in range(my + 1)]
    for coords, length in ((xs, Lx), (ys, Ly)):
        assert coords[0] == -length / 2 and coords[-1] == length / 2
        widths = [q - p for p, q in zip(coords, coords[1:])]
        assert min(widths) > 0
        assert widths[-1] / widths[0] == pytest.approx(g, rel=1e-12)
        ratios = [w1 / w0 for w0, w1 in zip(widths, widths[1:])]
        assert max(ratios) - min(ratios) < 1e-9
    assert ms.mesh_stats(vertices, faces)["area"] == pytest.approx(Lx * Ly, rel=1e-12)


@pytest.mark.parametrize("kwargs, words", [
    (dict(pattern="equilateral", grade=2.0), "--grade goes with"),
    (dict(pattern="alternate", grade=2.0, jitter=0.1), "--grade goes with"),
    (dict(pattern="alternate", grade=0.5), "1 <= g <= 4"),
    (dict(pattern="right", grade=5.0), "1 <= g <= 4")])
def test_rectangle_grade_refused(kwargs, words):
    with pytest.raises(ValueError, match=words):
        ms.rectangle(0.3, 0.2, 0.01, **kwargs)
