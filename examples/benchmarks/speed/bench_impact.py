#!/usr/bin/env python3
"""Speed of peridynamic styles on the projectile-impact deck (examples/impact).

Runs each deck with build/lmp, serial and on 2 MPI ranks, and prints the cost in microseconds
per particle-step (LAMMPS's "Loop time" divided by steps x particles) and the ratio to peri/lps
measured in the same invocation, so machine speed cancels out.

peri/nosb+sissm is the nosb deck integrated by fix sissm with exactly 5 iterations per step
(in.impact.sissm: plain SISSM sweeps, solver jacobi); peri/nosb+krylov the same with solver
krylov (1 Newton residual + 4 conjugate-gradient products per step). Their rows are per step
(5 iterations + the regular force evaluation). A separate line gives the cost of ONE
iteration relative to one peri/nosb explicit step:
(time per SISSM step / iterations per step) / (time per peri/nosb step), at each rank count
(goal of issue 4: at most 1.5).

    /usr/bin/python3 examples/benchmarks/speed/bench_impact.py [--steps 1000] [--ranks 1 2]
"""
import argparse
import re
import shutil
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "unittest" / "python"))
sys.path.insert(0, str(REPO / "tools"))
from lammps_run import run_deck  # noqa: E402
from progress import Progress  # noqa: E402

IMPACT = REPO / "examples" / "impact"
# column name -> deck; later styles add their decks here
STYLES = {"peri/pmb": "in.impact.pmb", "peri/lps": "in.impact.lps", "peri/nosb": "in.impact.nosb",
          "peri/nosb+sissm": "in.impact.sissm", "peri/nosb+krylov": "in.impact.sissm"}
EXTRA = {"peri/nosb+krylov": {"opts": "solver krylov"}}
SISSM = ("peri/nosb+sissm", "peri/nosb+krylov")
LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")


def measure(deck: str, ranks: int, steps: int, workdir: Path, extra=None) -> tuple:
    """Microseconds per particle-step of one run, and fix sissm's mean iterations per step
    (f_integrate[3] in the last thermo line; None for decks without fix sissm)."""
    shutil.copy(IMPACT / "impact.geometry", workdir)
    run = run_deck(IMPACT / deck, workdir, nprocs=ranks,
                   variables={"nsteps": steps, "thermo_every": steps, **(extra or {})})
    seconds, procs, nsteps, atoms = LOOP.findall(run.log)[-1]
    assert int(procs) == ranks
    table = run.thermo[-1]
    iterations = float(table["f_integrate[3]"][-1]) if "f_integrate[3]" in table else None
    return float(seconds) / (int(nsteps) * int(atoms)) * 1e6, iterations


def cost(deck: str, ranks: int, steps: int, workdir: Path) -> float:
    """Microseconds per particle-step of one run."""
    return measure(deck, ranks, steps, workdir)[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--styles", nargs="+", default=list(STYLES), choices=list(STYLES))
    args = parser.parse_args()

    results, iterations = {}, {}
    progress = Progress(len(args.ranks) * len(args.styles), "bench_impact")
    with tempfile.TemporaryDirectory() as tmp:
        for ranks in args.ranks:
            for style in args.styles:
                work = Path(tmp) / f"{style.replace('/', '_').replace('+', '_')}-{ranks}"
                work.mkdir()
                results[style, ranks], iterations[style, ranks] = measure(
                    STYLES[style], ranks, args.steps, work, EXTRA.get(style))
                progress.step(f"{style} on {ranks} rank(s)")

    print(f"impact deck, {args.steps} steps: microseconds per particle-step "
          "(ratio to peri/lps at the same rank count)")
    print(f"{'style':<16}" + "".join(f"{f'{r} rank(s)':>24}" for r in args.ranks))
    for style in args.styles:
        cells = []
        for r in args.ranks:
            us = results[style, r]
            ref = results.get(("peri/lps", r))
            cells.append(f"{us:10.3f} us" + (f" ({us / ref:5.2f}x)" if ref else ""))
        print(f"{style:<16}" + "".join(f"{c:>24}" for c in cells))

    solvers = [s for s in SISSM if s in args.styles]
    if solvers and "peri/nosb" in args.styles:
        print("\nfix sissm: one iteration per particle relative to one peri/nosb explicit step "
              "((time per step / iterations per step) / peri/nosb time per step; goal <= 1.5)")
        for style in solvers:
            cells = []
            for r in args.ranks:
                per_iteration = results[style, r] / iterations[style, r]
                cells.append(f"{per_iteration / results['peri/nosb', r]:10.2f}x")
            print(f"{style:<16}" + "".join(f"{c:>24}" for c in cells))


if __name__ == "__main__":
    main()
