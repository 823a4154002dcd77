"""Independent reference values for the peri/nosb tests, computed in numpy from the formulas of
doc/pair_peri_nosb.rst and doc/theory.rst (not from the C++): strain energy densities on signed singular values,
the non-affine part of a deformation (the zero-energy-mode measure |eta - F xi|), and the
elastic constants of LAMMPS's peri/lps on a simple cubic lattice.
"""
from __future__ import annotations

import numpy as np

# The material of the test decks (decks/nosb_*.lmp): K = 1 GPa, G = 0.6 K (nu = 1/4).
K_TEST = 1.0e9
G_TEST = 0.6e9
A_TEST = 1.0e-3                 # lattice spacing
HORIZON_TEST = 3.0002 * A_TEST  # horizon: 3 spacings


def lame(K: float = K_TEST, G: float = G_TEST):
    """mu, lambda from bulk and shear modulus (doc/pair_peri_nosb.rst)."""
    return G, K - 2.0 * G / 3.0


def young_poisson(K: float = K_TEST, G: float = G_TEST):
    return 9.0 * K * G / (3.0 * K + G), (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G))


def signed_singular_values(F) -> np.ndarray:
    """Singular values of F with the sign convention of doc/pair_peri_nosb.rst: F = U diag(s) V^T with
    det U = det V = +1, so the smallest one is negative exactly when det F < 0."""
    s = np.linalg.svd(np.asarray(F, float), compute_uv=False)  # descending, >= 0
    if np.linalg.det(F) < 0.0:
        s[-1] = -s[-1]
    return s


def neohookean_volumetric(J: float, mu: float, lam: float, J0: float = 0.1) -> float:
    """g(J) = -mu ln J + lambda/2 (ln J)^2, continued below J0 by its Taylor polynomial of
    second order about J0 (doc/pair_peri_nosb.rst: 'continued smoothly and documented below a small
    positive J'; J0 = 0.1 for lambda >= 0 as documented in material_neohookean.h)."""
    assert lam >= 0.0, "the continuation threshold differs for lambda < 0"
    if J >= J0:
        return -mu * np.log(J) + 0.5 * lam * np.log(J) ** 2
    l0 = np.log(J0)
    g0 = -mu * l0 + 0.5 * lam * l0 ** 2
    g1 = (lam * l0 - mu) / J0
    g2 = (mu + lam * (1.0 - l0)) / J0 ** 2
    return g0 + g1 * (J - J0) + 0.5 * g2 * (J - J0) ** 2


def strain_energy_density(model: str, F, K: float = K_TEST, G: float = G_TEST) -> float:
    """W(F) of the models of doc/pair_peri_nosb.rst."""
    F = np.asarray(F, float)
    mu, lam = lame(K, G)
    if model == "linear":
        s = signed_singular_values(F)
        return mu * np.sum((s - 1.0) ** 2) + 0.5 * lam * np.sum(s - 1.0) ** 2
    if model == "stvk":
        E = 0.5 * (F.T @ F - np.eye(3))
        return mu * np.sum(E * E) + 0.5 * lam * np.trace(E) ** 2
    if model == "neohookean":
        J = np.linalg.det(F)
        return 0.5 * mu * (np.trace(F.T @ F) - 3.0) + neohookean_volumetric(J, mu, lam)
    raise ValueError(model)


def signed_svd(F):
    """U, s, V with F = U diag(s) V^T, det U = det V = +1 (s[-1] < 0 when det F < 0)."""
    U, s, Vt = np.linalg.svd(np.asarray(F, float))
    V = Vt.T.copy()
    if np.linalg.det(U) < 0.0:
        U[:, -1] *= -1.0
        s[-1] *= -1.0
    if np.linalg.det(V) < 0.0:
        V[:, -1] *= -1.0
        s[-1] *= -1.0
    return U, s, V


