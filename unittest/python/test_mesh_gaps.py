"""tools/mesh_gaps.py: the exact distances against hand-computed values and brute force, the
grid broad phase against all pairs, sheets at a known gap, a folded sheet that crosses itself,
the dump reader and the command line. Needs neither LAMMPS nor build/lmp."""
import itertools
import json
import math
import os
import subprocess
import sys
from collections import deque
from pathlib import Path

import numpy as np
import pytest

TOOL = Path(__file__).resolve().parents[2] / "tools" / "mesh_gaps.py"
sys.path.insert(0, str(TOOL.parent))
import make_sheet as ms  # noqa: E402
import mesh_gaps as mg  # noqa: E402

SCALES = [1e-8, 1.0, 1e8]       # every exact distance again on a mesh scaled by these


@pytest.fixture(scope="session", autouse=True)
def lmp_built():
    """Overrides conftest's check that build/lmp exists: nothing here runs LAMMPS."""
    yield


# ---------------------------------------------------------------- point-triangle


# the triangle (0,0,0) (2,0,0) (0,2,0); a point in each Voronoi region, its closest point and
# the distance worked out by hand
TRIANGLE = [(0, 0, 0), (2, 0, 0), (0, 2, 0)]
REGIONS = [
    ("face, above", (0.5, 0.5, 3), (0.5, 0.5, 0), 3.0),
    ("face, below", (1, 0.5, -0.25), (1, 0.5, 0), 0.25),
    ("face, on it", (0.5, 0.5, 0), (0.5, 0.5, 0), 0.0),
    ("edge ab", (1, -1, 1), (1, 0, 0), math.sqrt(2)),
    ("edge bc", (2, 2, 1), (1, 1, 0), math.sqrt(3)),
    ("edge ca", (-1, 1, 0), (0, 1, 0), 1.0),
    ("corner a", (-1, -1, 1), (0, 0, 0), math.sqrt(3)),
    ("corner b", (3, -1, 0), (2, 0, 0), math.sqrt(2)),
    ("corner c", (-0.5, 3, 0), (0, 2, 0), math.sqrt(1.25)),
    ("corner b, beyond bc", (4, 0.5, 0), (2, 0, 0), math.sqrt(4.25)),
]


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize("region, p, closest, distance", REGIONS, ids=[r[0] for r in REGIONS])
def test_point_triangle_in_each_voronoi_region(region, p, closest, distance, scale):
    a, b, c = (scale * np.array(v, float) for v in TRIANGLE)
    d, q = mg.point_triangle_distance(scale * np.array(p, float), a, b, c)
    assert d == pytest.approx(scale * distance, rel=1e-14, abs=1e-30)
    assert q == pytest.approx(scale * np.array(closest, float), rel=1e-14, abs=1e-14 * scale)


def test_point_triangle_rows_and_degenerate_triangles():
    """All regions in one call give the same as one by one; a triangle with collinear corners
    is its longest side, one with all corners equal is a point."""
    p = np.array([r[1] for r in REGIONS], float)
    abc = [np.tile(np.array(v, float), (len(p), 1)) for v in TRIANGLE]
    d, _ = mg.point_triangle_distance(p, *abc)
    assert d == pytest.approx([r[3] for r in REGIONS], rel=1e-14)
    line = [np.array(v, float) for v in ((0, 0, 0), (1, 0, 0), (3, 0, 0))]
    assert mg.point_triangle_distance(np.array([2.0, 1, 1]), *line)[0] == pytest.approx(2 ** 0.5)
    assert mg.point_triangle_distance(np.array([4.0, 0, 0]), *line)[0] == pytest.approx(1.0)
    point = [np.array([1.0, 1, 1])] * 3
    assert mg.point_triangle_distance(np.array([1.0, 1, 3]), *point)[0] == pytest.approx(2.0)


