#!/usr/bin/env python3
"""Error against run time: peri/lps + fix nve, peri/nosb + fix nve and peri/nosb + fix sissm.

Regenerates doc/reports/error-vs-time.md, its CSVs and plots (doc/reports/error-vs-time/) from
runs of the decks in this folder (one serial `nice build/lmp` at a time):

  static   gravity-loaded cantilever (cantilever.geometry, soft solid) brought to rest; error =
           tip-deflection error against a damped explicit run of the same pair style converged
           to round-off; plus a convergence study at fixed delta/a = 3 towards Euler-Bernoulli
  dynamic  the same cantilever, gravity switched on at t = 0, undamped free vibration; error =
           largest tip-deflection difference over a fixed time against an explicit run of the
           same pair style at 0.1 x its stable time step, relative to the largest deflection
  stiff    the static scene with a steel-like solid (fix sissm's tolerance is a length relative
           to the particle size, so a stiff, hardly deflected body shows what it means)

Every run is a point (or, for the static scenes, one point per thermo checkpoint of a run):
error, force evaluations (explicit: steps; fix sissm: steps x (f_ID[3] + 1)), wall time (the
thermo `cpu` column = LAMMPS loop time so far; "Loop time" at the end), steps and iterations.

    /usr/bin/python3 examples/benchmarks/error-vs-time/run.py [--quick] [--lmp PATH]
        [--out DIR] [--report FILE] [--keep DIR]

--quick: a few points per method (smoke test, < 3 minutes); writes to doc/reports/
error-vs-time-quick* unless --out/--report say otherwise.

Which runs and checkpoints exist never depends on the machine's speed: a fix sissm run is
capped in force evaluations (fix halt in in.sissm, on steps x (f_ID[3] + 1)), not in seconds.
Wall time is only reported. The report's last section, the cloth in motion, is written by
examples/benchmarks/dynamics/pareto.py and kept when this script rewrites the report.
"""
from __future__ import annotations

import argparse
import csv
import math
import os
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
sys.path.insert(0, str(HERE.parent))
from deck_runs import DeckRunner, fmt, lammps_run, pareto  # noqa: E402

# ----------------------------------------------------------------------------------------------
# fix sissm variants: ONE place.  Each entry is the option string given to fix sissm.  Entries
# with "solver krylov" (or any other keyword the build rejects) are probed with a tiny run and
# left out when build/lmp does not accept them; "solver jacobi" is stripped from the jacobi
# entries for a build that predates the solver keyword (jacobi was the only solver then).
# The empty string is fix sissm with no keywords at all: what a user gets (solver krylov,
# precond amg, iterations 100, tolerance 1e-6, unconverged cutback 4; doc/fix_sissm.rst).
# What a step that misses its tolerance does (unconverged_mode() below, stated in the report):
# - tolerance 0 (SISSM as its authors use it, a fixed number of sweeps): every step runs all
#   its iterations and is kept; never redone, never stopped, whatever "unconverged" says;
# - "unconverged warn": kept as the solver left it (truncated), counted in f_ID[4];
# - otherwise the default "unconverged cutback 4": redone as 2..16 sub-steps, and the run
#   stops with an ERROR when even 16 do not converge.
SISSM_VARIANTS = [
    "solver jacobi iterations 5 tolerance 0",
    "solver jacobi iterations 20 tolerance 0",
    # up to 200 sweeps, fewer when 1e-6 is met: meant to show truncated steps where 200 are
    # not enough (at 16x the limit every step stops at 200), so warn, not the default cutback
    "solver jacobi iterations 200 tolerance 1e-6 unconverged warn",
    "solver krylov precond amg iterations 20 tolerance 0",
    "solver krylov precond amg iterations 50 tolerance 1e-8",
    "solver krylov precond amg iterations 200 tolerance 1e-10",
    "solver krylov precond amg iterations 5000 tolerance 1e-4",
    "solver krylov precond block iterations 50 tolerance 1e-8",
    "",
]
# The second-order time schemes (doc/fix_sissm.rst, "Time schemes"): the dynamic scene only (for
# bringing a body to rest backward Euler, the default, is the right scheme), at their own time
# steps (sissm_scheme_dt), with a tolerance for dynamics (the vibration moves particles by a small
# fraction of their size per step).
SCHEME_VARIANTS = [
    "scheme bdf2 tolerance 1e-8",
    "scheme genalpha tolerance 1e-8",
    "scheme genalpha 1.0 tolerance 1e-8",
]
QUICK_SCHEME_VARIANTS = [
    "scheme genalpha tolerance 1e-8",
]
QUICK_VARIANTS = [
    "solver jacobi iterations 5 tolerance 0",
    "solver jacobi iterations 200 tolerance 1e-6 unconverged warn",
    "solver krylov precond block iterations 50 tolerance 1e-8",
    "",
]
# ----------------------------------------------------------------------------------------------

# Sweeps (multiples of each pair style's measured explicit stability limit)
FULL = dict(
    beam=(20, 5),                       # nx, nt of the swept cantilever (a = 10 mm)
    explicit_static_dt={"nosb": [0.5, 0.9], "lps": [0.5, 0.9]},   # x limit
    explicit_static_damp=[0.5, 1.0, 2.0],   # x critical damping of the first bending mode
    explicit_dynamic_dt={"nosb": [0.25, 0.5, 0.9], "lps": [0.25, 0.5, 0.9]},
    sissm_static_dt=[10, 100, 1000, 10000],   # 1000 and 10000: not the jacobi variants
    sissm_dynamic_dt=[0.25, 1, 4, 16],
    sissm_scheme_dt=[1, 4, 16, 64],
    sissm_stiff_dt=[10, 100, 1000, 10000],
    # budget of one fix sissm run in force evaluations (fix halt stops it at the first thermo
    # row with at least that many): a static run keeps its checkpoints up to there, a dynamic
    # run that does not reach its end within it gives no point.  It is checked at thermo rows
    # only, so a run overshoots it by up to one thermo interval's evaluations, and a cut-back
    # step alone can take up to 31 x iterations (+ 2 x iterations with precond amg).
    sissm_static_evaluations=20000,
    sissm_dynamic_evaluations=20000,
    dynamic_periods=2.0,                # simulated time of the dynamic scene, x Euler-Bernoulli T1
    reference_dt=0.1,                   # dynamic reference: x limit
    static_periods=6.0,                 # length of a static explicit run, x T1
    reference_periods=10.0,             # static reference (damped explicit), x T1
    bisect_steps=1500, bisect_rounds=4,
    convergence=[(24, 6, 0.010), (32, 8, 0.0075), (40, 10, 0.006), (48, 12, 0.005)],
    convergence_styles=["nosb"],
)
QUICK = dict(
    beam=(20, 5),
    explicit_static_dt={"nosb": [0.9], "lps": [0.9]},
    explicit_static_damp=[1.0],
    explicit_dynamic_dt={"nosb": [0.5, 0.9], "lps": [0.5, 0.9]},
    sissm_static_dt=[30],
    sissm_dynamic_dt=[1, 8],
    sissm_scheme_dt=[8],
    sissm_stiff_dt=[30],
    # every quick variant gives a dynamic point at 1x and 8x the limit but jacobi iterations
    # 200 at 8x (every step stops at 200 sweeps: ~16000 for its 81 steps)
    sissm_static_evaluations=4000,
    sissm_dynamic_evaluations=8000,
    dynamic_periods=1.0,
    reference_dt=0.2,
    static_periods=4.0,
    reference_periods=7.0,
    bisect_steps=800, bisect_rounds=1,
    convergence=[(16, 4, 0.015), (24, 6, 0.010)],
    convergence_styles=["nosb"],
)

