#!/usr/bin/env python3
"""Candidate bending energies of a flat sheet, compared in numpy on the five mesh kinds of
validate_bending.py (examples/membranes/README.md, "Choosing a bending energy"):

    /usr/bin/python3 bending_prototype.py [--quick]

Small deflections w(x, y) of a plate in the plane z = 0, each energy a quadratic form
E = w^T K w / 2 assembled from the flat mesh:

hinge     the discrete-shells hinge of membrane/hinge.h linearised: sum over interior edges of
          c_e theta_e^2, c_e = D |e|^2 / (2 A_e), theta_e the jump of the slope of the piecewise
          linear w across the edge.
cotan     the quadratic energy of Wardetzky et al. 2007 / Bergou et al. 2006 for a flat rest
          state: D/2 sum_i (L w)_i^2 / A_i, L the cotangent Laplacian, A_i a third of the
          vertex's triangles; interior vertices only (at a flat boundary vertex L x is an
          in-plane vector, not zero). It is (tr k)^2 alone: no det k term.
avgnormal the per-triangle shape operator of Grinspun et al. 2006 with mid-edge normals the
          mean of the two triangles' normals: k_T = 1/A_T sum_i |e_i| theta_i / 2 t_i t_i^T
          (t_i the edge's outward in-plane normal), energy sum_T A_T W(k_T).
fit6      per triangle the quadratic through its three vertices and the three across its
          edges (least squares over the vertices' 1-rings when an edge is on the boundary),
          k_T its Hessian, energy sum_T A_T W(k_T).
midedge   per triangle k_T = 1/A_T sum_i |e_i| (d_i - g_T . t_i) t_i t_i^T, g_T the slope of
          the piecewise linear w on T and d_i the slope across edge i at its midpoint, the mean
          over the edge's triangles of the fit6 quadratics' slopes there: exact for quadratic
          w (as fit6), and one d_i per edge shared by both triangles, so that sum_T A_T k_T
          depends only on the boundary values (as for the hinge; fit6 lacks this).
W(k) = D/2 [(tr k)^2 - 2 (1 - nu) det k] (Kirchhoff plate).

Tables (ratios to the formula, 1 = exact):
cylinder  w = kappa s^2 / 2 on the whole 30 cm sheet (s across an axis at 0..90 degrees to the
          rows): energy over D kappa^2 / 2 times the area; relaxed: the same with only the
          vertices within 3 cells of the rim prescribed, the rest at their energy minimum
          (below 1: the mesh has softer states than the interpolated cylinder).
plate     the cantilever of validate_bending.py (nu = 0, top two rows held, uniform load,
          lumped to a third of each triangle per vertex): free-edge sag over q L^4 / (8 D),
          with L from the middle of the two held rows (mid) and from the inner held row (inner).
simply    the 30 cm square simply supported (w = 0 on the rim), nu = 0.3: centre deflection
          over Timoshenko's 0.00406 q a^4 / D.
"""
import argparse
import math
import sys
from pathlib import Path

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import make_sheet as ms  # noqa: E402

KINDS = {"equilateral": dict(pattern="equilateral"), "right": dict(pattern="right"),
         "alternate": dict(pattern="alternate"),
         "jittered": dict(pattern="alternate", jitter=0.25, seed=3),
         "graded": dict(pattern="alternate", grade=2.0)}
METHODS = ("hinge", "cotan", "avgnormal", "fit6", "midedge")