def test_point_triangle_against_sampled_triangles():
    """Random points and triangles: the distance is that of the returned closest point, which
    lies in the triangle, and no sample of a fine barycentric grid of the triangle is closer."""
    rng = np.random.default_rng(5)
    n = 40
    p, a, b, c = (rng.normal(size=(n, 3)) for _ in range(4))
    d, q = mg.point_triangle_distance(p, a, b, c)
    assert np.linalg.norm(p - q, axis=1) == pytest.approx(d, rel=1e-12)
    m = 400
    u, v = np.meshgrid(np.arange(m + 1) / m, np.arange(m + 1) / m)
    u, v = u[u + v <= 1], v[u + v <= 1]
    for k in range(n):
        samples = a[k] + u[:, None] * (b[k] - a[k]) + v[:, None] * (c[k] - a[k])
        nearest = np.linalg.norm(samples - p[k], axis=1).min()
        longest = max(np.linalg.norm(b[k] - a[k]), np.linalg.norm(c[k] - a[k]))
        assert d[k] <= nearest + 1e-12
        assert d[k] >= nearest - 2 * longest / m          # the grid's spacing
        assert mg.point_triangle_distance(q[k], a[k], b[k], c[k])[0] < 1e-12


# ---------------------------------------------------------------- segment-segment


# (name, p1, q1, p2, q2, exact distance)
SEGMENTS = [
    ("skew, interior", (0, 0, 0), (2, 0, 0), (1, -1, 1), (1, 1, 1), 1.0),
    ("skew, end of one", (0, 0, 0), (2, 0, 0), (3, -1, 1), (3, 1, 1), math.sqrt(2)),
    ("skew, two ends", (0, 0, 0), (1, 0, 0), (2, 1, 1), (2, 2, 1), math.sqrt(3)),
    ("crossing", (-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), 0.0),
    ("parallel, overlapping", (0, 0, 0), (2, 0, 0), (1, 0.5, 0), (3, 0.5, 0), 0.5),
    ("parallel, opposite ways", (0, 0, 0), (2, 0, 0), (3, 0, 1), (-1, 0, 1), 1.0),
    ("parallel, disjoint", (0, 0, 0), (1, 0, 0), (2, 0, 1), (3, 0, 1), math.sqrt(2)),
    ("collinear, overlapping", (0, 0, 0), (2, 0, 0), (1, 0, 0), (3, 0, 0), 0.0),
    ("collinear, disjoint", (0, 0, 0), (1, 0, 0), (4, 0, 0), (2.5, 0, 0), 1.5),
    ("nearly parallel", (0, 0, 0), (1, 0, 0), (0.5, 1, 1e-9), (1.5, 1, -1e-9), 1.0),
    ("zero length, one", (0, 0, 0), (2, 0, 0), (1, 1, 1), (1, 1, 1), math.sqrt(2)),
    ("zero length, other", (3, 1, 0), (3, 1, 0), (0, 0, 0), (2, 0, 0), math.sqrt(2)),
    ("zero length, both", (0, 0, 0), (0, 0, 0), (1, 2, 2), (1, 2, 2), 3.0),
]


def brute_segment_distance(p1, q1, p2, q2, m=2000):
    """The smallest distance over an (m+1) x (m+1) grid of parameters s, t in [0, 1]."""
    s = (np.arange(m + 1) / m)[:, None]
    on1, on2 = p1 + s * (q1 - p1), p2 + s * (q2 - p2)
    best = np.inf
    for k in range(0, m + 1, 200):                       # rows of s in blocks: bounded memory
        diff = on1[k:k + 200, None, :] - on2[None, :, :]
        best = min(best, float(np.sqrt(np.einsum("ijk,ijk->ij", diff, diff).min())))
    return best


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize("name, p1, q1, p2, q2, exact", SEGMENTS, ids=[s[0] for s in SEGMENTS])
def test_segment_segment(name, p1, q1, p2, q2, exact, scale):
    """Against the exact value and a brute-force minimization: the grid's best is never below
    the true distance, and at most half a grid step along each segment above it."""
    p1, q1, p2, q2 = (scale * np.array(v, float) for v in (p1, q1, p2, q2))
    d, on1, on2 = mg.segment_segment_distance(p1, q1, p2, q2)
    assert d == pytest.approx(scale * exact, rel=1e-12, abs=1e-15 * scale)
    assert np.linalg.norm(on1 - on2) == pytest.approx(d, rel=1e-12, abs=1e-15 * scale)
    for on, (p, q) in ((on1, (p1, q1)), (on2, (p2, q2))):    # on its segment
        assert mg.point_segment_distance(on, p, q)[0] <= 1e-15 * scale
    m = 2000
    brute = brute_segment_distance(p1, q1, p2, q2, m)
    slack = (np.linalg.norm(q1 - p1) + np.linalg.norm(q2 - p2)) / (2 * m)
    assert brute - slack - 1e-15 * scale <= d <= brute + 1e-15 * scale


