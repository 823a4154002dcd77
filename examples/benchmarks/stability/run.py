#!/usr/bin/env python3
"""Stability report of PERI-SISSM (issue 5): stiffness x time-step matrix and extreme
deformations, for peri/lps + fix nve, peri/nosb + fix nve and peri/nosb + fix sissm.

One command regenerates everything (CSV files, PNG images, doc/reports/stability.md):

    /usr/bin/python3 examples/benchmarks/stability/run.py            # full run, ~10-25 min
    /usr/bin/python3 examples/benchmarks/stability/run.py --quick    # smoke test, < 3 min

The decks it drives sit beside this script (in.stability.matrix, in.stability.extreme,
stability.geometry); every run's exact command is in the CSV files.  One lmp at a time, serial,
niced.  build/lmp is used unless PERI_SISSM_LMP or --lmp names another wrapper.

  1. Explicit limits: bisection of the largest stable fix nve time step for peri/lps and
     peri/nosb (linear) on the matrix scene at E_REF; the limit at another E is that value
     times sqrt(E_REF / E) (same density and geometry: the wave speed scales as sqrt(E)).
  2. Matrix: E over STIFFNESS x time step = factor x limit(E) for every method in METHODS
     (fix nve methods relative to their own limit, fix sissm relative to the peri/nosb one);
     each cell runs MATRIX_STEPS steps and is classified (see classify()).
  3. Extreme cases: a 6^3 block bonded at rest, deformed (plane, point, nearly a point,
     scramble, stretch x5, mirror, fold) and released; recovery measured from the positions
     (RMS distance to the rest shape after the best rigid alignment) and from J = det F.
"""
from __future__ import annotations

import argparse
import csv
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
sys.path.insert(0, str(REPO / "unittest" / "python"))
import lammps_run  # noqa: E402

sys.path.insert(0, str(REPO / "tools"))
from progress import Progress  # noqa: E402

sys.path.insert(0, str(HERE.parent))
from deck_runs import SUMMARY  # noqa: E402  (fix sissm's run summary line)

MATRIX_DECK = HERE / "in.stability.matrix"
EXTREME_DECK = HERE / "in.stability.extreme"
GEOMETRY = HERE / "stability.geometry"

# ---------------------------------------------------------------------------------------------
# The one place for the integrators.  Each SISSM variant: fix sissm keywords ("args"; empty:
# none at all), its label, and a "fallback" used when build/lmp rejects them (None: drop the
# variant).  Every variant is probed with a 2-step run before use.  (The "solver" keyword is
# new: a build without it runs the Jacobi sweep, so the jacobi variant falls back to the same
# options without "solver" and "unconverged", which such a build predates.)
SISSM_OPTIONS = {
    # SISSM as its authors use it: at most 20 Jacobi sweeps per step (fewer when a step meets
    # 1e-6); a step that stops at the 20th is kept truncated (unconverged warn; the default
    # cutback would redo it as sub-steps, or stop the run)
    "jacobi": {"args": "solver jacobi iterations 20 tolerance 1e-6 unconverged warn",
               "label": "peri/nosb + fix sissm jacobi",
               "fallback": "iterations 20 tolerance 1e-6"},
    # Newton-Krylov with the block preconditioner; otherwise as the defaults (unconverged
    # cutback 4)
    "block": {"args": "solver krylov precond block iterations 100 tolerance 1e-6",
              "label": "peri/nosb + fix sissm krylov, precond block", "fallback": None},
    # no keywords: what a user gets (solver krylov, precond amg, iterations 100, tolerance 1e-6,
    # unconverged cutback 4)
    "defaults": {"args": "", "label": "peri/nosb + fix sissm, defaults (krylov, precond amg)",
                 "fallback": None},
}
DEFAULT_ITERATIONS = 100   # fix sissm's default "iterations" (doc/fix_sissm.rst)
CUTBACK_LEVELS = 4         # ... and of "unconverged cutback": up to 2^4 = 16 sub-steps
SISSM_ITERATIONS = 20   # jacobi's "iterations" above; the explicit extreme-case runs get the same
                        # budget of force evaluations per fix sissm step (iterations + 1)


def option_value(fix: str, key: str, default=None):
    words = fix.split()
    return words[words.index(key) + 1] if key in words[:-1] else default


def unconverged_mode(fix: str) -> str:
    """What a step of this fix sissm that misses its tolerance does (doc/fix_sissm.rst)."""
    if float(option_value(fix, "tolerance", 1e-6)) == 0:
        return "tolerance 0: every step runs all its iterations and is kept"
    mode = option_value(fix, "unconverged")
    if mode == "warn":
        return ("unconverged warn: a step that misses the tolerance is kept truncated "
                "(counted in f_ID[4])")
    if mode == "error":
        return "unconverged error: the run stops at the first such step"
    if "solver" not in fix.split() and fix.split() != ["sissm"]:
        return "this build's default"
    return (f"unconverged cutback {CUTBACK_LEVELS} (the default): redone as 2, 4, ..., "
            f"{2 ** CUTBACK_LEVELS} sub-steps; the run stops with an ERROR when even "
            f"{2 ** CUTBACK_LEVELS} do not converge")


@dataclass
class Method:
    key: str
    label: str
    pair: str            # nosb | lps
    fix: str             # arguments of "fix integrate all ..."
    limit_of: str        # whose explicit limit the time-step factor refers to
    sissm: bool = False
    fallback: str | None = None


def methods_list() -> list:
    methods = [
        Method("lps_nve", "peri/lps + fix nve", "lps", "nve", "lps"),
        Method("nosb_nve", "peri/nosb + fix nve", "nosb", "nve", "nosb"),
    ]
    for name, opt in SISSM_OPTIONS.items():
        fb = ("sissm " + opt["fallback"]) if opt["fallback"] else None
        methods.append(Method(f"sissm_{name}", opt["label"], "nosb",
                              ("sissm " + opt["args"]).strip(), "nosb", sissm=True,
                              fallback=fb))
    return methods


# ---------------------------------------------------------------------------------------------
# Material, scene and criteria (documented in the report)
RHO = 1000.0          # kg/m^3 (stability.geometry)
SPACING = 1.0e-3      # m
NU = 0.25
E_REF = 1.0e9         # Pa: stiffness of the bisection and of the extreme cases
V0 = 2.0              # m/s, amplitude of the matrix scene's velocity field (in.stability.matrix)
ENERGY_FACTOR = 2.0   # a run whose etotal exceeds this factor x its initial value has failed
RECOVERED = 0.05      # RMS distance to the rest shape after alignment, in spacings


@dataclass
class Config:
    stiffness: list
    factors: list
    matrix_steps: int
    bisect_steps: int
    bisect_ratio: float
    cases: list
    models: list
    extreme_steps: int
    extreme_factor: float
    images: bool = True


EXTREME_CASES = [  # name, deck variables
    ("plane", {"case": "plane"}),
    ("point", {"case": "point"}),
    ("nearpoint 1e-1", {"case": "nearpoint", "eps": 0.1}),
    ("nearpoint 1e-2", {"case": "nearpoint", "eps": 0.01}),
    ("nearpoint 1e-3", {"case": "nearpoint", "eps": 0.001}),
    ("pointnoise 1e-3", {"case": "pointnoise", "noise": 0.001}),
    ("scramble", {"case": "scramble"}),
    ("stretch5", {"case": "stretch5"}),
    ("mirror", {"case": "mirror"}),
    ("fold", {"case": "fold"}),
]
CASE_TEXT = {
    "plane": "all z set to the block's mid plane (F = diag(1,1,0))",
    "point": "all particles at the block centre (F = 0)",
    "nearpoint 1e-1": "uniformly crushed to 0.1 of its size (F = 0.1 I, J = 1e-3)",
    "nearpoint 1e-2": "uniformly crushed to 0.01 (F = 0.01 I, J = 1e-6)",
    "nearpoint 1e-3": "uniformly crushed to 0.001 (F = 0.001 I, J = 1e-9)",
    "pointnoise 1e-3": "every particle within +-0.001 a of the centre at random",
    "scramble": "every coordinate uniform at random inside the rest bounding box",
    "stretch5": "uniaxial stretch x5 along z",
    "mirror": "whole block reflected, z -> 2c - z (J = -1, all bond lengths kept)",
    "fold": "upper half reflected about c + a/4: pushed through the lower half (inverted)",
}

