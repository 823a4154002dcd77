#!/usr/bin/env python3
"""How the work of a run splits over 2 ranks, counted in instructions (valgrind's callgrind),
which do not depend on what else the machine is doing.

    /usr/bin/python3 examples/benchmarks/speed/work_split.py [--quick] [--size 54k] [--steps 2]
        [--styles nosb jacobi block] [--ranks 2] [--top 5] [--lmp build/lmp]

Each configuration of bench_impact.py (same decks, same 54K geometry) runs once serially and
once on --ranks ranks under `valgrind --tool=callgrind`, counting only LAMMPS's run loop
(Verlet::run; the set-up is not counted). All runs go at once: counts do not depend on the
load. Instructions in the MPI libraries (Open MPI's progress engine spins while a rank waits,
so that count measures waiting, not work) are reported apart from the rest, the work: the
plugin, LAMMPS, and the C and math libraries, halo packing included. Printed per
configuration:

- serial work, each rank's work and MPI-library count, in 10^9 instructions;
- extra work, sum over the ranks / serial - 1 (halo packing, per-rank overheads);
- work balance, mean over the ranks / max, beside the atom balance (LAMMPS's Nlocal, ave / max,
  at the end of the run);
- work efficiency, serial / (ranks x max rank): the parallel efficiency the run would have if
  an instruction took the same time on every rank and in the serial run, and waiting and
  moving data were free;
- the --top functions whose count grew most from the serial run to the sum over the ranks.

--quick: the small size, peri/nosb + nve only (a smoke test; explicit options override).

bench_impact.py measures the time; the 2-rank efficiency it prints is the work efficiency
here times what the machine adds (its report of the time inside MPI calls and of the ranks'
own work against the serial run says which). About 6 minutes for the three configurations at
54K and 2 steps on 2 cores.
"""
from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import bench_impact as bi  # noqa: E402

# objects whose instructions are MPI's (its progress engine spins while a rank waits)
MPI_OBJECT = re.compile(r"openmpi|libopen-|libmpi|libpmix|libevent|libhwloc|libuc[pst]|"
                        r"libfabric|mca_")
# callgrind_annotate --inclusive=no: "5,342,284,344 (33.01%)  file:function [object]"
LINE = re.compile(r"^\s*([0-9,]+)\s+\([ 0-9.]+%\)\s+(.*?)(?:\s+\[(.*)\])?\s*$")
TOGGLE = "LAMMPS_NS::Verlet::run(int)"


def callgrind_command(out: Path) -> list:
    return ["valgrind", "--tool=callgrind", "--trace-children=yes", "--collect-atstart=no",
            f"--toggle-collect={TOGGLE}", f"--callgrind-out-file={out}"]


def functions(path: Path) -> dict:
    """{(function, object): instructions} of one callgrind file."""
    out = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100", str(path)],
                         capture_output=True, text=True, check=True).stdout
    counts, body = {}, False
    for line in out.splitlines():
        if "file:function" in line:
            body = True
            continue
        m = LINE.match(line) if body else None
        if m:
            key = (m.group(2), m.group(3) or "")
            counts[key] = counts.get(key, 0) + int(m.group(1).replace(",", ""))
    return counts


def processes(workdir: Path, ranks: int) -> list:
    """The counts of the LAMMPS processes of a run: the callgrind files with counts in the run
    loop (a launcher or the wrapper script before its exec counts none), one per rank."""
    found = [c for c in (functions(p) for p in sorted(workdir.glob("cg.*"))) if sum(c.values())]
    if len(found) != ranks:
        raise RuntimeError(f"{workdir}: {len(found)} counted processes, expected {ranks}")
    return found


def split(counts: dict) -> tuple:
    """(work, MPI-library instructions) of one process."""
    mpi = sum(v for (_, obj), v in counts.items() if MPI_OBJECT.search(obj))
    return sum(counts.values()) - mpi, mpi


def atom_balance(workdir: Path) -> float:
    """Owned atoms ave / max over the ranks (the log's Nlocal line at the end of the run)."""
    found = bi.NLOCAL.findall((workdir / "log.lammps").read_text(errors="replace"))
    ave, most = (float(v) for v in found[-1])
    return ave / most


def report(label: str, serial: dict, ranks: list, atoms: float, top: int) -> None:
    """Print one configuration's split (atoms: the atom balance)."""
    w1 = split(serial)[0]
    works, mpis = zip(*(split(c) for c in ranks))
    n = len(ranks)
    print(f"\n{label}: serial work {w1 / 1e9:.3f}; on {n} ranks work "
          + ", ".join(f"{w / 1e9:.3f}" for w in works) + " (MPI libraries "
          + ", ".join(f"{m / 1e9:.3f}" for m in mpis) + ") x 10^9 instructions")
    print(f"  extra work {100 * (sum(works) / w1 - 1):+.2f} %, work balance "
          f"{sum(works) / n / max(works):.4f} (atoms {atoms:.4f}), work efficiency "
          f"{w1 / (n * max(works)):.4f}")
    grown = {}
    for counts, sign in [(c, 1) for c in ranks] + [(serial, -1)]:
        for key, v in counts.items():
            if not MPI_OBJECT.search(key[1]):
                grown[key] = grown.get(key, 0) + sign * v
    for (fn, _), v in sorted(grown.items(), key=lambda kv: -kv[1])[:top]:
        if v > 0:
            print(f"  +{v / w1 * 100:6.2f} % of the serial work: {fn[:110]}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smoke test: small size, nosb only")
    ap.add_argument("--size", choices=list(bi.GEOMETRY), default=None)
    ap.add_argument("--steps", type=int, default=2)
    ap.add_argument("--styles", nargs="+", choices=list(bi.BY_KEY), default=None)
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--top", type=int, default=5, help="functions listed per configuration")
    ap.add_argument("--lmp", type=Path, default=bi.LMP)
    args = ap.parse_args()
    args.size = args.size or ("small" if args.quick else "54k")
    args.styles = args.styles or (["nosb"] if args.quick else ["nosb", "jacobi", "block"])
    if not shutil.which("valgrind") or not shutil.which("callgrind_annotate"):
        sys.exit("work_split.py: needs valgrind (Debian package valgrind)")
    configs = [bi.BY_KEY[k] for k in args.styles if not bi.BY_KEY[k].beside]
    start_info = bi.build_info()
    with tempfile.TemporaryDirectory(prefix="work_split-") as tmp:
        runs = {}
        for c in configs:
            for r in (1, args.ranks):
                d = Path(tmp) / f"{c.key}-{r}"
                # bench_impact's run, each rank's lmp under callgrind instead of /usr/bin/time
                runs[c.key, r] = (d, bi.start(c, args.size, r, args.steps, d, args.lmp, [],
                                              launcher=callgrind_command(d / "cg.%p")))
        failed = []
        for (key, r), (d, proc) in runs.items():
            _, err = proc.communicate()
            if proc.returncode != 0:
                failed.append(f"{key} on {r} rank(s): exit {proc.returncode}: "
                              + " | ".join(err.splitlines()[-3:]))
        if failed:
            sys.exit("work_split.py: failed runs:\n  " + "\n  ".join(failed))
        print(f"Work split over {args.ranks} ranks, in instructions counted by callgrind in "
              f"LAMMPS's run loop: impact deck, {args.size}, {args.steps} steps")
        bi.print_build(start_info)
        for c in configs:
            serial = processes(runs[c.key, 1][0], 1)[0]
            d = runs[c.key, args.ranks][0]
            report(c.label, serial, processes(d, args.ranks), atom_balance(d), args.top)


if __name__ == "__main__":
    main()