def test_segment_segment_random_rows_against_brute_force():
    """Random segments in one vectorized call, including pairs made parallel and collinear."""
    rng = np.random.default_rng(11)
    p1, q1, p2, q2 = (rng.normal(size=(24, 3)) for _ in range(4))
    q2[:8] = p2[:8] + 0.7 * (q1[:8] - p1[:8])                        # parallel
    p2[8:12] = p1[8:12] + 1.5 * (q1[8:12] - p1[8:12])                # collinear
    q2[8:12] = p1[8:12] - 0.3 * (q1[8:12] - p1[8:12])
    d, _, _ = mg.segment_segment_distance(p1, q1, p2, q2)
    m = 1000
    for k in range(len(d)):
        brute = brute_segment_distance(p1[k], q1[k], p2[k], q2[k], m)
        slack = (np.linalg.norm(q1[k] - p1[k]) + np.linalg.norm(q2[k] - p2[k])) / (2 * m)
        assert brute - slack - 1e-13 <= d[k] <= brute + 1e-13


def test_segment_crosses_triangle():
    a, b, c = (np.array(v, float) for v in TRIANGLE)
    cases = [((0.5, 0.5, -1), (0.5, 0.5, 1), True),      # through the face
             ((0.2, 0.2, -1e-4), (0.3, 0.3, 1e-4), True),  # steep and shallow, still through
             ((-1, 0.5, -1e-9), (3, 0.5, 1e-9), False),   # in the plane to 1e-9 (a dump's digits)
             ((0.5, 0.5, 0.1), (0.5, 0.5, 1), False),     # above it
             ((3, 3, -1), (3, 3, 1), False),              # past edge bc
             ((0.5, 0.5, 0), (0.5, 0.5, 1), False),       # touching: not crossing
             ((-1, 0.5, 0), (3, 0.5, 0), False)]          # in the plane
    for p, q, crosses in cases:
        assert bool(mg.segment_crosses_triangle(np.array(p, float), np.array(q, float),
                                                a, b, c)) is crosses

    # two coplanar triangles of a falling flat cloth (examples/tablecloth, cloth_ci.obj, step 58
    # of the CI run with contact yes, as its 8-digit dump has them): 1e-10 apart out of the
    # plane, far apart in it; the signs of their volumes are round-off, not a crossing
    one = [(0.52, -0.39428571, 0.008866506), (0.56, -0.39428571, 0.0088665068),
           (0.54, -0.36, 0.0088665064)]
    other = [(0.58, -0.36, 0.0088665071), (0.6, -0.32571429, 0.0088665075),
             (0.56, -0.32571429, 0.0088665068)]
    one, other = np.array(one), np.array(other)
    for s, t in ((0, 1), (1, 2), (2, 0)):
        assert not mg.segment_crosses_triangle(one[s], one[t], *other)
        assert not mg.segment_crosses_triangle(other[s], other[t], *one)


# ---------------------------------------------------------------- brute force over a mesh


def graph_distances(n, faces):
    """Edge counts between all vertex pairs (breadth-first from each vertex)."""
    neighbours = [set() for _ in range(n)]
    for f in faces:
        for u, v in itertools.permutations(f, 2):
            neighbours[u].add(v)
    far = np.full((n, n), n + 1)
    for s in range(n):
        far[s, s], todo = 0, deque([s])
        while todo:
            u = todo.popleft()
            for v in neighbours[u]:
                if far[s, v] > far[s, u] + 1:
                    far[s, v] = far[s, u] + 1
                    todo.append(v)
    return far


