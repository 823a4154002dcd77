#!/usr/bin/env python3
"""Cost of fix sissm's AMG preconditioner (assembly + set-up, and one application), expressed in
force evaluations, and how often a run pays the set-up (issue 11).

    /usr/bin/python3 examples/benchmarks/solver/setup_cost.py [--quick] [--ranks N] [--k K1 K2]
                                                              [--petsc "OPTIONS"]

PETSc is never finalized (a plugin has no hook before MPI_Finalize), so -log_view prints
nothing, and the fix's output vector counts evaluations, not seconds. The costs are therefore
separated by wall time, with the work of every step fixed in evaluations:

  * scaling.py's clamped beams, 8 x 8 x 40 (= examples/cantilever) and 8 x 8 x 160, starting at
    rest, undeformed, at dt = 7.3e-3 s (100 x the explicit limit), with `contact no` (a single
    body: its contact forces are zero, but with contact fix sissm asks for a neighbor list build
    whenever an atom moved skin/8 since the last one, and every build is a new sparsity
    pattern) and `neigh_modify delay 1000` (no neighbor list build after the first), so that
    only the configuration decides when the hierarchy is set up;
  * `fix sissm iterations k tolerance 0 unconverged warn precond P` for k = K1, K2 (tolerance 0:
    every step uses exactly k evaluations, plus the regular one that ends it, and nothing is
    redone), STEPS single-step runs (`run 1`, then `run 1 pre no post no`: the fix, and with it
    the AMG hierarchy, is kept from run to run; each step's time is its run's loop time), each
    configuration in its own LAMMPS process from the same start;
  * the hierarchy is lagged: it is set up again only when the sparsity pattern, the step length
    or the convergence says so, so a tolerance-0 run at a fixed step and without neighbor list
    builds sets it up once. To make every step pay a set-up with the pattern kept, the
    `timestep` before each run alternates between dt and dt (1 + 1e-9): the fix's reset_dt()
    changes the force factor h^2, which sets the hierarchy up again (reusing its interpolation,
    with no new pattern); the dynamics do not notice. The configurations:
        block    precond block, dt alternating (the block preconditioner has no set-up)
        amg      precond amg, dt alternating: a set-up at every step, reusing the pattern and
                 the interpolation (what a cut-back sub-step, a new `timestep`, an unconverged
                 step or a slow step pays)
        rebuilt  precond amg, dt fixed, `neigh_modify every 1 delay 0 check no`: a neighbor list
                 build at every step, hence a new sparsity pattern, new PETSc objects and a
                 set-up from scratch (what a neighbor list build pays; it includes the build
                 itself, a few ms)
        lagged   precond amg, dt fixed: the first step's set-up only
        none     precond amg petsc "-pc_type none", dt alternating: the same assembly of the
                 bond-projected stiffness, near-null space and PETSc calls at every step, but
                 no multigrid (the assembly alone)
    The fix's end-of-run line ("K set-up(s) of the AMG hierarchy (P with a new sparsity
    pattern)", cumulative over the runs of one process, since `pre no` keeps the fix) is checked
    against what each configuration should do (amg and none: STEPS set-ups, 1 pattern; rebuilt:
    STEPS and STEPS; lagged: 1 and 1) and printed;
  * `fix nve` at 1e-9 s: t_nve, the time of one explicit step (one plain force evaluation),
    without and with contact.

A step applies the preconditioner a = (Newton steps + CG iterations) times (f_ID[8] + f_ID[7]).
The first step of a process (sparsity pattern, PETSc objects) is reported separately; medians of
the others are used. With t_eval = the block runs' time per evaluation (the slope between K1 and
K2; it includes the per-particle block pass that fix sissm adds to a force evaluation):

    t_P(k) - (k + 1) t_eval = S_P + A_P a_P(k)         (two k, two unknowns)

S_P is the per-step set-up (amg: assembly + PCSetUp of GAMG with the interpolation reused;
rebuilt: pattern + assembly + PCSetUp from scratch; none: the assembly; lagged: nothing, so
S_lagged ~ 0 is a check), A_P the time of one application beyond a block application. The
set-ups are also measured directly, amg - lagged and rebuilt - lagged at the same k. All are
printed in seconds, in t_eval and in t_nve. The estimates carried forward are the ones least
exposed to the machine's other jobs (a configuration's 20 steps take from a few seconds to two
minutes, and a job that starts meanwhile shifts its median): S_kept = amg - lagged and S_new =
rebuilt - lagged at k = K1 (the shortest steps), and A from the lagged runs (no set-up in the
timed steps: the two-k fit of pure applications).

How often a run pays it: the same beams as they are (contact on, LAMMPS's neighbor settings)
from rest at dt = 7.3e-3 s with the fix's defaults (`fix sissm` with no keyword: precond amg,
iterations 100, tolerance 1e-6, unconverged cutback 4), REAL steps: set-ups per step (K and P
of the end-of-run line), evaluations and applications, and the share of the loop time that the
set-ups take (P x S_new + (K - P) x S_kept), with the t_eval of the block runs (contact adds
little to an evaluation of these beams: compare t_nve with and without it) and A; what is left
("rest") is the step's other work (the regular evaluation's neighbor list builds, the line
search's bookkeeping) and the noise of the estimates.

Wall-time numbers on a shared machine: information, not a measure (the evaluation and set-up
counts are). 21 steps per configuration (20 timed) and 50 steps of the realistic run; --quick:
the cantilever only, 6 steps and 20.
"""
from __future__ import annotations

