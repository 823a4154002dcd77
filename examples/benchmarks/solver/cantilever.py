#!/usr/bin/env python3
"""Cost of bringing examples/cantilever to rest within 1e-4 of its static deflection (issue 11).

    /usr/bin/python3 examples/benchmarks/solver/cantilever.py [--quick] [--ranks N]

Runs, in one invocation and one temporary folder (the decks are those of examples/cantilever,
copied with cantilever.geometry; except in the rows "defaults" and "deck" the fix sissm line gets
`precond ${precond} unconverged ${unconv}`):

  reference   fix sissm precond amg, tolerance 1e-8, 5000 iterations, dt = 1000 s, 2 steps: the
              static deflection of the peri/nosb beam (cross-checked against the last row of
              examples/cantilever/log.29Nov26.cantilever.nosb.g++.1, damped fix nve, 4000 steps)
  defaults    fix sissm iterations 100 tolerance 1e-6 and no other keyword: what a user gets
              (the fix's defaults: precond amg, unconverged cutback 4), dt = 100 s, 3 steps (the
              first brings the beam to rest; the others show it stays)
  amg         fix sissm precond amg, tolerance 1e-6, 5000 iterations (a budget large enough for
              block too; the deck's default is 100), unconverged cutback (every option given: the
              numbers do not follow the fix's defaults), dt = 100 s, 3 steps
  block       the same with precond block
  block/100   precond block with the fix's default budget, iterations 100, unconverged cutback
  deck        examples/cantilever/in.cantilever.sissm as it is (fix sissm defaults, tolerance
              1e-4, dt = 0.73 s = 10^4 x the explicit limit, 10 steps): the example's own step,
              where backward Euler takes several steps to remove the motion
  nosb 0.9c   peri/nosb + fix nve + fix viscous 1.02e5 (0.9 x critical, the deck's tuned value),
              dt 6e-5 s, 6000 steps, thermo every 10
  nosb 1.0c   the same at critical damping, fix viscous 1.13e5 (2 rho omega1)
  lps 0.9c    built-in peri/lps + fix nve + fix viscous 1.103e5 (the deck's), dt 1e-4 s, 6000
              steps; peri/lps is another discretization and rests elsewhere (3.87 mm against
              4.55 mm): it is measured against its own final deflection

"At rest within 1e-4": the first thermo row after which |defl - ref| / |ref| < 1e-4 holds in every
row to the end of the run. Force evaluations to rest: one per step for fix nve (the thermo row's
step); for fix sissm the sum of f_integrate[1] + 1 (the regular evaluation that ends the step)
over the steps up to that row. The evaluation of the run's set-up is counted for nobody. Wall
time to rest: LAMMPS's CPU thermo column (elapsed wall time of the run) at that row; on a
shared machine it is information only, the evaluations are the measure. --quick: 4000 explicit
steps (enough for both explicit methods to rest), no block/100 and deck rows. For every fix
sissm run the fix's end-of-run line is printed (unconverged steps, cut-backs, preconditioner
switches, set-ups of the AMG hierarchy).
"""
from __future__ import annotations

import argparse
import re
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench_common import LOOP, REPO, build_info, print_build  # noqa: E402
from lammps_run import parse_thermo, run_deck  # noqa: E402
from progress import Progress  # noqa: E402


CANTILEVER = REPO / "examples" / "cantilever"
EXPLICIT_LOG = CANTILEVER / "log.29Nov26.cantilever.nosb.g++.1"
REST = 1.0e-4


def sissm_deck(options: bool = True) -> str:
    """in.cantilever.sissm with all nine fix outputs in thermo; options: the fix sissm line also
    gets `precond ${precond} unconverged ${unconv}` (without: the fix's defaults)."""
    text = (CANTILEVER / "in.cantilever.sissm").read_text()
    old = "fix             integrate free sissm iterations ${iters} tolerance ${tol}"
    assert text.count(old) == 1, "the fix sissm line of in.cantilever.sissm changed"
    if options:
        text = text.replace(old, old + " precond ${precond} unconverged ${unconv}")
    cols = "f_integrate[3] f_integrate[4]"
    assert text.count(cols) == 1, "the thermo_style line of in.cantilever.sissm changed"
    return text.replace(cols, cols + " f_integrate[5] f_integrate[6] f_integrate[7] "
                        "f_integrate[8] f_integrate[9]")