def all_pairs(x, faces, ring=1):
    """(point-triangle distances, edge-edge distances, intersecting triangle pairs) of every
    non-adjacent pair, adjacency by graph distances: what the grid must reproduce."""
    faces = np.asarray(faces)
    far = graph_distances(len(x), faces)
    used = np.unique(faces)
    apart = far[np.ix_(used, faces.ravel())].reshape(len(used), len(faces), 3).min(axis=2)
    v, f = np.nonzero(apart >= ring)
    v, f = used[v], faces[f]
    d_pt = mg.point_triangle_distance(x[v], x[f[:, 0]], x[f[:, 1]], x[f[:, 2]])[0]
    edges = np.array(sorted({tuple(sorted(e)) for f in faces.tolist()
                             for e in itertools.combinations(f, 2)}))
    e, g = (edges[k] for k in np.triu_indices(len(edges), 1))
    apart = np.min([far[e[:, s], g[:, t]] for s in (0, 1) for t in (0, 1)], axis=0)
    e, g = e[apart >= ring], g[apart >= ring]
    d_ee = mg.segment_segment_distance(x[e[:, 0]], x[e[:, 1]], x[g[:, 0]], x[g[:, 1]])[0]
    f1, f2 = (faces[k] for k in np.triu_indices(len(faces), 1))
    apart = ~(f1[:, :, None] == f2[:, None, :]).any(axis=(1, 2))
    f1, f2 = f1[apart], f2[apart]
    crossing = np.zeros(len(f1), dtype=bool)
    for one, other in ((f1, f2), (f2, f1)):
        for s, t in ((0, 1), (1, 2), (2, 0)):
            crossing |= mg.segment_crosses_triangle(x[one[:, s]], x[one[:, t]], x[other[:, 0]],
                                                    x[other[:, 1]], x[other[:, 2]])
    return d_pt, d_ee, int(crossing.sum())


def crumpled_sheet(seed=3):
    """A 0.6 x 0.6 sheet of spacing 0.1 whose vertices jump by up to 0.15 along each axis: it
    passes through itself in many places (a height field z(x, y) alone never would)."""
    vertices, faces = ms.rectangle(0.6, 0.6, 0.1, "alternate", 0.2, seed)
    x = np.array(vertices) + np.random.default_rng(seed).uniform(-0.15, 0.15, (len(vertices), 3))
    return x, faces


@pytest.mark.parametrize("ring", [1, 2, 3])
def test_grid_finds_what_all_pairs_find(ring):
    x, faces = crumpled_sheet()
    mesh = mg.MeshGaps(x, faces, exclude_ring=ring)
    d_pt, d_ee, crossings = all_pairs(x, faces, ring)
    for radius in (10.0, 0.3, 0.05):                     # 10: every pair within it
        gaps = mesh.check(x, radius)
        for kind, d in (("point_triangle", d_pt), ("edge_edge", d_ee)):
            assert gaps.measured[kind] == np.count_nonzero(d < radius)
            found = getattr(gaps, kind)
            if d.min() < radius:
                assert found.distance == pytest.approx(d.min(), rel=1e-14)
            else:
                assert found is None
        assert gaps.intersections == crossings > 0       # intersections need no radius
    assert mesh.check(x, 10.0).measured == {"point_triangle": len(d_pt), "edge_edge": len(d_ee)}