import argparse
import re
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import HERE, LOOP, build_info, print_build  # noqa: E402
sys.path.insert(0, str(HERE))
sys.dont_write_bytecode = True     # no __pycache__ next to the scripts
from lammps_run import run_deck  # noqa: E402
from progress import Progress  # noqa: E402
from scaling import geometry  # noqa: E402


DT = 7.3e-3
ALTERNATE = 1.0e-9
# name: (fix sissm options, the time step alternates, a neighbor list build at every step)
VARIANTS = {"block": ("precond block", True, False), "amg": ("precond amg", True, False),
            "rebuilt": ("precond amg", False, True), "lagged": ("precond amg", False, False),
            "none": ('precond amg petsc "-pc_type none"', True, False)}
AMG = ("amg", "rebuilt", "lagged", "none")
# "Fix sissm integrate run: ... ; K set-up(s) of the AMG hierarchy (P with a new sparsity pattern)"
SUMMARY = re.compile(r"Fix sissm integrate run: (.*)")
SETUPS = re.compile(r"(\d+) set-ups? of the AMG hierarchy \((\d+) with a new sparsity pattern\)")
THERMO = """\
thermo_style    custom step cpu f_integrate[1] f_integrate[2] f_integrate[4] f_integrate[6] &
                f_integrate[7] f_integrate[8] f_integrate[9]
thermo_modify   format float %.10g
thermo          1
"""


def no_contact(n: int, L: int) -> str:
    text = geometry(n, L)
    old = " break no\n"
    assert text.count(old) == 1, "the pair_coeff line of scaling.py's geometry changed"
    return text.replace(old, " break no contact no\n")


def sissm_deck(n: int, L: int, k: int, variant: str, steps: int, petsc: str = "") -> str:
    opts, alternate, rebuild = VARIANTS[variant]
    if petsc and variant in ("amg", "rebuilt", "lagged"):
        opts += f' petsc "{petsc}"'
    neigh = "every 1 delay 0 check no" if rebuild else "delay 1000"
    text = no_contact(n, L) + f"""
neigh_modify    {neigh}
fix             integrate free sissm iterations {k} tolerance 0 unconverged warn {opts}
{THERMO}"""
    for s in range(steps):
        dt = DT * (1.0 + ALTERNATE) if alternate and s % 2 else DT
        text += f"timestep        {dt:.17g}\n"
        text += "run             1\n" if s == 0 else "run             1 pre no post no\n"
    return text


def real_deck(n: int, L: int, steps: int) -> str:
    return geometry(n, L) + f"""
fix             integrate free sissm
timestep        {DT}
{THERMO}run             {steps}
"""


def nve_deck(n: int, L: int, steps: int, contact: bool = False) -> str:
    return (geometry(n, L) if contact else no_contact(n, L)) + f"""
timestep        1.0e-9
fix             integrate free nve
thermo_style    custom step cpu
thermo          {steps}
run             {steps}
"""


