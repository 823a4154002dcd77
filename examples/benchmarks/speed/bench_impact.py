#!/usr/bin/env python3
"""Speed of peridynamic styles on the projectile-impact deck (examples/impact).

Runs each deck with build/lmp, serial and on 2 MPI ranks, and prints the cost in microseconds
per particle-step (LAMMPS's "Loop time" divided by steps x particles) and the ratio to peri/lps
measured in the same invocation, so machine speed cancels out.

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
from lammps_run import run_deck  # noqa: E402

IMPACT = REPO / "examples" / "impact"
# column name -> deck; later styles add their decks here
STYLES = {"peri/pmb": "in.impact.pmb", "peri/lps": "in.impact.lps", "peri/nosb": "in.impact.nosb"}
LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")


def cost(deck: str, ranks: int, steps: int, workdir: Path) -> float:
    """Microseconds per particle-step of one run."""
    shutil.copy(IMPACT / "impact.geometry", workdir)
    run = run_deck(IMPACT / deck, workdir, nprocs=ranks,
                   variables={"nsteps": steps, "thermo_every": steps})
    seconds, procs, nsteps, atoms = LOOP.findall(run.log)[-1]
    assert int(procs) == ranks
    return float(seconds) / (int(nsteps) * int(atoms)) * 1e6


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--styles", nargs="+", default=list(STYLES), choices=list(STYLES))
    args = parser.parse_args()

    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for ranks in args.ranks:
            for style in args.styles:
                work = Path(tmp) / f"{style.replace('/', '_')}-{ranks}"
                work.mkdir()
                results[style, ranks] = cost(STYLES[style], ranks, args.steps, work)

    print(f"impact deck, {args.steps} steps: microseconds per particle-step "
          "(ratio to peri/lps at the same rank count)")
    print(f"{'style':<12}" + "".join(f"{f'{r} rank(s)':>24}" for r in args.ranks))
    for style in args.styles:
        cells = []
        for r in args.ranks:
            us = results[style, r]
            ref = results.get(("peri/lps", r))
            cells.append(f"{us:10.3f} us" + (f" ({us / ref:5.2f}x)" if ref else ""))
        print(f"{style:<12}" + "".join(f"{c:>24}" for c in cells))


if __name__ == "__main__":
    main()
