#!/usr/bin/python3
"""How close a triangle mesh comes to itself in LAMMPS dumps, and where it passes through itself.

    tools/mesh_gaps.py MESH.obj DUMP [DUMP ...] [--first-id N] [--radius R] [--dmin D]
                       [--exclude-ring K] [--json]
    tools/mesh_gaps.py cloth.obj dump.ci.* --dmin 1e-3

It needs numpy: it runs with Debian's /usr/bin/python3 (its first line), whose numpy
tools/setup.sh installs (python3-numpy); another python3 on the PATH may lack it.

An independent checker of self-contact, written for tests and for looking at scenes: it shares
no code with the simulation. MESH.obj is the OBJ file `read_mesh` read (read with
make_sheet.read_obj: `o`/`g` groups, `f a/t/n` entries, negative indices, polygons cut into
fans); vertex k of the file (k = 0, 1, ...) is LAMMPS atom ID first-id + k (`read_mesh` numbers
a mesh's atoms after the largest ID already present, in file order; default first-id 1). Each
DUMP is a text `dump custom` file with columns id and x y z (xu yu zu, the unwrapped positions,
are used instead when present), one frame or several: every frame is checked. A mesh atom
missing from a frame is an error naming the atom and the frame's timestep; atoms that are not
the mesh's are ignored.

For every frame it finds, over pairs closer than the search radius R (default: the mean edge
length of the mesh as the OBJ file has it; at least D when --dmin is given):
  - the closest point-triangle pair: a vertex and a triangle it is not adjacent to;
  - the closest edge-edge pair: two edges that are not adjacent;
  - the triangle pairs that intersect: two triangles sharing no vertex whose interiors cross,
    i.e. an edge of one passes through the other (strictly: an edge that only touches the other
    triangle, or lies in its plane to a millionth of the triangles' size, is not counted; such
    a contact shows as a distance 0).
Adjacent means near on the mesh graph, not in space: a pair is left out when some vertex of one
and some vertex of the other are fewer than K edges apart (--exclude-ring K). K = 1, the
default, is the mesh-only rule: pairs that share a vertex (a vertex and a triangle it is a
corner of, two edges with a common end). K = 2 also leaves out pairs joined by an edge (a vertex
and every triangle touching one of its neighbours, two edges with neighbouring ends), K = 3 the
next ring. A contact model that excludes pairs sharing a triangle or a bond lies between these:
a bond may be longer than an edge. Intersections are counted over all triangle pairs that share
no vertex, whatever K.
Under K = 1 even a flat sheet has pairs closer than its edges: a vertex and the far side of a
neighbouring triangle, sqrt(3)/2 of the edge apart inside an equilateral sheet, sqrt(3)/4 at
the right-angled halves that end make_sheet's equilateral rows, 1/sqrt(2) across a right
triangle's diagonal; a radius of the mean edge finds them. Under K = 2 a flat sheet of these
patterns has no pair within its mean edge.

How: a uniform grid whose cells are the largest box plus R wide (each box filed by its lowest
corner, so boxes within R lie in neighbouring cells) pairs the bounding boxes of the vertices,
edges and triangles, numpy-vectorized; the pairs whose boxes lie within R are measured exactly
in double precision: point-triangle distance over all its Voronoi regions (the face, the three
edges, the three corners), segment-segment distance including parallel, collinear and
zero-length segments (the interior solution of the two lines or an end point against the other
segment, whichever is closer). Intersections: orientation (signed volume) tests of each edge of
one triangle against the other.

Output: a header line (`#`) and one line per frame: the file, the timestep, the smallest
point-triangle distance with its pair (vertex ID; the triangle's three IDs) and where (the
middle of the two closest points), the same for edge-edge (each edge's two IDs), the number of
intersecting triangle pairs, and the seconds the frame took. `none closer than R` where no pair
is. --json prints one JSON object instead. Exit status: 0; 1 with --dmin D when any distance
is below D or any triangles intersect in any frame; 2 on a bad file or argument.

From Python (tests): MeshGaps(vertices, faces, first_id, exclude_ring).check(x, radius, dmin)
returns a FrameGaps; read_dump(path) yields DumpFrame(step, ids, xyz);
point_triangle_distance(), segment_segment_distance(), segment_crosses_triangle() and
box_pairs() are the pieces.
"""
from __future__ import annotations