@pytest.mark.parametrize("gap", [0.0, 0.05, 0.3, 5.0])
def test_box_pairs_against_all_pairs(gap):
    """Random boxes of up to 0.2 in a unit cube, gaps from 0 to far more than the boxes: the
    grid's pairs are exactly those of the all-pairs test, each once."""
    rng = np.random.default_rng(2)
    lo_a, lo_b = rng.uniform(size=(60, 3)), rng.uniform(size=(50, 3))
    hi_a, hi_b = lo_a + rng.uniform(0, 0.2, (60, 3)), lo_b + rng.uniform(0, 0.2, (50, 3))

    def near(lo1, hi1, lo2, hi2):
        return (np.all(lo2[None] - hi1[:, None] <= gap, axis=2)
                & np.all(lo1[:, None] - hi2[None] <= gap, axis=2))

    def found(chunks):
        pairs = [(int(i), int(j)) for ci, cj in chunks for i, j in zip(ci, cj)]
        assert len(pairs) == len(set(pairs))
        return set(pairs)

    expected = set(zip(*np.nonzero(near(lo_a, hi_a, lo_b, hi_b))))
    assert found(mg.box_pairs(lo_a, hi_a, lo_b, hi_b, gap)) == expected
    expected = {(i, j) for i, j in zip(*np.nonzero(near(lo_a, hi_a, lo_a, hi_a))) if i < j}
    assert found(mg.box_pairs(lo_a, hi_a, gap=gap)) == expected
    points = mg.box_pairs(lo_a, lo_a, lo_b, lo_b, gap)               # boxes of size 0
    assert found(points) == set(zip(*np.nonzero(near(lo_a, lo_a, lo_b, lo_b))))


def test_exclude_ring_leaves_out_the_rings():
    """The closest pair found under ring K has no two vertices fewer than K edges apart, and
    larger K never finds a closer pair."""
    x, faces = crumpled_sheet(seed=8)
    far = graph_distances(len(x), faces)
    previous = 0.0
    for ring in (1, 2, 3, 4):
        gaps = mg.MeshGaps(x, faces, exclude_ring=ring).check(x, radius=10.0)
        for best in (gaps.point_triangle, gaps.edge_edge):
            first, second = np.array(best.first) - 1, np.array(best.second) - 1
            assert far[np.ix_(first, second)].min() >= ring
        assert gaps.point_triangle.distance >= previous
        previous = gaps.point_triangle.distance
    with pytest.raises(ValueError, match="exclude-ring must be >= 1"):
        mg.MeshGaps(x, faces, exclude_ring=0)


# ---------------------------------------------------------------- sheets


def two_sheets(gap, a=0.1, shift=(0.013, 0.021)):
    """Two 1 x 1 equilateral sheets, the second `gap` above the first and shifted in x, y so
    that its vertices lie over the first one's faces."""
    lower, faces = ms.rectangle(1.0, 1.0, a, "equilateral")
    upper, _ = ms.rectangle(1.0, 1.0, a, "equilateral", center=(*shift, gap))
    n = len(lower)
    return np.array(lower + upper), faces + [tuple(v + n for v in f) for f in faces], n


def test_parallel_sheets_give_their_gap():
    gap = 0.03
    x, faces, n = two_sheets(gap)
    mesh = mg.MeshGaps(x, faces)
    gaps = mesh.check(x)
    for best in (gaps.point_triangle, gaps.edge_edge):
        assert best.distance == pytest.approx(gap, rel=1e-12)
        ids = best.first + best.second                   # one side in each sheet
        assert min(ids) <= n < max(ids)
        assert best.at[2] == pytest.approx(gap / 2)
    assert gaps.intersections == 0 and not gaps.fails
    assert not mesh.check(x, dmin=0.02).fails
    below = mesh.check(x, dmin=0.04)
    assert below.fails and below.radius == gaps.radius           # the mean edge, above dmin
    assert below.below_dmin["point_triangle"] > 0 and below.below_dmin["edge_edge"] > 0
    assert mesh.check(x, radius=0.01, dmin=0.04).radius == 0.04  # raised to dmin


def folded_sheet(tilt):
    """A 2 x 1 sheet (x from -1 to 1) bent at x = 0 round a half cylinder of radius 0.1 into a
    hairpin: the part beyond the bend comes back 0.2 above the flat half, and sinks by
    tilt * y * (distance past the bend), so that for tilt 1 its y > 0.2 side passes through
    the flat half."""
    vertices, faces = ms.rectangle(2.0, 1.0, 0.1, "alternate")
    rho = 0.1
    x = []
    for u, y, _ in vertices:
        if u <= 0:
            x.append((u, y, 0.0))
        elif u <= math.pi * rho:
            x.append((rho * math.sin(u / rho), y, rho * (1 - math.cos(u / rho))))
        else:
            past = u - math.pi * rho
            x.append((-past, y, 2 * rho - tilt * y * past))
    return np.array(x), faces, [u for u, _, _ in vertices]


