#!/usr/bin/env python3
"""Krylov iterations per Newton step of fix sissm against the length of a clamped beam (issue 11).

    /usr/bin/python3 examples/benchmarks/solver/scaling.py [--quick] [--ranks N]
        [--sections 8 4] [--lengths 20 40 80 160] [--precond amg block] [--petsc "OPTIONS"]

Beams of square section n x n particles (n = 8, the section of examples/cantilever, and n = 4)
and free length L = 20, 40, 80, 160 particles; the material, lattice (a = 10 mm), horizon
(3.0002 a), neighbor skin and clamp (3 layers outside the integrated group) are those of
examples/cantilever/cantilever.geometry. Gravity is scaled so that every beam's Euler-Bernoulli
tip deflection is the cantilever's, 0.39 a (g = 9.81 (40/L)^4 (n/8)^2 m/s^2): all beams stay in
the same small-deflection regime (at g = 9.81 the 160-particle beam would sag by ~1.1 m and
its one-step solve would move atoms farther than short-range contact can follow). One static
backward-Euler step of dt = 100 s with `fix sissm iterations 5000 tolerance 1e-6 unconverged warn
precond amg|block`, the same options for both preconditioners (warn: a step that misses the
tolerance is reported, not cut back; the budget is large enough for block on the longest
beams). The PETSc options are the fix's defaults
unless --petsc adds some.

Printed per beam: force evaluations of the step (f_ID[1]), Newton steps (f_ID[8]), CG iterations
(f_ID[7]), CG iterations per Newton step, steps that missed the tolerance (f_ID[4], must be 0),
the convergence measure (f_ID[2]) with the step's attainable tolerance (the round-off floor fix
sissm warns about at this step size), the tip deflection and the loop time (information only);
then the ratio L = 160 / L = 20 of CG iterations per Newton step (goal of the issue: < 1.5) and
of force evaluations. The unconverged counter is printed with the steps redone with the other
preconditioner (f_ID[9], "unc/fb"). --petsc passes options to precond amg (to try PETSc
settings on the same beams). --quick: n = 8, L = 20 and 40.
"""
from __future__ import annotations

import argparse
import re
import tempfile
from pathlib import Path

from bench_common import LOOP, build_info, print_build  # noqa: E402
from lammps_run import run_deck  # noqa: E402
from progress import Progress  # noqa: E402


FLOOR = re.compile(r"limits the convergence measure to about ([0-9.eE+-]+)")

GEOMETRY = """\
# clamped beam, section {n} x {n}, free length {L} particles (examples/benchmarks/solver/scaling.py;
# n = 8, L = 40 is examples/cantilever/cantilever.geometry)
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
variable        a equal 0.01
variable        K equal 1.0e7
variable        nu equal 0.25
variable        G equal 3*v_K*(1-2*v_nu)/(2*(1+v_nu))
variable        rho equal 1000
variable        horizon equal 3.0002*v_a
neighbor        $(0.5*v_a) bin
lattice         sc ${{a}}
region          beam block -3.25 {xhi} -0.25 {yhi} -0.25 {yhi} units lattice
create_box      1 beam
create_atoms    1 region beam
set             group all density ${{rho}}
set             group all volume $(v_a^3)
region          clampzone block INF -0.5 INF INF INF INF units lattice
region          tipzone block {xtip} INF INF INF INF INF units lattice
group           clamp region clampzone
group           free subtract all clamp
group           tip region tipzone
fix             grav free gravity {g:.10g} vector 0 0 -1
compute         ztip tip reduce ave z
variable        defl equal c_ztip-{zmid}*v_a
pair_style      peri/nosb
pair_coeff      * * linear ${{K}} ${{G}} ${{horizon}} 0.5 0.0 break no
"""

STEP = """\
fix             integrate free sissm iterations {iters} tolerance 1e-6 unconverged warn &
                precond {precond}{petsc}
timestep        {dt}
thermo_style    custom step v_defl cpu f_integrate[1] f_integrate[2] f_integrate[4] &
                f_integrate[7] f_integrate[8] f_integrate[9]
thermo_modify   format float %.10g
thermo          1
run             1
"""


def geometry(n: int, L: int) -> str:
    """The clamped n x n x L beam with peri/nosb and gravity scaled to the cantilever's tip
    deflection (also used by setup_cost.py)."""
    g = 9.81 * (40.0 / L) ** 4 * (n / 8.0) ** 2
    return GEOMETRY.format(n=n, L=L, xhi=L - 0.75, yhi=n - 0.75, xtip=L - 1.5,
                           zmid=(n - 1) / 2, g=g)