import argparse
import itertools
import json
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

try:
    import numpy as np
except ImportError:
    print(f"mesh_gaps: {sys.executable} has no numpy: run it with /usr/bin/python3 (numpy "
          f"from Debian's python3-numpy, which tools/setup.sh installs)", file=sys.stderr)
    sys.exit(2)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from make_sheet import read_obj  # noqa: E402

CROSSINGS_KEPT = 20         # intersecting triangle pairs listed per frame (all are counted)
COPLANAR = 1e-6             # signed volumes below this times the size cubed count as zero


# ---------------------------------------------------------------- exact distances
# Every function takes arrays whose last axis holds x, y, z and works row by row (leading axes
# broadcast); single points of shape (3,) work too.


def _dot(u, v):
    return np.einsum("...i,...i->...", u, v)


def _cross(u, v):
    """u x v row by row (numpy's cross moves axes around on every call: slow on small chunks)."""
    u, v = np.broadcast_arrays(u, v)
    return np.stack([u[..., 1] * v[..., 2] - u[..., 2] * v[..., 1],
                     u[..., 2] * v[..., 0] - u[..., 0] * v[..., 2],
                     u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]], axis=-1)


def point_segment_distance(p, a, b):
    """Distance from points p to segments ab, and the closest points of the segments.

    Inputs:  p, a, b arrays (..., 3); a segment with a == b is the point a.
    Outputs: (distance (...), closest point (..., 3)).
    The closest point is a + t (b - a) with t = (p - a).(b - a) / |b - a|^2 clamped to [0, 1].
    """
    ab = b - a
    length2 = _dot(ab, ab)
    t = _dot(p - a, ab) / np.where(length2 > 0, length2, 1.0)
    t = np.clip(np.where(length2 > 0, t, 0.0), 0.0, 1.0)
    closest = a + t[..., None] * ab
    return np.sqrt(_dot(p - closest, p - closest)), closest


def point_triangle_distance(p, a, b, c):
    """Distance from points p to triangles abc, and the closest points of the triangles.

    Inputs:  p, a, b, c arrays (..., 3); degenerate triangles (zero area) are allowed.
    Outputs: (distance (...), closest point (..., 3)).
    The face region: the projection q of p onto the triangle's plane (normal n) lies inside
    when each edge sees it on the inner side, ((b - a) x (p - a)).n >= 0 and likewise for bc
    and ca (p - q is along n, so p itself may be used); then the distance is
    |(p - a).n| / |n|. Otherwise the closest point lies on the boundary: the nearest of the
    three edges, each clamped to its ends (the edge and corner regions).
    """
    n = _cross(b - a, c - a)
    nn = _dot(n, n)
    best, closest = point_segment_distance(p, a, b)
    for u, v in ((b, c), (c, a)):
        d, q = point_segment_distance(p, u, v)
        nearer = d < best
        best = np.where(nearer, d, best)
        closest = np.where(nearer[..., None], q, closest)
    inside = nn > 0
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= _dot(_cross(v - u, p - u), n) >= 0
    height = _dot(p - a, n) / np.where(nn > 0, nn, 1.0)
    foot = p - height[..., None] * n
    best = np.where(inside, np.abs(height) * np.sqrt(nn), best)
    closest = np.where(inside[..., None], foot, closest)
    return best, closest


