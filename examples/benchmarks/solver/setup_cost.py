#!/usr/bin/env python3
"""Cost of fix sissm's AMG preconditioner (assembly + set-up, and one application), expressed in
force evaluations (issue 11).

    /usr/bin/python3 examples/benchmarks/solver/setup_cost.py [--quick] [--ranks N]

PETSc is never finalized (a plugin has no hook before MPI_Finalize), so -log_view prints
nothing, and the fix's output vector counts evaluations, not seconds. The costs are therefore
separated by wall time, with every step's work fixed in evaluations, in one LAMMPS process per
beam (so that machine speed cancels in the ratios):

  1. `run 1` at dt = 100 s with precond amg, tolerance 1e-6: the beam (scaling.py's clamped
     n x n x L beam; 8 x 8 x 40 is examples/cantilever) comes to rest.
  2. For k = K1 and K2 force evaluations per step and precond = block, amg: the fix is redefined
     as `fix sissm iterations k tolerance 0 unconverged warn precond P` (tolerance 0: every step
     uses exactly k evaluations, plus the regular one that ends it) and runs STEPS steps at
     dt = 100 s. Each amg step sets the preconditioner up once (assembly of the bond-projected
     stiffness and PCSetUp of PETSc's GAMG, at its first Newton step; later Newton steps reuse
     it), and applies it once per Newton step and once per CG iteration.
  3. `fix nve`, STEPS_NVE steps of 1e-9 s: the time of one explicit step (one force evaluation),
     t_nve.

Per-step wall times are the differences of the CPU thermo column (elapsed wall time); the first
step of each run is left out (it also builds the matrix's sparsity pattern), and it is reported
separately. Then, with t_eval = the block runs' time per evaluation (the slope between K1 and
K2; it includes the per-particle block pass that fix sissm adds to a plain force evaluation),
and a = Newton steps + CG iterations of the step (the applications; f_ID[8] + f_ID[7]):

    t_amg(step) - (k + 1) t_eval = S + A a        (least squares over the steps of both k)

S is the set-up (assembly + PCSetUp), A the extra time of one AMG application over a block
application. Both are printed in seconds, in t_eval and in t_nve. They are wall-time numbers on
a shared machine: information, not a measure (the evaluation counts are). --quick: the
cantilever only, fewer steps.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
sys.path.insert(0, str(REPO / "unittest" / "python"))
sys.path.insert(0, str(REPO / "tools"))
sys.path.insert(0, str(HERE))
from lammps_run import run_deck  # noqa: E402
from progress import Progress  # noqa: E402
from scaling import geometry  # noqa: E402

COLUMNS = "step cpu f_integrate[1] f_integrate[2] f_integrate[7] f_integrate[8]"


def deck(n: int, L: int, k1: int, k2: int, steps: int, steps_nve: int) -> str:
    text = geometry(n, L)
    text += f"""
timestep        100
fix             integrate free sissm iterations 5000 tolerance 1e-6 precond amg
thermo_style    custom {COLUMNS}
thermo_modify   format float %.10g
thermo          1
run             1
"""
    for k in (k1, k2):
        for p in ("block", "amg"):
            text += f"""
fix             integrate free sissm iterations {k} tolerance 0 unconverged warn precond {p}
run             {steps}
"""
    text += f"""
