#!/usr/bin/env python3
"""Dynamic benchmark: error of the tip trajectory against force evaluations on a vibrating
steel-like cantilever, peri/lps + fix nve, peri/nosb + fix nve and peri/nosb + fix sissm.

    /usr/bin/python3 examples/benchmarks/dynamics/run.py [--quick] [--out DIR] [--keep DIR]
        [--lmp PATH] [--refined]

Writes a markdown report on standard output (progress goes to standard error); with --out DIR
also DIR/report.md, DIR/points.csv (every point) and DIR/pareto.png.

Scene (beam.geometry): a 50 x 5 x 5 steel-like cantilever (a = 1 mm) that starts undeformed
with the velocity field of its first bending mode and vibrates freely for two periods.  Each
pair style is measured against its own discretization: a fix nve run at 0.25 x its stable
explicit step (peri/lps for peri/lps; peri/nosb for peri/nosb and every fix sissm run).  Error
of a run = max over its output times t <= 2T of |z_tip(t) - z_ref(t)| / max|z_ref| (the
reference interpolated linearly in time).  Cost = force evaluations (fix nve: steps; fix sissm:
steps x (f_ID[3] + 1), every attempt and sub-step included) and wall time (LAMMPS loop time).

Which runs exist never depends on the machine's speed: fix sissm runs are capped in force
evaluations (fix halt in in.nosb), explicit runs by their number of steps.

--quick: a CI-size sweep (a 25 x 5 x 5 beam, a few points per method; about 2 minutes).
--refined: also measure the first period of the beam at half the spacing (100 x 10 x 10
particles, same size; about 3 minutes more) to check how steps per period grow.
"""
from __future__ import annotations

import argparse
import csv
import math
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
from deck_runs import DeckRunner, describe_build, fmt, lammps_run, pareto  # noqa: E402

# ----------------------------------------------------------------------------------------------
# fix sissm variants: ONE place.  Each entry is the option string given to fix sissm ("" = no
# keywords, its defaults: backward Euler).  Each is first tried in a 2-step probe run; one that
# the build refuses (an ERROR, e.g. "unknown keyword 'scheme'" before the second-order schemes
# land) is reported as "not available in this build" and left out of the sweep.
SISSM_VARIANTS = [
    "",
    "tolerance 1e-8",
    "scheme bdf2",
    "scheme bdf2 tolerance 1e-8",
    "scheme genalpha 1.0",
    "scheme genalpha 1.0 tolerance 1e-8",
    "scheme genalpha 0.8",
    "scheme genalpha 0.8 tolerance 1e-8",
]
QUICK_VARIANTS = ["", "tolerance 1e-8", "scheme bdf2", "scheme genalpha 1.0"]
# the check of the peri/nosb reference against fix sissm (backward Euler, three step sizes over
# the first half period, Richardson-extrapolated twice) and, when the build has one, a
# second-order scheme at the finest of those steps (the first of these the build accepts)
CHECK_OPTS = "tolerance 1e-10"
CHECK_SECOND_ORDER = ["scheme genalpha 1.0 tolerance 1e-10", "scheme bdf2 tolerance 1e-10"]
# ----------------------------------------------------------------------------------------------

FULL = dict(
    beam=dict(nx=50, nt=5, a=1.0e-3, amp=0.25),
    bisect_steps=1500, bisect_rounds=5,
    explicit_dt=[0.9, 0.5],           # x the stable step; plus the reference run itself
    reference_dt=0.25,                # x the stable step
    periods=2.0,                      # simulated time, x the first period
    sissm_steps_per_period=[12, 25, 50, 100, 200, 400],   # fix sissm dt = T / these
    # budget of one fix sissm run in force evaluations (fix halt stops it at the first thermo
    # row, here every step, with at least that many): a run that has not reached 2T by then
    # gives no point.  A finer dt is not run when the next coarser one's evaluations x the
    # step ratio x 0.75 (iterations per step fall slowly with dt) already exceed the budget.
    # 7000 is above explicit peri/lps's cost (~4900) and below peri/nosb's (~8600).
    sissm_evaluations=7000,
    # one more run per variant whose sweep brackets 1% error: at the n where the two
    # bracketing points' power law (error ~ n^-p) gives 1%, x 1.05 (the cost at 1% is then
    # not an artefact of the coarse sweep)
    targeted=True,
    check_steps_per_period=[100, 200, 400],
    check_periods=0.5,
)
QUICK = dict(
    beam=dict(nx=25, nt=5, a=1.0e-3, amp=0.25),
    bisect_steps=800, bisect_rounds=2,
    explicit_dt=[0.9],
    reference_dt=0.5,
    periods=2.0,
    sissm_steps_per_period=[12, 25, 50],
    sissm_evaluations=3000,
    targeted=False,
    check_steps_per_period=[50, 100, 200],
    check_periods=0.5,
)
REFINED = dict(nx=100, nt=10, a=0.5e-3, amp=0.5)   # same size, half the spacing
TARGETS = (1e-2, 1e-3)