def segment_segment_distance(p1, q1, p2, q2):
    """Distance between segments p1q1 and p2q2, and the closest point of each.

    Inputs:  p1, q1, p2, q2 arrays (..., 3); zero-length segments are allowed.
    Outputs: (distance (...), closest point on p1q1 (..., 3), closest point on p2q2 (..., 3)).
    |p1 + s d1 - p2 - t d2|^2 (d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2) is a convex quadratic
    on the square 0 <= s, t <= 1: its minimum is either the lines' closest pair,
    s = (b f - c e) / D, t = (a f - b c) / D with a = d1.d1, b = d1.d2, c = d1.r, e = d2.d2,
    f = d2.r, D = a e - b^2, when both lie in [0, 1], or on an edge of the square: an end point
    of one segment against the other segment. All five candidates are real pairs of points,
    so the smallest is never below the true distance; parallel lines (D <= 1e-14 a e, where the
    lines' pair is ill-defined) and zero-length segments are left to the four end-point
    candidates, among which a closest pair then always is.
    """
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, b, c, e, f = _dot(d1, d1), _dot(d1, d2), _dot(d1, r), _dot(d2, d2), _dot(d2, r)
    D = a * e - b * b
    lines = D > 1e-14 * a * e
    safe = np.where(lines, D, 1.0)
    s, t = (b * f - c * e) / safe, (a * f - b * c) / safe
    lines &= (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)
    on1 = p1 + np.where(lines, s, 0.0)[..., None] * d1
    on2 = p2 + np.where(lines, t, 0.0)[..., None] * d2
    best = np.where(lines, np.sqrt(_dot(on1 - on2, on1 - on2)), np.inf)
    for point, (u, v), first in ((p1, (p2, q2), True), (q1, (p2, q2), True),
                                 (p2, (p1, q1), False), (q2, (p1, q1), False)):
        d, q = point_segment_distance(point, u, v)
        nearer = d < best
        best = np.where(nearer, d, best)
        near3 = nearer[..., None]
        on1 = np.where(near3, point if first else q, on1)
        on2 = np.where(near3, q if first else point, on2)
    return best, on1, on2


def _volume(a, b, c, d):
    """Six times the signed volume of the tetrahedron abcd: (b - a).((c - a) x (d - a))."""
    return _dot(b - a, _cross(c - a, d - a))


def segment_crosses_triangle(p, q, a, b, c):
    """Whether segments pq pass through the interiors of triangles abc (strictly).

    Inputs:  p, q, a, b, c arrays (..., 3).
    Outputs: bool (...): p and q on strictly opposite sides of the triangle's plane, and the
    line pq passing strictly inside the three edges (the signed volumes pqab, pqbc, pqca all
    of one sign). Touching, grazing and coplanar cases give False: a signed volume within
    COPLANAR times the cube of the pair's size counts as zero, i.e. crossings shallower than
    about a millionth of the triangles' size are not counted (a dump prints 8 digits or more;
    the triangles of a flat sheet are coplanar to that precision, and the signs of their volumes
    would be those of the last digits).
    """
    size = (np.linalg.norm(b - a, axis=-1) + np.linalg.norm(c - a, axis=-1) +
            np.linalg.norm(q - p, axis=-1)) / 3.0
    tol = COPLANAR * size ** 3
    vp, vq = _volume(a, b, c, p), _volume(a, b, c, q)
    sides = ((vp > tol) & (vq < -tol)) | ((vp < -tol) & (vq > tol))
    u, v, w = _volume(p, q, a, b), _volume(p, q, b, c), _volume(p, q, c, a)
    return sides & (((u > tol) & (v > tol) & (w > tol)) | ((u < -tol) & (v < -tol) & (w < -tol)))


# ---------------------------------------------------------------- broad phase