def test_folded_sheet_crossing_itself():
    x, faces, u = folded_sheet(tilt=1.0)
    mesh = mg.MeshGaps(x, faces)
    gaps = mesh.check(x)
    assert gaps.intersections > 0
    assert gaps.intersections == all_pairs(x, faces)[2]
    assert len(gaps.crossing_pairs) == min(gaps.intersections, mg.CROSSINGS_KEPT)
    for pair in gaps.crossing_pairs:                     # the flat half against the flap
        sides = sorted(max(u[i - 1] for i in tri) for tri in pair)
        assert sides[0] <= 0 and sides[1] > math.pi * 0.1
    assert mesh.check(x, dmin=1e-6).fails

    x, faces, _ = folded_sheet(tilt=0.0)                 # the plain hairpin
    assert mg.MeshGaps(x, faces).check(x).intersections == 0


def test_flat_sheets():
    """Adjacent pairs left out, a flat sheet's closest pairs are a triangle's altitude apart:
    across a right triangle's diagonal a / sqrt(2) (alternate pattern); on the equilateral
    pattern the right-angled halves at the ends of the rows (legs a/2 and h) are the closest,
    the corner on the edge to the half's hypotenuse: (a/2) h / sqrt(a^2/4 + h^2) = sqrt(3)/4 a.
    Nothing closer than 0.4 a, and nothing within the mean edge once the one-ring is left out
    too."""
    a = 0.1
    h = a * math.sqrt(3) / 2
    for (vertices, faces), altitude in ((ms.rectangle(1.0, 0.6, a, "alternate"), a / 2 ** 0.5),
                                        (ms.rectangle(10 * a, 8 * h, a, "equilateral"),
                                         a * 3 ** 0.5 / 4)):
        mesh = mg.MeshGaps(vertices, faces)
        gaps = mesh.check(mesh.vertices)
        assert gaps.point_triangle.distance == pytest.approx(altitude, rel=1e-12)
        assert gaps.edge_edge.distance == pytest.approx(altitude, rel=1e-12)
        assert gaps.intersections == 0
        near = mesh.check(mesh.vertices, radius=0.4 * a)
        assert near.point_triangle is None and near.edge_edge is None
        assert near.measured == {"point_triangle": 0, "edge_edge": 0}
        assert near.intersections == 0
        assert not mesh.check(mesh.vertices, dmin=0.4 * a).fails
        ring2 = mg.MeshGaps(vertices, faces, exclude_ring=2).check(mesh.vertices)
        assert ring2.point_triangle is None and ring2.edge_edge is None


def test_a_40k_vertex_sheet():
    """The full-size tablecloth's mesh (make_sheet rectangle 1.2 1.2 --spacing 0.0065
    --pattern equilateral: 39911 vertices, 79023 triangles) is processed; its closest pairs are
    those of its row-end halves (a does not fit exactly: legs dx/2 and dy)."""
    vertices, faces = ms.rectangle(1.2, 1.2, 0.0065, "equilateral")
    assert (len(vertices), len(faces)) == (39911, 79023)
    dx, dy = 1.2 / round(1.2 / 0.0065), 1.2 / round(1.2 / (0.0065 * math.sqrt(3) / 2))
    altitude = (dx / 2) * dy / math.hypot(dx / 2, dy)
    mesh = mg.MeshGaps(vertices, faces)
    gaps = mesh.check(mesh.vertices)
    assert gaps.point_triangle.distance == pytest.approx(altitude, rel=1e-9)
    assert gaps.edge_edge.distance == pytest.approx(altitude, rel=1e-9)
    assert gaps.intersections == 0
    assert gaps.measured["point_triangle"] > len(vertices)


# ---------------------------------------------------------------- dumps


