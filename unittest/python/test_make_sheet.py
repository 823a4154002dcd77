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
# (one cell across)
RECTANGLES = [(1.0, 0.5, 0.1, "alternate"), (1.0, 0.5, 0.1, "right"),
              (0.7, 0.3, 0.045, "alternate"), (0.7, 0.3, 0.045, "right"),
              (0.2, 0.04, 0.1, "alternate")]
DISCS = [(0.5, 0.05), (1.0, 0.3), (0.1, 0.5)]      # (R, a): n = 10, 3 and 1 (the minimum)
JITTERS = [0.0, 0.1, 0.29]


def cells(length, a):
    return max(1, round(length / a))


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
    mx, my = cells(Lx, a), cells(Ly, a)
    vertices, faces = ms.rectangle(Lx, Ly, a, pattern, jitter, seed=7)
    assert len(vertices) == (mx + 1) * (my + 1)
    assert len(faces) == 2 * mx * my
    check_sheet(vertices, faces, 2 * (mx + my))
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
        # right triangles with legs dx and dy: the smallest angle is atan(short/long)
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
    assert moved == len(vertices) - 4 if (mx, my) != (1, 1) else moved == 0
    d = jitter * max(min(a, dx), min(a, dy))
    for face in faces:
        assert min(corner_angles(vertices, face)) >= angle_bound(regular, face, d) - 1e-12


@pytest.mark.parametrize("Lx, Ly, a, pattern", RECTANGLES)
def test_rectangle_jitter_below_03_cannot_invert(Lx, Ly, a, pattern):
    """The documented guarantee for every seed: seen in units of (dx, dy) the offsets are at
    most f long, and three vertices that end up on one line lie in a strip of width 2f, so a
    triangle whose smallest altitude (its least width) exceeds 2 x 0.3 cannot flip."""
    mx, my = cells(Lx, a), cells(Ly, a)
    vertices, faces = ms.rectangle(Lx, Ly, a, pattern)
    unit = [(x / (Lx / mx), y / (Ly / my), 0.0) for x, y, _ in vertices]
    assert min(smallest_altitude(unit, f) for f in faces) > 2 * ms.MAX_JITTER
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


# ---------------------------------------------------------------- shared


def test_center_moves_the_sheet():
    for make, args in ((ms.rectangle, (1.0, 0.5, 0.1, "alternate", 0.2, 3)),
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
    assert ms.disc(1, 0.1, 0.2, 5)[0] != ms.disc(1, 0.1, 0.2, 6)[0]
    assert ms.disc(1, 0.1, 0.2)[0] == ms.disc(1, 0.1, 0.2, 1)[0]              # default seed 1


@pytest.mark.parametrize("call, words", [
    (lambda: ms.rectangle(0, 1, 0.1), ["rectangle", "Lx", "0"]),
    (lambda: ms.rectangle(1, float("nan"), 0.1), ["rectangle", "Ly", "nan"]),
    (lambda: ms.rectangle(1, 1, -0.1), ["--spacing", "-0.1", "> 0"]),
    (lambda: ms.rectangle(1, 1, 0.1, "left"), ["--pattern", "left", "alternate, right"]),
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
    return subprocess.run([str(TOOL), *args], capture_output=True, text=True, timeout=60)


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


@pytest.mark.parametrize("args, words", [
    (["disc", "1", "--spacing", "0.1", "--jitter", "0.3"], ["--jitter", "0.3", "0 <= f < 0.3"]),
    (["rectangle", "1", "0", "--spacing", "0.1"], ["rectangle", "Ly", "0"]),
    (["rectangle", "1", "1", "--spacing", "0.1", "--pattern", "left"], ["--pattern", "left"]),
    (["disc", "1"], ["--spacing", "required"]),
])
def test_command_line_refuses_bad_values(tmp_path, args, words):
    out = tmp_path / "never.obj"
    run = run_tool(*args, "-o", str(out))
    assert run.returncode == 2
    for word in words:
        assert word in run.stderr
    assert not out.exists()