def first_piola(model: str, F, K: float = K_TEST, G: float = G_TEST) -> np.ndarray:
    """P = dW/dF of the models of doc/pair_peri_nosb.rst (closed forms; test_nosb_reference checks them
    against finite differences of strain_energy_density)."""
    F = np.asarray(F, float)
    mu, lam = lame(K, G)
    if model == "linear":
        U, s, V = signed_svd(F)
        return U @ np.diag(2.0 * mu * (s - 1.0) + lam * np.sum(s - 1.0)) @ V.T
    if model == "stvk":
        E = 0.5 * (F.T @ F - np.eye(3))
        return F @ (2.0 * mu * E + lam * np.trace(E) * np.eye(3))
    if model == "neohookean":
        J = np.linalg.det(F)
        cof = J * np.linalg.inv(F).T
        J0 = 0.1
        if J >= J0:
            dg = (lam * np.log(J) - mu) / J
        else:
            l0 = np.log(J0)
            dg = (lam * l0 - mu) / J0 + (mu + lam * (1.0 - l0)) / J0 ** 2 * (J - J0)
        return mu * F + dg * cof
    raise ValueError(model)


def affine_force_vectors(X: np.ndarray, V: np.ndarray, horizon: float = HORIZON_TEST,
                         chunk: int = 256) -> np.ndarray:
    """Geometry part of the correspondence forces of an affine deformation (doc/theory.rst,
    "Correspondence"): with the same first Piola stress P at every particle (the stabilization term
    vanishes), f_i = sum_j omega_ij (P K_i^-1 + P K_j^-1) xi_ij = P d_i with
    d_i = sum_j omega_ij (K_i^-1 + K_j^-1) xi_ij and K_i = sum_j omega_ij xi_ij xi_ij^T.
    Returns d (n x 3); the force densities are d @ P.T."""
    n = len(X)
    Kinv = np.empty((n, 3, 3))
    for lo in range(0, n, chunk):
        xi, om = _bonds(X, V, horizon, lo, min(lo + chunk, n))
        Kinv[lo:lo + chunk] = np.linalg.inv(np.einsum("ij,ija,ijb->iab", om, xi, xi))
    d = np.empty((n, 3))
    for lo in range(0, n, chunk):
        hi = min(lo + chunk, n)
        xi, om = _bonds(X, V, horizon, lo, hi)
        d[lo:hi] = (np.einsum("iab,ij,ijb->ia", Kinv[lo:hi], om, xi)
                    + np.einsum("jab,ij,ijb->ia", Kinv, om, xi))
    return d


def _bonds(X, V, horizon, lo, hi):
    """bond_weights for the rows lo:hi."""
    xi = X[None, :, :] - X[lo:hi, None, :]
    r = np.linalg.norm(xi, axis=2)
    h = 0.5 * (np.cbrt(V[lo:hi])[:, None] + np.cbrt(V)[None, :])
    beta = np.clip((horizon + 0.5 * h - r) / h, 0.0, 1.0)
    return xi, np.where((r > 0.0) & (r <= horizon), beta * V[None, :], 0.0)