class Mesh:
    def __init__(self, kind, side, a):
        v, f = ms.rectangle(side, side, a, **KINDS[kind])
        self.rows = []
        start = 0
        for k in range(1, len(v) + 1):
            if k == len(v) or v[k][0] < v[k - 1][0]:
                self.rows.append(list(range(start, k)))
                start = k
        self.X = np.array(v, float)[:, :2]
        self.F = np.array(f, int)
        self.n = len(self.X)
        p = self.X[self.F]
        d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        self.area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        self.vertex_area = np.zeros(self.n)
        for t, tri in enumerate(self.F):
            self.vertex_area[tri] += self.area[t] / 3.0
        self.edges = {}                         # (a, b) sorted -> [(triangle, opposite vertex)]
        self.ring = [set() for _ in range(self.n)]
        for t, tri in enumerate(self.F):
            for k in range(3):
                a, b, c = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
                self.edges.setdefault((min(a, b), max(a, b)), []).append((t, c))
                self.ring[tri[k]].update(tri)
        self.boundary = np.zeros(self.n, bool)
        for (a, b), lst in self.edges.items():
            if len(lst) == 1:
                self.boundary[[a, b]] = True

    def slope(self, t):
        """g_T = G @ w[F[t]] (2 x 3), the slope of the piecewise linear w on triangle t."""
        P = self.X[self.F[t]]
        Minv = np.linalg.inv(np.array([P[1] - P[0], P[2] - P[0]]))
        return np.column_stack([-Minv[:, 0] - Minv[:, 1], Minv[:, 0], Minv[:, 1]])

    def outward(self, t, a, b):
        """Unit in-plane normal of edge (a, b) pointing out of triangle t, and the length."""
        e = self.X[b] - self.X[a]
        le = np.linalg.norm(e)
        tn = np.array([e[1], -e[0]]) / le
        if tn @ (0.5 * (self.X[a] + self.X[b]) - self.X[self.F[t]].mean(0)) < 0:
            tn = -tn
        return tn, le


def assemble(n, blocks):
    """Sparse sum of dense blocks (stencil, matrix)."""
    r, c, v = [], [], []
    for S, M in blocks:
        ii, jj = np.meshgrid(S, S, indexing="ij")
        r.append(ii.ravel())
        c.append(jj.ravel())
        v.append(M.ravel())
    return sp.csr_matrix((np.concatenate(v), (np.concatenate(r), np.concatenate(c))),
                         shape=(n, n))


def plate_matrix(nu):
    """W(k) = h^T Wm h / 2 for h = (k_xx, k_xy, k_yy), D = 1."""
    return np.array([[1.0, 0.0, nu], [0.0, 2.0 * (1.0 - nu), 0.0], [nu, 0.0, 1.0]])


def hinge_rows(m):
    """Per interior edge: theta_e as a row over its stencil, and its weight |e|^2 / (2 A_e)."""
    out = []
    for (a, b), lst in m.edges.items():
        if len(lst) != 2:
            continue
        (t1, _), (t2, _) = lst
        tn, le = m.outward(t1, a, b)
        row = {}
        for t, sign in ((t1, -1.0), (t2, 1.0)):
            g = tn @ m.slope(t)
            for k, p in enumerate(m.F[t]):
                row[p] = row.get(p, 0.0) + sign * g[k]
        out.append((row, le * le / (2.0 * (m.area[t1] + m.area[t2])), (t1, t2), (a, b)))
    return out


def K_hinge(m, nu):
    blocks = []
    for row, c, _, _ in hinge_rows(m):
        S = np.array(list(row))
        g = np.array([row[p] for p in S])
        blocks.append((S, 2.0 * c * np.outer(g, g)))
    return assemble(m.n, blocks)


def K_cotan(m, nu):
    r, c, v = [], [], []
    for tri in m.F:
        for k in range(3):
            i, j, o = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
            u, w = m.X[i] - m.X[o], m.X[j] - m.X[o]
            cot = 0.5 * (u @ w) / abs(u[0] * w[1] - u[1] * w[0])
            r += [i, j, i, j]
            c += [j, i, i, j]
            v += [cot, cot, -cot, -cot]
    L = sp.csr_matrix((v, (r, c)), shape=(m.n, m.n))
    Minv = sp.diags(np.where(m.boundary, 0.0, 1.0 / m.vertex_area))
    return L.T @ Minv @ L