def beam(n: int, L: int, precond: str, dt: float, iters: int, petsc: str = "") -> str:
    extra = f' petsc "{petsc}"' if petsc and precond == "amg" else ""
    return geometry(n, L) + STEP.format(precond=precond, dt=dt, iters=iters, petsc=extra)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--dt", type=float, default=100.0)
    ap.add_argument("--iterations", type=int, default=5000)
    ap.add_argument("--sections", type=int, nargs="+")
    ap.add_argument("--lengths", type=int, nargs="+")
    ap.add_argument("--precond", nargs="+", choices=["amg", "block"])
    ap.add_argument("--petsc", default="", help="PETSc options for precond amg (fix sissm's "
                    "petsc keyword), e.g. \"-pc_gamg_threshold 0.01\"")
    args = ap.parse_args()
    build_start = build_info()
    sections = args.sections or ([8] if args.quick else [8, 4])
    lengths = args.lengths or ([20, 40] if args.quick else [20, 40, 80, 160])
    preconds = args.precond or ["amg", "block"]
    cases = [(n, L, p) for n in sections for p in preconds for L in lengths]
    # weights for the time estimate: atoms x (a guess of) evaluations
    weight = {c: c[1] * c[0] ** 2 * (1 if c[2] == "amg" else c[1] / 8) for c in cases}
    progress = Progress(sum(weight.values()), "scaling")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n, L, p in cases:
            work = Path(tmp) / f"beam{n}x{L}-{p}"
            res = run_deck(beam(n, L, p, args.dt, args.iterations, args.petsc), work,
                           nprocs=args.ranks,
                           timeout=None, check=False)
            row = dict(n=n, L=L, p=p, ok=res.ok)
            if res.ok:
                t = res.thermo[-1]
                loop = LOOP.findall(res.log)[-1]
                floor = FLOOR.findall(res.log)
                row.update(atoms=int(loop[3]), loop=float(loop[0]),
                           evals=int(t["f_integrate[1]"][-1]),
                           measure=float(t["f_integrate[2]"][-1]),
                           unconverged=int(t["f_integrate[4]"][-1]),
                           fallback=int(t["f_integrate[9]"][-1]),
                           krylov=int(t["f_integrate[7]"][-1]), newton=int(t["f_integrate[8]"][-1]),
                           defl=float(t["v_defl"][-1]),
                           floor=float(floor[0]) if floor else 1e-6)
                row["per"] = row["krylov"] / row["newton"] if row["newton"] else float("nan")
            else:
                row["error"] = (res.errors or [res.describe()])[0]
            rows.append(row)
            progress.step(f"{n}x{n} L={L} {p}", weight=weight[(n, L, p)])
    progress.done()

    print_build(build_start)
    print(f"clamped beams, one static step dt = {args.dt:g} s, fix sissm iterations "
          f"{args.iterations} tolerance 1e-6 unconverged warn, {args.ranks} rank(s)"
          + (f', amg with petsc "{args.petsc}"' if args.petsc else ""))
    hdr = (f"{'section':>7} {'L':>4} {'atoms':>6} {'precond':>7} {'evals':>6} {'Newton':>6} "
           f"{'CG':>6} {'CG/Newton':>9} {'unc/fb':>6} {'measure':>9} {'attainable':>10} "
           f"{'tip defl (m)':>13} {'loop (s)':>9}")
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        head = f"{r['n']}x{r['n']:<5} {r['L']:>4}"
        if not r["ok"]:
            print(f"{head} {'':>6} {r['p']:>7}  FAILED: {r['error'][:120]}")
            continue
        unc = f"{r['unconverged']}/{r['fallback']}"
        print(f"{head} {r['atoms']:>6} {r['p']:>7} {r['evals']:>6} {r['newton']:>6} "
              f"{r['krylov']:>6} {r['per']:>9.1f} {unc:>6} "
              f"{r['measure']:>9.3g} "
              f"{r['floor']:>10.3g} {r['defl']:>13.6e} {r['loop']:>9.2f}")
    print()
    lo, hi = lengths[0], lengths[-1]
    print(f"ratios L = {hi} / L = {lo} (same section, same preconditioner), and block / amg at "
          f"L = {hi}")
    for n in sections:
        by = {(r["L"], r["p"]): r for r in rows if r["n"] == n and r["ok"]}
        for p in preconds:
            a, b = by.get((lo, p)), by.get((hi, p))
            if a and b:
                note = " (L = %d missed the tolerance)" % hi if b["unconverged"] else ""
                print(f"  {n}x{n} {p:>5}: CG/Newton {b['per'] / a['per']:.2f}, force evaluations "
                      f"{b['evals'] / a['evals']:.2f}{note}")
        a, b = by.get((hi, "amg")), by.get((hi, "block"))
        if a and b:
            bound = " (block did not converge: lower bounds)" if b["unconverged"] else ""
            print(f"  {n}x{n} block/amg at L = {hi}: force evaluations "
                  f"{b['evals'] / a['evals']:.1f}, "
                  f"loop time {b['loop'] / a['loop']:.1f}{bound}")


if __name__ == "__main__":
    main()