# time step of the static reference, x the explicit limit of the bisection.  (peri/lps seemed
# to change with the time step far below its limit: that was LAMMPS's uninitialised critical
# stretch breaking bonds at the first step; in.lps now sets it with two empty runs first)
STATIC_REFERENCE_DT = {"nosb": 0.9, "lps": 0.9}

EB = re.compile(r"^Euler-Bernoulli tip deflection = ([0-9.eE+-]+) m", re.M)
MATERIALS = {"soft": dict(rho=1000.0, K=1.0e7, G=6.0e6), "steel": dict(rho=7800.0, K=160.0e9,
                                                                       G=80.0e9)}
# rough first guesses of the explicit limit for a = 10 mm, soft (examples/cantilever README);
# the bisection brackets them and scales them with the wave speed
LIMIT_GUESS = {"nosb": 7.3e-5, "lps": 1.2e-4}
# methods in the tables and plots: the explicit styles, then fix sissm by solver and
# preconditioner (method_of), the keyword-less variant on its own
METHODS = ("lps", "nosb", "jacobi", "block", "amg", "defaults", "bdf2", "genalpha")
SISSM_METHODS = ("jacobi", "block", "amg", "defaults", "bdf2", "genalpha")
LABEL = {"lps": "peri/lps + fix nve", "nosb": "peri/nosb + fix nve",
         "jacobi": "peri/nosb + fix sissm (jacobi)",
         "block": "peri/nosb + fix sissm (krylov, precond block)",
         "amg": "peri/nosb + fix sissm (krylov, precond amg)",
         "defaults": "peri/nosb + fix sissm (defaults)",
         "bdf2": "peri/nosb + fix sissm (scheme bdf2)",
         "genalpha": "peri/nosb + fix sissm (scheme genalpha)"}
COLOR = {"lps": "tab:blue", "nosb": "tab:green", "jacobi": "tab:red", "block": "tab:orange",
         "amg": "tab:purple", "defaults": "black", "bdf2": "tab:brown",
         "genalpha": "tab:cyan"}

def previous_run_count(quick: bool):
    """The number of LAMMPS runs the last full report says it took (None for --quick, whose
    report goes elsewhere, or without a report)."""
    report = REPO / "doc" / "reports" / "error-vs-time.md"
    if quick or not report.exists():
        return None
    found = re.search(r"\((\d+) LAMMPS runs", report.read_text())
    return int(found.group(1)) if found else None


# ---------------------------------------------------------------------------------------------
# helpers

def beam_vars(beam, material, extra=None):
    nx, nt = beam[:2]
    a = beam[2] if len(beam) > 2 else 0.01
    v = dict(nx=nx, nt=nt, a=a, material=material)
    v.update(extra or {})
    return v


def euler_bernoulli(beam, material):
    """Static tip deflection and first bending period (Euler-Bernoulli), m and s."""
    nx, nt = beam[:2]
    a = beam[2] if len(beam) > 2 else 0.01
    m = MATERIALS[material]
    E = 9 * m["K"] * m["G"] / (3 * m["K"] + m["G"])
    L, t = nx * a, nt * a
    EI, rA = E * t ** 4 / 12, m["rho"] * t * t
    w = rA * 9.81 * L ** 4 / (8 * EI)
    omega = 1.8751 ** 2 * math.sqrt(EI / (rA * L ** 4))
    # Timoshenko: shear adds E/(3 kappa G) (t/L)^2 with kappa = 5/6 for the tip load; for a
    # uniform load the added fraction is (8 E I)/(kappa G A L^2) * (1/2) / ... use the uniform
    # load result w_s / w_b = 4 E I / (kappa G A L^2)
    shear = 4 * EI / ((5.0 / 6.0) * m["G"] * t * t * L * L)
    return w, 2 * math.pi / omega, shear


def wave_speed(material):
    m = MATERIALS[material]
    return math.sqrt(m["K"] / m["rho"])


def method_of(opts):
    """jacobi, block, amg (krylov with precond amg, the default preconditioner), defaults
    (no keywords at all), or the second-order scheme (bdf2, genalpha) it names."""
    words = opts.split()
    if not words:
        return "defaults"
    if "scheme" in words and words[words.index("scheme") + 1] != "euler":
        return words[words.index("scheme") + 1]
    if "krylov" not in words:
        return "jacobi"
    return "block" if "block" in words else "amg"


def variant_name(opts):
    return opts if opts.strip() else "defaults"


def unconverged_mode(opts):
    """What a step of this variant that misses its tolerance does (doc/fix_sissm.rst)."""
    words = opts.split()
    if "tolerance" in words and float(words[words.index("tolerance") + 1]) == 0:
        return "tolerance 0: every step runs all its iterations, never redone or stopped"
    if "unconverged" in words:
        mode = words[words.index("unconverged") + 1]
        return {"warn": "unconverged warn: a step that misses the tolerance is kept "
                        "(truncated), counted in f_ID[4]",
                "error": "unconverged error: the run stops at the first such step"}.get(
                    mode, "unconverged " + " ".join(words[words.index("unconverged") + 1:]))
    return ("unconverged cutback 4 (the default): redone as 2..16 sub-steps; ERROR when even "
            "16 do not converge")


def stop_reason(errors):
    """A short description of the ERROR that ended a fix sissm run."""
    if not errors:
        return ""
    msg = errors[0]
    if "not even as" in msg and "sub-steps" in msg:
        subs = re.search(r"not even as (\d+) sub-steps", msg)
        step = re.search(r"step (\d+)", msg)
        return (f"stopped: did not converge even as {subs.group(1)} sub-steps "
                f"(unconverged cutback) at step {step.group(1) if step else '?'}")
    if "(unconverged error)" in msg:
        return "stopped: unconverged error"
    return "ERROR: " + msg[:160]