unfix           integrate
fix             integrate free nve
timestep        1.0e-9
thermo_style    custom step cpu
thermo          {steps_nve}
run             {steps_nve}
"""
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--k", type=int, nargs=2, default=[3, 43], metavar=("K1", "K2"))
    args = ap.parse_args()
    beams = [(8, 40)] if args.quick else [(8, 40), (8, 160)]
    steps = 6 if args.quick else 11
    steps_nve = 100
    k1, k2 = args.k
    progress = Progress(sum(L for _, L in beams), "setup_cost")
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for n, L in beams:
            res = run_deck(deck(n, L, k1, k2, steps, steps_nve), Path(tmp) / f"beam{n}x{L}",
                           nprocs=args.ranks, timeout=None, check=False)
            progress.step(f"{n}x{n}x{L}", weight=L)
            if not res.ok:
                print(f"{n}x{n}x{L}: FAILED\n{res.describe()}")
                continue
            tables = res.thermo      # [rest, k1 block, k1 amg, k2 block, k2 amg, nve]
            assert len(tables) == 6, len(tables)
            nve = tables[5]
            t_nve = (nve["CPU"][-1] - nve["CPU"][0]) / steps_nve
            runs = {}
            for idx, (k, p) in enumerate([(k1, "block"), (k1, "amg"), (k2, "block"), (k2, "amg")]):
                t = tables[1 + idx]
                dt_steps = np.diff(t["CPU"])
                evals = t["f_integrate[1]"][1:]
                assert np.all(evals == k), f"steps of {p} k={k} did not use k evaluations: {evals}"
                runs[k, p] = dict(first=dt_steps[0], times=dt_steps[1:],
                                  applies=(t["f_integrate[7]"] + t["f_integrate[8]"])[2:],
                                  newton=t["f_integrate[8]"][2:], cg=t["f_integrate[7]"][2:])
            tb1 = np.median(runs[k1, "block"]["times"])
            tb2 = np.median(runs[k2, "block"]["times"])
            t_eval = (tb2 - tb1) / (k2 - k1)
            # least squares: t_amg - (k + 1) t_eval = S + A a
            y, X = [], []
            for k in (k1, k2):
                r = runs[k, "amg"]
                y += list(r["times"] - (k + 1) * t_eval)
                X += [[1.0, a] for a in r["applies"]]
            (S, A), *_ = np.linalg.lstsq(np.array(X), np.array(y), rcond=None)
            first_extra = np.mean([runs[k, "amg"]["first"] - np.median(runs[k, "amg"]["times"])
                                   for k in (k1, k2)])
            results.append(dict(n=n, L=L, t_nve=t_nve, t_eval=t_eval,
                                tb=(tb1, tb2), ta=(np.median(runs[k1, "amg"]["times"]),
                                                  np.median(runs[k2, "amg"]["times"])),
                                applies=(np.mean(runs[k1, "amg"]["applies"]),
                                         np.mean(runs[k2, "amg"]["applies"])),
                                newton=(np.mean(runs[k1, "amg"]["newton"]),
                                        np.mean(runs[k2, "amg"]["newton"])),
                                S=S, A=A, first=first_extra,
                                matrix=[ln for ln in res.log.splitlines()
                                        if "precond amg:" in ln][:1]))
    progress.done()

    print(f"cost of fix sissm precond amg in force evaluations; k = {k1} and {k2} evaluations "
          f"per step, {steps - 1} timed steps each, {args.ranks} rank(s); wall-time derived "
          "(information only)")
    for r in results:
        print()
        print(f"beam {r['n']}x{r['n']}x{r['L']}: " + (r["matrix"][0].split(": ", 1)[1]
                                                       if r["matrix"] else ""))
        print(f"  t_nve (fix nve step)             {r['t_nve'] * 1e3:9.2f} ms")
        print(f"  t_eval (block, per evaluation)   {r['t_eval'] * 1e3:9.2f} ms "
              f"= {r['t_eval'] / r['t_nve']:.2f} t_nve")
        for i, k in enumerate((k1, k2)):
            print(f"  step of k = {k:>3}: block {r['tb'][i]:7.3f} s, amg {r['ta'][i]:7.3f} s "
                  f"(amg: {r['newton'][i]:.1f} Newton steps, {r['applies'][i]:.1f} applications)")
        print(f"  set-up S (assembly + PCSetUp)    {r['S']:9.3f} s "
              f"= {r['S'] / r['t_eval']:7.1f} t_eval = {r['S'] / r['t_nve']:7.1f} t_nve")
        print(f"  one AMG application, extra A     {r['A'] * 1e3:9.2f} ms "
              f"= {r['A'] / r['t_eval']:7.2f} t_eval = {r['A'] / r['t_nve']:7.2f} t_nve")
        print(f"  first step of a run, extra       {r['first']:9.3f} s "
              f"= {r['first'] / r['t_eval']:7.1f} t_eval (sparsity pattern, symbolic set-up)")
    if results:
        print()
        print("a step of E evaluations and a applications with amg costs about "
              "E + S/t_eval + a (1 + A/t_eval) evaluations' time")


if __name__ == "__main__":
    main()
