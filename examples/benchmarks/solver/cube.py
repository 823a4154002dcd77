#!/usr/bin/env python3
"""A cube of ~10^5 particles under gravity at 100 x the explicit step with fix sissm on 1 and 2
MPI ranks: evaluations per step and parallel efficiency (issue 11).

    /usr/bin/python3 examples/benchmarks/solver/cube.py [--quick] [--sizes 30 46] [--steps 3]
                                                        [--precond amg block] [--ranks 1 2]
                                                        [--petsc "OPTIONS"]

Scene: N^3 particles on a simple cubic lattice (a = 10 mm), pair_style peri/nosb linear with the
soft solid of examples/cantilever (K = 10 MPa, G = 6 MPa, rho = 1000 kg/m^3; bonds unbreakable),
horizon 3.0015 a; the bottom three layers (one horizon) are clamped (outside the integrated
group), gravity acts on the rest. (A steel-like cube would sag under gravity by ~1e-6 particle
sizes, the solver's tolerance: its steps would converge at the first residual and measure
nothing. The soft solid sags by ~1e-3 a, and the step of 100 x the explicit limit is about two
wave crossings of the cube.) The explicit step is the estimate of compute nosb/atom column 11
(smallest over the atoms, `run 0`); dt = 100 x that. Then STEPS steps of `fix sissm precond
amg|block iterations 1000 tolerance 1e-6 unconverged cutback` (every option given, so that the
numbers do not follow the fix's defaults; a budget large enough for both preconditioners to
converge a step without cutting it back), thermo every step, and 5 steps of fix nve at the
explicit step on the same cube (t_nve: the time of one plain force evaluation). Each size runs
with each preconditioner on 1 and 2 ranks (a build that refuses precond amg on 2 ranks gets its
error printed in the table).

Printed per run: the explicit estimate and dt, force evaluations per step (f_ID[1]; the regular
evaluation that ends each step is not included), Newton steps and CG iterations per step
(f_ID[8], f_ID[7]), CG per Newton step, unconverged steps / steps cut back / steps redone with
the other preconditioner (f_ID[4], [6], [9]), the set-ups of the AMG hierarchy in the run (all,
and those with a new sparsity pattern: fix sissm's end-of-run line), fix sissm's loop time, the
time its evaluations alone would take (evaluations x t_nve: the rest is the preconditioner's
assembly, set-up and applications), and the peak resident memory per rank (/usr/bin/time). Parallel efficiency
t1 / (2 t2) of the loop time, and of fix nve for comparison, with LAMMPS's "CPU use" of each
loop (CPU time / wall time, mean over the ranks): below 100% the machine's other jobs took the
cores, and the efficiency says more about them than about the code. Wall times are information
only (shared machine). --quick: N = 20.
"""
from __future__ import annotations

import argparse
import re
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from bench_common import LOOP, build_info, print_build  # noqa: E402
from lammps_run import LMP, mpirun_prefix, parse_thermo  # noqa: E402
from progress import Progress  # noqa: E402


RSS = re.compile(r"PEAKRSS (\d+)")
# LAMMPS after each run: "99.1% CPU use with 2 MPI tasks x 1 OpenMP threads" (CPU time over wall
# time of the loop, averaged over the ranks)
CPU = re.compile(r"([0-9.]+)% CPU use with")
# fix sissm at the end of a run: "... ; K set-up(s) of the AMG hierarchy (P with a new sparsity
# pattern)"
SETUPS = re.compile(r"(\d+) set-ups? of the AMG hierarchy \((\d+) with a new sparsity pattern\)")

DECK = """\
# clamped cube of {N}^3 particles under gravity (examples/benchmarks/solver/cube.py)
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
variable        a equal 0.01
variable        K equal 1.0e7
variable        G equal 6.0e6
variable        rho equal 1000
variable        horizon equal 3.0015*v_a
neighbor        $(0.5*v_a) bin
lattice         sc ${{a}}
region          cube block -0.25 {hi} -0.25 {hi} -0.25 {hi} units lattice
create_box      1 cube
create_atoms    1 region cube
set             group all density ${{rho}}
set             group all volume $(v_a^3)
region          clampzone block INF INF INF INF INF 2.5 units lattice
group           clamp region clampzone
group           free subtract all clamp
fix             grav free gravity 9.81 vector 0 0 -1
pair_style      peri/nosb
pair_coeff      * * linear ${{K}} ${{G}} ${{horizon}} 0.5 0.0 break no
compute         top free reduce ave z
variable        sag equal c_top-{zmid}*v_a

compute         nosb all nosb/atom
compute         dtmin all reduce min c_nosb[11]
thermo_style    custom step c_dtmin
thermo_modify   format float %.10g
run             0
variable        dtexp equal $(c_dtmin:%.10g)
print           "EXPLICIT_STEP ${{dtexp}}"
uncompute       dtmin
uncompute       nosb

fix             integrate free sissm {opts} {common}
timestep        $(100*v_dtexp)
thermo_style    custom step time v_sag cpu f_integrate[1] f_integrate[2] f_integrate[4] &
                f_integrate[5] f_integrate[6] f_integrate[7] f_integrate[8] f_integrate[9]
thermo          1
run             {steps}

unfix           integrate
fix             integrate free nve
timestep        ${{dtexp}}
thermo_style    custom step cpu
thermo          5
run             5
"""