def quadratic_fits(m):
    """Per triangle: stencil and the pseudo-inverse of the quadratic basis about its centroid
    (rows: value, slope x, slope y, k_xx, k_xy, k_yy)."""
    fits = []
    for t, tri in enumerate(m.F):
        S = list(tri)
        for k in range(3):
            a, b = tri[k], tri[(k + 1) % 3]
            S += [c for (t2, c) in m.edges[(min(a, b), max(a, b))] if t2 != t and c not in S]
        if len(S) < 6:
            S += sorted(set().union(*[m.ring[v] for v in tri]) - set(S))
        c = m.X[tri].mean(0)
        d = m.X[S] - c
        B = np.column_stack([np.ones(len(S)), d[:, 0], d[:, 1], 0.5 * d[:, 0] ** 2,
                             d[:, 0] * d[:, 1], 0.5 * d[:, 1] ** 2])
        fits.append((np.array(S), np.linalg.pinv(B), c))
    return fits


def curvature_energy(m, nu, curvature_rows):
    Wm = plate_matrix(nu)
    blocks = []
    for t in range(len(m.F)):
        coef = curvature_rows(t)
        S = np.array(list(coef))
        B = np.array([coef[p] for p in S]).T            # 3 x |S|
        blocks.append((S, m.area[t] * B.T @ Wm @ B))
    return assemble(m.n, blocks)


def tt(tn):
    return np.array([tn[0] ** 2, tn[0] * tn[1], tn[1] ** 2])


def K_fit6(m, nu):
    fits = quadratic_fits(m)
    return curvature_energy(m, nu, lambda t: dict(zip(fits[t][0], fits[t][1][3:6].T)))


def K_avgnormal(m, nu):
    jumps = {}
    for row, _, _, edge in hinge_rows(m):
        jumps[edge] = row

    def rows(t):
        coef = {}
        tri = m.F[t]
        for k in range(3):
            a, b = tri[k], tri[(k + 1) % 3]
            edge = (min(a, b), max(a, b))
            if edge not in jumps:
                continue
            tn, le = m.outward(t, a, b)
            # the row is (g_T2 - g_T1) . n with n out of the edge's first triangle T1: from
            # either triangle the other's slope minus its own along its outward normal
            for p, g in jumps[edge].items():
                coef[p] = coef.get(p, 0.0) + le * 0.5 * g / m.area[t] * tt(tn)
        return coef
    return curvature_energy(m, nu, rows)


def K_midedge(m, nu):
    fits = quadratic_fits(m)

    def rows(t):
        coef = {}

        def add(p, v):
            coef[p] = coef.get(p, 0.0) + v
        tri = m.F[t]
        G = m.slope(t)
        for k in range(3):
            a, b = tri[k], tri[(k + 1) % 3]
            tn, le = m.outward(t, a, b)
            mid = 0.5 * (m.X[a] + m.X[b])
            lst = m.edges[(min(a, b), max(a, b))]
            for (t2, _) in lst:                 # d: the fits' slope across the edge at mid
                S, P, c = fits[t2]
                d = mid - c
                gx = P[1] + P[3] * d[0] + P[4] * d[1]
                gy = P[2] + P[4] * d[0] + P[5] * d[1]
                for p, v in zip(S, tn[0] * gx + tn[1] * gy):
                    add(p, le / (m.area[t] * len(lst)) * v * tt(tn))
            for kk, p in enumerate(tri):        # minus g_T . t
                add(p, -le / m.area[t] * (tn @ G[:, kk]) * tt(tn))
        return coef
    return curvature_energy(m, nu, rows)


def stiffness(method, m, nu=0.0):
    return {"hinge": K_hinge, "cotan": K_cotan, "avgnormal": K_avgnormal, "fit6": K_fit6,
            "midedge": K_midedge}[method](m, nu).tocsr()