FULL = Config(stiffness=[1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11],
              factors=[0.5, 1, 2, 10, 100, 1000], matrix_steps=300, bisect_steps=2000,
              bisect_ratio=1.01, cases=[c for c, _ in EXTREME_CASES],
              models=["linear", "stvk", "neohookean"], extreme_steps=200, extreme_factor=100)
QUICK = Config(stiffness=[1e5, 1e8, 1e11], factors=[0.5, 2, 100], matrix_steps=100,
               bisect_steps=400, bisect_ratio=1.08,
               cases=["plane", "nearpoint 1e-1", "stretch5", "mirror"],
               models=["linear", "stvk", "neohookean"], extreme_steps=100, extreme_factor=100)


def moduli(E):
    return E / (3 * (1 - 2 * NU)), E / (2 * (1 + NU))


# ---------------------------------------------------------------------------------------------
# Running decks
@dataclass
class Outcome:
    status: str                 # "stable" or a short failure word
    detail: str                 # e.g. "step 14"
    steps_done: int = 0
    max_ratio: float = float("nan")   # max etotal / initial
    final_ratio: float = float("nan")
    iterations: float = float("nan")  # fix sissm mean iterations per step
    unconverged: float = float("nan")
    cut_back: float = float("nan")    # fix sissm steps redone as sub-steps (log summary line)
    switches: float = float("nan")    # ... redone with the other preconditioner
    amg_setups: float = float("nan")  # ... set-ups of the AMG hierarchy (precond amg)
    wall: float = 0.0
    error: str = ""
    suspicious: str = ""        # crash without ERROR, NaN without error under fix sissm, hang
    table: dict = field(default_factory=dict)
    log: str = ""


def command_line(deck: Path, variables: dict) -> str:
    words = ["build/lmp", "-in", str(deck.relative_to(REPO))]
    for k, v in variables.items():
        words += ["-var", k, str(v)]
    return " ".join(shlex.quote(w) for w in words)


# A guard against a hung lmp only, never a criterion: every run is capped in steps (its deck's
# nsteps), and the slowest one measured takes ~20 s on one core, so a run that has not ended
# after an hour is stuck, whatever the machine's load.
HANG_GUARD_S = 3600.0