def rotation(axis, degrees: float) -> np.ndarray:
    """Rotation matrix about axis by the right-hand rule."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    t = np.radians(degrees)
    Kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(t) * Kx + (1 - np.cos(t)) * Kx @ Kx


def lattice_index(coords, a: float = A_TEST) -> np.ndarray:
    """Integer lattice indices of reference positions on the sc lattice of the decks."""
    return np.rint(np.asarray(coords) / a).astype(int)


def surface_depth(reference: np.ndarray, n: int, a: float = A_TEST) -> np.ndarray:
    """Distance of each particle of an n^3 block from the nearest face, in lattice spacings."""
    idx = lattice_index(reference, a)
    return np.min(np.minimum(idx, n - 1 - idx), axis=1)


def bond_weights(X: np.ndarray, V: np.ndarray, horizon: float = HORIZON_TEST):
    """Reference bonds xi_ij = X_j - X_i and weights omega_ij = beta_ij V_j of every pair
    within the horizon (influence function 1 and the partial-volume factor beta of the
    built-in PERI styles: 1 up to delta - h/2, linear to 0 at delta + h/2)."""
    xi = X[None, :, :] - X[:, None, :]
    r = np.linalg.norm(xi, axis=2)
    h = 0.5 * (np.cbrt(V)[:, None] + np.cbrt(V)[None, :])
    beta = np.clip((horizon + 0.5 * h - r) / h, 0.0, 1.0)
    omega = np.where((r > 0.0) & (r <= horizon), beta * V[None, :], 0.0)
    return xi, omega


def nonaffine_measure(X: np.ndarray, Y: np.ndarray, V: np.ndarray,
                      horizon: float = HORIZON_TEST) -> float:
    """RMS non-affine bond strain: sqrt( sum_ij omega |eta - F_i xi|^2 / sum_ij omega |xi|^2 )
    with F_i the weighted least-squares fit of eta ~ F xi over i's family (doc/theory.rst).
    Zero for any affine deformation; it measures the zero-energy-mode content of Y."""
    xi, omega = bond_weights(X, V, horizon)
    eta = Y[None, :, :] - Y[:, None, :]
    Kt = np.einsum("ij,ija,ijb->iab", omega, xi, xi)
    M = np.einsum("ij,ija,ijb->iab", omega, eta, xi)
    F = M @ np.linalg.inv(Kt)
    res = eta - np.einsum("iab,ijb->ija", F, xi)
    num = np.einsum("ij,ija,ija->", omega, res, res)
    den = np.einsum("ij,ija,ija->", omega, xi, xi)
    return float(np.sqrt(num / den))


def lps_lattice_young_poisson(m: int = 3, K: float = K_TEST, G: float = G_TEST):
    """Young's modulus and Poisson's ratio along a cube axis of LAMMPS's peri/lps on an
    infinite simple cubic lattice with horizon (m + 0.0002) a, from its small-strain energy
    W = K theta^2 / 2 + 15 G / (2 m_w) sum_j w beta V (e^d)^2 with w = 1/|xi| and the same
    partial-volume factor (pair_peri_lps.cpp). The fourth moment of the lattice family is not
    isotropic, so the lattice is cubic, not isotropic: E and nu differ from the continuum's."""
    a = 1.0
    delta = (m + 0.0002) * a
    r = np.arange(-(m + 1), m + 2) * a
    P = np.stack(np.meshgrid(r, r, r, indexing="ij"), -1).reshape(-1, 3)
    d = np.linalg.norm(P, axis=1)
    keep = (d > 0) & (d <= delta)
    P, d = P[keep], d[keep]
    beta = np.where(np.abs(d - delta) <= 0.5 * a, (delta + 0.5 * a - d) / a, 1.0)
    w = 1.0 / d
    mw = np.sum(w * d ** 2 * beta)
    n = P / d[:, None]

    def energy(eps):
        theta = np.trace(eps)
        dev = eps - theta / 3.0 * np.eye(3)
        ed = np.einsum("ni,ij,nj->n", n, dev, n) * d
        return 0.5 * K * theta ** 2 + 7.5 * G / mw * np.sum(w * beta * ed ** 2)

    # stiffness in Voigt notation by exact second differences of the quadratic energy
    pairs = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]

    def strain(v):
        e = np.zeros((3, 3))
        for q, (i, j) in enumerate(pairs):
            e[i, j] += v[q] if i == j else 0.5 * v[q]
            if i != j:
                e[j, i] += 0.5 * v[q]
        return e

    C = np.zeros((6, 6))
    for p in range(6):
        for q in range(6):
            ep, eq = np.eye(6)[p], np.eye(6)[q]
            C[p, q] = (energy(strain(ep + eq)) - energy(strain(ep)) - energy(strain(eq))) / 1.0
    S = np.linalg.inv(C)
    return 1.0 / S[0, 0], -S[0, 1] / S[0, 0]