STYLES = ("nosb", "lps")
LABEL = {"nosb": "peri/nosb + fix nve", "lps": "peri/lps + fix nve"}
RHO, K, G = 7800.0, 160.0e9, 80.0e9
ESTIMATE = re.compile(r"^explicit step estimate = ([0-9.eE+-]+) s", re.M)


def label(variant):
    return "fix sissm " + (variant if variant.strip() else "(defaults)")


def euler_bernoulli_period(beam):
    E = 9 * K * G / (3 * K + G)
    L, t = beam["nx"] * beam["a"], beam["nt"] * beam["a"]
    omega = 1.875104069 ** 2 * math.sqrt(E * t * t / 12 / (RHO * L ** 4))
    return 2 * math.pi / omega


def crossings(t, z):
    """Times where z changes sign (linear interpolation), after the start."""
    out = []
    for k in range(1, len(z)):
        if t[k - 1] > 0 and z[k - 1] != 0 and np.sign(z[k]) != np.sign(z[k - 1]):
            out.append(t[k - 1] - z[k - 1] * (t[k] - t[k - 1]) / (z[k] - z[k - 1]))
        elif t[k - 1] > 0 and z[k - 1] == 0:
            out.append(t[k - 1])
    return np.array(out)


class Benchmark:
    def __init__(self, args):
        self.args = args
        self.cfg = QUICK if args.quick else FULL
        self.beam = dict(self.cfg["beam"])
        self.t0 = time.time()
        self.work = Path(tempfile.mkdtemp(prefix="dyn-")) if not args.keep else args.keep
        self.work.mkdir(parents=True, exist_ok=True)
        self.runner = DeckRunner(args.lmp, self.work, HERE, ["beam.geometry"], "dynamics")
        self.points, self.notes, self.sissm_runs = [], [], []
        self.build = describe_build(args.lmp)

    def say(self, *msg):
        print(f"[{time.time() - self.t0:7.1f} s]", *msg, file=sys.stderr, flush=True)

    def vars(self, extra, beam=None):
        v = dict(beam or self.beam)
        v.update(extra)
        return v

    # -- the build -------------------------------------------------------------------------
    def probe(self, opts):
        r = self.runner.run("in.nosb", dict(nx=6, nt=4, a=1e-3, nsteps=2, thermo_every=1,
                                            dt=1e-7, integrator="sissm", opts=opts), check=False)
        return r["ok"], (r["errors"][0] if r["errors"] else "")

    def probe_variants(self):
        variants = QUICK_VARIANTS if self.args.quick else SISSM_VARIANTS
        self.variants, self.refused = [], {}
        for opts in variants:
            ok, err = self.probe(opts)
            if ok:
                self.variants.append(opts)
            else:
                self.refused[opts] = err
        self.say("fix sissm variants:", self.variants, "not available:", list(self.refused))

    # -- explicit limits ---------------------------------------------------------------------
    def stable(self, style, dt, beam=None):
        beam = beam or self.beam
        steps = self.cfg["bisect_steps"]
        zmax = 10 * beam["amp"] * beam["a"]
        r = self.runner.run(f"in.{style}", self.vars(dict(dt=dt, nsteps=steps,
                                                          thermo_every=100, halt=zmax), beam),
                            check=False)
        th = r["thermo"]
        return bool(r["ok"] and "Step" in th and int(th["Step"][-1]) == steps
                    and np.all(np.isfinite(th["v_ztip"])) and np.max(np.abs(th["v_ztip"])) < zmax
                    and np.max(th["KinEng"]) < 2 * th["KinEng"][0])

    def limit(self, style, guess):
        lo, hi = guess, 1.5 * guess
        while not self.stable(style, lo):
            hi, lo = lo, lo / 1.3
        while self.stable(style, hi):
            lo, hi = hi, hi * 1.3
        for _ in range(self.cfg["bisect_rounds"]):
            mid = math.sqrt(lo * hi)
            if self.stable(style, mid):
                lo = mid
            else:
                hi = mid
        self.say(f"explicit limit {style}: stable {lo:.4g} s, unstable {hi:.4g} s")
        return lo, hi

    # -- runs --------------------------------------------------------------------------------
    def explicit(self, style, dt, nsteps, every, beam=None):
        r = self.runner.run(f"in.{style}", self.vars(dict(dt=dt, nsteps=nsteps,
                                                          thermo_every=every), beam))
        th = r["thermo"]
        return dict(t=th["Time"], z=th["v_ztip"], steps=int(th["Step"][-1]), loop=r["loop"],
                    atoms=r["atoms"], evaluations=int(th["Step"][-1]))

    def sissm(self, opts, dt, nsteps, maxevals, every=1):
        r = self.runner.run("in.nosb", self.vars(dict(
            dt=dt, nsteps=nsteps, thermo_every=every, integrator="sissm", opts=opts,
            maxevals=maxevals)), check=False)
        th = r["thermo"]
        steps = int(th["Step"][-1]) if "Step" in th and len(th["Step"]) else 0
        evals = int(round(steps * (th["f_integrate[3]"][-1] + 1))) if steps else 0
        s = r["summary"]   # fix sissm's summary line (deck_runs.SUMMARY), None after an ERROR
        rec = dict(variant=opts, dt=dt, steps=steps, steps_planned=nsteps, evaluations=evals,
                   per_step=(evals / steps - 1) if steps else None,
                   cut_back=int(s[3]) if s else None,
                   unconverged=int(s[2]) if s else None,
                   amg_setups=int(s[5]) if s and s[5] else None,
                   loop=r["loop"], ok=r["ok"], errors=r["errors"],
                   t=th.get("Time"), z=th.get("v_ztip"))
        rec["complete"] = r["ok"] and steps == nsteps
        return rec

    # -- the scene ---------------------------------------------------------------------------
    def first_period(self, style, dt, beam=None):
        """First period from the first zero crossing (half a period) of a short explicit run:
        sets the simulated time 2T of every run."""
        beam = beam or self.beam
        T_eb = euler_bernoulli_period(beam)
        n = int(math.ceil(0.7 * T_eb / dt))
        run = self.explicit(style, dt, n, 5, beam)
        c = crossings(run["t"], run["z"])
        if not len(c):
            raise RuntimeError(f"{style}: no zero crossing of the tip within {0.7 * T_eb:.3g} s")
        return 2 * c[0], run

    def reference(self, style):
        cfg = self.cfg
        lim = self.limits[style][0]
        T = self.T_half[style]
        S = cfg["periods"] * T
        n = int(math.ceil(S / (cfg["reference_dt"] * lim)))
        every = max(1, int(round(n / (cfg["periods"] * 2000))))   # ~2000 samples a period
        self.say(f"reference {style}: {n} steps of {S / n:.4g} s")
        run = self.explicit(style, S / n, n, every)
        t, z = run["t"], run["z"]
        c = crossings(t, z)
        c = c[c < S * (1 - 1e-6)]
        # crossings at T/2, T, 3T/2, ...: the slope of their times against k/2 is the period
        k = np.arange(1, len(c) + 1) / 2
        T_ref = float(np.polyfit(k, c, 1)[0]) if len(c) >= 2 else 2 * c[0]
        # content other than the first mode: what is left of a least-squares fit of
        # A sin(wt) + B cos(wt) + C at the measured frequency
        w = 2 * math.pi / T_ref
        M = np.column_stack([np.sin(w * t), np.cos(w * t), np.ones_like(t)])
        coef, *_ = np.linalg.lstsq(M, z, rcond=None)
        resid = float(np.max(np.abs(z - M @ coef)) / np.max(np.abs(z)))
        return dict(t=t, z=z, dt=S / n, steps=n, loop=run["loop"], S=S, T=T_ref,
                    crossings=c, zmax=float(np.max(np.abs(z))), resid=resid,
                    atoms=run["atoms"], every=every)

    def error(self, style, t, z):
        ref = self.refs[style]
        keep = t <= ref["S"] * (1 + 1e-9)
        zr = np.interp(t[keep], ref["t"], ref["z"])
        return float(np.max(np.abs(z[keep] - zr)) / ref["zmax"])

    def add_point(self, method, variant, dt, lim, steps, evaluations, wall, error, note=""):
        self.points.append(dict(method=method, variant=variant, dt=dt, dt_over_limit=dt / lim,
                                steps_per_period=self.T["nosb" if method != "lps" else "lps"] / dt,
                                steps=steps, evaluations=evaluations, wall_s=wall, error=error,
                                note=note))

    def check(self):
        """fix sissm against the peri/nosb reference: backward Euler at T/n for the three n of
        check_steps_per_period over the first check_periods, extrapolated twice (Richardson:
        first order, then second), compared at the coarsest run's step times; and, when
        available, a second-order scheme at the finest step, compared directly."""
        cfg, T = self.cfg, self.T["nosb"]
        ns = cfg["check_steps_per_period"]
        span = cfg["check_periods"] * T
        runs = []
        for n in ns:
            steps = int(round(cfg["check_periods"] * n))
            self.say(f"check: fix sissm {CHECK_OPTS} at T/{n} ({steps} steps)")
            rec = self.sissm(CHECK_OPTS, T / n, steps, 0)
            if not rec["complete"]:
                self.notes.append(f"check: fix sissm `{CHECK_OPTS}` at T/{n} did not complete: "
                                  + "; ".join(rec["errors"][:1]))
                return None
            runs.append(rec)
        z = [r["z"] for r in runs]
        t0 = runs[0]["t"]
        r1 = 2 * z[1][::2] - z[0]              # first-order term removed, at T/n0 times
        r2 = 2 * z[2][::2] - z[1]              # at T/n1 times
        rr = (4 * r2[::2] - r1) / 3            # second-order term removed, at T/n0 times
        ref = self.refs["nosb"]
        zr = np.interp(t0, ref["t"], ref["z"])
        out = dict(ns=ns, span=span, opts=CHECK_OPTS,
                   be=[self.error("nosb", r["t"], r["z"]) for r in runs],
                   rich1=float(np.max(np.abs(r1 - zr)) / ref["zmax"]),
                   rich2=float(np.max(np.abs(rr - zr)) / ref["zmax"]),
                   evaluations=[r["evaluations"] for r in runs],
                   loop=sum(r["loop"] for r in runs), second=None)
        for opts in CHECK_SECOND_ORDER:
            if not self.probe(opts)[0]:
                continue
            steps = int(round(cfg["check_periods"] * ns[-1]))
            self.say(f"check: fix sissm {opts} at T/{ns[-1]} ({steps} steps)")
            rec = self.sissm(opts, T / ns[-1], steps, 0)
            if rec["complete"]:
                out["second"] = dict(opts=opts, n=ns[-1],
                                     error=self.error("nosb", rec["t"], rec["z"]))
            else:
                self.notes.append(f"check: fix sissm `{opts}` did not complete: "
                                  + "; ".join(rec["errors"][:1]))
            break
        return out

    def refined(self):
        """Steps per period at half the spacing: the first period from half a period of
        explicit peri/nosb at 0.9 x the stable step scaled with the spacing (the stable step
        of a lattice of the same shape is proportional to its spacing), and the estimate of
        compute nosb/atom column 11."""
        beam = dict(REFINED)
        t0 = time.time()
        r = self.runner.run("in.nosb", self.vars(dict(nsteps=0, estimate=1), beam))
        est = float(ESTIMATE.search(r["log"]).group(1))
        lim = self.limits["nosb"][0] * beam["a"] / self.beam["a"]
        self.say(f"refined: {beam['nx']}x{beam['nt']}x{beam['nt']}, first half period")
        T, run = self.first_period("nosb", 0.9 * lim, beam)
        return dict(beam=beam, estimate=est, limit=lim, T=T, atoms=run["atoms"],
                    T_eb=euler_bernoulli_period(beam), wall=time.time() - t0)

    def run(self):
        cfg = self.cfg
        self.probe_variants()
        # explicit limits: peri/nosb from compute nosb/atom's estimate, peri/lps from
        # peri/nosb's (about 1.8 x; the bisection brackets it either way)
        r = self.runner.run("in.nosb", self.vars(dict(nsteps=0, estimate=1)))
        self.estimate = float(ESTIMATE.search(r["log"]).group(1))
        self.limits = {"nosb": self.limit("nosb", self.estimate)}
        self.limits["lps"] = self.limit("lps", 1.6 * self.limits["nosb"][0])
        # first periods (half-period crossing of a short run at 0.9 x), references over 2T
        self.T_half, self.refs, self.T = {}, {}, {}
        for style in STYLES:
            self.T_half[style] = self.first_period(style, 0.9 * self.limits[style][0])[0]
            self.say(f"{style}: first period ~ {self.T_half[style]:.5g} s")
            self.refs[style] = self.reference(style)
            self.T[style] = self.T_half[style]      # dt = T / n uses this one
            self.say(f"{style}: reference period {self.refs[style]['T']:.5g} s")
        # explicit sweep
        for style in STYLES:
            lim = self.limits[style][0]
            ref = self.refs[style]
            for f in cfg["explicit_dt"]:
                n = int(math.ceil(ref["S"] / (f * lim)))
                self.say(f"{style}: fix nve at {f} x the stable step ({n} steps)")
                run = self.explicit(style, ref["S"] / n, n, max(1, n // 400))
                self.add_point(style, "", ref["S"] / n, lim, n, n, run["loop"],
                               self.error(style, run["t"], run["z"]))
            self.add_point(style, "", ref["dt"], lim, ref["steps"], ref["steps"], ref["loop"],
                           0.0, note="the reference itself")
        self.chk = self.check()
        # fix sissm sweep, coarse to fine
        S, lim = self.refs["nosb"]["S"], self.limits["nosb"][0]
        cap = cfg["sissm_evaluations"]
        for opts in self.variants:
            prev = None
            for n_per in cfg["sissm_steps_per_period"]:
                n = int(round(cfg["periods"] * n_per))
                if prev is not None:
                    guess = prev["evaluations"] * n / prev["steps_planned"] * 0.75
                    if not prev["complete"] and prev["evaluations"] >= cap:
                        guess = math.inf
                    if guess > cap:
                        self.notes.append(
                            f"`{label(opts)}`: T/{n_per} and finer not run: the run at "
                            f"T/{prev['n_per']} took {prev['evaluations']} evaluations, so this "
                            f"one would exceed the budget of {cap}")
                        break
                self.say(f"fix sissm `{opts}` at T/{n_per} ({n} steps)")
                rec = self.sissm(opts, S / n, n, cap)
                rec["n_per"] = n_per
                self.sissm_runs.append(rec)
                prev = rec
                if rec["complete"]:
                    rec["error"] = self.error("nosb", rec["t"], rec["z"])
                    self.add_point(label(opts), opts, S / n, lim, n, rec["evaluations"],
                                   rec["loop"], rec["error"])
                elif rec["ok"] or (rec["steps"] and rec["evaluations"] >= cap):
                    rec["end"] = (f"evaluation budget ({cap}) reached at step {rec['steps']} "
                                  f"of {n}")
                    self.notes.append(f"`{label(opts)}` at T/{n_per}: {rec['end']}: no point")
                else:
                    rec["end"] = "ERROR: " + (rec["errors"][0][:200] if rec["errors"] else "?")
                    self.notes.append(f"`{label(opts)}` at T/{n_per}: stopped with {rec['end']}")
            if cfg["targeted"]:
                self.targeted(opts, 1e-2)
        self.ref_dt_err = {}
        for style in STYLES:   # the reference's own error: second order, from the 0.5x point
            half = [p for p in self.points if p["method"] == style
                    and abs(p["dt_over_limit"] - 2 * cfg["reference_dt"]) < 0.02]
            if half:
                self.ref_dt_err[style] = half[0]["error"] / 3
        self.fine = self.refined() if self.args.refined else None
        self.elapsed = time.time() - self.t0
        end = describe_build(self.args.lmp)
        if end != self.build:
            self.notes.append(f"the build changed during the benchmark: at the start "
                              f"{self.build}, at the end {end}")

    def targeted(self, opts, target):
        """One more run of a variant whose sweep brackets the target error: at n = n1
        (e1/target)^(1/p) x 1.05, p from the bracketing points (n1, e1 > target) and
        (n2, e2 <= target), when that n lies strictly between them."""
        cfg = self.cfg
        done = sorted((r for r in self.sissm_runs if r["variant"] == opts and r["complete"]),
                      key=lambda r: r["n_per"])
        below = [k for k, r in enumerate(done) if r["error"] <= target]
        if not below or below[0] == 0:
            return
        r1, r2 = done[below[0] - 1], done[below[0]]
        if not (r1["error"] > r2["error"] > 0):
            return
        p = math.log(r1["error"] / r2["error"]) / math.log(r2["n_per"] / r1["n_per"])
        n_per = int(math.ceil(r1["n_per"] * (r1["error"] / target) ** (1 / p) * 1.05))
        if not r1["n_per"] < n_per < r2["n_per"]:
            return
        n = int(round(cfg["periods"] * n_per))
        S, lim = self.refs["nosb"]["S"], self.limits["nosb"][0]
        self.say(f"fix sissm `{opts}` at T/{n_per} ({n} steps; aimed at error {target:g})")
        rec = self.sissm(opts, S / n, n, cfg["sissm_evaluations"])
        rec["n_per"], rec["targeted"] = n_per, target
        self.sissm_runs.append(rec)
        if rec["complete"]:
            rec["error"] = self.error("nosb", rec["t"], rec["z"])
            self.add_point(label(opts), opts, S / n, lim, n, rec["evaluations"], rec["loop"],
                           rec["error"], note=f"aimed at {target:g}")
        else:
            rec["end"] = ("evaluation budget reached" if rec["ok"] else
                          "ERROR: " + (rec["errors"][0][:200] if rec["errors"] else "?"))
            self.notes.append(f"`{label(opts)}` at T/{n_per} (aimed at {target:g}): "
                              f"{rec['end']}: no point")


# ---------------------------------------------------------------------------------------------
# output

def methods_of(bm):
    return list(STYLES) + [label(v) for v in bm.variants]


def cheapest(points, method, target, key="evaluations"):
    ok = [p for p in points if p["method"] == method and 0 < p["error"] <= target]
    return min(ok, key=lambda p: p[key]) if ok else None


def method_name(m):
    return LABEL.get(m, m)


def second_order(variant):
    return "scheme" in variant.split()


def report(bm, command):
    cfg, b = bm.cfg, bm.beam
    L = []
    L.append("# Dynamic benchmark: vibrating steel-like cantilever, error against cost\n")
    L.append(f"Generated by `{command}` in {bm.elapsed / 60:.1f} minutes ({bm.runner.count} "
             "LAMMPS runs, one at a time, serial, niced"
             + ("; QUICK settings" if bm.args.quick else "")
             + (f"; the refined run took {bm.fine['wall'] / 60:.1f} of them" if bm.fine else "")
             + "). Decks: `examples/benchmarks/dynamics/` (`beam.geometry`, `in.nosb`, "
             f"`in.lps`). Build: {bm.build}.\n")
    nfree = b["nx"] * b["nt"] ** 2
    atoms = nfree + 3 * b["nt"] ** 2
    T_eb = euler_bernoulli_period(b)
    L.append("## Scene\n")
    L.append(f"Cantilever {b['nx']} x {b['nt']} x {b['nt']} free particles + 3 clamp layers "
             f"({atoms} atoms), a = {b['a'] * 1e3:g} mm, horizon 3.0015 a, L = "
             f"{b['nx'] * b['a'] * 1e3:g} mm, t = {b['nt'] * b['a'] * 1e3:g} mm; steel-like "
             "(rho 7800 kg/m^3, K 160 GPa, G 80 GPa); peri/nosb `linear`, stabilize 2 (its "
             "default), `break no`; peri/lps with s00 = 0.5 (no bond breaks). It starts "
             "undeformed with the velocity field of the Euler-Bernoulli first bending mode "
             f"(tip speed {2 * math.pi / T_eb * b['amp'] * b['a']:.3g} m/s, amplitude about "
             f"{b['amp']:g} a) and vibrates freely (no load, no damping) for "
             f"{cfg['periods']:g} periods. Tip = mean z of the free-end layer.\n")
    L.append("## Explicit stable step, period, steps per period\n")
    L.append(f"Bisection on dt (fix nve, {cfg['bisect_steps']} steps; stable = all steps done, "
             "tip within 10 x the amplitude, energy not grown); `compute nosb/atom` column 11 "
             f"estimates {bm.estimate:.4g} s for peri/nosb. Periods: from the zero crossings "
             "of each reference's tip trajectory; Euler-Bernoulli "
             f"{T_eb:.5g} s.\n")
    L.append("| pair style | stable dt (s) | unstable dt (s) | first period T (s) | "
             "vs Euler-Bernoulli | explicit steps per period (T / stable dt) |")
    L.append("|---|---|---|---|---|---|")
    for s in STYLES:
        lo, hi = bm.limits[s]
        T = bm.refs[s]["T"]
        L.append(f"| peri/{s} | {lo:.4g} | {hi:.4g} | {T:.5g} | {(T / T_eb - 1) * 100:+.1f}% | "
                 f"{T / lo:.0f} |")
    L.append("")
    if bm.fine:
        f = bm.fine
        ratio_c = bm.refs["nosb"]["T"] / bm.limits["nosb"][0]
        ratio_f = f["T"] / f["limit"]
        L.append(f"Refined (same beam, a = {f['beam']['a'] * 1e3:g} mm, {f['beam']['nx']} x "
                 f"{f['beam']['nt']} x {f['beam']['nt']}, {f['atoms']} atoms): peri/nosb "
                 f"period {f['T']:.5g} s (Euler-Bernoulli {f['T_eb']:.5g} s), stable step "
                 f"{f['limit']:.4g} s (the measured one scaled with a; column 11: "
                 f"{f['estimate']:.4g} s): {ratio_f:.0f} steps per period, "
                 f"{ratio_f / ratio_c:.2f} x the {ratio_c:.0f} at a = {b['a'] * 1e3:g} mm "
                 "(beam theory: T ~ L^2/(t c), dt ~ a/c, so T/dt ~ L^2/(t a) doubles).\n")
    L.append("## References\n")
    L.append(f"Each pair style against its own discretization: fix nve at "
             f"{cfg['reference_dt']:g} x its stable step over {cfg['periods']:g} periods, the "
             "tip written every few steps (about 2000 samples a period) and interpolated "
             "linearly in time. peri/nosb's is the reference of every fix sissm run.\n")
    L.append("| pair style | dt (s) | steps | max tip displacement (m) | not first mode "
             "(max residual of a sine fit) | own time error (0.5x point / 3) | loop time (s) |")
    L.append("|---|---|---|---|---|---|---|")
    for s in STYLES:
        r = bm.refs[s]
        L.append(f"| peri/{s} | {r['dt']:.4g} | {r['steps']} | {r['zmax']:.4g} | "
                 f"{r['resid']:.2g} | {fmt(bm.ref_dt_err.get(s), 2)} | {r['loop']:.1f} |")
    L.append("")
    c = bm.chk
    if c:
        L.append(f"Check of the peri/nosb reference with fix sissm (`{c['opts']}`, backward "
                 f"Euler) at T/{c['ns'][0]}, T/{c['ns'][1]}, T/{c['ns'][2]} over the first "
                 f"{cfg['check_periods']:g} period: errors {', '.join(fmt(e, 2) for e in c['be'])} "
                 f"(first order: halve with the step); Richardson-extrapolated once "
                 f"{c['rich1']:.2g}, twice {c['rich2']:.2g} (relative to the reference's "
                 f"largest displacement; {sum(c['evaluations'])} evaluations, "
                 f"{c['loop']:.0f} s)."
                 + (f" Second order, `{c['second']['opts']}` at T/{c['second']['n']}: "
                    f"{c['second']['error']:.2g}." if c["second"] else
                    " No second-order scheme in this build to check with directly.") + "\n")
    L.append("## fix sissm variants\n")
    for v in (QUICK_VARIANTS if bm.args.quick else SISSM_VARIANTS):
        if v in bm.refused:
            L.append(f"- `{label(v)}`: **not available in this build** "
                     f"({bm.refused[v].strip()[:160]})")
        else:
            L.append(f"- `{label(v)}`: run")
    L.append("")
    L.append(f"fix sissm dt = T/n for n in {cfg['sissm_steps_per_period']} (T = "
             f"{bm.T['nosb']:.5g} s, from the first zero crossing); each run capped at "
             f"{cfg['sissm_evaluations']} force evaluations (fix halt, checked every step), "
             "finer steps skipped when the coarser run's cost says they would exceed it"
             + ("; plus, for each variant whose sweep brackets 1% error, one run at the n "
                "where the power law through the two bracketing points gives 1% (x 1.05; "
                "\"aimed at 0.01\")" if cfg["targeted"] else "") + ".\n")
    # all points
    L.append("## Points\n")
    L.append("| method | dt (s) | dt / stable | steps per period | evaluations | wall (s) | "
             "error |")
    L.append("|---|---|---|---|---|---|---|")
    order = methods_of(bm)
    for p in sorted(bm.points, key=lambda p: (order.index(p["method"]), -p["dt"])):
        L.append(f"| {method_name(p['method'])} | {p['dt']:.4g} | {p['dt_over_limit']:.3g} | "
                 f"{p['steps_per_period']:.0f} | {p['evaluations']} | {p['wall_s']:.1f} | "
                 + (p["note"] if p["error"] == 0 else f"{p['error']:.3g}"
                    + (f" ({p['note']})" if p["note"] else "")) + " |")
    L.append("")
    if bm.sissm_runs:
        L.append("fix sissm runs (iterations per step besides the evaluation that ends it; cut "
                 "back and AMG set-ups from the log's summary line):\n")
        L.append("| variant | T/n | steps | evaluations | iterations per step | cut back | "
                 "AMG set-ups | end |")
        L.append("|---|---|---|---|---|---|---|---|")
        for r in sorted(bm.sissm_runs, key=lambda r: (bm.variants.index(r["variant"]),
                                                      r["n_per"])):
            L.append(f"| `{label(r['variant'])}` | T/{r['n_per']} | {r['steps']} of "
                     f"{r['steps_planned']} | {r['evaluations']} | {fmt(r['per_step'])} | "
                     f"{fmt(r['cut_back'])} | {fmt(r['amg_setups'])} | "
                     + ("complete" if r["complete"] else r.get("end", "")) + " |")
        L.append("")
    # per method
    L.append("## Pareto fronts and equal-error costs\n")
    L.append("Front: force evaluations -> error (no other point of the method is both cheaper "
             "and more accurate). Ratio = evaluations of the cheapest explicit point at 1% / "
             "those of the method's (> 1: the method needs fewer).\n")
    expl = {s: cheapest(bm.points, s, 1e-2) for s in STYLES}
    L.append("| method | Pareto front | cheapest at <= 1% | cheapest at <= 0.1% | "
             "vs peri/nosb at 1% | vs peri/lps at 1% |")
    L.append("|---|---|---|---|---|---|")
    for m in methods_of(bm):
        pts = [p for p in bm.points if p["method"] == m and p["error"] > 0]
        if not pts:
            L.append(f"| {method_name(m)} | no point | - | - | - | - |")
            continue
        front = sorted(pareto([(p["evaluations"], p["error"]) for p in pts]),
                       key=lambda k: pts[k]["evaluations"])
        ftxt = ", ".join(f"{pts[k]['evaluations']} -> {pts[k]['error']:.2g}" for k in front)
        cells = []
        for tgt in TARGETS:
            ch = cheapest(pts, m, tgt)
            cells.append("not reached" if ch is None else
                         f"{ch['evaluations']} ({ch['wall_s']:.1f} s; dt "
                         f"{ch['dt_over_limit']:.3g} x stable, T/{ch['steps_per_period']:.0f})")
        ch = cheapest(pts, m, 1e-2)
        ratios = []
        for s in STYLES:
            if ch is None or expl[s] is None:
                ratios.append("-")
            else:
                ratios.append(f"{expl[s]['evaluations'] / ch['evaluations']:.2f} x "
                              f"({expl[s]['wall_s'] / max(ch['wall_s'], 1e-9):.2f} x wall)")
        L.append(f"| {method_name(m)} | {ftxt} | {cells[0]} | {cells[1]} | {ratios[0]} | "
                 f"{ratios[1]} |")
    L.append("")
    # acceptance
    L.append("## Acceptance: second-order fix sissm at 1% against explicit\n")
    so = [v for v in bm.variants if second_order(v)]
    best = None
    for v in so:
        ch = cheapest(bm.points, label(v), 1e-2)
        if ch and (best is None or ch["evaluations"] < best["evaluations"]):
            best = ch
    if not so:
        L.append("No second-order scheme is available in this build (`scheme` refused); "
                 "best backward-Euler result: "
                 + (", ".join(f"`{label(v)}` {cheapest(bm.points, label(v), 1e-2)['evaluations']}"
                              " evaluations at <= 1%" for v in bm.variants
                              if cheapest(bm.points, label(v), 1e-2))
                    or "no backward-Euler variant reaches 1% within the budget")
                 + ".\n")
    elif best is None:
        L.append("No second-order variant reached 1% within the budget: **not met**"
                 + (" (--quick: a short beam and three time steps, a smoke test, not the "
                    "measurement)" if bm.args.quick else "") + ".\n")
    else:
        parts = []
        met = True
        for s in STYLES:
            e = expl[s]
            if e is None:
                parts.append(f"peri/{s} never reached 1%")
                continue
            r = e["evaluations"] / best["evaluations"]
            met = met and r > 1
            parts.append(f"peri/{s} {e['evaluations']} ({r:.2f} x)")
        L.append(f"Cheapest second-order point at <= 1%: `{best['method']}` at "
                 f"T/{best['steps_per_period']:.0f}, {best['evaluations']} evaluations "
                 f"(error {best['error']:.3g}); explicit: " + ", ".join(parts) + ". "
                 + ("**Met.**" if met else "**Not met.**")
                 + (" (--quick: a smoke test, not the measurement.)" if bm.args.quick else "")
                 + "\n")
    if bm.notes:
        L.append("## Notes from the runs\n")
        for n in bm.notes:
            L.append(f"- {n}")
        L.append("")
    return "\n".join(L)


def write_csv(path, points):
    cols = ["method", "variant", "dt", "dt_over_limit", "steps_per_period", "steps",
            "evaluations", "wall_s", "error", "note"]
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=cols)
        w.writeheader()
        for p in points:
            w.writerow({k: (f"{p[k]:.6g}" if isinstance(p[k], float) else p[k]) for k in cols})


def plot(path, bm):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    colors = {"nosb": "tab:green", "lps": "tab:blue"}
    palette = ["black", "dimgray", "tab:red", "tab:orange", "tab:purple", "tab:pink",
               "tab:brown", "tab:olive", "tab:cyan"]
    for k, v in enumerate(bm.variants):
        colors[label(v)] = palette[k % len(palette)]
    for ax, key, xlabel in ((axes[0], "evaluations", "force evaluations"),
                            (axes[1], "wall_s", "wall time (s, LAMMPS loop time)")):
        for m in methods_of(bm):
            pts = [(p[key], p["error"]) for p in bm.points if p["method"] == m
                   and p["error"] > 0 and p[key] > 0]
            if not pts:
                continue
            x, y = np.array(pts).T
            ax.scatter(x, y, s=14, alpha=0.35, color=colors[m])
            front = sorted(pareto(pts), key=lambda k: pts[k][0])
            style = "--" if "tolerance" in m else "-"
            ax.plot(x[front], y[front], style, marker="o", ms=5, lw=3, color=colors[m],
                    label=method_name(m))
        for tgt in TARGETS:
            ax.axhline(tgt, color="gray", lw=0.8, ls=":")
        for s in STYLES:   # no explicit run is cheaper: its step is bounded by stability
            pts = [p[key] for p in bm.points if p["method"] == s and p["error"] > 0]
            if pts:
                ax.axvline(min(pts), color=colors[s], lw=1, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("tip trajectory error over 2 periods (relative)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    b = bm.beam
    fig.suptitle(f"vibrating steel-like cantilever {b['nx']}x{b['nt']}x{b['nt']}: error "
                 "against cost (each method against its own discretization; dotted verticals: "
                 "explicit at 0.9 x its stable step)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="CI-size sweep")
    p.add_argument("--refined", action="store_true",
                   help="also measure the period at half the spacing")
    p.add_argument("--lmp", type=Path, default=Path(lammps_run.LMP))
    p.add_argument("--out", type=Path, default=None, help="write report.md, points.csv, "
                   "pareto.png here")
    p.add_argument("--keep", type=Path, default=None, help="keep the run folders here")
    args = p.parse_args()
    if not args.lmp.exists():
        sys.exit(f"no LAMMPS wrapper at {args.lmp}")
    bm = Benchmark(args)
    bm.run()
    cmd = "/usr/bin/python3 examples/benchmarks/dynamics/run.py" + \
        (" --quick" if args.quick else "") + (" --refined" if args.refined else "")
    text = report(bm, cmd)
    print(text)
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "report.md").write_text(text + "\n")
        write_csv(args.out / "points.csv", bm.points)
        plot(args.out / "pareto.png", bm)
    bm.say(f"done in {bm.elapsed:.0f} s")
    if not args.keep:
        shutil.rmtree(bm.work, ignore_errors=True)


if __name__ == "__main__":
    main()