def run(deck: Path, workdir: Path, variables: dict, timeout: float = HANG_GUARD_S):
    shutil.copy(GEOMETRY, workdir)
    t0 = time.time()
    try:
        r = lammps_run.run_deck(deck, workdir, nprocs=1, variables=variables, check=False,
                                timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, time.time() - t0
    return r, time.time() - t0



def classify(r, wall: float, nsteps: int, sissm: bool) -> Outcome:
    """stable, or the first way the run failed: an ERROR line of LAMMPS (non-finite positions,
    lost atoms, lost partners, ...) or fix sissm's stop (unconverged cutback: not even 16
    sub-steps converged), non-finite thermo values, or etotal growing beyond ENERGY_FACTOR
    times its initial value."""
    if r is None:
        return Outcome("hang", f"no end after {HANG_GUARD_S:.0f} s", wall=wall,
                       suspicious=f"lmp did not end within {HANG_GUARD_S:.0f} s (hang?)")
    table = r.thermo[-1] if r.thermo else {}
    out = Outcome("stable", "", wall=wall, table=table, log=r.log)
    steps = table.get("Step", np.array([]))
    out.steps_done = int(steps[-1]) if len(steps) else 0
    etot = table.get("TotEng", np.array([]))
    e0 = etot[0] if len(etot) else float("nan")
    finite = np.isfinite(etot)
    if len(etot) and e0 > 0:
        ratio = etot / e0
        out.max_ratio = float(np.nanmax(np.where(finite, ratio, np.nan))) if finite.any() else float("nan")
        out.final_ratio = float(ratio[-1])
    if sissm and "f_integrate[3]" in table and len(steps):
        out.iterations = float(table["f_integrate[3]"][-1])
        out.unconverged = float(table["f_integrate[4]"][-1])
    if sissm:
        # the summary line of the last run (not written when the run stopped with an ERROR)
        found = SUMMARY.findall(r.log)
        if found:
            s = found[-1]
            out.cut_back, out.switches = float(s[3]), float(s[4])
            out.amg_setups = float(s[5]) if s[5] else float("nan")
    growth = None
    if len(etot) and e0 > 0:
        big = np.nonzero(finite & (etot > ENERGY_FACTOR * e0))[0]
        if len(big):
            growth = int(steps[big[0]])
    nonfinite = None
    for name, col in table.items():
        bad = np.nonzero(~np.isfinite(col))[0]
        if len(bad):
            s = int(steps[bad[0]])
            nonfinite = s if nonfinite is None else min(nonfinite, s)
    errors = r.errors
    if errors:
        msg = errors[0]
        out.error = msg
        low = msg.lower()
        if "fix sissm" in low and (("not even as" in low and "sub-steps" in low)
                                   or "(unconverged error)" in low):
            # the documented stop of unconverged cutback (a step that did not converge even
            # as 2^levels sub-steps) or unconverged error: a clean error stop
            out.status = "stopped"
        elif "the run is unstable" in low:   # the blow-up guard of peri/nosb
            out.status = "NaN" if "non-finite" in low else "blow-up"
        elif "halt" in low or "too many neighbor bins" in low:
            out.status = "blow-up"
        elif "non-numeric" in low or "non-finite" in low or "nan" in low.split():
            out.status = "NaN"
        elif "lost atoms" in low:
            out.status = "lost atoms"
        elif "partner" in low or "ghost cutoff" in low or "bond" in low:
            out.status = "lost partners"
        else:
            out.status = "error"
        out.detail = f"step {out.steps_done}"
    elif r.returncode != 0:
        out.status, out.detail = "crash", f"exit {r.returncode}"
        where = crash_site(r.stdout + r.stderr)
        out.error = f"crash (exit {r.returncode}) in {where}" if where else ""
        if not where or any(k in where for k in ("Nosb", "NOSB", "Sissm", "perisissm")):
            out.suspicious = (f"lmp exited with {r.returncode} without an ERROR line"
                              + (f", in {where}" if where else ""))
        else:  # LAMMPS core (e.g. binning a box that exploded within one step)
            out.status = "crash (core)"
    elif nonfinite is not None:
        out.status, out.detail = "NaN", f"thermo step {nonfinite}"
        if sissm:
            out.suspicious = "non-finite thermo under fix sissm without its documented error"
    elif growth is not None:
        out.status, out.detail = f"E>{ENERGY_FACTOR:g}x", f"step {growth}"
    elif out.steps_done < nsteps:
        out.status, out.detail = "incomplete", f"step {out.steps_done}"
        out.suspicious = "run ended early without an error"
    if out.status not in ("stable",) and growth is not None and out.status != f"E>{ENERGY_FACTOR:g}x":
        out.detail += f" (E>{ENERGY_FACTOR:g}x at step {growth})"
    return out


def crash_site(text: str) -> str:
    """First frame of a backtrace printed by a crashed lmp, demangled when c++filt exists."""
    frames = re.findall(r"\((_Z\w+)\+0x", text)
    if not frames:
        return ""
    name = frames[0]
    if shutil.which("c++filt"):
        try:
            name = subprocess.run(["c++filt", name], capture_output=True, text=True,
                                  timeout=10).stdout.strip() or name
        except (OSError, subprocess.SubprocessError):
            pass
    return name


def short(o: Outcome) -> str:
    if o.status == "stable":
        return "ok"
    text = f"{o.status} @{o.detail.replace('step ', '').replace('thermo ', '')}"
    if o.status.startswith("E>") and math.isfinite(o.max_ratio):
        text += f" (max {o.max_ratio:.3g}x, end {o.final_ratio:.2g}x)"
    return text


# ---------------------------------------------------------------------------------------------
def probe(method: Method, fix: str, work: Path) -> tuple:
    """Does build/lmp accept these fix arguments?  A 2-step run on a 5^3 block."""
    d = work / f"probe_{method.key}"
    d.mkdir(parents=True, exist_ok=True)
    r, _ = run(MATRIX_DECK, d, {"n": 5, "nsteps": 2, "dt": 1e-7, "pair": method.pair,
                                "fix": fix, "sissm": int(method.sissm),
                                **sissm_skin(method.sissm)})
    if r is None:
        return False, "timeout"
    if r.ok:
        return True, ""
    return False, (r.errors[0] if r.errors else f"exit {r.returncode}")


# Neighbor skin (m) of the fix sissm runs: large enough that every pair of the small blocks is a
# neighbor. Their steps at 100-1000 x the explicit limit move a soft block by more than its
# own size per step, farther than short-range contact candidates chosen with the decks' thin
# skin (half a spacing) can follow, and fix sissm refuses such steps (doc/fix_sissm.rst,
# "Contact"); with every pair a neighbor it can follow any motion up to skin/4. All pairs of a
# few hundred atoms: the nsq list (no bins, which LAMMPS refuses far smaller than the cutoff).
SISSM_SKIN = 1.0


def sissm_skin(sissm: bool) -> dict:
    return {"skin": SISSM_SKIN, "nstyle": "nsq"} if sissm else {}


def matrix_vars(method: Method, E: float, dt: float, nsteps: int, thermo_every: int = 1):
    return {"E": f"{E:g}", "dt": f"{dt:.6g}", "nsteps": nsteps, "v0": V0, "pair": method.pair,
            "model": "linear", "fix": method.fix, "sissm": int(method.sissm),
            "thermo_every": thermo_every, **sissm_skin(method.sissm)}


def bisect_limit(method: Method, cfg: Config, work: Path, log) -> dict:
    """Largest stable fix nve step at E_REF over cfg.bisect_steps steps (classify() == stable)."""
    c = math.sqrt(E_REF / RHO)
    d = work / f"bisect_{method.key}"
    d.mkdir(parents=True, exist_ok=True)
    trials = []

    def stable(dt):
        r, wall = run(MATRIX_DECK, d, matrix_vars(method, E_REF, dt, cfg.bisect_steps, 10))
        o = classify(r, wall, cfg.bisect_steps, False)
        trials.append((dt, o.status))
        log(f"  bisect {method.key}: dt = {dt:.5g} s -> {short(o)}")
        return o.status == "stable"

    lo, hi = 0.3 * SPACING / c, 1.5 * SPACING / c
    while not stable(lo):
        hi, lo = lo, lo / 2
    while stable(hi):
        lo, hi = hi, hi * 2
    while hi / lo > cfg.bisect_ratio:
        mid = math.sqrt(lo * hi)
        if stable(mid):
            lo = mid
        else:
            hi = mid
    return {"stable": lo, "unstable": hi, "trials": len(trials), "steps": cfg.bisect_steps}


# ---------------------------------------------------------------------------------------------
def kabsch_rms(X, Y, allow_reflection: bool) -> float:
    """RMS of |R (X - Xc) - (Y - Yc)| minimised over rotations R (or orthogonal R)."""
    Xc, Yc = X - X.mean(0), Y - Y.mean(0)
    U, S, Vt = np.linalg.svd(Yc.T @ Xc)
    D = np.eye(3)
    if not allow_reflection and np.linalg.det(U @ Vt) < 0:
        D[2, 2] = -1
    R = U @ D @ Vt
    return float(np.sqrt(np.mean(np.sum((Xc @ R.T - Yc) ** 2, axis=1))))


def principal_extents(Y) -> list:
    """Extents of the point cloud along its principal axes, smallest first."""
    Yc = Y - Y.mean(0)
    _, vecs = np.linalg.eigh(Yc.T @ Yc)
    P = Yc @ vecs
    return sorted(float(P[:, k].max() - P[:, k].min()) for k in range(3))


def shape_metrics(rest, frame, has_J: bool = True) -> dict:
    X = np.column_stack([rest[k] for k in "x y z".split()])
    Y = np.column_stack([frame[k] for k in "x y z".split()])
    if not np.all(np.isfinite(Y)):
        return {"finite": False}
    m = {"finite": True,
         "rms": kabsch_rms(X, Y, False) / SPACING,
         "rms_mirror": kabsch_rms(X, Y, True) / SPACING,
         "extents": [e / SPACING for e in principal_extents(Y)]}
    if "vx" in frame:
        V = np.column_stack([frame[k] for k in ("vx", "vy", "vz")])
        Yc = Y - Y.mean(0)
        vcm = V.mean(0)
        Lz = np.cross(Yc, V - vcm).sum(0)                 # angular momentum / (rho V_i)
        I = np.sum(Yc * Yc) * np.eye(3) - Yc.T @ Yc       # inertia tensor / (rho V_i)
        m["v_cm"] = float(np.linalg.norm(vcm))
        m["omega"] = float(np.linalg.norm(np.linalg.solve(I, Lz))) if np.linalg.det(I) > 0 else float("nan")
        if "mass" in frame and "c_vfrac" in frame:
            # total linear momentum p = sum rho_i V_i v_i and angular momentum about the centre
            # of mass L = sum rho_i V_i (x_i - x_cm) x v_i (rmass is the density)
            mass = frame["mass"] * frame["c_vfrac"]
            xcm = (mass[:, None] * Y).sum(0) / mass.sum()
            m["p"] = float(np.linalg.norm((mass[:, None] * V).sum(0)))
            m["L"] = float(np.linalg.norm((mass[:, None] * np.cross(Y - xcm, V)).sum(0)))
    if has_J and "v_J" in frame:
        J = frame["v_J"]
        m["Jmin"], m["Jmax"] = float(J.min()), float(J.max())
        m["Jdev"] = float(np.max(np.abs(J - 1)))
    return m


def verdict(m: dict, rest_extent: float) -> str:
    if not m.get("finite", False):
        return "NaN"
    if m["rms"] < RECOVERED:
        return "recovered"
    if m["rms_mirror"] < RECOVERED:
        return "mirror image"
    e = m["extents"]
    if e[2] < 0.5:
        return "still a point"
    if e[0] < 0.5:
        return "still flat"
    if e[2] > 1.5 * rest_extent:
        return "expanded"
    return "distorted"


@dataclass
class XMethod:
    key: str
    label: str
    pair: str
    fix: str
    sissm: bool
    factor: float      # time step / explicit limit of its pair style
    limit_of: str
    images: bool


def extreme_methods(methods: list, cfg: Config) -> list:
    out = []
    for m in methods:
        if m.sissm:
            out.append(XMethod(m.key, m.label, "nosb", m.fix, True,
                               cfg.extreme_factor, "nosb", images=(m.key == "sissm_defaults")))
        else:
            out.append(XMethod(m.key, m.label + " + viscous", m.pair, m.fix, False, 0.5,
                               m.limit_of, images=False))
    return out


def run_extreme(xm: XMethod, model: str, case: str, cfg: Config, limits: dict, work: Path,
                imgdir: Path) -> dict:
    casevars = dict(EXTREME_CASES)[case]
    dt = xm.factor * limits[xm.limit_of]
    # same budget of force evaluations: fix sissm at most (iterations + 1) per step
    iters = SISSM_ITERATIONS
    nsteps = cfg.extreme_steps if xm.sissm else cfg.extreme_steps * (iters + 1)
    cs = math.sqrt(moduli(E_REF)[1] / RHO)
    n = 6
    gamma = 0.0 if xm.sissm else RHO * math.pi * cs / (n * SPACING)   # ~ lowest mode rate
    tag = f"{xm.key}.{model if xm.pair == 'nosb' else 'lps'}.{case.replace(' ', '_')}"
    d = work / "extreme" / tag
    d.mkdir(parents=True, exist_ok=True)
    variables = {"E": f"{E_REF:g}", "n": n, "pair": xm.pair, "model": model,
                 "dt": f"{dt:.6g}", "nsteps": nsteps, "fix": xm.fix, "sissm": int(xm.sissm),
                 "gamma": f"{gamma:.6g}", "img": int(xm.images and cfg.images),
                 "prefix": "x", "thermo_every": max(1, nsteps // 50), **sissm_skin(xm.sissm)}
    variables.update(casevars)
    r, wall = run(EXTREME_DECK, d, variables)
    o = classify(r, wall, nsteps, xm.sissm)
    res = {"method": xm.key, "method_label": xm.label, "model": model if xm.pair == "nosb" else "-",
           "case": case, "dt": dt, "steps": nsteps, "gamma": gamma, "outcome": o,
           "command": command_line(EXTREME_DECK, variables)}
    # LAMMPS's own errors first; energy growth is not a failure here (the runs start far
    # from equilibrium and only have to come back)
    rest_extent = (n - 1)
    if (d / "x.rest").exists() and (d / "x.after").exists() and o.status not in ("NaN", "crash", "hang"):
        rest = lammps_run.read_dump(d / "x.rest")[0]
        after = lammps_run.read_dump(d / "x.after")[0]
        before = lammps_run.read_dump(d / "x.before")[0]
        res["metrics"] = shape_metrics(rest, after, xm.pair == "nosb")
        res["before"] = shape_metrics(rest, before, xm.pair == "nosb")
        res["verdict"] = verdict(res["metrics"], rest_extent)
        if o.error:
            res["verdict"] = o.status
    else:
        res["metrics"], res["before"] = {}, {}
        res["verdict"] = o.status if o.status != "stable" else "no output"
    if o.table and "KinEng" in o.table and len(o.table["KinEng"]):
        ke = float(o.table["KinEng"][-1])
        res["v_rms"] = math.sqrt(max(ke, 0.0) * 2 / (RHO * n ** 3)) if math.isfinite(ke) else float("nan")
    else:
        res["v_rms"] = float("nan")
    res["images"] = {}
    if xm.images and cfg.images:
        for which in ("before", "after"):
            src = d / f"x.{which}.png"
            if src.exists():
                name = f"{model}_{case.replace(' ', '_')}_{which}.png"
                shutil.copy(src, imgdir / name)
                res["images"][which] = name
    return res


# ---------------------------------------------------------------------------------------------
def fmt(x, spec=".3g"):
    return "-" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, spec)


def write_report(path: Path, imgrel: str, cfg: Config, quick: bool, methods: list,
                 probes: dict, limits: dict, bis: dict, matrix: dict, extreme: list,
                 runtime: float, argv: str):
    L = []
    add = L.append
    add("# Stability report: stiffness x time step, and extreme deformations")
    add("")
    add(f"Generated by `{argv}` "
        f"({'QUICK smoke run: reduced matrix and cases' if quick else 'full run'}) in "
        f"{runtime / 60:.1f} minutes on one core (one serial lmp at a time). Every number and "
        "every outcome word below comes from those runs; the CSV files "
        f"[`{imgrel}/matrix.csv`]({imgrel}/matrix.csv) and [`{imgrel}/extreme.csv`]({imgrel}/extreme.csv) "
        "hold all of them with the exact `build/lmp` command of each run "
        "(decks in `examples/benchmarks/stability/`).")
    add("")
    add("## Methods")
    add("")
    for m in methods:
        if m.key in probes:
            ok, msg = probes[m.key]
            state = (f"used, `fix integrate all {m.fix}`" + (f" ({msg})" if msg else "")
                     + f"; a step that misses its tolerance: {unconverged_mode(m.fix)}"
                     if ok else f"**not used**: build/lmp rejected it (`{msg}`)")
            add(f"- {m.label}: probed with a 2-step run: {state}")
        else:
            add(f"- {m.label}: `fix integrate all {m.fix}`")
    add("")
    add("The jacobi variant is SISSM as its authors use it, a small fixed budget of sweeps per "
        "step whose truncated steps are kept (`unconverged warn`); the krylov variants are "
        "about the converged implicit step: with the default `unconverged cutback "
        f"{CUTBACK_LEVELS}` a step that misses the tolerance is redone as 2, 4, ..., "
        f"{2 ** CUTBACK_LEVELS} sub-steps (with `precond amg` first with a fresh AMG hierarchy "
        "and then with the block preconditioner, a \"preconditioner switch\"), and a run in "
        f"which even {2 ** CUTBACK_LEVELS} sub-steps do not converge stops with fix sissm's "
        f"ERROR (outcome `stopped`: did not converge even as {2 ** CUTBACK_LEVELS} sub-steps).  "
        "`fix integrate all sissm` with nothing after it is what a user gets: solver krylov, "
        f"precond amg, iterations {DEFAULT_ITERATIONS}, tolerance 1e-6, unconverged cutback "
        f"{CUTBACK_LEVELS}.")
    add("")
    add("## Explicit limits")
    add("")
    c = math.sqrt(E_REF / RHO)
    add(f"Scene of the matrix at E_REF = {E_REF:g} Pa (bar wave speed {c:.0f} m/s, a / c = "
        f"{SPACING / c:.3g} s), peri/nosb with the linear model; largest `fix nve` step that "
        f"stays stable (the matrix's criterion below) over {bis['nosb']['steps']} steps, by "
        f"geometric bisection to a ratio of {cfg.bisect_ratio}:")
    add("")
    add("| pair style | stable | unstable | trials | limit used (= stable) | limit / (a/c) |")
    add("|---|---|---|---|---|---|")
    for k in ("lps", "nosb"):
        b = bis[k]
        add(f"| peri/{k} | {b['stable']:.4g} s | {b['unstable']:.4g} s | {b['trials']} | "
            f"{limits[k]:.4g} s | {limits[k] * c / SPACING:.3f} |")
    add("")
    add("At another stiffness the limit is taken as limit(E_REF) x sqrt(E_REF / E): with the "
        "same density and geometry every frequency scales as sqrt(E).  `fix nve` methods use "
        "their own pair style's limit; fix sissm uses that of peri/nosb (same material).")
    add("")
    add("## Matrix")
    add("")
    add(f"Scene (`in.stability.matrix`): a free 8 x 8 x 8 block (spacing {SPACING * 1e3:g} mm, "
        f"horizon 3a, rho = {RHO:g} kg/m^3, Poisson ratio {NU}; peri/nosb linear, bonds "
        "unbreakable; peri/lps s00 = 10) released with a velocity field of amplitude "
        f"v0 = {V0:g} m/s at every stiffness: shear + stretch + twist + 5% random noise "
        "(zero net momentum), so smooth modes and the shortest waves are both excited.  A fixed "
        "v0 makes the strain amplitude ~ v0 / c scale from large (soft rows) to small (stiff "
        "rows), so the rows are not copies of each other.")
    add("")
    add(f"Length: a fixed number of steps, {cfg.matrix_steps}, in every cell.  An unstable "
        "explicit step amplifies its fastest mode by a fixed factor per step, so a fixed step "
        "count gives every cell the same number of chances to blow up and keeps each cell to "
        "seconds; a fixed simulated time would give the 1000x cells only a handful of steps "
        "and the 0.5x cells thousands.  (Simulated time = steps x dt is in the CSV.)")
    add("")
    add(f"Cell: `ok` = completed without error, finite, etotal never above {ENERGY_FACTOR:g} x "
        "its initial value.  Otherwise how the run ended and the last thermo step before it: "
        "`NaN` (LAMMPS ERROR about non-numeric/non-finite positions, or non-finite thermo), "
        "`lost atoms`, `lost partners` (ERROR lines of LAMMPS/peri/nosb), `blow-up` (the "
        "bounding box grew beyond 100 x the block's, stopped by fix halt, or the blow-up guard of "
        "peri/nosb, \"the run is unstable\", or LAMMPS's \"Too "
        f"many neighbor bins\" for a box that exploded within one step), `E>{ENERGY_FACTOR:g}x` "
        "(energy growth, the run otherwise completed), `crash (core)` (lmp died with a signal "
        "inside LAMMPS itself, not the plugin: first backtrace frame in the CSV), `stopped` "
        "(fix sissm's documented error stop, a clean end, not a crash: with `unconverged "
        f"cutback` a step did not converge even as {2 ** CUTBACK_LEVELS} sub-steps, or with "
        "`unconverged error` a step missed the tolerance), `error` "
        f"(another ERROR line, in the CSV); `(E>{ENERGY_FACTOR:g}x at N)` = first step with "
        "energy growth.  Strain ~ v0/c is the scale of the "
        "excitation.")
    add("")
    fac = cfg.factors
    for m in methods:
        if m.key not in matrix:
            continue
        add(f"### {m.label}")
        add("")
        add("| E (Pa) | v0/c | " + " | ".join(f"{f:g}x" for f in fac) + " |")
        add("|---|---|" + "---|" * len(fac))
        for E in cfg.stiffness:
            cells = [short(matrix[m.key][(E, f)]["outcome"]) for f in fac]
            add(f"| {E:.0e} | {V0 / math.sqrt(E / RHO):.2g} | " + " | ".join(cells) + " |")
        add("")
        if m.sissm:
            its = [matrix[m.key][(E, f)]["outcome"] for E in cfg.stiffness for f in fac]
            # cells that ran at least one step (a run stopped in its first step has only the
            # step-0 row, whose f_ID[3] is 0)
            its = [o for o in its if math.isfinite(o.iterations) and o.steps_done > 0]
            if its:
                summ = [o for o in its if math.isfinite(o.cut_back)]
                cut = [o for o in summ if o.cut_back > 0]
                sw = [o for o in summ if o.switches > 0]
                amg = [o for o in summ if math.isfinite(o.amg_setups)]
                fin = [o for o in its if math.isfinite(o.final_ratio)]
                add(f"Over the {len(its)} cells with fix sissm output: mean iterations per step "
                    f"(every attempt and sub-step of a step counted) "
                    f"{min(o.iterations for o in its):.3g} to {max(o.iterations for o in its):.3g}; "
                    f"steps kept above the tolerance (f_ID[4]): {min(o.unconverged for o in its):.0f} to "
                    f"{max(o.unconverged for o in its):.0f} of {cfg.matrix_steps}"
                    + (f"; steps cut back to sub-steps: {len(cut)} cells, "
                       f"{max(o.cut_back for o in cut):.0f} steps at most"
                       + (" (" + ", ".join(f"E = {E:g} Pa {f:g}x: {matrix[m.key][(E, f)]['outcome'].cut_back:.0f}"
                                           for E in cfg.stiffness for f in fac
                                           if matrix[m.key][(E, f)]['outcome'].cut_back > 0) + ")"
                          if len(cut) <= 12 else "")
                       if cut else "; no step cut back")
                    + (f"; steps redone with the other preconditioner: {len(sw)} cells"
                       + (" (" + ", ".join(f"E = {E:g} Pa {f:g}x: {matrix[m.key][(E, f)]['outcome'].switches:.0f}"
                                           for E in cfg.stiffness for f in fac
                                           if matrix[m.key][(E, f)]['outcome'].switches > 0) + ")"
                          if len(sw) <= 12 else "")
                       if sw else ("; no preconditioner switch" if amg else ""))
                    + (f"; AMG hierarchy set-ups per run: {min(o.amg_setups for o in amg):.0f} to "
                       f"{max(o.amg_setups for o in amg):.0f}" if amg else "")
                    + (f"; final etotal / initial: {min(o.final_ratio for o in fin):.3g} to "
                       f"{max(o.final_ratio for o in fin):.3g}" if fin else "") + ".")
                add("")
    # summary sentences from the data
    add("### Where each method fails")
    add("")
    for m in methods:
        if m.key not in matrix:
            continue
        fails = {}
        for (E, f), cell in matrix[m.key].items():
            if cell["outcome"].status != "stable":
                fails.setdefault(f, []).append(E)
        if not fails:
            add(f"- {m.label}: stable in every cell ({len(cfg.stiffness)} stiffnesses x "
                f"{', '.join(f'{f:g}' for f in fac)} x its limit).")
            continue
        parts = []
        for f in fac:
            if f in fails:
                kinds = sorted({matrix[m.key][(E, f)]["outcome"].status for E in fails[f]})
                n = len(fails[f])
                parts.append(f"{f:g}x: {n}/{len(cfg.stiffness)} rows fail ({', '.join(kinds)})")
        stable_f = [f for f in fac if f not in fails]
        add(f"- {m.label}: " + "; ".join(parts) +
            (f"; stable at {', '.join(f'{f:g}x' for f in stable_f)} in every row." if stable_f else "."))
        growth = [matrix[m.key][(E, f)]["outcome"] for f, Es in fails.items() for E in Es
                  if matrix[m.key][(E, f)]["outcome"].status.startswith("E>")]
        if m.sissm and growth:
            unconv = [o.unconverged / max(o.steps_done, 1) for o in growth]
            add(f"  Its {len(growth)} energy-growth cells completed without NaN; etotal peaked at "
                f"{min(o.max_ratio for o in growth):.3g} to {max(o.max_ratio for o in growth):.3g} x "
                f"its initial value and ended at {min(o.final_ratio for o in growth):.2g} to "
                f"{max(o.final_ratio for o in growth):.2g} x; {100 * min(unconv):.0f}-"
                f"{100 * max(unconv):.0f}% of their steps stopped at the iteration limit.  A "
                "converged backward-Euler step cannot raise the energy; the step starts from "
                "y^n + h v^n (doc/fix_sissm.rst), whose strain grows with h, and "
                f"{option_value(m.fix, 'iterations', DEFAULT_ITERATIONS)} iterations leave it "
                "far from the implicit solution.")
    add("")
    # extreme
    add("## Extreme deformations")
    add("")
    add(f"Scene (`in.stability.extreme`): a free 6 x 6 x 6 block, E = {E_REF:g} Pa, same "
        "material otherwise, bonded in its rest shape (`run 0`), then deformed with `set` and "
        "atom-style variables and released at rest:")
    add("")
    for case in cfg.cases:
        add(f"- **{case}**: {CASE_TEXT[case]}")
    add("")
    xs = extreme
    xkeys = []
    for r in xs:
        if (r["method"], r["method_label"]) not in xkeys:
            xkeys.append((r["method"], r["method_label"]))
    add("Integrators:")
    add("")
    for key, label in xkeys:
        r0 = next(r for r in xs if r["method"] == key)
        add(f"- `{key}`: {label}, dt = {r0['dt']:.3g} s ({'%g' % (r0['dt'] / limits['lps' if key == 'lps_nve' else 'nosb'])} x "
            f"its explicit limit), {r0['steps']} steps"
            + (f", fix viscous {r0['gamma']:.3g} (damping rate gamma/rho = pi c_s / (6a), about "
               "the lowest mode's frequency)" if r0["gamma"] > 0 else "")
            + ".")
    add("")
    add(f"fix sissm jacobi runs at most {SISSM_ITERATIONS + 1} force evaluations per step "
        f"({SISSM_ITERATIONS} sweeps and the evaluation that ends the step), so the explicit "
        f"runs get that budget ({SISSM_ITERATIONS + 1} x the SISSM step count); the krylov "
        f"variants may use up to {DEFAULT_ITERATIONS} per step, and a cut-back step up to "
        f"{2 ** (CUTBACK_LEVELS + 1) - 1} times that (their mean iterations per step, cut-back "
        "steps and preconditioner switches are in the CSV and summed up below the table).  "
        "Recovery: `rms` = RMS distance "
        "to the rest shape after the best rigid rotation + translation, in spacings; "
        f"`recovered` when rms < {RECOVERED} a, `mirror image` when only a reflection brings it "
        "back below that, `still a point` / `still flat` / `expanded` (longest principal extent > 1.5 x the rest edge) from the principal "
        "extents of the final cloud, `distorted` otherwise.  |J-1| = max over particles of "
        "|det F - 1| (peri/nosb only); v_rms = final RMS speed (m/s), v_cm = speed of the "
        "centre of mass, omega = rigid angular velocity from the final angular momentum and "
        "inertia.  Every block starts at rest (zero linear and angular momentum) and no "
        "external force acts, so v_cm and omega measure momentum created by the integrator; a "
        "spinning block whose shape is back counts as recovered.  p = |sum_i rho_i V_i v_i| "
        "and L = |sum_i rho_i V_i (x_i - x_cm) x v_i| are the total linear and angular "
        "momentum (about the centre of mass) at the end of the run, from the final dump; both "
        "are zero at the start.")
    add("")
    add("| case | model | integrator | outcome | rms / a | max abs(J-1) | J range | v_rms | v_cm | omega (rad/s) | p (kg m/s) | L (kg m^2/s) | before: J range |")
    add("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in xs:
        m = r.get("metrics", {})
        b = r.get("before", {})
        jr = f"{fmt(m.get('Jmin'))} .. {fmt(m.get('Jmax'))}" if "Jmin" in m else "-"
        bjr = f"{fmt(b.get('Jmin'))} .. {fmt(b.get('Jmax'))}" if "Jmin" in b else "-"
        out = r["verdict"]
        if r["outcome"].error:
            out += f" (`{r['outcome'].error[:80]}`)"
        add(f"| {r['case']} | {r['model']} | {r['method']} | {out} | {fmt(m.get('rms'))} | "
            f"{fmt(m.get('Jdev'))} | {jr} | {fmt(r.get('v_rms'))} | {fmt(m.get('v_cm'))} | "
            f"{fmt(m.get('omega'))} | {fmt(m.get('p'))} | {fmt(m.get('L'))} | {bjr} |")
    add("")
    # summary per model/method
    add("### Outcomes in brief")
    add("")
    for key, label in xkeys:
        models = sorted({r["model"] for r in xs if r["method"] == key},
                        key=lambda s: ["linear", "stvk", "neohookean", "-"].index(s))
        for model in models:
            rows = [r for r in xs if r["method"] == key and r["model"] == model]
            good = [r["case"] for r in rows if r["verdict"] == "recovered"]
            bad = [f"{r['case']} ({r['verdict']})" for r in rows if r["verdict"] != "recovered"]
            add(f"- `{key}` {model}: recovered {len(good)}/{len(rows)}"
                + (f"; not: {', '.join(bad)}" if bad else "") + ".")
    add("")
    # what fix sissm did in these runs (mean iterations, cut-backs, switches: the CSV)
    for key, label in xkeys:
        rr = [r for r in xs if r["method"] == key and r["method"].startswith("sissm")]
        its = [r["outcome"] for r in rr if math.isfinite(r["outcome"].iterations)
               and r["outcome"].steps_done > 0]
        if not its:
            continue
        summ = [o for o in its if math.isfinite(o.cut_back)]
        cut = [r for r in rr if math.isfinite(r["outcome"].cut_back) and r["outcome"].cut_back > 0]
        sw = [r for r in rr if math.isfinite(r["outcome"].switches) and r["outcome"].switches > 0]
        amg = [o for o in summ if math.isfinite(o.amg_setups)]
        add(f"- `{key}` over its {len(its)} runs that completed a thermo interval: mean "
            "iterations per step "
            f"{min(o.iterations for o in its):.3g} to {max(o.iterations for o in its):.3g}; "
            f"steps kept above the tolerance (f_ID[4]) {min(o.unconverged for o in its):.0f} to "
            f"{max(o.unconverged for o in its):.0f} of {cfg.extreme_steps}"
            + (("; steps cut back to sub-steps in " + ", ".join(
                f"{r['model']} {r['case']} ({r['outcome'].cut_back:.0f})" for r in cut))
               if cut else "; no step cut back")
            + (("; steps redone with the other preconditioner in " + ", ".join(
                f"{r['model']} {r['case']} ({r['outcome'].switches:.0f})" for r in sw))
               if sw else ("; no preconditioner switch" if amg else ""))
            + (f"; AMG hierarchy set-ups per run {min(o.amg_setups for o in amg):.0f} to "
               f"{max(o.amg_setups for o in amg):.0f}" if amg else "")
            + (f"; {len(rr) - len(summ)} runs ended with an ERROR (no summary line)"
               if len(summ) < len(rr) else "") + ".")
    add("")
    spin = [r for r in xs if r["verdict"] == "recovered" and math.isfinite(r["metrics"].get("omega", float("nan")))]
    if spin:
        add("Momentum created (blocks start at rest, no external force), over the recovered runs:")
        add("")
        add("| integrator | runs | max v_cm (m/s) | max omega (rad/s) | runs with omega > 1 rad/s |")
        add("|---|---|---|---|---|")
        for key, _ in xkeys:
            rr = [r for r in spin if r["method"] == key]
            if rr:
                add(f"| `{key}` | {len(rr)} | {max(r['metrics']['v_cm'] for r in rr):.3g} | "
                    f"{max(r['metrics']['omega'] for r in rr):.3g} | "
                    f"{sum(r['metrics']['omega'] > 1 for r in rr)} |")
        add("")
    notes = mechanism_notes(xs)
    if notes:
        add("### Why (mechanisms behind the failures observed above)")
        add("")
        for n in notes:
            add(f"- {n}")
        add("")
    # images
    imgs = [r for r in xs if r["images"]]
    if imgs:
        add("### Pictures (fix sissm with its defaults, before / after; colour = J = det F: "
            "blue -1, yellow 0, green 1, red >= 2)")
        add("")
        add("The after picture is taken once the block has been moved back to the centre (a "
            "block that moves, e.g. an explicit run that picked up momentum, would drift out of "
            "the frame; velocities and momenta are in the table above).")
        add("")
        models = [mm for mm in cfg.models if any(r["model"] == mm for r in imgs)]
        add("| case | " + " | ".join(f"{mm} before | {mm} after" for mm in models) + " |")
        add("|---|" + "---|---|" * len(models))
        for case in cfg.cases:
            cells = []
            for mm in models:
                r = next((r for r in imgs if r["case"] == case and r["model"] == mm), None)
                for which in ("before", "after"):
                    name = r["images"].get(which) if r else None
                    cells.append(f"![{mm} {case} {which}]({imgrel}/{name})" if name else "-")
            add(f"| {case} | " + " | ".join(cells) + " |")
        add("")
    # suspicious
    sus = []
    for key, cells in matrix.items():
        for (E, f), cell in cells.items():
            if cell["outcome"].suspicious:
                sus.append((cell["outcome"].suspicious, cell["command"]))
    stopped = []   # fix sissm's documented stop (unconverged cutback / error): listed apart
    for key, cells in matrix.items():
        if key.startswith("sissm"):
            for (E, f), cell in cells.items():
                o = cell["outcome"]
                if o.status == "stopped":
                    stopped.append((f"{key}, matrix cell E = {E:g} Pa, {f:g}x, after step "
                                    f"{o.steps_done}: `{o.error[:200]}`", cell["command"]))
                elif o.status != "stable" and not o.suspicious:
                    sus.append((f"fix sissm ({key}) failed a matrix cell, E = {E:g} Pa, {f:g}x: "
                                f"{o.status} {o.detail}", cell["command"]))
    for r in xs:
        if r["outcome"].suspicious:
            sus.append((r["outcome"].suspicious, r["command"]))
        elif r["outcome"].status == "stopped":
            stopped.append((f"{r['method']}, extreme case {r['model']} {r['case']}, after step "
                            f"{r['outcome'].steps_done}: `{r['outcome'].error[:200]}`",
                            r["command"]))
        elif r["method"].startswith("sissm") and r["outcome"].status not in ("stable",):
            sus.append((f"fix sissm ({r['method']}) {r['model']} {r['case']}: "
                        f"{r['outcome'].status} ({r['outcome'].error or r['outcome'].detail})",
                        r["command"]))
    core = [(cell["outcome"].error, cell["command"]) for cells in matrix.values()
            for cell in cells.values() if cell["outcome"].status == "crash (core)"]
    core += [(r["outcome"].error, r["command"]) for r in xs if r["outcome"].status == "crash (core)"]
    add("## Crashes inside LAMMPS itself")
    add("")
    if core:
        sites = sorted({e for e, _ in core})
        add(f"{len(core)} runs died with a signal in LAMMPS's own code ({'; '.join(sites)}), "
            "not in the plugin, all after the run had already blown up; e.g. "
            f"`{core[0][1]}`.  (peri/nosb runs stop before that with the error \"the run is "
            "unstable\" of its blow-up guard, see pair_style peri/nosb; the built-in styles "
            "have no such guard.)")
    else:
        add("None: every run that blew up ended with an ERROR line (peri/nosb: \"the run is "
            "unstable\", its blow-up guard, which names the step, an atom and the likely "
            "cause).")
    add("")
    add("## fix sissm runs stopped by their tolerance")
    add("")
    if stopped:
        add(f"{len(stopped)} fix sissm runs ended with fix sissm's documented error stop (outcome "
            f"`stopped`): with `unconverged cutback` a step did not converge even as "
            f"{2 ** CUTBACK_LEVELS} sub-steps.  A clean stop that names the step and says what "
            "to do (raise iterations, lower the time step, or accept unconverged steps with "
            "`unconverged warn`), not a crash and not a success; each with the command that "
            "reproduces it:")
        add("")
        for what, cmd in stopped:
            add(f"- {what}: `{cmd}`")
    else:
        add("None: no fix sissm run stopped because a step did not converge (with `unconverged "
            f"cutback`: not even as {2 ** CUTBACK_LEVELS} sub-steps).")
    add("")
    add("## Plugin problems found")
    add("")
    if sus:
        add("Runs that crashed without an ERROR line, hung, produced non-finite values under "
            "fix sissm without its documented error, or in which fix sissm (documented as "
            "stable at any time step) failed or diverged.  Each with the command that "
            "reproduces it (run it in a folder holding a copy of `stability.geometry`; "
            "`build/lmp` and the deck path are relative to the repository root):")
        add("")
        for what, cmd in sus:
            add(f"- {what}: `{cmd}`")
    else:
        add("None: no run crashed without an ERROR line, hung, or went non-finite under fix sissm "
            "without its documented error.")
    add("")
    path.write_text("\n".join(L) + "\n")


def mechanism_notes(xs: list) -> list:
    """Explanations, printed only for outcomes that actually occurred."""
    notes = []

    def happened(model=None, case=None, verdict=None, method_prefix="sissm"):
        return [r for r in xs if (model is None or r["model"] == model)
                and (case is None or r["case"].startswith(case))
                and (verdict is None or r["verdict"] == verdict)
                and r["method"].startswith(method_prefix)]

    if happened("stvk", verdict="mirror image") or happened("stvk", verdict="mirror image", method_prefix="nosb"):
        cases = sorted({r["case"] for r in xs if r["model"] == "stvk" and r["verdict"] == "mirror image"})
        notes.append("stvk ends as a mirror image (" + ", ".join(cases) + "): W_stvk depends on F "
                     "only through F^T F, so every reflection (J = -1, E = 0) is a rest state as "
                     "good as the original one; a block that passes through a flat state on its "
                     "way back may settle inverted and stay there.")
    if happened("stvk", "plane", "still flat") or happened("stvk", "plane", "still flat", "nosb"):
        notes.append("stvk stays flat after the collapse to a plane: with F = diag(1,1,0) the "
                     "St. Venant-Kirchhoff stress P = F S has a zero third column (P_33 = s_3 S_33 "
                     "= 0), so nothing pushes the layers apart, although W > 0.")
    pts = [r for r in xs if r["verdict"] == "still a point"]
    if pts:
        which = sorted({f"{r['model'] if r['model'] != '-' else 'peri/lps'} {r['case']} ({r['method']})" for r in pts})
        notes.append("still a point: " + ", ".join(which) + ".  F = 0 is a critical point of "
                     "every smooth isotropic W (P(0) = 0, doc/pair_peri_nosb.rst) and the bond "
                     "vectors are zero, so stabilization and contact have no direction either; "
                     "the corotated linear model is not smooth at F = 0 (its P(0) is -(2mu+3lambda) "
                     "times the rotation the SVD returns), which is why it can push back.")
    stopped = [r for r in xs if r["method"].startswith("sissm") and r["verdict"] == "stopped"]
    if stopped:
        def measure(r):
            found = re.search(r"convergence measure ([0-9.eE+-]+)", r["outcome"].error)
            return found.group(1) if found else "?"
        def step(r):
            found = re.search(r"step (\d+) did not converge", r["outcome"].error)
            return found.group(1) if found else "?"
        notes.append("fix sissm stopped (`unconverged cutback`, the default) in "
                     + ", ".join(f"{r['model']} {r['case']} ({r['method']}, step {step(r)}, "
                                 f"measure {measure(r)})" for r in stopped)
                     + f": the block is released at rest far from its rest shape, with forces "
                     "far larger than near it, and the step's Newton-Krylov solve does not "
                     "reach the tolerance within its iterations even as "
                     f"{2 ** CUTBACK_LEVELS} sub-steps; the run stops with the ERROR, "
                     "which says what to do (raise iterations, lower the time step, or accept "
                     "truncated steps with `unconverged warn`).")
    lps_mirror = [r for r in xs if r["method"] == "lps_nve" and r["verdict"] == "mirror image"]
    if lps_mirror:
        notes.append("peri/lps stays mirrored (" + ", ".join(r["case"] for r in lps_mirror) + "): "
                     "its energy sees bond lengths and the dilatation only, and a reflection "
                     "keeps every bond length.")
    nve_nan = [r for r in xs if r["method"] == "nosb_nve" and r["verdict"] in ("NaN", "error", "lost atoms")]
    if nve_nan:
        notes.append("explicit peri/nosb fails in " + ", ".join(f"{r['model']} {r['case']}" for r in nve_nan)
                     + ": the explicit limit was measured near the rest state; strongly compressed "
                     "or inverted particles are much stiffer (neohookean's volumetric term) and "
                     "contact springs engage, so 0.5 x the rest-state limit is no longer stable.")
    made = [r for r in xs if r["method"].startswith("sissm") and r["verdict"] == "recovered"
            and r["metrics"].get("omega", 0) > 1]
    if made:
        notes.append(f"{len(made)} fix sissm runs end as recovered but moving rigid bodies "
                     "(omega > 1 rad/s, table above) although they started at rest with no "
                     "external force: the internal forces sum to zero and have no torque, but "
                     "a step that stops at the iteration limit is not their backward-Euler "
                     "step (each particle's correction uses its own block D_i), so momentum is "
                     "conserved only as far as the steps converge.")
    return notes


# ---------------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="reduced matrix and cases (< 3 min)")
    ap.add_argument("--out", default=None, help="report folder (default doc/reports; with "
                    "--quick a temporary folder)")
    ap.add_argument("--keep", default=None, help="keep the working folder of all runs here")
    ap.add_argument("--lmp", default=None, help="lmp wrapper (default PERI_SISSM_LMP or build/lmp)")
    args = ap.parse_args()
    if args.lmp:
        lammps_run.LMP = Path(args.lmp).resolve()
    try:
        os.nice(5)
    except OSError:
        pass
    cfg = QUICK if args.quick else FULL
    t_start = time.time()
    if args.out:
        outdir = Path(args.out).resolve()
    elif args.quick:
        outdir = Path(tempfile.mkdtemp(prefix="stability-quick-"))
    else:
        outdir = REPO / "doc" / "reports"
    imgdir = outdir / "stability"
    imgdir.mkdir(parents=True, exist_ok=True)
    for old in imgdir.glob("*.png"):
        old.unlink()
    work = Path(args.keep).resolve() if args.keep else Path(tempfile.mkdtemp(prefix="stability-"))
    work.mkdir(parents=True, exist_ok=True)

    def log(msg):
        print(f"[{time.time() - t_start:6.0f} s] {msg}", file=sys.stderr, flush=True)

    methods = methods_list()
    probes = {}
    active = []
    for m in methods:
        if not m.sissm:
            active.append(m)
            continue
        ok, msg = probe(m, m.fix, work)
        log(f"probe {m.key} '{m.fix}': {'accepted' if ok else 'rejected: ' + msg}")
        if not ok and m.fallback:
            rejected = msg
            ok, msg = probe(m, m.fallback, work)
            log(f"probe {m.key} fallback '{m.fallback}': {'accepted' if ok else 'rejected: ' + msg}")
            if ok:
                msg = f"`fix integrate all {m.fix}` rejected ({rejected}); using `{m.fallback}`"
                m.fix = m.fallback
        probes[m.key] = (ok, msg)
        if ok:
            active.append(m)

    bis = {}
    for m in active:
        if not m.sissm and m.limit_of not in bis:
            bis[m.limit_of] = bisect_limit(m, cfg, work, log)
    limits = {k: b["stable"] for k, b in bis.items()}
    log(f"limits at E_REF: {limits}")

    matrix = {}
    rows = []
    progress = Progress(len(active) * len(cfg.stiffness) * len(cfg.factors), "stability matrix")
    for m in active:
        matrix[m.key] = {}
        for E in cfg.stiffness:
            for f in cfg.factors:
                dt = f * limits[m.limit_of] * math.sqrt(E_REF / E)
                d = work / "matrix" / f"{m.key}_E{E:g}_f{f:g}"
                d.mkdir(parents=True, exist_ok=True)
                variables = matrix_vars(m, E, dt, cfg.matrix_steps)
                r, wall = run(MATRIX_DECK, d, variables)
                o = classify(r, wall, cfg.matrix_steps, m.sissm)
                o.log, o.table = "", {}
                cmd = command_line(MATRIX_DECK, variables)
                matrix[m.key][(E, f)] = {"outcome": o, "command": cmd}
                progress.step(f"{m.key} E={E:g} {f:g}x dt={dt:.3g}: {short(o)}, {wall:.1f} s")
                rows.append({"method": m.key, "E_Pa": f"{E:g}", "strain_v0_over_c": f"{V0 / math.sqrt(E / RHO):.3g}",
                             "factor": f"{f:g}", "dt_s": f"{dt:.6g}", "steps": cfg.matrix_steps,
                             "simulated_time_s": f"{dt * cfg.matrix_steps:.4g}",
                             "status": o.status, "detail": o.detail, "steps_done": o.steps_done,
                             "max_etotal_ratio": fmt(o.max_ratio, ".4g"),
                             "final_etotal_ratio": fmt(o.final_ratio, ".4g"),
                             "sissm_mean_iterations": fmt(o.iterations, ".4g"),
                             "sissm_unconverged_steps": fmt(o.unconverged, ".0f"),
                             "sissm_cut_back_steps": fmt(o.cut_back, ".0f"),
                             "sissm_precond_switches": fmt(o.switches, ".0f"),
                             "sissm_amg_setups": fmt(o.amg_setups, ".0f"),
                             "error": o.error, "suspicious": o.suspicious,
                             "wall_s": f"{wall:.2f}", "command": cmd})
    with open(imgdir / "matrix.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    extreme = []
    xrows = []
    xruns = [(xm, model, case) for xm in extreme_methods(active, cfg)
             for model in (cfg.models if xm.pair == "nosb" else ["-"]) for case in cfg.cases]
    progress = Progress(len(xruns), "stability extreme")
    for xm, model, case in xruns:
        res = run_extreme(xm, model if model != "-" else "linear", case, cfg, limits,
                          work, imgdir)
        o = res["outcome"]
        o.log, o.table = "", {}
        extreme.append(res)
        m = res["metrics"]
        progress.step(f"{xm.key} {res['model']} {case}: {res['verdict']} rms={fmt(m.get('rms'))} "
                      f"Jdev={fmt(m.get('Jdev'))}, {o.wall:.1f} s")
        xrows.append({"method": xm.key, "model": res["model"], "case": case,
                      "dt_s": f"{res['dt']:.6g}", "steps": res["steps"],
                      "viscous_gamma": f"{res['gamma']:.4g}",
                      "verdict": res["verdict"], "status": o.status, "detail": o.detail,
                      "rms_over_a": fmt(m.get("rms"), ".4g"),
                      "rms_mirror_over_a": fmt(m.get("rms_mirror"), ".4g"),
                      "extents_over_a": " ".join(f"{e:.3g}" for e in m.get("extents", [])),
                      "Jmin": fmt(m.get("Jmin"), ".4g"), "Jmax": fmt(m.get("Jmax"), ".4g"),
                      "max_abs_J_minus_1": fmt(m.get("Jdev"), ".4g"),
                      "before_rms_over_a": fmt(res["before"].get("rms"), ".4g"),
                      "before_Jmin": fmt(res["before"].get("Jmin"), ".4g"),
                      "before_Jmax": fmt(res["before"].get("Jmax"), ".4g"),
                      "final_v_rms_m_s": fmt(res["v_rms"], ".3g"),
                      "final_p_kg_m_s": fmt(m.get("p"), ".4g"),
                      "final_L_kg_m2_s": fmt(m.get("L"), ".4g"),
                      "sissm_mean_iterations": fmt(o.iterations, ".4g"),
                      "sissm_unconverged_steps": fmt(o.unconverged, ".0f"),
                      "sissm_cut_back_steps": fmt(o.cut_back, ".0f"),
                      "sissm_precond_switches": fmt(o.switches, ".0f"),
                      "sissm_amg_setups": fmt(o.amg_setups, ".0f"),
                      "error": o.error, "suspicious": o.suspicious,
                      "images": " ".join(res["images"].values()),
                      "wall_s": f"{o.wall:.2f}", "command": res["command"]})
    with open(imgdir / "extreme.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(xrows[0]))
        w.writeheader()
        w.writerows(xrows)

    runtime = time.time() - t_start
    argv = "/usr/bin/python3 examples/benchmarks/stability/run.py" + (" --quick" if args.quick else "")
    report = outdir / "stability.md"
    write_report(report, "stability", cfg, args.quick, methods, probes, limits, bis, matrix,
                 extreme, runtime, argv)
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    log(f"report: {report} (total {runtime / 60:.1f} min)")
    print(report)


if __name__ == "__main__":
    main()