def setups(log: str):
    """(K, P) from the last end-of-run line of fix sissm (None when there is none)."""
    lines = SUMMARY.findall(log)
    m = SETUPS.search(lines[-1]) if lines else None
    return (int(m[1]), int(m[2])) if m else None, (lines[-1] if lines else "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--k", type=int, nargs=2, default=[3, 43], metavar=("K1", "K2"))
    ap.add_argument("--petsc", default="", help="PETSc options for precond amg")
    args = ap.parse_args()
    build_start = build_info()
    beams = [(8, 40)] if args.quick else [(8, 40), (8, 160)]
    steps = 6 if args.quick else 21
    real_steps = 20 if args.quick else 50
    steps_nve = 100
    k1, k2 = args.k
    configs = [(k, v) for v in VARIANTS for k in (k1, k2)]
    progress = Progress(sum(L * (len(configs) + 4) for _, L in beams), "setup_cost")
    results = []
    problems = []
    with tempfile.TemporaryDirectory() as tmp:
        for n, L in beams:
            work = Path(tmp) / f"beam{n}x{L}"
            name = f"{n}x{n}x{L}"
            nve = run_deck(nve_deck(n, L, steps_nve), work / "nve", nprocs=args.ranks,
                           timeout=None)
            t_nve = float(nve.thermo[-1]["CPU"][-1]) / steps_nve
            nve = run_deck(nve_deck(n, L, steps_nve, contact=True), work / "nve-contact",
                           nprocs=args.ranks, timeout=None)
            t_nve_contact = float(nve.thermo[-1]["CPU"][-1]) / steps_nve
            progress.step(f"{name} nve", weight=L)
            runs, matrix = {}, {}
            for k, v in configs:
                res = run_deck(sissm_deck(n, L, k, v, steps, args.petsc), work / f"{v}-{k}",
                               nprocs=args.ranks, timeout=None)
                tables = res.thermo
                assert len(tables) == steps, f"{v} k={k}: {len(tables)} thermo tables"
                last = {c: np.array([t[c][-1] for t in tables]) for c in tables[0]}
                times = np.array([float(lp[0]) for lp in LOOP.findall(res.log)])
                assert len(times) == steps, f"{v} k={k}: {len(times)} loop times"
                evals = last["f_integrate[1]"]
                # the budget may end a step one evaluation early (no room for a CG product
                # and the check of its Newton iterate)
                assert np.all((evals <= k) & (evals >= k - 1)), f"{v} k={k}: {evals}"
                applies = last["f_integrate[7]"] + last["f_integrate[8]"]
                count, line = setups(res.log)
                expect = {"block": None, "lagged": (1, 1),
                          "rebuilt": (steps, steps)}.get(v, (steps, 1))
                if count != expect:
                    problems.append(f"{name} {v} k={k}: set-ups (K, P) = {count}, expected "
                                    f"{expect}: {line}")
                runs[k, v] = dict(first=times[0], times=times[1:], evals=evals[1:],
                                  t=float(np.median(times[1:])), e=float(np.median(evals[1:])),
                                  a=float(np.median(applies[1:])), applies=applies[1:],
                                  newton=float(np.median(last["f_integrate[8]"][1:])),
                                  setups=count, summary=line)
                if v == "amg":
                    matrix[v] = [ln.split(": ", 1)[1] for ln in res.log.splitlines()
                                 if "precond amg:" in ln][:1]
                progress.step(f"{name} {v} k={k}", weight=L)
            b1, b2 = runs[k1, "block"], runs[k2, "block"]
            t_eval = (b2["t"] - b1["t"]) / (b2["e"] - b1["e"])
            fits = {}
            for v in AMG:
                r1, r2 = runs[k1, v], runs[k2, v]
                # per step: time beyond its evaluations, medians over the steps
                y1 = float(np.median(r1["times"] - (r1["evals"] + 1) * t_eval))
                y2 = float(np.median(r2["times"] - (r2["evals"] + 1) * t_eval))
                A = (y2 - y1) / (r2["a"] - r1["a"])
                S = y1 - A * r1["a"]
                first = np.mean([runs[k, v]["first"] - runs[k, v]["t"] for k in (k1, k2)])
                fits[v] = dict(S=S, A=A, first=first)
            direct = {(v, k): float(np.median(runs[k, v]["times"] - runs[k, "lagged"]["times"]))
                      for v in ("amg", "rebuilt") for k in (k1, k2)}

            # a realistic run: the fix's defaults, from rest
            res = run_deck(real_deck(n, L, real_steps), work / "real", nprocs=args.ranks,
                           timeout=None, check=False)
            real = dict(ok=res.ok)
            if res.ok:
                t = res.thermo[-1]
                count, line = setups(res.log)
                real.update(loop=float(LOOP.findall(res.log)[-1][0]), setups=count, summary=line,
                            evals=int(t["f_integrate[1]"][1:].sum()) + real_steps,
                            applies=int((t["f_integrate[7]"] + t["f_integrate[8]"])[1:].sum()),
                            per_step=t["f_integrate[1]"][1:].astype(int),
                            unconverged=int(t["f_integrate[4]"][-1]),
                            cutback=int(t["f_integrate[6]"][-1]),
                            fallback=int(t["f_integrate[9]"][-1]))
            else:
                real["error"] = (res.errors or [res.describe()])[0]
            progress.step(f"{name} defaults, {real_steps} steps", weight=2 * L)
            results.append(dict(n=n, L=L, t_nve=t_nve, t_nve_contact=t_nve_contact,
                                t_eval=t_eval, runs=runs, fits=fits,
                                direct=direct, matrix=matrix, real=real))
    progress.done()

    print_build(build_start)
    print(f"cost of fix sissm precond amg in force evaluations: clamped beams at dt = {DT:g} s, "
          f"k = {k1} and {k2} evaluations per step, tolerance 0, {steps} single-step runs per "
          f"configuration (median of the last {steps - 1}), contact no, {args.ranks} rank(s); "
          f"wall-time derived (information only)"
          + (f'; amg with petsc "{args.petsc}"' if args.petsc else ""))
    for r in results:
        te, tn = r["t_eval"], r["t_nve"]
        print()
        m = r["matrix"].get("amg")
        print(f"beam {r['n']}x{r['n']}x{r['L']}" + (f": {m[0]}" if m else ""))
        print(f"  t_nve (fix nve step)                {tn * 1e3:9.2f} ms (with contact "
              f"{r['t_nve_contact'] * 1e3:.2f} ms)")
        print(f"  t_eval (block, per evaluation)      {te * 1e3:9.2f} ms = {te / tn:.2f} t_nve")
        names = [f"{v} k={k}" for k in (k1, k2) for v in VARIANTS]
        print(f"  {'':<32}" + "".join(f"{s:>13}" for s in names))
        print(f"  {'step time (s), median':<32}" + "".join(
            f"{r['runs'][k, v]['t']:>13.4f}" for k in (k1, k2) for v in VARIANTS))
        print(f"  {'applications per step (a)':<32}" + "".join(
            f"{r['runs'][k, v]['a']:>13.0f}" for k in (k1, k2) for v in VARIANTS))
        print(f"  {'AMG set-ups in the run (K/P)':<32}" + "".join(
            f"{'-' if r['runs'][k, v]['setups'] is None else '%d/%d' % r['runs'][k, v]['setups']:>13}"
            for k in (k1, k2) for v in VARIANTS))
        for v, what in (("amg", "amg (set-up, pattern kept)"),
                        ("rebuilt", "rebuilt (new pattern)"),
                        ("lagged", "lagged (no set-up)"), ("none", "pc none (assembly only)")):
            f = r["fits"][v]
            print(f"  {what:<26} set-up per step S        {f['S']:8.3f} s  = "
                  f"{f['S'] / te:7.1f} t_eval = {f['S'] / tn:7.1f} t_nve")
            print(f"  {'':<26} one application, A       {f['A'] * 1e3:8.2f} ms = "
                  f"{f['A'] / te:7.2f} t_eval = {f['A'] / tn:7.2f} t_nve  (beyond a block one)")
            print(f"  {'':<26} first step of a run      {f['first']:8.3f} s  = "
                  f"{f['first'] / te:7.1f} t_eval  (extra)")
        print("  set-up directly, minus lagged at the same k (median per step): "
              + ", ".join(f"{v} k={k}: {d:.3f} s = {d / te:.1f} t_eval" for (v, k), d in
                          r["direct"].items()))
        print(f"  carried forward: S_kept {r['direct']['amg', k1] / te:.1f} t_eval, S_new "
              f"{r['direct']['rebuilt', k1] / te:.1f} t_eval (minus lagged at k={k1}), A "
              f"{r['fits']['lagged']['A'] / te:.2f} t_eval (lagged)")
        real = r["real"]
        print(f"  defaults from rest, {real_steps} steps at dt = {DT:g} s (fix sissm with no "
              f"keyword):", end="")
        if not real["ok"]:
            print(f" FAILED: {real['error'][:200]}")
            continue
        K, P = real["setups"] if real["setups"] else (0, 0)
        S, S_new, A = r["direct"]["amg", k1], r["direct"]["rebuilt", k1], r["fits"]["lagged"]["A"]
        t_ev, t_set, t_app = real["evals"] * te, P * S_new + (K - P) * S, real["applies"] * A
        print()
        print(f"    {real['summary']}")
        print(f"    evaluations per step (f_ID[1]) {' '.join(str(e) for e in real['per_step'])}")
        print(f"    set-ups per step {K / real_steps:.2f} ({P} with a new pattern); loop "
              f"{real['loop']:.2f} s = evaluations {real['evals']} x t_eval "
              f"{t_ev:.2f} s + set-ups {P} x S_new + {K - P} x S_kept {t_set:.2f} s + "
              f"applications {real['applies']} x A {t_app:.2f} s + rest "
              f"{real['loop'] - t_ev - t_set - t_app:.2f} s; share of the set-ups "
              f"{t_set / real['loop']:.0%}; {real['evals'] / real_steps:.1f} evaluations, "
              f"{real['applies'] / real_steps:.1f} applications per step, step time "
              f"{real['loop'] / real_steps / te:.0f} t_eval")
    if results:
        print()
        print("a fix sissm step of E evaluations and a applications with amg takes about "
              "E + a A/t_eval evaluations' time, plus S_kept/t_eval or S_new/t_eval when it "
              "sets the hierarchy up (S_new: with a new sparsity pattern)")
    for p in problems:
        print(f"UNEXPECTED: {p}")


if __name__ == "__main__":
    main()