def write_dump(path, frames, columns="id x y z"):
    """frames: (step, {id: (x, y, z)}); rows written in reverse id order with a type column
    when asked, as LAMMPS may when not sorting."""
    names = columns.split()
    with open(path, "w") as out:
        for step, atoms in frames:
            out.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(atoms)}\n"
                      "ITEM: BOX BOUNDS ff ff ff\n-1 1\n-1 1\n-1 1\n"
                      f"ITEM: ATOMS {columns}\n")
            for i in sorted(atoms, reverse=True):
                row = {"id": i, "type": 1}
                for k, axis in enumerate("xyz"):
                    row[axis] = row[axis + "u"] = atoms[i][k]
                out.write(" ".join(repr(row[c]) for c in names) + "\n")


def test_dump_frames_and_a_missing_atom(tmp_path):
    x, faces, n = two_sheets(0.03)
    atoms = {i + 1: tuple(p) for i, p in enumerate(x)}
    moved = {i: (p[0], p[1], p[2] + 1.0) for i, p in atoms.items()}
    missing = {i: p for i, p in atoms.items() if i != 17}
    path = tmp_path / "dump.three"
    write_dump(path, [(0, atoms), (100, moved), (200, missing)], "id type x y z")
    frames = list(mg.read_dump(path))
    assert [f.step for f in frames] == [0, 100, 200]
    assert [len(f.ids) for f in frames] == [len(x), len(x), len(x) - 1]
    assert mg.mesh_positions(frames[0], len(x)) == pytest.approx(x, abs=0)
    assert mg.mesh_positions(frames[1], len(x))[:, 2] == pytest.approx(x[:, 2] + 1.0)
    with pytest.raises(ValueError, match=r"dump\.three timestep 200: atom 17 \(mesh vertex 17"):
        mg.mesh_positions(frames[2], len(x))
    n = len(x)          # with first-id 101, atoms 1..100 are not the mesh's, 101..n + 100 are
    with pytest.raises(ValueError, match=rf"timestep 0: atom {n + 1} \(mesh vertex {n - 99} "
                                         rf"with first-id 101\) is missing \(and 99 more\)"):
        mg.mesh_positions(frames[0], n, first_id=101)
    assert mg.mesh_positions(frames[0], n - 100, first_id=101) == pytest.approx(x[100:], abs=0)


def test_dump_columns(tmp_path):
    """Unwrapped xu yu zu are preferred; a frame without id or coordinates, or cut short, is
    an error naming its timestep."""
    path = tmp_path / "dump.u"
    path.write_text("ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n"
                    "0 1\n0 1\n0 1\nITEM: ATOMS x y z id xu yu zu\n"
                    "0.5 0.5 0.5 2 1.5 -0.5 0.5\n0.25 0.5 0.75 1 0.25 0.5 0.75\n")
    frame = next(mg.read_dump(path))
    assert frame.ids.tolist() == [2, 1] and frame.xyz.tolist() == [[1.5, -0.5, 0.5],
                                                                   [0.25, 0.5, 0.75]]
    write_dump(path, [(7, {1: (0.0, 1.0, 2.0)})], "id type x y")
    with pytest.raises(ValueError, match=r"timestep 7: needs columns id and x y z"):
        list(mg.read_dump(path))
    write_dump(path, [(9, {1: (0.0, 1.0, 2.0), 2: (3.0, 4.0, 5.0)})])
    path.write_text(path.read_text().rsplit("\n", 2)[0] + "\n")      # the last row gone
    with pytest.raises(ValueError, match=r"timestep 9: expected 2 rows of 4 columns"):
        list(mg.read_dump(path))


# ---------------------------------------------------------------- command line


def run_tool(*args):
    return subprocess.run([str(TOOL), *map(str, args)], capture_output=True, text=True,
                          timeout=120)