# ---------------------------------------------------------------------------------------------
# the benchmark

class Benchmark:
    def __init__(self, args):
        self.args = args
        self.cfg = QUICK if args.quick else FULL
        self.beam = self.cfg["beam"]
        self.work = Path(tempfile.mkdtemp(prefix="evt-")) if not args.keep else args.keep
        self.work.mkdir(parents=True, exist_ok=True)
        self.runner = DeckRunner(args.lmp, self.work, HERE, ["cantilever.geometry"],
                                 "error-vs-time", expected=previous_run_count(args.quick))
        self.rows = {"static": [], "dynamic": [], "stiff": []}
        self.notes = []
        self.t0 = time.time()

    def say(self, *msg):
        print(f"[{time.time() - self.t0:7.1f} s]", *msg, file=sys.stderr, flush=True)

    # -- capabilities ---------------------------------------------------------------------------
    def probe_variants(self):
        variants = QUICK_VARIANTS if self.args.quick else SISSM_VARIANTS
        tiny = dict(nx=6, nt=4, nsteps=2, thermo_every=1, dt=1e-4)
        has_solver = self.runner.run("in.sissm", dict(tiny, opts="solver jacobi iterations 2"),
                                     check=False)["ok"]
        self.has_solver = has_solver
        accepted, skipped = [], []
        self.defaults_line = ""
        for opts in variants:
            o = opts if has_solver else opts.replace("solver jacobi ", "")
            r = self.runner.run("in.sissm", dict(tiny, opts=o), check=False)
            if r["ok"]:
                accepted.append(o)
                if not o.strip():   # what the keyword-less fix sissm set up on this build
                    found = re.search(r"^Fix sissm \S+ precond .*$", r["log"], re.M)
                    self.defaults_line = found.group(0) if found else ""
            else:
                skipped.append(o)
        self.variants, self.skipped = accepted, skipped
        self.scheme_variants = []
        for opts in (QUICK_SCHEME_VARIANTS if self.args.quick else SCHEME_VARIANTS):
            r = self.runner.run("in.sissm", dict(tiny, opts=opts), check=False)
            (self.scheme_variants if r["ok"] else self.skipped).append(opts)
        self.say("fix sissm variants:", accepted, "scheme variants:", self.scheme_variants,
                 "skipped:", self.skipped)

    # -- explicit limits -----------------------------------------------------------------------
    def stable(self, style, material, dt, ebw):
        steps = self.cfg["bisect_steps"]
        r = self.runner.run(f"in.{style}", beam_vars(self.beam, material, dict(
            dt=dt, nsteps=steps, thermo_every=100, halt=10 * ebw)), check=False)
        th = r["thermo"]
        return (r["ok"] and "Step" in th and int(th["Step"][-1]) == steps
                and np.all(np.isfinite(th["v_defl"])) and np.max(np.abs(th["v_defl"])) < 10 * ebw)

    def limit(self, style, material):
        ebw = euler_bernoulli(self.beam, material)[0]
        guess = LIMIT_GUESS[style] * wave_speed("soft") / wave_speed(material)
        lo, hi = 0.85 * guess, 1.2 * guess
        while not self.stable(style, material, lo, ebw):
            hi, lo = lo, lo / 1.3
        while self.stable(style, material, hi, ebw):
            lo, hi = hi, hi * 1.3
        for _ in range(self.cfg["bisect_rounds"]):
            mid = math.sqrt(lo * hi)
            if self.stable(style, material, mid, ebw):
                lo = mid
            else:
                hi = mid
        self.say(f"explicit limit {style} {material}: stable {lo:.4g}, unstable {hi:.4g}")
        return lo, hi

    # -- runs -------------------------------------------------------------------------------
    def explicit(self, style, material, dt, gamma, nsteps, thermo_every, beam=None):
        r = self.runner.run(f"in.{style}", beam_vars(beam or self.beam, material, dict(
            dt=dt, gamma=gamma, nsteps=nsteps, thermo_every=thermo_every)))
        th = r["thermo"]
        steps = th["Step"]
        return dict(step=steps, time=th["Time"], defl=th["v_defl"], cpu=th["CPU"], evals=steps,
                    iters=np.zeros_like(steps), loop=r["loop"], atoms=r["atoms"],
                    wEB=float(EB.search(r["log"]).group(1)), done=int(steps[-1]) == nsteps)

    def sissm(self, opts, material, dt, gamma, nsteps, thermo_every, maxevals):
        """A fix sissm run of at most nsteps steps, stopped at the first thermo row with at
        least maxevals force evaluations (in.sissm: fix halt)."""
        r = self.runner.run("in.sissm", beam_vars(self.beam, material, dict(
            dt=dt, gamma=gamma, nsteps=nsteps, thermo_every=thermo_every, opts=opts,
            maxevals=maxevals)), check=False)
        th = r["thermo"]
        steps = th.get("Step", np.array([]))
        # the run record for the report's fix sissm tables (cut-backs etc. from the log's
        # summary line, which a run stopped by an ERROR does not write)
        s = r["summary"]
        rec = dict(variant=variant_name(opts), material=material, dt=dt, steps_planned=nsteps,
                   steps=int(steps[-1]) if len(steps) else 0,
                   evaluations=int(round(steps[-1] * (th["f_integrate[3]"][-1] + 1)))
                   if len(steps) else 0,
                   unconverged=int(s[2]) if s else None, cut_back=int(s[3]) if s else None,
                   switches=int(s[4]) if s else None,
                   amg_setups=int(s[5]) if s and s[5] else None,
                   wall=r["loop"], end="", ok=r["ok"])
        self.sissm_runs.setdefault(self.scene_now, []).append(rec)
        if not r["ok"] or "Step" not in th or len(th["Step"]) < 2:
            rec["end"] = stop_reason(r["errors"]) or "failed"
            self.notes.append(f"{self.scene_now}: fix sissm `{variant_name(opts)}` at dt = "
                              f"{dt:.3g} s ({material}) {rec['end']}: no point ("
                              + "; ".join(r["errors"][:2]) + ")")
            return None
        iters = np.round(th["f_integrate[3]"] * steps)
        rec["end"] = ("complete" if int(steps[-1]) == nsteps else
                      f"evaluation cap ({maxevals})")
        return dict(step=steps, time=th["Time"], defl=th["v_defl"], cpu=th["CPU"],
                    evals=iters + steps, iters=iters, loop=r["loop"], atoms=r["atoms"],
                    unconverged=th["f_integrate[4]"], done=int(steps[-1]) == nsteps,
                    wEB=float(EB.search(r["log"]).group(1)))

    # -- scene helpers ------------------------------------------------------------------------
    def static_points(self, scene, method, variant, dt, lim, gamma, run, ref):
        """Checkpoints of a static run: error = largest |defl - ref| / |ref| from the checkpoint
        to the end of the run (a damped oscillation passing through the reference does not
        count as converged)."""
        err = np.abs(run["defl"] - ref) / abs(ref)
        env = np.maximum.accumulate(err[::-1])[::-1]
        n = len(err)
        picks = sorted(set(np.unique(np.geomspace(1, n - 1, min(n - 1, 40)).astype(int))))
        for k in picks:
            self.rows[scene].append(dict(
                scene=scene, method=method, variant=variant, dt=dt, dt_over_limit=dt / lim,
                gamma=gamma, steps=int(run["step"][k]), evaluations=int(run["evals"][k]),
                iterations=int(run["iters"][k]), wall_s=float(run["cpu"][k]),
                error=float(env[k]), run_complete=run["done"],
                loop_time_s=run["loop"]))

    def damping(self, material, omega1, factor):
        return factor * 2 * MATERIALS[material]["rho"] * omega1

    def sissm_gamma(self, material, omega1, dt, lim, opts):
        """fix viscous for a static fix sissm run: 0 when the steps are meant to converge (the
        backward-Euler step dissipates by itself); with a fixed sweep budget (tolerance 0) the
        beam moves as if its inertia were (omega1/omega_eff)^2 larger, omega_eff/omega1 ~
        0.48 sqrt(iterations) limit/dt (fitted to examples/cantilever, where 9.5e6 was tuned),
        and critical damping is 2 rho omega1^2 / omega_eff."""
        words = opts.split()
        tol = float(words[words.index("tolerance") + 1]) if "tolerance" in words else 1e-6
        iters = int(words[words.index("iterations") + 1]) if "iterations" in words else 100
        if tol > 0:
            return 0.0
        ratio = min(1.0, 0.48 * math.sqrt(iters) * lim / dt)
        return 0.9 * 2 * MATERIALS[material]["rho"] * omega1 / ratio

    # -- scenes -----------------------------------------------------------------------------
    def static_scene(self, scene, material):
        cfg = self.cfg
        w_eb, T_eb, shear = euler_bernoulli(self.beam, material)
        omega_eb = 2 * math.pi / T_eb
        refs = {}
        for style in ("nosb", "lps"):
            lim = self.limits[(style, material)][0]
            # first bending frequency of this discretization: measured in the dynamic scene
            # (soft); the steel beam scales with the bar wave speed
            omega1 = self.omega1[style] * omega_eb / self.omega_eb_soft
            T1 = 2 * math.pi / omega1
            dt = STATIC_REFERENCE_DT[style] * lim
            nsteps = int(cfg["reference_periods"] * T1 / dt)
            self.say(f"{scene}: reference {style} ({nsteps} steps)")
            ref = self.explicit(style, material, dt, self.damping(material, omega1, 1.0), nsteps,
                                max(1, nsteps // 400))
            d = ref["defl"]
            last = int(round(T1 / dt / max(1, nsteps // 400)))
            change = abs(d[-1] - d[-1 - max(1, last)]) / abs(d[-1])
            refs[style] = dict(defl=float(d[-1]), change=change, steps=nsteps, dt=dt,
                               loop=ref["loop"], omega1=omega1)
            for dtf in cfg["explicit_static_dt"][style]:
                for df in cfg["explicit_static_damp"]:
                    dts = dtf * lim
                    n = int(cfg["static_periods"] * T1 / dts)
                    gamma = self.damping(material, omega1, df)
                    self.say(f"{scene}: {style} dt {dtf} x limit, damping {df} x critical")
                    run = self.explicit(style, material, dts, gamma, n, max(1, n // 200))
                    self.static_points(scene, style, f"damping {df} x critical", dts, lim, gamma,
                                       run, refs[style]["defl"])
        lim = self.limits[("nosb", material)][0]
        for opts in self.variants:
            for m in (cfg["sissm_static_dt"] if scene == "static" else cfg["sissm_stiff_dt"]):
                if m > 100 and method_of(opts) == "jacobi":
                    continue  # plain sweeps hardly move a beam per step there (README)
                dt = m * lim
                gamma = self.sissm_gamma(material, refs["nosb"]["omega1"], dt, lim, opts)
                self.say(f"{scene}: sissm `{opts}` dt {m} x limit gamma {gamma:.3g}")
                run = self.sissm(opts, material, dt, gamma, 100000, 5,
                                 cfg["sissm_static_evaluations"])
                if run is None:
                    continue
                # error of the run's last checkpoint (for the report's notes)
                self.sissm_runs[scene][-1]["final_error"] = float(
                    abs(run["defl"][-1] - refs["nosb"]["defl"]) / abs(refs["nosb"]["defl"]))
                self.static_points(scene, method_of(opts), variant_name(opts) + (
                    f", viscous {gamma:.3g}" if gamma > 0 else ""), dt, lim, gamma, run,
                    refs["nosb"]["defl"])
        return dict(refs=refs, w_eb=w_eb, shear=shear)

    def dynamic_scene(self):
        cfg, material = self.cfg, "soft"
        w_eb, T_eb, _ = euler_bernoulli(self.beam, material)
        T = cfg["dynamic_periods"] * T_eb
        refs = {}
        for style in ("nosb", "lps"):
            lim = self.limits[(style, material)][0]
            dt = cfg["reference_dt"] * lim
            n = int(round(T / dt))
            self.say(f"dynamic: reference {style} ({n} steps)")
            ref = self.explicit(style, material, dt, 0.0, n, 2)
            t, d = ref["time"], ref["defl"]
            # first bending period from the first minimum of the step response (half a period)
            window = t <= min(T, 1.2 * T_eb)   # the first minimum: half a period
            k = int(np.argmin(np.where(window, d, np.inf)))
            if 0 < k < len(d) - 1:  # parabola through the three samples around the minimum
                y0, y1, y2 = d[k - 1], d[k], d[k + 1]
                shift = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2)
                tmin = t[k] + shift * (t[1] - t[0])
            else:
                tmin = t[k]
            refs[style] = dict(t=t, d=d, dt=dt, steps=n, loop=ref["loop"], T1=2 * tmin,
                               dmax=float(np.max(np.abs(d))), tmin=tmin)
            self.omega1[style] = math.pi / tmin
            self.say(f"dynamic: {style} first period {2 * tmin:.4g} s (Euler-Bernoulli {T_eb:.4g})")

        def error(style, run):
            r = refs[style]
            dref = np.interp(run["time"], r["t"], r["d"])
            return float(np.max(np.abs(run["defl"] - dref)) / r["dmax"])

        for style in ("nosb", "lps"):
            lim = self.limits[(style, material)][0]
            for f in cfg["explicit_dynamic_dt"][style]:
                dt = T / round(T / (f * lim))
                n = int(round(T / dt))
                self.say(f"dynamic: {style} dt {f} x limit")
                run = self.explicit(style, material, dt, 0.0, n, max(1, n // 200))
                self.rows["dynamic"].append(dict(
                    scene="dynamic", method=style, variant="", dt=dt, dt_over_limit=dt / lim,
                    gamma=0.0, steps=n, evaluations=n, iterations=0, wall_s=run["loop"],
                    error=error(style, run), run_complete=run["done"], loop_time_s=run["loop"]))
        lim = self.limits[("nosb", material)][0]
        runs = [(opts, m) for opts in self.variants for m in cfg["sissm_dynamic_dt"]] + \
            [(opts, m) for opts in self.scheme_variants for m in cfg["sissm_scheme_dt"]]
        for opts, m in runs:
            n = max(2, int(round(T / (m * lim))))
            dt = T / n
            self.say(f"dynamic: sissm `{opts}` dt {dt / lim:.3g} x limit ({n} steps)")
            run = self.sissm(opts, material, dt, 0.0, n, max(1, n // 200),
                             cfg["sissm_dynamic_evaluations"])
            if run is None:
                continue
            if not run["done"]:
                self.notes.append(f"dynamic: fix sissm `{variant_name(opts)}` at "
                                  f"{dt / lim:.3g} x the limit "
                                  f"stopped at the {cfg['sissm_dynamic_evaluations']}-"
                                  f"evaluation cap after {int(run['step'][-1])} of {n} steps "
                                  f"({int(run['evals'][-1])} evaluations): no point")
                continue
            self.sissm_runs["dynamic"][-1]["final_error"] = error("nosb", run)
            self.rows["dynamic"].append(dict(
                scene="dynamic", method=method_of(opts), variant=variant_name(opts), dt=dt,
                dt_over_limit=dt / lim, gamma=0.0, steps=n, evaluations=int(run["evals"][-1]),
                iterations=int(run["iters"][-1]), wall_s=run["loop"], error=error("nosb", run),
                run_complete=True, loop_time_s=run["loop"],
                ))
        return dict(refs=refs, T=T, T_eb=T_eb, w_eb=w_eb)

    def convergence_study(self):
        rows = []
        for style in self.cfg["convergence_styles"]:
            for (nx, nt, a) in self.cfg["convergence"]:
                beam = (nx, nt, a)
                w_eb, T_eb, shear = euler_bernoulli(beam, "soft")
                lim = self.limits[(style, "soft")][0] * a / 0.01
                omega1 = self.omega1[style] * (2 * math.pi / T_eb) / self.omega_eb_soft
                T1 = 2 * math.pi / omega1
                dt = STATIC_REFERENCE_DT[style] * lim
                n = int(self.cfg["static_periods"] * T1 / dt)
                self.say(f"convergence: {style} {nx}x{nt}x{nt}, a = {a} ({n} steps)")
                run = self.explicit(style, "soft", dt, self.damping("soft", omega1, 1.0), n,
                                    max(1, n // 100), beam=beam)
                d = run["defl"]
                per = max(1, int(round(T1 / dt / max(1, n // 100))))
                rows.append(dict(style=style, nx=nx, nt=nt, a=a, atoms=run["atoms"],
                                 defl=float(d[-1]), w_eb=w_eb, shear=shear,
                                 change=abs(d[-1] - d[-1 - per]) / abs(d[-1]),
                                 loop=run["loop"], steps=n))
        return rows

    # -- main -------------------------------------------------------------------------------
    def run(self):
        self.probe_variants()
        self.sissm_runs = {}
        self.limits = {}
        for material in ("soft", "steel"):
            for style in ("nosb", "lps"):
                self.limits[(style, material)] = self.limit(style, material)
        self.omega1 = {}
        self.omega_eb_soft = 2 * math.pi / euler_bernoulli(self.beam, "soft")[1]
        self.scene_now = "dynamic"
        self.dyn = self.dynamic_scene()
        self.scene_now = "static"
        self.stat = self.static_scene("static", "soft")
        self.scene_now = "stiff"
        self.stiff = self.static_scene("stiff", "steel")
        self.conv = self.convergence_study()
        self.elapsed = time.time() - self.t0


# ---------------------------------------------------------------------------------------------
# output

def write_csv(path, rows):
    if not rows:
        return
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})


def plot_scene(path, title, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, key, xlabel in ((axes[0], "evaluations", "force evaluations"),
                            (axes[1], "wall_s", "wall time (s, LAMMPS loop time)")):
        for method in METHODS:
            pts = [(r[key], r["error"]) for r in rows if r["method"] == method
                   and r[key] > 0 and r["error"] > 0]
            if not pts:
                continue
            x, y = np.array(pts).T
            ax.scatter(x, y, s=8, alpha=0.25, color=COLOR[method])
            front = sorted(pareto(pts), key=lambda k: pts[k][0])
            fx, fy = x[front], y[front]
            ax.step(fx, fy, where="post", color=COLOR[method], lw=2, label=LABEL[method])
            ax.plot(fx, fy, "o", color=COLOR[method], ms=4)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("relative error")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_convergence(path, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for style in sorted({r["style"] for r in rows}):
        rr = [r for r in rows if r["style"] == style]
        ax.plot([r["nt"] for r in rr], [-r["defl"] / r["w_eb"] for r in rr], "o-",
                color=COLOR[style], label=f"peri/{style}")
    nts = sorted({r["nt"] for r in rows})
    shear = rows[0]["shear"]
    ax.axhline(1.0, color="k", lw=1, label="Euler-Bernoulli")
    ax.axhline(1.0 + shear, color="gray", ls="--", lw=1, label="Timoshenko (kappa = 5/6)")
    ax.set_xlabel("particles across the thickness (delta = 3a, L/t fixed)")
    ax.set_ylabel("tip deflection / Euler-Bernoulli")
    ax.set_xticks(nts)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def cheapest(rows, method, target, key="evaluations"):
    ok = [r for r in rows if r["method"] == method and r["error"] <= target]
    return min(ok, key=lambda r: r[key]) if ok else None


def stalled_notes(bm):
    """Runs with a tolerance whose steps (nearly) all met it at the first residual evaluation,
    without a cut-back, and that still ended far from the reference (error > 0.1)."""
    out = []
    for scene in ("dynamic", "static", "stiff"):
        lim = bm.limits[("nosb", "soft" if scene != "stiff" else "steel")][0]
        for rec in bm.sissm_runs.get(scene, []):
            if not rec["steps"] or rec.get("final_error", 0) <= 0.1 or rec["cut_back"] != 0:
                continue
            per = rec["evaluations"] / rec["steps"] - 1
            opts = rec["variant"] if rec["variant"] != "defaults" else ""
            if per > 1.05 or unconverged_mode(opts).startswith("tolerance 0"):
                continue
            out.append(
                f"{scene}: fix sissm `{rec['variant']}` at {rec['dt'] / lim:.3g} x the limit: "
                f"{per:.3g} evaluations per step besides the one that ends it (the steps met "
                "their tolerance at the first residual evaluation, none was cut back) and "
                + (f"an error of {rec['final_error']:.3g} at the end of the simulated time"
                   if scene == "dynamic" else
                   f"a tip deflection still {rec['final_error']:.3g} (relative) from the "
                   f"reference after {rec['steps']} steps")
                + ": its tolerance (a length relative to the particle size, doc/fix_sissm.rst "
                "\"Convergence\") is met by the residual of the predictor y^n + h v^n at this "
                "step size, so each step is that predictor plus the one SISSM correction the "
                "evaluation gives, not the converged implicit step (compare the variants with a "
                "tighter tolerance at the same time step)")
    return out


def report(bm, out: Path, report_path: Path, command: str):
    rel = os.path.relpath(out, report_path.parent)
    cfg = bm.cfg
    L = []
    nx, nt = bm.beam
    L.append("# Error against run time: peri/lps, peri/nosb explicit and fix sissm\n")
    L.append(f"Generated by `{command}` in {bm.elapsed / 60:.1f} minutes "
             f"({bm.runner.count} LAMMPS runs, one at a time, serial, niced; "
             f"{'QUICK smoke-test settings' if bm.args.quick else 'full settings'}). "
             "Every number below comes from those runs; rerun the command to regenerate this "
             "file, the CSVs and the plots.\n")
    L.append("Decks: `examples/benchmarks/error-vs-time/` (`cantilever.geometry`, `in.lps`, "
             "`in.nosb`, `in.sissm`, `in.minimize`). Cost measures: **force evaluations** "
             "(machine independent: one per step for `fix nve`; for `fix sissm` the iterations "
             "of every step plus the regular evaluation that ends it, steps x (f_ID[3] + 1)) and "
             "**wall time** (LAMMPS loop time; the machine has 2 cores shared with other jobs, so "
             "wall times are noisy by tens of percent).  Each method is measured against a "
             "reference of **its own discretization** (peri/lps against peri/lps; nosb explicit "
             "and SISSM against peri/nosb); Euler-Bernoulli is context only.\n")
    L.append("## Setup\n")
    L.append(f"Swept beam: {nx} x {nt} x {nt} free particles (a = 10 mm, horizon 3.0002a, "
             f"L = {nx * 0.01:.2f} m, t = {nt * 0.01:.2f} m) + 3 clamp layers, "
             f"{(nx + 3) * nt * nt} atoms; gravity 9.81 m/s^2. Soft solid: rho = 1000, K = 10 MPa, "
             "G = 6 MPa; steel-like: rho = 7800, K = 160 GPa, G = 80 GPa.\n")
    L.append("fix sissm variants run (`fix integrate free sissm ...`; method = the group each "
             "variant is plotted and tabulated in; what a step that misses its tolerance does):\n")
    L.append("| variant | method | a step that misses the tolerance |")
    L.append("|---|---|---|")
    for v in bm.variants:
        L.append((f"| `{v}` | " if v.strip() else
                  "| `defaults` (no keywords: solver krylov, precond amg, iterations 100, "
                  "tolerance 1e-6) | ")
                 + f"{LABEL[method_of(v)]} | {unconverged_mode(v)} |")
    for v in bm.scheme_variants:
        steps = ", ".join(f"{m:g}" for m in cfg["sissm_scheme_dt"])
        L.append(f"| `{v}` (dynamic scene only, dt {steps} x the limit) | "
                 f"{LABEL[method_of(v)]} | {unconverged_mode(v)} |")
    L.append("")
    L.append((f"Left out (rejected by this build's fix sissm): "
              f"{', '.join('`' + v + '`' for v in bm.skipped)}. " if bm.skipped else "")
             + ("This build accepts `solver jacobi|krylov`." if bm.has_solver else
                "This build does not accept `solver` (jacobi only).")
             + (f" `defaults` is `fix integrate free sissm` with no keywords (the `fix "
                f"viscous` that in.sissm adds to the static tolerance-0 runs is never added to "
                f"it); its probe run logged \"{bm.defaults_line}\"." if bm.defaults_line
                else ""))
    L.append("")
    L.append("The jacobi variants are SISSM as its authors use it: a fixed, small number of "
             "sweeps per step (tolerance 0, so every step runs them all and is never cut back; "
             "in the static scenes the tolerance-0 runs get `fix viscous` to come to rest, the "
             "`viscous` value in their point labels), and "
             "`iterations 200 tolerance 1e-6` with `unconverged warn`, whose steps stop early "
             "when they converge and are kept truncated when 200 sweeps are not enough. The "
             "krylov variants with a tolerance, and the defaults, are about the converged "
             "implicit step: with the default `unconverged cutback 4` a step that misses the "
             "tolerance is redone as 2, 4, 8 or 16 sub-steps (its evaluations include every "
             "attempt and sub-step), and a run in which even 16 sub-steps do not converge stops "
             "with an ERROR (\"stopped: did not converge even as 16 sub-steps\") and gives no "
             "point.  `precond amg` steps that miss the tolerance are first redone with a fresh "
             "AMG hierarchy and then with the block preconditioner (a \"preconditioner switch\") "
             "before they are cut back.\n")
    L.append("Every fix sissm run is capped in **force evaluations**, not in wall time (`fix halt` "
             "on steps x (f_ID[3] + 1), checked at every thermo row), so which points exist does "
             "not depend on the machine's speed: a static or stiff run stops at its first "
             f"checkpoint with at least {cfg['sissm_static_evaluations']} evaluations and keeps "
             "its checkpoints up to there; a dynamic run that has not reached the end of its "
             f"simulated time within {cfg['sissm_dynamic_evaluations']} evaluations gives no "
             "point (listed under \"Notes from the runs\").  The evaluations of a step count "
             "every attempt and sub-step (f_ID[3]), so cut-back steps use the budget up faster: "
             "a step cut back to 2^L sub-steps costs up to (2^(L+1) - 1) x iterations (31 x for "
             "16 sub-steps, plus up to 2 x iterations for the `precond amg` retries), and since "
             "the cap is only checked at thermo rows (every 5 steps in the static and stiff "
             "scenes), such steps can carry a run past it.  Force evaluations do not count the "
             "AMG set-ups (assembling the bond matrix, PETSc's GAMG set-up) nor the bond pass "
             "per Newton step of `precond amg`: those show in the wall time only.\n")
    L.append("Explicit stability limits (fix nve, bisection: a run of "
             f"{cfg['bisect_steps']} steps with gravity is stable when the tip stays within 10x "
             "the Euler-Bernoulli deflection); every time step below is given as a multiple of "
             "the stable value of its pair style and material:\n")
    L.append("| pair style | material | stable (s) | unstable (s) |")
    L.append("|---|---|---|---|")
    for (style, mat), (lo, hi) in bm.limits.items():
        L.append(f"| peri/{style} | {mat} | {lo:.4g} | {hi:.4g} |")
    L.append("")

    targets = {"static": [1e-2, 1e-3, 1e-4], "stiff": [1e-2, 1e-3, 1e-4],
               "dynamic": [1e-1, 3e-2, 1e-2]}
    scenes = [("static", "Static: gravity-loaded cantilever brought to rest (soft solid)"),
              ("dynamic", "Dynamic: free vibration after gravity is switched on"),
              ("stiff", "Stiff: the static scene with a steel-like solid")]
    for scene, title in scenes:
        rows = bm.rows[scene]
        L.append(f"## {title}\n")
        L.append(f"![{scene}]({rel}/{scene}.png)\n")
        L.append(f"Points: `{rel}/{scene}.csv` ({len(rows)} rows).  Thick lines: each "
                 "method's Pareto front (no other point of the method is both cheaper and more "
                 "accurate); pale dots: all points.\n")
        if scene in ("static", "stiff"):
            info = bm.stat if scene == "static" else bm.stiff
            L.append("Reference (\"solved to round-off\"): a damped explicit run of the same "
                     "pair style (fix nve + fix viscous at critical damping of the first bending "
                     f"mode; time step {STATIC_REFERENCE_DT['nosb']:g} x the stable step for "
                     f"peri/nosb and {STATIC_REFERENCE_DT['lps']:g} x for peri/lps, after two "
                     "empty runs that set peri/lps's critical stretch (in.lps); "
                     f"{cfg['reference_periods']:g} first-mode periods).  Convergence evidence: the relative change of the tip deflection "
                     "over the last period of that run.  Error of a checkpoint = the largest "
                     "relative tip-deflection error from that checkpoint to the end of its run "
                     "(a damped oscillation crossing the reference does not count).\n")
            L.append("| pair style | reference tip deflection (m) | change over the last period "
                     "| vs Euler-Bernoulli | steps | loop time (s) |")
            L.append("|---|---|---|---|---|---|")
            for style, r in info["refs"].items():
                L.append(f"| peri/{style} | {r['defl']:.12g} | {r['change']:.2g} | "
                         f"{(-r['defl'] / info['w_eb'] - 1) * 100:+.1f}% | {r['steps']} | "
                         f"{r['loop']:.1f} |")
            L.append(f"\nEuler-Bernoulli: {info['w_eb']:.6g} m (Timoshenko adds "
                     f"{info['shear'] * 100:.1f}%).\n")
        else:
            d = bm.dyn
            L.append(f"Simulated time {d['T']:.4g} s ({cfg['dynamic_periods']:g} x the "
                     f"Euler-Bernoulli period {d['T_eb']:.4g} s). Error = largest tip-deflection "
                     "difference from the reference over that time (reference interpolated "
                     "at each output), relative to the reference's largest deflection.  Reference: "
                     f"fix nve at {cfg['reference_dt']:g} x the stable step of the same pair "
                     "style.\n")
            L.append("| pair style | reference dt (s) | steps | first period (s) | "
                     "vs Euler-Bernoulli period | loop time (s) |")
            L.append("|---|---|---|---|---|---|")
            for style, r in d["refs"].items():
                L.append(f"| peri/{style} | {r['dt']:.4g} | {r['steps']} | {r['T1']:.5g} | "
                         f"{(r['T1'] / d['T_eb'] - 1) * 100:+.1f}% | {r['loop']:.1f} |")
            L.append("")
        # equal-error table
        L.append("Cheapest point of each method at equal error (force evaluations; wall time "
                 "of the same point; configuration):\n")
        head = "| method | " + " | ".join(f"error <= {t:g}" for t in targets[scene]) + " |"
        L.append(head)
        L.append("|---" * (len(targets[scene]) + 1) + "|")
        for method in METHODS:
            if not any(r["method"] == method for r in rows):
                continue
            cells = []
            for t in targets[scene]:
                c = cheapest(rows, method, t)
                if c is None:
                    cells.append("not reached")
                else:
                    cfgtxt = (f"dt {c['dt_over_limit']:.3g}x" +
                              (f", {c['variant']}" if c["variant"] else ""))
                    cells.append(f"{c['evaluations']} evals, {c['wall_s']:.2f} s ({cfgtxt})")
            L.append(f"| {LABEL[method]} | " + " | ".join(cells) + " |")
        L.append("")
        # ratio sentences
        for t in targets[scene]:
            base = cheapest(rows, "nosb", t)
            if base is None:
                continue
            parts = []
            for method in SISSM_METHODS + ("lps",):
                c = cheapest(rows, method, t)
                if c is not None:
                    parts.append(f"{LABEL[method]} {c['evaluations'] / base['evaluations']:.2g}x "
                                 f"the evaluations ({c['wall_s'] / max(base['wall_s'], 1e-9):.2g}x "
                                 "the wall time)")
                elif any(r["method"] == method for r in rows):
                    parts.append(f"{LABEL[method]} never reached it")
            if parts:
                L.append(f"- At error <= {t:g}, relative to peri/nosb + fix nve: "
                         + "; ".join(parts) + ".")
        L.append("")
        # Pareto fronts in words
        L.append("Pareto fronts (force evaluations -> error):\n")
        for method in METHODS:
            pts = [r for r in rows if r["method"] == method]
            if not pts:
                continue
            front = sorted(pareto([(r["evaluations"], r["error"]) for r in pts]),
                           key=lambda k: pts[k]["evaluations"])
            # at most 8 representative points
            sel = front if len(front) <= 8 else [front[int(round(i))] for i in
                                                 np.linspace(0, len(front) - 1, 8)]
            txt = ", ".join(f"{pts[k]['evaluations']} -> {pts[k]['error']:.2g}" +
                            (f" (dt {pts[k]['dt_over_limit']:.3g}x" +
                             (f", {pts[k]['variant']}" if pts[k]['variant'] else "") + ")")
                            for k in sel)
            L.append(f"- {LABEL[method]}: {txt}")
        L.append("")

    # per-run sissm summaries
    def opt(x):
        return "-" if x is None else str(x)

    def per_step(rec):   # mean iterations per step = evaluations / steps - 1
        return fmt(rec["evaluations"] / rec["steps"] - 1) if rec["steps"] else "-"

    L.append("## fix sissm runs in the dynamic scene\n")
    L.append("Every run of the scene, with its point's error when it reached the end of the "
             "simulated time.  Cut back (steps redone as sub-steps), unconverged (steps kept "
             "above the tolerance: tolerance 0 or `unconverged warn`), switches (steps redone "
             "with the other preconditioner) and AMG set-ups: the summary line fix sissm logs at "
             "the end of a run (\"-\": no such line, because the run stopped with an ERROR, "
             "or, for AMG set-ups, because the variant does not use `precond amg`).\n")
    L.append("| variant | dt / limit | steps | evaluations | mean iterations per step | "
             "cut back | unconverged | switches | AMG set-ups | error | wall (s) | end |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    lim = bm.limits[("nosb", "soft")][0]
    for rec in bm.sissm_runs.get("dynamic", []):
        pt = next((r for r in bm.rows["dynamic"] if r["method"] in SISSM_METHODS
                   and r["variant"] == rec["variant"] and r["dt"] == rec["dt"]), None)
        L.append(f"| `{rec['variant']}` | {rec['dt'] / lim:.3g} | {rec['steps']} of "
                 f"{rec['steps_planned']} | {rec['evaluations']} | {per_step(rec)} | "
                 f"{opt(rec['cut_back'])} | {opt(rec['unconverged'])} | {opt(rec['switches'])} | "
                 f"{opt(rec['amg_setups'])} | {fmt(pt['error']) if pt else '-'} | "
                 f"{fmt(rec['wall'])} | {rec['end']} |")
    L.append("")
    for scene, material in (("static", "soft"), ("stiff", "steel")):
        runs = bm.sissm_runs.get(scene, [])
        if not runs:
            continue
        lim = bm.limits[("nosb", material)][0]
        L.append(f"## fix sissm runs in the {scene} scene\n")
        L.append("One row per run (its checkpoints are the points above): how far it got "
                 "before the evaluation cap, and the log's summary line (columns as in the "
                 "dynamic table).\n")
        L.append("| variant | dt / limit | steps | evaluations | mean iterations per step | "
                 "cut back | unconverged | switches | AMG set-ups | wall (s) | end |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|")
        for rec in runs:
            L.append(f"| `{rec['variant']}` | {rec['dt'] / lim:.3g} | {rec['steps']} | "
                     f"{rec['evaluations']} | {per_step(rec)} | "
                     f"{opt(rec['cut_back'])} | {opt(rec['unconverged'])} | "
                     f"{opt(rec['switches'])} | {opt(rec['amg_setups'])} | {fmt(rec['wall'])} | "
                     f"{rec['end']} |")
        L.append("")

    # convergence study
    L.append("## Convergence of the discretization to Euler-Bernoulli (fixed delta/a = 3)\n")
    L.append(f"![convergence]({rel}/convergence.png)\n")
    L.append("Beam L = 0.24 m, t = 0.06 m (L/t = 4) at several spacings; static deflection by a "
             "damped explicit run (critical damping, 0.9 x the stable step, "
             f"{cfg['static_periods']:g} first-mode periods; the last column shows how settled "
             "it is).\n")
    L.append("| pair style | particles (free) | a (mm) | atoms | tip deflection (m) | / "
             "Euler-Bernoulli | / Timoshenko | change over the last period | loop time (s) |")
    L.append("|---|---|---|---|---|---|---|---|---|")
    for r in bm.conv:
        L.append(f"| peri/{r['style']} | {r['nx']}x{r['nt']}x{r['nt']} | {r['a'] * 1e3:.3g} | "
                 f"{r['atoms']} | {r['defl']:.6g} | {-r['defl'] / r['w_eb']:.4f} | "
                 f"{-r['defl'] / (r['w_eb'] * (1 + r['shear'])):.4f} | {r['change']:.1g} | "
                 f"{r['loop']:.1f} |")
    L.append("")
    notes = bm.notes + stalled_notes(bm)
    if notes:
        L.append("## Notes from the runs\n")
        for n in notes:
            L.append(f"- {n}")
        L.append("")
    return "\n".join(L)


# where dynamics/pareto.py's section of the report begins (its CLOTH_BEGIN)
CLOTH_BEGIN = "<!-- cloth in motion: written by examples/benchmarks/dynamics/pareto.py -->"


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true")
    p.add_argument("--lmp", type=Path, default=Path(lammps_run.LMP))
    p.add_argument("--out", type=Path, default=None)
    p.add_argument("--report", type=Path, default=None)
    p.add_argument("--keep", type=Path, default=None, help="keep the run folders here")
    args = p.parse_args()
    suffix = "-quick" if args.quick else ""
    out = (args.out or REPO / "doc" / "reports" / f"error-vs-time{suffix}").resolve()
    rpt = (args.report or REPO / "doc" / "reports" / f"error-vs-time{suffix}.md").resolve()
    if not args.lmp.exists():
        sys.exit(f"no LAMMPS wrapper at {args.lmp}")
    bm = Benchmark(args)
    bm.run()
    out.mkdir(parents=True, exist_ok=True)
    for scene, rows in bm.rows.items():
        write_csv(out / f"{scene}.csv", rows)
        plot_scene(out / f"{scene}.png", {"static": "static cantilever (soft)",
                                          "dynamic": "free vibration (soft)",
                                          "stiff": "static cantilever (steel-like)"}[scene], rows)
    write_csv(out / "convergence.csv", bm.conv)
    plot_convergence(out / "convergence.png", bm.conv)
    cmd = "/usr/bin/python3 examples/benchmarks/error-vs-time/run.py" + (" --quick" if args.quick
                                                                         else "")
    # the cloth-in-motion section that dynamics/pareto.py writes into the report stays
    cloth = rpt.read_text().split(CLOTH_BEGIN, 1) if rpt.exists() else []
    rpt.write_text(report(bm, out, rpt, cmd) + ("\n" + CLOTH_BEGIN + cloth[1] if len(cloth) == 2
                                                else ""))
    bm.say(f"done: {rpt} and {out} ({bm.elapsed:.0f} s)")
    if not args.keep:
        shutil.rmtree(bm.work, ignore_errors=True)


if __name__ == "__main__":
    main()