VARIANTS = {"amg": "precond amg", "block": "precond block"}


COMMON = "iterations 1000 tolerance 1e-6 unconverged cutback"


def run(N: int, ranks: int, variant: str, steps: int, workdir: Path, petsc: str = "") -> dict:
    workdir.mkdir(parents=True, exist_ok=True)
    deck = workdir / "in.cube"
    deck.write_text(DECK.format(N=N, hi=N - 0.75, zmid=(N + 2) / 2, steps=steps,
                                opts=VARIANTS[variant] + (f' petsc "{petsc}"' if petsc and
                                                          variant == "amg" else ""),
                                common=COMMON))
    log = workdir / "log.lammps"
    rssfile = workdir / "rss.txt"          # one line per rank, appended by /usr/bin/time
    cmd = mpirun_prefix(ranks) + ["/usr/bin/time", "-a", "-o", str(rssfile), "-f", "PEAKRSS %M",
                                  str(LMP), "-in",
                                  str(deck), "-log", str(log), "-echo", "log", "-nocite"]
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL)
    text = log.read_text(errors="replace") if log.exists() else ""
    out = dict(N=N, ranks=ranks, variant=variant,
               ok=proc.returncode == 0 and "ERROR" not in text,
               rss=[int(v) for v in RSS.findall(rssfile.read_text() if rssfile.exists() else "")])
    if not out["ok"]:
        errors = [ln for ln in (text + proc.stdout).splitlines() if ln.startswith("ERROR")]
        out["error"] = errors[0] if errors else "\n".join(
            (proc.stdout + proc.stderr).splitlines()[-15:])
        return out
    tables = parse_thermo(text)          # run 0, fix sissm, fix nve
    loops = LOOP.findall(text)
    cpu = [float(m[1]) / 100 if (m := CPU.search(chunk)) else float("nan")
           for chunk in text.split("Loop time of ")[1:]]
    t = tables[1]
    out.update(
        atoms=int(loops[1][3]), dtexp=float(re.search(r"EXPLICIT_STEP ([0-9.eE+-]+)", text)[1]),
        loop=float(loops[1][0]), t_nve=float(loops[2][0]) / int(loops[2][2]),
        cpu=cpu[1], cpu_nve=cpu[2],
        summary=[ln.split(" run: ", 1)[1] for ln in text.splitlines()
                 if ln.startswith("Fix sissm integrate run: ")][:1],
        evals=t["f_integrate[1]"][1:].astype(int), measure=t["f_integrate[2]"][1:],
        krylov=t["f_integrate[7]"][1:].astype(int), newton=t["f_integrate[8]"][1:].astype(int),
        unconverged=int(t["f_integrate[4]"][-1]), cutback=int(t["f_integrate[6]"][-1]),
        fallback=int(t["f_integrate[9]"][-1]),
        substeps=t["f_integrate[5]"][1:].astype(int), sag=t["v_sag"][1:],
        step_times=np.diff(t["CPU"]),
        amg=[ln.split(": ", 1)[1] for ln in text.splitlines() if "precond amg:" in ln][:1],
        warnings=[ln for ln in text.splitlines() if ln.startswith("WARNING") and
                  ("sissm" in ln or "PETSc" in ln)],
        petsc=[ln for ln in (proc.stdout + proc.stderr).splitlines()
               if "PETSC" in ln.upper() and "precond amg:" not in ln])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--sizes", type=int, nargs="+")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--precond", nargs="+", default=list(VARIANTS), choices=list(VARIANTS))
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--petsc", default="", help="PETSc options for precond amg")
    args = ap.parse_args()
    build_start = build_info()
    sizes = args.sizes or ([20] if args.quick else [30, 46])
    cases = [(N, v, r) for N in sizes for v in args.precond for r in args.ranks]
    progress = Progress(sum(N ** 3 / r for N, v, r in cases), "cube")
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for N, v, r in cases:
            results.append(run(N, r, v, args.steps, Path(tmp) / f"cube{N}-{v}-{r}", args.petsc))
            progress.step(f"{N}^3 {v} on {r} rank(s)", weight=N ** 3 / r)
    progress.done()

    print_build(build_start)
    print(f"clamped soft cube under gravity, fix sissm precond amg|block {COMMON}, "
          f"dt = 100 x the explicit estimate, {args.steps} steps"
          + (f', amg with petsc "{args.petsc}"' if args.petsc else ""))
    hdr = (f"{'N^3':>6} {'atoms':>7} {'precond':>7} {'ranks':>5} {'dt (s)':>10} "
           f"{'evals/step':>16} {'Newton/step':>12} {'CG/step':>14} {'CG/Newton':>9} "
           f"{'unc/cut/fb':>10} {'set-ups':>7} {'loop (s)':>9} {'evals x t_nve':>13} "
           f"{'peak RSS/rank (GB)':>18}")
    print(hdr)
    print("-" * len(hdr))
    for r in results:
        if not r["ok"]:
            print(f"{r['N']:>4}^3 {'':>7} {r['variant']:>7} {r['ranks']:>5}  FAILED (peak RSS "
                  f"{max(r['rss'], default=0) / 1e6:.2f} GB): {r['error']}")
            continue
        ev = "/".join(str(v) for v in r["evals"])
        nw = "/".join(str(v) for v in r["newton"])
        cg = "/".join(str(v) for v in r["krylov"])
        per = r["krylov"].sum() / max(r["newton"].sum(), 1)
        rss = "/".join(f"{v / 1e6:.2f}" for v in sorted(r["rss"], reverse=True))
        unc = f"{r['unconverged']}/{r['cutback']}/{r['fallback']}"
        m = SETUPS.search(r["summary"][0]) if r["summary"] else None
        setups = f"{m[1]}/{m[2]}" if m else "-"
        print(f"{r['N']:>4}^3 {r['atoms']:>7} {r['variant']:>7} {r['ranks']:>5} "
              f"{100 * r['dtexp']:>10.4g} {ev:>16} {nw:>12} {cg:>14} {per:>9.1f} {unc:>10} "
              f"{setups:>7} {r['loop']:>9.2f} {r['evals'].sum() * r['t_nve']:>13.2f} {rss:>18}")
    print("unc/cut/fb: steps that missed the tolerance / steps cut back / steps redone with the "
          "other preconditioner (f_ID[4], [6], [9]); set-ups: of the AMG hierarchy in the run / "
          "of them with a new sparsity pattern (fix sissm's end-of-run line); evals x t_nve: the "
          "loop time the force evaluations alone would take")
    print()
    for N in sizes:
        for v in args.precond:
            by = {r["ranks"]: r for r in results if r["N"] == N and r["variant"] == v and r["ok"]}
            if 1 in by and 2 in by:
                a, b = by[1], by[2]
                dsag = np.max(np.abs(a["sag"] - b["sag"]))
                print(f"{N}^3 {v}: parallel efficiency t1/(2 t2) {a['loop'] / (2 * b['loop']):.2f} "
                      f"(fix sissm loop time; fix nve {a['t_nve'] / (2 * b['t_nve']):.2f}); "
                      f"CPU use 1 rank {a['cpu']:.0%}, 2 ranks {b['cpu']:.0%}; "
                      f"evaluations 1 rank {a['evals'].sum()}, 2 ranks {b['evals'].sum()}; "
                      f"largest difference of the mean sag, 1 vs 2 ranks {dsag:.2e} m")
    for r in results:
        if r["ok"]:
            print(f"{r['N']}^3 {r['variant']} on {r['ranks']}: explicit estimate "
                  f"{r['dtexp']:.4g} s, "
                  f"t_nve {r['t_nve'] * 1e3:.1f} ms, CPU use {r['cpu']:.0%} (fix nve "
                  f"{r['cpu_nve']:.0%}), step times "
                  + ", ".join(f"{s:.1f}" for s in r["step_times"]) + " s, measures "
                  + ", ".join(f"{m:.2g}" for m in r["measure"]) + ", mean sag "
                  + ", ".join(f"{m:.4e}" for m in r["sag"]) + " m"
                  + (f"; {r['amg'][0]}" if r["amg"] else ""))
            for w in r["warnings"] + r["petsc"]:
                print(f"    {w[:240]}")


if __name__ == "__main__":
    main()