def cylinder(m, K, angle, relaxed):
    ph = math.radians(angle)
    s = -m.X[:, 0] * math.sin(ph) + m.X[:, 1] * math.cos(ph)
    w = 0.5 * s * s
    if not relaxed:
        return 0.5 * w @ (K @ w) / (0.5 * m.area.sum())
    h = np.median([np.linalg.norm(m.X[a] - m.X[b]) for a, b in m.edges])
    lo, hi = m.X.min(0), m.X.max(0)
    rim = np.minimum(np.minimum(m.X[:, 0] - lo[0], hi[0] - m.X[:, 0]),
                     np.minimum(m.X[:, 1] - lo[1], hi[1] - m.X[:, 1])) < 3 * h
    free = ~rim
    wr = w.copy()
    wr[free] = spl.spsolve(K[free][:, free].tocsc(), -(K[free][:, rim] @ w[rim]))
    return (wr @ (K @ wr)) / (w @ (K @ w))


def solve(K, m, held):
    free = ~held
    w = np.zeros(m.n)
    w[free] = spl.spsolve(K[free][:, free].tocsc(), m.vertex_area[free])
    return w


def cantilever(m, K):
    held = np.zeros(m.n, bool)
    held[m.rows[-1] + m.rows[-2]] = True
    y = [m.X[r, 1].mean() for r in m.rows]
    tip = solve(K, m, held)[m.rows[0]].mean()
    L_mid, L_inner = 0.5 * (y[-1] + y[-2]) - y[0], y[-2] - y[0]
    return tip / (L_mid ** 4 / 8.0), tip / (L_inner ** 4 / 8.0)


def simply(m, K):
    w = solve(K, m, m.boundary)
    side = m.X[:, 0].max() - m.X[:, 0].min()
    return w[np.argmin(np.linalg.norm(m.X, axis=1))] / (0.00406 * side ** 4)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="1 cm cells only")
    ap.add_argument("--methods", default=",".join(METHODS))
    args = ap.parse_args()
    methods = args.methods.split(",")
    sizes = (0.01,) if args.quick else (0.01, 0.005)
    head = "".join(f"{k:>12s}" for k in KINDS)
    for method in methods:
        print(f"== {method}")
        print(f"{'':28s}{head}")
        meshes = {k: Mesh(k, 0.3, 0.01) for k in KINDS}
        K0 = {k: stiffness(method, meshes[k]) for k in KINDS}
        for angle in (0, 30, 45, 60, 90):
            print(f"cylinder {angle:2d} deg              " +
                  "".join(f"{cylinder(meshes[k], K0[k], angle, False):12.4f}" for k in KINDS))
        for angle in (0, 45):
            print(f"cylinder {angle:2d} deg relaxed      " +
                  "".join(f"{cylinder(meshes[k], K0[k], angle, True):12.4f}" for k in KINDS))
        if method == "cotan":                   # its rim vertices carry no energy: singular
            continue
        for a in sizes:
            ms_ = {k: (meshes[k] if a == 0.01 else Mesh(k, 0.3, a)) for k in KINDS}
            Ks = {k: (K0[k] if a == 0.01 else stiffness(method, ms_[k])) for k in KINDS}
            sag = {k: cantilever(ms_[k], Ks[k]) for k in KINDS}
            print(f"plate {a * 1000:3.0f} mm, L mid            " +
                  "".join(f"{sag[k][0]:12.4f}" for k in KINDS))
            print(f"plate {a * 1000:3.0f} mm, L inner          " +
                  "".join(f"{sag[k][1]:12.4f}" for k in KINDS))
            Kp = {k: stiffness(method, ms_[k], 0.3) for k in KINDS}
            print(f"simply {a * 1000:3.0f} mm, nu 0.3        " +
                  "".join(f"{simply(ms_[k], Kp[k]):12.4f}" for k in KINDS), flush=True)


if __name__ == "__main__":
    main()
