#!/usr/bin/env python3
"""Cost of fix sissm's AMG preconditioner (assembly + set-up, and one application), expressed in
force evaluations (issue 11).

    /usr/bin/python3 examples/benchmarks/solver/setup_cost.py [--quick] [--ranks N] [--k K1 K2]
                                                              [--petsc "OPTIONS"]

PETSc is never finalized (a plugin has no hook before MPI_Finalize), so -log_view prints
nothing, and the fix's output vector counts evaluations, not seconds. The costs are therefore
separated by wall time, with the work of every step fixed in evaluations:

  * scaling.py's clamped beams, 8 x 8 x 40 (= examples/cantilever) and 8 x 8 x 160, starting at
    rest, undeformed, at dt = 7.3e-3 s (100 x the explicit limit);
  * `fix sissm iterations k tolerance 0 unconverged warn precond P` for k = K1, K2 (tolerance 0:
    every step uses exactly k evaluations, plus the regular one that ends it) and P = block,
    amg, and amg with `petsc "-pc_type none"` (the same assembly of the bond-projected
    stiffness, near-null space and PETSc calls, but no AMG: the assembly alone); STEPS steps,
    each configuration in its own LAMMPS process from the same start;
  * `fix nve` at 1e-9 s: t_nve, the time of one explicit step (one plain force evaluation).

Each amg step sets the preconditioner up once (at its first Newton step; later Newton steps
reuse it) and applies it a = (Newton steps + CG iterations) times (f_ID[8] + f_ID[7]). Per-step
wall times are differences of the CPU thermo column; the first step of a run (sparsity pattern,
PETSc objects) is reported separately, and the medians of the others are used (a neighbor list
build in a run also rebuilds the pattern at that step; the median ignores such a step). With
t_eval = the block runs' time per evaluation (the slope between K1 and K2; it includes the
per-particle block pass that fix sissm adds to a force evaluation):

    t_P(k) - (k + 1) t_eval = S_P + A_P a_P(k)         (two k, two unknowns)

S_P is the per-step set-up (amg: assembly + PCSetUp of GAMG; none: the assembly), A_P the time
of one application beyond a block application. Both are printed in seconds, in t_eval and in
t_nve. Wall-time numbers on a shared machine: information, not a measure (the evaluation counts
are). 21 steps per configuration (20 timed); --quick: the cantilever only, 6 steps.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import HERE, build_info, print_build  # noqa: E402
sys.path.insert(0, str(HERE))
sys.dont_write_bytecode = True     # no __pycache__ next to the scripts
from lammps_run import run_deck  # noqa: E402
from progress import Progress  # noqa: E402
from scaling import geometry  # noqa: E402


DT = 7.3e-3
VARIANTS = {"block": "precond block", "amg": "precond amg",
            "none": 'precond amg petsc "-pc_type none"'}


def sissm_deck(n: int, L: int, k: int, variant: str, steps: int, petsc: str = "") -> str:
    opts = VARIANTS[variant]
    if petsc and variant == "amg":
        opts += f' petsc "{petsc}"'
    return geometry(n, L) + f"""
timestep        {DT}
fix             integrate free sissm iterations {k} tolerance 0 unconverged warn {opts}
thermo_style    custom step cpu f_integrate[1] f_integrate[2] f_integrate[7] f_integrate[8]
thermo_modify   format float %.10g
thermo          1
run             {steps}
"""


def nve_deck(n: int, L: int, steps: int) -> str:
    return geometry(n, L) + f"""