def write_two_sheets_obj(path, gap):
    """The two sheets as an OBJ file of two groups, the second one's faces by negative
    indices."""
    x, faces, n = two_sheets(gap)
    lines = ["o lower"] + [f"v {p[0]!r} {p[1]!r} {p[2]!r}" for p in x[:n]]
    lines += [f"f {f[0] + 1} {f[1] + 1} {f[2] + 1}" for f in faces[:len(faces) // 2]]
    lines += ["o upper"] + [f"v {p[0]!r} {p[1]!r} {p[2]!r}" for p in x[n:]]
    lines += ["f " + " ".join(f"{v - len(x)}//1" for v in f) for f in faces[len(faces) // 2:]]
    path.write_text("\n".join(lines) + "\n")
    return x, faces


def test_command_line(tmp_path):
    """Atom IDs from 101 (100 other atoms before the mesh), two dump files, text and JSON, and
    the exit status with --dmin."""
    assert os.access(TOOL, os.X_OK)
    gap = 0.03
    x, faces = write_two_sheets_obj(tmp_path / "sheets.obj", gap)
    assert mg.read_obj(tmp_path / "sheets.obj") == ([tuple(p) for p in x], faces)
    others = {i: (5.0 + i, 0.0, 0.0) for i in range(1, 101)}
    mesh_atoms = {i + 101: tuple(p) for i, p in enumerate(x)}
    apart = {i: (p[0], p[1], p[2] + (0.005 if i >= 101 + len(x) // 2 else 0.0))
             for i, p in mesh_atoms.items()}
    write_dump(tmp_path / "dump.s.0", [(0, {**others, **mesh_atoms})])
    write_dump(tmp_path / "dump.s.10", [(10, {**others, **apart})])
    args = [tmp_path / "sheets.obj", tmp_path / "dump.s.0", tmp_path / "dump.s.10",
            "--first-id", 101]

    run = run_tool(*args)
    assert run.returncode == 0, run.stderr
    header, first, second = run.stdout.splitlines()
    assert header.startswith(f"# {tmp_path / 'sheets.obj'}: {len(x)} vertices, {len(faces)} "
                             f"triangles, atom IDs from 101")
    assert first.startswith(f"{tmp_path / 'dump.s.0'} step 0: point-triangle 0.03 (vertex ")
    assert "edge-edge 0.03 (edge " in first and "; 0 intersecting triangle pairs;" in first
    assert "point-triangle 0.035 (vertex" in second     # the upper sheet moved up by 0.005

    assert run_tool(*args, "--dmin", 0.02).returncode == 0
    run = run_tool(*args, "--dmin", 0.032, "--json")
    assert run.returncode == 1
    report = json.loads(run.stdout)
    assert not report["ok"] and report["first_id"] == 101 and report["dmin"] == 0.032
    assert [f["step"] for f in report["frames"]] == [0, 10]
    frame = report["frames"][0]
    assert frame["point_triangle"]["distance"] == pytest.approx(gap, rel=1e-12)
    assert frame["below_dmin"]["point_triangle"] > 0 and frame["intersections"] == 0
    assert frame["fails"] and not report["frames"][1]["fails"]
    assert all(101 <= i < 101 + len(x) for i in frame["edge_edge"]["first"])
    assert report["frames"][1]["below_dmin"] == {"point_triangle": 0, "edge_edge": 0}

    run = run_tool(*args, "--radius", 0.01)
    assert "point-triangle none closer than 0.01;" in run.stdout.splitlines()[1]


def test_command_line_errors(tmp_path):
    x, _ = write_two_sheets_obj(tmp_path / "sheets.obj", 0.03)
    write_dump(tmp_path / "dump.short", [(40, {i + 1: tuple(p) for i, p in enumerate(x[:-1])})])
    run = run_tool(tmp_path / "sheets.obj", tmp_path / "dump.short")
    assert run.returncode == 2
    assert f"timestep 40: atom {len(x)} (mesh vertex {len(x)}" in run.stderr
    run = run_tool(tmp_path / "none.obj", tmp_path / "dump.short")
    assert run.returncode == 2 and "none.obj" in run.stderr
    run = run_tool(tmp_path / "sheets.obj", tmp_path / "dump.short", "--dmin", -1)
    assert run.returncode == 2 and "--dmin must be >= 0" in run.stderr
