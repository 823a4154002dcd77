"""Shared pieces of the fix sissm tests (issue 4): measured explicit stability limits, a check
that they still bracket the limit of the current build, and small array helpers."""
from __future__ import annotations

import functools
import tempfile
from pathlib import Path

import numpy as np

from lammps_run import run_deck

DECKS = Path(__file__).parent / "decks"
BLOCK = DECKS / "sissm_block.lmp"
CANTILEVER = DECKS / "sissm_cantilever.lmp"
CONTINUE = DECKS / "sissm_continue.lmp"
PRESCRIBED = DECKS / "sissm_prescribed.lmp"

A = 1.0e-3  # lattice spacing of every deck (m)

# The decks name fix sissm's keywords (iterations ${iters} tolerance ${tol} solver ${solver},
# and relax/external where they have them); these values are the fix's defaults
# (doc/fix_sissm.rst), so a test that passes them runs the defaults. precond (amg with PETSc)
# and unconverged (cutback 4) are left out: the decks only name them through opts.
# test_fix_sissm_amg.py checks that a bare `fix sissm` gives the same trajectory.
FIX_DEFAULTS = {"iters": 100, "tol": 1e-6, "solver": "krylov", "relax": "no",
                "external": "implicit"}

STEEL = {"K": 160e9, "Gr": 0.5, "rho": 7800}  # G = 80 GPa

# Explicit (fix nve, velocity Verlet) stability limits of the decks, measured by bisection:
# fix nve at growing dt from a pseudo-random velocity field (vrand = 0.01 m/s excites every
# mode), 3000 steps, "stable" = finite and etotal below twice its initial value (cantilevers:
# 6000 steps under gravity, bisection between 3e-7 and 1.2e-6; pair_coeff defaults, measured
# 2026-11-29). Values are the largest stable
# dt found (the smallest unstable one is within 0.3 %). Small blocks are limited by their
# corner/edge particles, whose shape tensors are small (large K^-1), so the limit is not
# monotonic in the block size. explicit_limit_brackets() re-checks them cheaply.
EXPLICIT_LIMIT = {
    "block 2x2x2": 5.72e-7,
    "block 3x3x3": 9.35e-7,
    "block 4x3x3": 9.70e-7,
    "block 6x6x6": 1.558e-6,
    "steel 4x3x3": 2.15e-7,
    "steel 6x6x6": 3.508e-7,
    "cantilever 16x4x4": 1.048e-6,
    "cantilever 10x3x3": 8.06e-7,
}


def block_variables(name: str) -> dict:
    """sissm_block.lmp variables of the systems named in EXPLICIT_LIMIT ("block"/"steel")."""
    kind, dims = name.split()
    nx, ny, nz = (int(d) for d in dims.split("x"))
    v = {"nx": nx, "ny": ny, "nz": nz}
    if kind == "steel":
        v.update(STEEL)
    return v


def nve_is_stable(variables: dict, dt: float, workdir, nsteps: int = 3000) -> bool:
    # initial ke of the vrand field ~ N rho/2 * 3 * (0.01 m/s)^2 / 12: halt the run at 1000
    # times that, so that a blow-up ends early instead of running into huge boxes
    natoms = variables["nx"] * variables["ny"] * variables["nz"]
    halt = 1000.0 * natoms * variables.get("rho", 1000) * 1.25e-5
    run = run_deck(BLOCK, workdir, variables={**variables, "integ": "nve", "dt": dt,
                                              "nsteps": nsteps, "vrand": 0.01, "halt": halt,
                                              "thermo_every": 100}, check=False)
    if not run.ok:  # a blow-up stops the run (atoms lost, too many neighbor bins, ...)
        return False
    t = run.thermo[-1]
    e = t["TotEng"]
    return bool(t["Step"][-1] == nsteps and np.all(np.isfinite(e)) and e.max() < 2.0 * e[0])


@functools.lru_cache(maxsize=None)
def explicit_limit_brackets(name: str) -> bool:
    """fix nve is stable at 0.9 and unstable at 1.15 times the tabulated limit (checked once
    per session and system)."""
    v = block_variables(name)
    dt = EXPLICIT_LIMIT[name]
    with tempfile.TemporaryDirectory(prefix="sissm-limit-") as workdir:
        return (nve_is_stable(v, 0.9 * dt, Path(workdir) / "below")
                and not nve_is_stable(v, 1.15 * dt, Path(workdir) / "above"))


def positions(frame) -> np.ndarray:
    return np.column_stack([frame["x"], frame["y"], frame["z"]])


def velocities(frame) -> np.ndarray:
    return np.column_stack([frame["vx"], frame["vy"], frame["vz"]])


def forces(frame) -> np.ndarray:
    return np.column_stack([frame["fx"], frame["fy"], frame["fz"]])


def rotation(theta):
    """Rotation matrix of the rotation vector theta (Rodrigues)."""
    angle = np.linalg.norm(theta)
    if angle == 0.0:
        return np.eye(3)
    k = theta / angle
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(angle) * K + (1.0 - np.cos(angle)) * K @ K


def balance_momentum(yn, vn, y, m, h):
    """The rigid correction fix sissm applies to the step y of a free group without external
    forces (doc/fix_sissm.rst, "Momentum"): the result moved rigidly, its centre so that the
    momentum sum m (y' - y^n)/h equals sum m v^n, and rotated about the centre so that the
    angular momentum (1/h) sum m q^n x (y' - y^n) (q^n = y^n - c^n) equals sum m q^n x v^n.
    Written here independently of the C++ code: the rotation from Newton's method on its
    rotation vector with a finite-difference Jacobian."""
    m = np.broadcast_to(np.asarray(m, float), (len(y),))
    mass = m.sum()
    cn = (m[:, None] * yn).sum(0) / mass
    c = (m[:, None] * y).sum(0) / mass
    q = yn - cn
    shift = (h * (m[:, None] * vn).sum(0) - (m[:, None] * (y - yn)).sum(0)) / mass
    target = (m[:, None] * np.cross(q, vn)).sum(0)
    r0 = y - c

    def residual(theta):
        return (m[:, None] * np.cross(q, r0 @ rotation(theta).T)).sum(0) / h - target

    theta = np.zeros(3)
    for _ in range(20):
        g = residual(theta)
        jac = np.empty((3, 3))
        for k in range(3):
            e = np.zeros(3)
            e[k] = 1e-7
            jac[:, k] = (residual(theta + e) - residual(theta - e)) / 2e-7
        step = np.linalg.solve(jac, -g)
        theta = theta + step
        if np.linalg.norm(step) < 1e-15:
            break
    return c + shift + r0 @ rotation(theta).T