def box_pairs(lo_a, hi_a, lo_b=None, hi_b=None, gap=0.0):
    """Pairs of axis-aligned boxes whose gap is at most `gap` along every axis, in chunks.

    Inputs:  lo_a, hi_a (n, 3) the boxes' corners; lo_b, hi_b (m, 3) a second set, or None to
             pair the first set with itself; gap >= 0.
    Outputs: yields (i, j) index arrays: every pair with lo_b[j] - hi_a[i] <= gap and
             lo_a[i] - hi_b[j] <= gap on all three axes exactly once (with i < j when pairing a
             set with itself), in one chunk.
    The grid: cells h = (largest box side) + gap wide, each box filed under the cell of its
    lowest corner. Two boxes within `gap` have lowest corners less than h apart on each axis,
    so they are filed in the same or neighbouring cells: each box of a is matched against the
    27 cells around its own, through the b boxes sorted by cell.
    """
    same = lo_b is None
    if same:
        lo_b, hi_b = lo_a, hi_a
    if len(lo_a) == 0 or len(lo_b) == 0:
        return
    h = max(float((hi_a - lo_a).max()), float((hi_b - lo_b).max())) + gap
    h = h if h > 0 else 1.0
    origin = np.minimum(lo_a.min(axis=0), lo_b.min(axis=0))
    cell_a = np.floor((lo_a - origin) / h).astype(np.int64) + 1     # 0 and top + 1 stay free
    cell_b = np.floor((lo_b - origin) / h).astype(np.int64) + 1
    dims = np.maximum(cell_a.max(axis=0), cell_b.max(axis=0)) + 2
    if int(dims[0]) * int(dims[1]) * int(dims[2]) >= 2**62:
        raise ValueError(f"mesh_gaps: the positions span {dims.tolist()} grid cells of "
                         f"{h:.3g}: too many to number (has the mesh blown apart?)")

    def key(cells):
        return (cells[:, 0] * dims[1] + cells[:, 1]) * dims[2] + cells[:, 2]

    order = np.argsort(key(cell_b), kind="stable")
    sorted_keys = key(cell_b)[order]
    offsets = np.array(list(itertools.product((-1, 0, 1), repeat=3)))
    wanted = key((cell_a[:, None, :] + offsets[None, :, :]).reshape(-1, 3))   # 27 per box of a
    start = np.searchsorted(sorted_keys, wanted, "left")
    count = np.searchsorted(sorted_keys, wanted, "right") - start
    total = int(count.sum())
    if total == 0:
        return
    i = np.repeat(np.arange(len(wanted)) // len(offsets), count)
    first = np.cumsum(count) - count                 # where each cell's run starts in i
    j = order[np.repeat(start - first, count) + np.arange(total)]
    if same:
        keep = i < j
        i, j = i[keep], j[keep]
    for axis in range(3):                            # one axis at a time, on what is left
        keep = ((lo_b[j, axis] - hi_a[i, axis] <= gap)
                & (lo_a[i, axis] - hi_b[j, axis] <= gap))
        i, j = i[keep], j[keep]
    yield i, j


# ---------------------------------------------------------------- the mesh and one frame


@dataclass
class Nearest:
    """The closest pair of one kind: atom IDs of each side, the distance, and where (the middle
    of the two closest points)."""
    distance: float
    first: list
    second: list
    at: list


@dataclass
class FrameGaps:
    """What one frame shows. point_triangle / edge_edge: the closest pair closer than the
    radius, or None; measured: the pairs closer than the radius; below_dmin: those closer than
    dmin (0 without dmin); intersections: triangle pairs whose interiors cross, the first
    CROSSINGS_KEPT of them (atom IDs) in crossing_pairs."""
    radius: float
    dmin: float | None = None
    point_triangle: Nearest | None = None
    edge_edge: Nearest | None = None
    measured: dict = field(default_factory=lambda: {"point_triangle": 0, "edge_edge": 0})
    below_dmin: dict = field(default_factory=lambda: {"point_triangle": 0, "edge_edge": 0})
    intersections: int = 0
    crossing_pairs: list = field(default_factory=list)

    @property
    def fails(self) -> bool:
        """A distance below dmin or an intersection (False without dmin)."""
        return self.dmin is not None and (self.intersections > 0
                                          or any(self.below_dmin.values()))


class MeshGaps:
    """A triangle mesh's topology, and the distances and intersections of its positions.

    Inputs:  vertices (n, 3) of the OBJ file (only for the default radius: the mean edge
             length); faces (m, 3) 0-based; first_id the atom ID of vertex 0; exclude_ring
             K >= 1: pairs with a vertex of one fewer than K edges from a vertex of the other
             are left out (1: pairs sharing a vertex).
    """

    def __init__(self, vertices, faces, first_id: int = 1, exclude_ring: int = 1):
        if exclude_ring < 1:
            raise ValueError(f"mesh_gaps: --exclude-ring must be >= 1 (got {exclude_ring})")
        self.vertices = np.asarray(vertices, dtype=float).reshape(-1, 3)
        self.faces = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
        self.first_id, self.ring = int(first_id), int(exclude_ring)
        n = len(self.vertices)
        pairs = np.sort(self.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        self.edges = np.unique(pairs, axis=0)
        self.used = np.unique(self.faces)            # vertices of some triangle
        lengths = np.linalg.norm(self.vertices[self.edges[:, 0]]
                                 - self.vertices[self.edges[:, 1]], axis=1)
        self.mean_edge = float(lengths.mean()) if len(lengths) else 0.0
        self._near = self._near_pairs(n) if self.ring > 1 else None

    def _near_pairs(self, n):
        """Sorted codes u n + w (u <= w) of the vertex pairs at most ring - 1 edges apart."""
        src = np.concatenate([self.edges[:, 0], self.edges[:, 1]])
        dst = np.concatenate([self.edges[:, 1], self.edges[:, 0]])
        order = np.argsort(src, kind="stable")
        src, dst = src[order], dst[order]
        start = np.searchsorted(src, np.arange(n + 1))   # neighbours of v: dst[start[v]:start[v+1]]
        u, w = np.arange(n), np.arange(n)                # distance 0, both orders kept
        for _ in range(self.ring - 1):                   # one more edge each time
            count = start[w + 1] - start[w]
            first = np.cumsum(count) - count
            step = dst[np.repeat(start[w] - first, count) + np.arange(int(count.sum()))]
            codes = np.unique(np.concatenate([u * n + w, np.repeat(u, count) * n + step]))
            u, w = codes // n, codes % n
        return np.unique(np.minimum(u, w) * n + np.maximum(u, w))

    def adjacent(self, va, vb):
        """Rows where a vertex of va (k, p) and a vertex of vb (k, q) are fewer than
        exclude_ring edges apart (bool (k,))."""
        if self._near is None or len(va) == 0:
            return (va[:, :, None] == vb[:, None, :]).any(axis=(1, 2))
        n = len(self.vertices)
        u, w = va[:, :, None], vb[:, None, :]
        codes = (np.minimum(u, w) * n + np.maximum(u, w)).reshape(len(va), -1)
        where = np.minimum(np.searchsorted(self._near, codes), len(self._near) - 1)
        return (self._near[where] == codes).any(axis=1)

    def ids(self, vertices):
        return [int(v) + self.first_id for v in vertices]

    def check(self, x, radius=None, dmin=None) -> FrameGaps:
        """Distances and intersections of the mesh at positions x (n, 3).

        radius: the search radius (default the mean edge length; raised to dmin); dmin: the
        distance below which pairs are counted in below_dmin.
        """
        x = np.asarray(x, dtype=float)
        radius = self.mean_edge if radius is None else float(radius)
        if dmin is not None:
            radius = max(radius, float(dmin))
        out = FrameGaps(radius=radius, dmin=dmin)
        tri = x[self.faces]
        tri_lo, tri_hi = tri.min(axis=1), tri.max(axis=1)

        points = x[self.used]
        for i, j in box_pairs(points, points, tri_lo, tri_hi, radius):
            v, f = self.used[i], self.faces[j]
            keep = ~self.adjacent(v[:, None], f)
            v, f = v[keep], f[keep]
            d, q = point_triangle_distance(x[v], x[f[:, 0]], x[f[:, 1]], x[f[:, 2]])
            self._keep_nearest(out, "point_triangle", d, v[:, None], f, x[v], q)

        ends = x[self.edges]
        edge_lo, edge_hi = ends.min(axis=1), ends.max(axis=1)
        for i, j in box_pairs(edge_lo, edge_hi, gap=radius):
            e1, e2 = self.edges[i], self.edges[j]
            keep = ~self.adjacent(e1, e2)
            e1, e2 = e1[keep], e2[keep]
            d, q1, q2 = segment_segment_distance(x[e1[:, 0]], x[e1[:, 1]],
                                                 x[e2[:, 0]], x[e2[:, 1]])
            self._keep_nearest(out, "edge_edge", d, e1, e2, q1, q2)

        for i, j in box_pairs(tri_lo, tri_hi, gap=0.0):
            f1, f2 = self.faces[i], self.faces[j]
            keep = ~(f1[:, :, None] == f2[:, None, :]).any(axis=(1, 2))
            f1, f2 = f1[keep], f2[keep]
            crossing = np.zeros(len(f1), dtype=bool)
            for one, other in ((f1, f2), (f2, f1)):
                a, b, c = x[other[:, 0]], x[other[:, 1]], x[other[:, 2]]
                for s, t in ((0, 1), (1, 2), (2, 0)):
                    crossing |= segment_crosses_triangle(x[one[:, s]], x[one[:, t]], a, b, c)
            out.intersections += int(crossing.sum())
            room = CROSSINGS_KEPT - len(out.crossing_pairs)
            for g, h in zip(f1[crossing][:room], f2[crossing][:room]):
                out.crossing_pairs.append([self.ids(g), self.ids(h)])
        return out

    def _keep_nearest(self, out, kind, d, va, vb, qa, qb):
        """Fold one chunk of measured pairs (distances d, vertex rows va, vb, closest points qa,
        qb) into out's nearest pair and counts of that kind."""
        close = d < out.radius
        out.measured[kind] += int(close.sum())
        if out.dmin is not None:
            out.below_dmin[kind] += int((d < out.dmin).sum())
        if not close.any():
            return
        k = int(np.argmin(np.where(close, d, np.inf)))
        best = getattr(out, kind)
        if best is None or d[k] < best.distance:
            setattr(out, kind, Nearest(float(d[k]), self.ids(va[k]), self.ids(vb[k]),
                                       (0.5 * (qa[k] + qb[k])).tolist()))


# ---------------------------------------------------------------- dumps


@dataclass
class DumpFrame:
    path: str
    step: int
    ids: np.ndarray         # (natoms,) int64
    xyz: np.ndarray         # (natoms, 3)


def read_dump(path):
    """Frames of a LAMMPS `dump custom` text file, one at a time.

    Inputs:  path of a file of frames ITEM: TIMESTEP / NUMBER OF ATOMS / BOX BOUNDS / ATOMS with
             columns including id and x y z (or xu yu zu, preferred when present).
    Outputs: yields DumpFrame(path, step, ids, xyz) in file order.
    Raises ValueError naming the file and timestep of a frame with missing columns or rows.
    """
    path = str(path)
    step, natoms = None, None
    with open(path) as src:
        for line in src:
            if line.startswith("ITEM: TIMESTEP"):
                step = int(src.readline())
            elif line.startswith("ITEM: NUMBER OF ATOMS"):
                natoms = int(src.readline())
            elif line.startswith("ITEM: ATOMS"):
                where = f"mesh_gaps: dump {path} timestep {step}"
                if step is None or natoms is None:
                    raise ValueError(f"{where}: ITEM: ATOMS before the TIMESTEP and NUMBER OF "
                                     f"ATOMS items")
                names = line.split()[2:]
                coords = next((c for c in (["xu", "yu", "zu"], ["x", "y", "z"])
                               if set(c) <= set(names)), None)
                if "id" not in names or coords is None:
                    raise ValueError(f"{where}: needs columns id and x y z (or xu yu zu); has "
                                     f"{' '.join(names)}")
                rows = list(itertools.islice(src, natoms))
                values = np.array(" ".join(rows).split(), dtype=float)
                if len(rows) < natoms or values.size != natoms * len(names):
                    raise ValueError(f"{where}: expected {natoms} rows of {len(names)} "
                                     f"columns; the frame is cut short or malformed")
                table = values.reshape(natoms, len(names))
                yield DumpFrame(path, step, table[:, names.index("id")].astype(np.int64),
                                table[:, [names.index(c) for c in coords]])
                step, natoms = None, None


def mesh_positions(frame: DumpFrame, n: int, first_id: int = 1):
    """Positions (n, 3) of atoms first_id .. first_id + n - 1 in a frame.

    Raises ValueError naming the first missing atom (and the frame's timestep), or an atom
    whose position is not finite.
    """
    where = f"mesh_gaps: dump {frame.path} timestep {frame.step}"
    k = frame.ids - first_id
    mine = (k >= 0) & (k < n)
    x = np.full((n, 3), np.nan)
    x[k[mine]] = frame.xyz[mine]
    present = np.zeros(n, dtype=bool)
    present[k[mine]] = True
    if not present.all():
        missing = np.flatnonzero(~present)
        more = f" (and {len(missing) - 1} more)" if len(missing) > 1 else ""
        raise ValueError(f"{where}: atom {missing[0] + first_id} (mesh vertex "
                         f"{missing[0] + 1} with first-id {first_id}) is missing{more}")
    bad = np.flatnonzero(~np.isfinite(x).all(axis=1))
    if len(bad):
        raise ValueError(f"{where}: atom {bad[0] + first_id} has position {x[bad[0]].tolist()}")
    return x


# ---------------------------------------------------------------- command line


def _pair_text(kind, best: Nearest | None, radius):
    if best is None:
        return f"{kind} none closer than {radius:.6g}"
    where = " ".join(f"{c:.6g}" for c in best.at)
    sides = (f"vertex {best.first[0]} - triangle {' '.join(map(str, best.second))}"
             if kind == "point-triangle" else
             f"edge {'-'.join(map(str, best.first))} - edge {'-'.join(map(str, best.second))}")
    return f"{kind} {best.distance:.6g} ({sides}) at ({where})"


def frame_line(frame: DumpFrame, gaps: FrameGaps, seconds: float) -> str:
    """The one line printed for a frame."""
    parts = [f"{frame.path} step {frame.step}:",
             _pair_text("point-triangle", gaps.point_triangle, gaps.radius) + ";",
             _pair_text("edge-edge", gaps.edge_edge, gaps.radius) + ";",
             f"{gaps.intersections} intersecting triangle pairs;"]
    if gaps.dmin is not None:
        parts.append(f"below dmin {gaps.dmin:.6g}: {gaps.below_dmin['point_triangle']} "
                     f"point-triangle, {gaps.below_dmin['edge_edge']} edge-edge;")
    parts.append(f"{seconds:.2f} s")
    return " ".join(parts)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh", metavar="MESH.obj", help="the OBJ file read_mesh read")
    ap.add_argument("dumps", metavar="DUMP", nargs="+", help="dump custom files (id x y z)")
    ap.add_argument("--first-id", type=int, default=1, metavar="N",
                    help="atom ID of the file's first vertex (default 1)")
    ap.add_argument("--radius", type=float, metavar="R",
                    help="search radius (default: the mesh's mean edge length; at least D)")
    ap.add_argument("--dmin", type=float, metavar="D",
                    help="exit 1 if a distance is below D or triangles intersect")
    ap.add_argument("--exclude-ring", type=int, default=1, metavar="K",
                    help="leave out pairs with vertices fewer than K edges apart (default 1: "
                         "sharing a vertex)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args(argv)
    for name in ("radius", "dmin"):
        value = getattr(args, name)
        if value is not None and not value >= 0:
            ap.error(f"--{name} must be >= 0 (got {value})")
    try:
        vertices, faces = read_obj(args.mesh)
        mesh = MeshGaps(vertices, faces, args.first_id, args.exclude_ring)
        radius = mesh.mean_edge if args.radius is None else args.radius
        report = {"mesh": args.mesh, "vertices": len(mesh.vertices),
                  "triangles": len(mesh.faces), "edges": len(mesh.edges),
                  "first_id": args.first_id, "exclude_ring": args.exclude_ring,
                  "radius": max(radius, args.dmin or 0.0), "dmin": args.dmin, "frames": []}
        if not args.json:
            print(f"# {args.mesh}: {report['vertices']} vertices, {report['triangles']} "
                  f"triangles, atom IDs from {args.first_id}; pairs within {report['radius']:.6g}"
                  f", excluding those fewer than {args.exclude_ring} edge(s) apart", flush=True)
        failed = False
        for path in args.dumps:
            for frame in read_dump(path):
                begin = time.perf_counter()
                x = mesh_positions(frame, len(mesh.vertices), args.first_id)
                gaps = mesh.check(x, radius, args.dmin)
                seconds = time.perf_counter() - begin
                failed |= gaps.fails
                if args.json:
                    report["frames"].append({"file": path, "step": frame.step, **asdict(gaps),
                                             "fails": gaps.fails, "seconds": seconds})
                else:
                    print(frame_line(frame, gaps, seconds), flush=True)
    except (OSError, ValueError) as err:
        print(err if str(err).startswith(("mesh_gaps", "read_obj")) else f"mesh_gaps: {err}",
              file=sys.stderr)
        return 2
    if args.json:
        report["ok"] = not failed
        print(json.dumps(report, indent=1))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