def run(name: str, deck: str, workdir: Path, ranks: int, variables: dict):
    work = workdir / name.replace("/", "_").replace(" ", "_")
    files = {"cantilever.geometry": (CANTILEVER / "cantilever.geometry").read_text()}
    result = run_deck(deck, work, nprocs=ranks, variables=variables, files=files, timeout=None,
                      check=False)
    return result


def rest_index(defl: np.ndarray, ref: float) -> int | None:
    """First row after which |defl - ref|/|ref| < REST holds to the end (None: never)."""
    ok = np.abs(defl - ref) / abs(ref) < REST
    if not ok[-1]:
        return None
    bad = np.nonzero(~ok)[0]
    return int(bad[-1] + 1) if len(bad) else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--ranks", type=int, default=1)
    args = ap.parse_args()
    build_start = build_info()
    nexplicit = 4000 if args.quick else 6000

    sissm = sissm_deck()
    plain = sissm_deck(options=False)
    nosb = (CANTILEVER / "in.cantilever.nosb").read_text()
    lps = (CANTILEVER / "in.cantilever.lps").read_text()
    # name, deck, variables, kind
    cases = [
        ("reference", sissm, dict(dt=1000, nsteps=2, tol=1e-8, iters=5000, precond="amg",
                                  unconv="cutback"), "sissm"),
        ("defaults", plain, dict(dt=100, nsteps=3, tol=1e-6, iters=100), "sissm"),
        ("amg", sissm, dict(dt=100, nsteps=3, tol=1e-6, iters=5000, precond="amg",
                            unconv="cutback"), "sissm"),
        ("block", sissm, dict(dt=100, nsteps=3, tol=1e-6, iters=5000, precond="block",
                              unconv="cutback"), "sissm"),
    ]
    if not args.quick:
        cases.append(("block/100", sissm, dict(dt=100, nsteps=3, tol=1e-6, iters=100,
                                               precond="block", unconv="cutback"), "sissm"))
        cases.append(("deck", plain, dict(dt=0.73, nsteps=10, tol=1e-4, iters=100), "sissm"))
    cases += [
        ("nosb 0.9c", nosb, dict(nsteps=nexplicit, thermo_every=10, gamma=1.02e5), "nosb"),
        ("nosb 1.0c", nosb, dict(nsteps=nexplicit, thermo_every=10, gamma=1.13e5), "nosb"),
        ("lps 0.9c", lps, dict(nsteps=nexplicit, thermo_every=10, gamma=1.103e5), "lps"),
    ]
    progress = Progress(len(cases), "cantilever")
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, deck, variables, kind in cases:
            res = run(name, deck, Path(tmp), args.ranks, variables)
            out[name] = (res, kind, variables)
            progress.step(name)
    progress.done()

    # the reference: the last row of the reference run
    ref_run = out["reference"][0]
    if not ref_run.ok:
        sys.exit("the reference run failed:\n" + ref_run.describe())
    reft = ref_run.thermo[-1]
    ref = float(reft["v_defl"][-1])
    explicit_log = float(parse_thermo(EXPLICIT_LOG.read_text())[-1]["v_defl"][-1])
    print_build(build_start)
    print(f"examples/cantilever (40 x 8 x 8 free particles, 2752 atoms), {args.ranks} rank(s)")
    print(f"reference static deflection: {ref:.10g} m (fix sissm precond amg, tolerance 1e-8, "
          f"dt 1000 s, 2 steps; step deflections "
          + ", ".join(f"{d:.10g}" for d in reft["v_defl"][1:])
          + "; evaluations " + ", ".join(f"{int(e)}" for e in reft["f_integrate[1]"][1:])
          + "; convergence measures " + ", ".join(f"{m:.3g}" for m in reft["f_integrate[2]"][1:])
          + f"; unconverged steps {int(reft['f_integrate[4]'][-1])})")
    roundoff = [w for w in ref_run.warnings if "round-off" in w]
    if roundoff:
        floor = re.search(r"limits the convergence measure to about ([0-9.eE+-]+)", roundoff[0])
        print(f"  (fix sissm: round-off in the coordinates limits the measure to about "
              f"{floor.group(1) if floor else '?'} at dt 1000 s: that, not 1e-8, was the step's "
              f"tolerance)")
    print(f"explicit cross-check: last row of {EXPLICIT_LOG.name} (damped fix nve, 4000 steps, "
          f"still creeping): {explicit_log:.10g} m, relative difference "
          f"{(explicit_log - ref) / abs(ref):+.2e}")
    print()

    rows = []
    for name, (res, kind, variables) in out.items():
        if name == "reference":
            continue
        row = dict(name=name, kind=kind, ok=res.ok, note="")
        if not res.ok:
            err = (res.errors or ["(no ERROR line)"])[0]
            row["note"] = err
            rows.append(row)
            continue
        t = res.thermo[-1]
        defl = t["v_defl"]
        target = ref if kind != "lps" else float(defl[-1])
        k = rest_index(defl, target)
        row["final"] = float(defl[-1])
        row["final_vs_ref"] = (float(defl[-1]) - ref) / abs(ref)
        row["target"] = "own final" if kind == "lps" else "reference"
        loop = LOOP.findall(res.log)
        row["loop"] = float(loop[-1][0]) if loop else float("nan")
        if kind == "sissm":
            evals = t["f_integrate[1]"] + 1.0
            evals[0] = 0.0                       # step 0: the set-up evaluation, not counted
            row["steps"] = [int(e) for e in t["f_integrate[1]"][1:]]
            row["newton"] = [int(e) for e in t["f_integrate[8]"][1:]]
            row["krylov"] = [int(e) for e in t["f_integrate[7]"][1:]]
            row["unconverged"] = int(t["f_integrate[4]"][-1])
            row["cutback"] = int(t["f_integrate[6]"][-1])
            row["fallback"] = int(t["f_integrate[9]"][-1])
            row["warnings"] = len(res.warnings)
            row["summary"] = [ln.split(" run: ", 1)[1] for ln in res.log.splitlines()
                              if ln.startswith("Fix sissm ") and " run: " in ln]
        else:
            evals = t["Step"].copy()
        if k is None:
            row["note"] = "not at rest at the end of the run"
            row["evals"] = row["wall"] = float("nan")
            row["rest_step"] = None
        else:
            row["rest_step"] = int(t["Step"][k])
            row["evals"] = float(np.sum(evals[:k + 1])) if kind == "sissm" else float(evals[k])
            row["wall"] = float(t["CPU"][k])
            row["sim"] = float(t["Time"][k])
        rows.append(row)

    base = next(r for r in rows if r["name"] == "amg")
    print(f"to rest within {REST:g} (relative) of the static deflection; ratios to amg "
          "measured in this run")
    hdr = (f"{'method':<11} {'dt (s)':>8} {'rest at step':>12} {'evaluations':>11} "
           f"{'x amg':>7} {'wall to rest (s)':>16} {'x amg':>7} {'loop (s)':>9} "
           f"{'final defl (m)':>15} {'final vs ref':>12}")
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        dt = out[r["name"]][2].get("dt", {"nosb": 6e-5, "lps": 1e-4}.get(r["kind"]))
        if not r["ok"]:
            print(f"{r['name']:<11} {dt:>8.3g}  FAILED (see below)")
            continue
        ev_ratio = r["evals"] / base["evals"]
        wall_ratio = r["wall"] / base["wall"]
        rest = str(r["rest_step"]) if r["rest_step"] is not None else "-"
        print(f"{r['name']:<11} {dt:>8.3g} {rest:>12} {r['evals']:>11.0f} {ev_ratio:>7.2f} "
              f"{r['wall']:>16.2f} {wall_ratio:>7.2f} {r['loop']:>9.2f} {r['final']:>15.10g} "
              f"{r['final_vs_ref']:>+12.2e}")
    print()
    for r in rows:
        if r["ok"] and r["kind"] == "sissm":
            print(f"{r['name']}: steps 1..{len(r['steps'])}: force evaluations {r['steps']}, "
                  f"Newton steps {r['newton']}, CG iterations {r['krylov']}; unconverged steps "
                  f"{r['unconverged']}, steps cut back {r['cutback']}, steps redone with the "
                  f"other preconditioner {r['fallback']}")
            for line in r["summary"]:
                print(f"  {r['name']}: fix sissm at the end of the run: {line}")
        if r["ok"] and r["kind"] == "lps":
            print(f"{r['name']}: rest measured against its own final deflection "
                  f"{r['final']:.8g} m ({r['final_vs_ref']:+.1%} from the peri/nosb reference: "
                  "another discretization)")
        if r["note"]:
            print(f"{r['name']}: {r['note']}")
    print("evaluations: fix sissm sum of (f_integrate[1] + 1) per step up to the rest row; "
          "fix nve one per step (rows every 10 steps)")


if __name__ == "__main__":
    main()