timestep        1.0e-9
fix             integrate free nve
thermo_style    custom step cpu
thermo          {steps}
run             {steps}
"""


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
    steps_nve = 100
    k1, k2 = args.k
    configs = [(k, v) for v in VARIANTS for k in (k1, k2)]
    progress = Progress(sum(L * (len(configs) + 1) for _, L in beams), "setup_cost")
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for n, L in beams:
            work = Path(tmp) / f"beam{n}x{L}"
            nve = run_deck(nve_deck(n, L, steps_nve), work / "nve", nprocs=args.ranks,
                           timeout=None)
            t_nve = float(nve.thermo[-1]["CPU"][-1]) / steps_nve
            progress.step(f"{n}x{n}x{L} nve", weight=L)
            runs, matrix = {}, {}
            for k, v in configs:
                res = run_deck(sissm_deck(n, L, k, v, steps, args.petsc), work / f"{v}-{k}",
                               nprocs=args.ranks, timeout=None)
                t = res.thermo[-1]
                times = np.diff(t["CPU"])
                evals = t["f_integrate[1]"][1:]
                # the budget may end a step one evaluation early (no room for a CG product
                # and the check of its Newton iterate)
                assert np.all((evals <= k) & (evals >= k - 1)), f"{v} k={k}: {evals}"
                applies = (t["f_integrate[7]"] + t["f_integrate[8]"])[2:]
                runs[k, v] = dict(first=times[0], times=times[1:], evals=evals[1:],
                                  t=float(np.median(times[1:])), e=float(np.median(evals[1:])),
                                  a=float(np.median(applies)), applies=applies,
                                  newton=float(np.median(t["f_integrate[8]"][2:])))
                matrix[v] = [ln.split(": ", 1)[1] for ln in res.log.splitlines()
                             if "precond amg:" in ln][:1]
                progress.step(f"{n}x{n}x{L} {v} k={k}", weight=L)
            b1, b2 = runs[k1, "block"], runs[k2, "block"]
            t_eval = (b2["t"] - b1["t"]) / (b2["e"] - b1["e"])
            fits = {}
            for v in ("amg", "none"):
                r1, r2 = runs[k1, v], runs[k2, v]
                # per step: time beyond its evaluations, medians over the steps
                y1 = float(np.median(r1["times"] - (r1["evals"] + 1) * t_eval))
                y2 = float(np.median(r2["times"] - (r2["evals"] + 1) * t_eval))
                A = (y2 - y1) / (r2["a"] - r1["a"])
                S = y1 - A * r1["a"]
                first = np.mean([runs[k, v]["first"] - runs[k, v]["t"] for k in (k1, k2)])
                fits[v] = dict(S=S, A=A, first=first)
            results.append(dict(n=n, L=L, t_nve=t_nve, t_eval=t_eval, runs=runs, fits=fits,
                                matrix=matrix))
    progress.done()

    print_build(build_start)
    print(f"cost of fix sissm precond amg in force evaluations: clamped beams at dt = {DT:g} s, "
          f"k = {k1} and {k2} evaluations per step, median of {steps - 1} steps, "
          f"{args.ranks} rank(s); wall-time derived (information only)"
          + (f'; amg with petsc "{args.petsc}"' if args.petsc else ""))
    for r in results:
        te, tn = r["t_eval"], r["t_nve"]
        print()
        m = r["matrix"].get("amg")
        print(f"beam {r['n']}x{r['n']}x{r['L']}" + (f": {m[0]}" if m else ""))
        print(f"  t_nve (fix nve step)                {tn * 1e3:9.2f} ms")
        print(f"  t_eval (block, per evaluation)      {te * 1e3:9.2f} ms = {te / tn:.2f} t_nve")
        print(f"  {'step time (s), median':<34}" + "".join(
            f"{f'{v} k={k}':>14}" for k in (k1, k2) for v in VARIANTS))
        print(f"  {'':<34}" + "".join(
            f"{r['runs'][k, v]['t']:>14.4f}" for k in (k1, k2) for v in VARIANTS))
        print(f"  {'applications per step (a)':<34}" + "".join(
            f"{r['runs'][k, v]['a']:>14.0f}" for k in (k1, k2) for v in VARIANTS))
        for v, what in (("amg", "amg (assembly + GAMG)"), ("none", "pc none (assembly only)")):
            f = r["fits"][v]
            print(f"  {what:<24} set-up per step S        {f['S']:8.3f} s  = "
                  f"{f['S'] / te:7.1f} t_eval = {f['S'] / tn:7.1f} t_nve")
            print(f"  {'':<24} one application, A       {f['A'] * 1e3:8.2f} ms = "
                  f"{f['A'] / te:7.2f} t_eval = {f['A'] / tn:7.2f} t_nve  (beyond a block one)")
            print(f"  {'':<24} first step of a run      {f['first']:8.3f} s  = "
                  f"{f['first'] / te:7.1f} t_eval  (extra)")
    if results:
        print()
        print("a fix sissm step of E evaluations and a applications with amg takes about "
              "E + S/t_eval + a A/t_eval evaluations' time")


if __name__ == "__main__":
    main()
