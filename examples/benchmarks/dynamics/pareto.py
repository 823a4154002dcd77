#!/usr/bin/env python3
"""Cloth in motion, error against wall time per frame: every integrator configuration of the
hanging cloth on one plot (doc/reports/error-vs-time.md, "Cloth in motion").

    /usr/bin/python3 examples/benchmarks/dynamics/pareto.py [--rounds R] [--time T] [--out DIR]
        [--report FILE] [--lmp PATH] [--keep DIR]

The scene is cloth.py's hanging cloth (examples/hanging-cloth/in.hanging, the shipped 3038
vertices), 0.3 s by default. The reference is fix nve at REFERENCE_DT (a quarter of the explicit
step below; cloth.py --halve measures that fix nve at 1e-4 s and 2e-4 s differ by 1.2e-7 of the
centre's motion and 2.0e-6 of the lowest point's). Every configuration of CONFIGS runs in one
invocation, one after the other in the listed order (reversed in every second round; --rounds R
keeps the fastest loop of each); the reference runs first. Error of a run: cloth.py's, the
centre of mass and the lowest point at the end against the reference's, relative to the
reference's motion since the start. Cost: the loop's CPU time per simulated frame of 1/60 s,
LAMMPS's loop time times its "% CPU use" (on a machine shared with other jobs the loop's wall
time is up to 5 times its CPU time; the CPU time is what the wall time is on a core of its
own); the wall time is in the table too.

Writes DIR/cloth.csv and DIR/cloth.png (default DIR doc/reports/error-vs-time), and the section
between CLOTH_BEGIN and CLOTH_END of the report (default doc/reports/error-vs-time.md; replaced
when present, appended otherwise; error-vs-time/run.py keeps it). The section also goes to
standard output, progress to standard error.
"""
from __future__ import annotations

import argparse
import csv
import datetime
import os
import re
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import cloth  # noqa: E402  (the hanging-cloth scene and its measures)
from deck_runs import DeckRunner, describe_build, fmt, lammps_run, pareto  # noqa: E402

REPO = HERE.parents[2]
SCENE = REPO / "examples" / "hanging-cloth"
CLOTH_BEGIN = "<!-- cloth in motion: written by examples/benchmarks/dynamics/pareto.py -->"
CLOTH_END = "<!-- end of cloth in motion -->"

NVE_DT = cloth.HANGING["nve_dt"]       # 0.9 x the largest step measured stable
REFERENCE_DT = NVE_DT / 4
SISSM_DT = cloth.SCENES["hanging"]["sissm_dt"]
GENALPHA = "scheme genalpha"
FIXED = "scheme genalpha solver jacobi relax yes unconverged warn"

# (group of the plot, label, deck variables): fix nve at its step and half of it; fix sissm
# (generalized-alpha, 2 ms) Newton-Krylov with the default stopping rule and others; the
# fixed-budget sweeps (the authors' mode) with and without Chebyshev acceleration
CONFIGS = [
    ("fix nve", "fix nve, dt 2e-4 s (0.9 x stable)", {"solver": "nve", "dt": NVE_DT}),
    ("fix nve", "fix nve, dt 1e-4 s", {"solver": "nve", "dt": NVE_DT / 2}),
    ("Newton", "defaults (error 1e-3)", {"opts": GENALPHA}),
    ("Newton", "error 1e-2", {"opts": GENALPHA + " error 1e-2"}),
    ("Newton", "error 1e-4", {"opts": GENALPHA + " error 1e-4"}),
    ("Newton", "tolerance 1e-3", {"opts": GENALPHA + " tolerance 1e-3"}),
    ("Newton", "tolerance 1e-6", {"opts": GENALPHA + " tolerance 1e-6"}),
    ("sweeps", "10 sweeps", {"opts": FIXED, "iters": 10, "precond": "block"}),
    ("sweeps", "30 sweeps", {"opts": FIXED, "iters": 30, "precond": "block"}),
    ("chebyshev", "10 sweeps, chebyshev 0.9", {"opts": FIXED + " chebyshev 0.9", "iters": 10,
                                               "precond": "block"}),
    ("chebyshev", "30 sweeps, chebyshev 0.95", {"opts": FIXED + " chebyshev 0.95", "iters": 30,
                                                "precond": "block"}),
]
CPU_USE = re.compile(r"^([0-9.]+)% CPU use with", re.M)
STYLE = {"fix nve": ("k", "s"), "Newton": ("tab:blue", "o"), "sweeps": ("tab:red", "v"),
         "chebyshev": ("tab:green", "^")}


class Pareto:
    def __init__(self, args):
        self.args = args
        work = args.keep or Path(tempfile.mkdtemp(prefix="cloth-pareto-"))
        work.mkdir(parents=True, exist_ok=True)
        self.runner = DeckRunner(args.lmp, work, SCENE, [], "cloth pareto",
                                 expected=1 + args.rounds * len(CONFIGS))
        self.frame = cloth.SCENES["hanging"]["frame"]
        self.n_sissm, _, _ = cloth.step_counts(args.time, SISSM_DT, None)
        self.time = self.n_sissm * SISSM_DT

    def variables(self, v):
        """The deck's variables of one run: steps and dt for the same simulated time, a dump
        at the start and the end, a thermo row per 2 ms."""
        dt = v.get("dt", SISSM_DT)
        steps = round(self.time / dt)
        every = max(1, round(SISSM_DT / dt))
        out = {"mesh": cloth.HANGING["mesh"], "a": cloth.HANGING["a"], "steps": steps,
               "dt": repr(dt), "every": every, "dump": steps, "name": "run"}
        out.update({k: val for k, val in v.items() if k != "dt"})
        return out

    def run_all(self):
        ref = self.runner.run("in.hanging", self.variables({"solver": "nve", "dt": REFERENCE_DT}),
                              label="reference")
        frames = cloth.dump_frames(ref)
        self.ref0, self.ref = cloth.centre_and_lowest(frames[0]), \
            cloth.centre_and_lowest(frames[-1])
        self.ref_run = ref
        best, self.cpu_runs = {}, {}
        for r in range(self.args.rounds):
            order = CONFIGS if r % 2 == 0 else CONFIGS[::-1]
            for group, label, v in order:
                run = self.runner.run("in.hanging", self.variables(v), check=False,
                                      label=f"{label}, round {r + 1}")
                run["cpu"] = cpu_seconds(run)
                if run["ok"]:
                    self.cpu_runs.setdefault(label, []).append((run["cpu"], run["loop"]))
                if label not in best or (run["ok"] and run["cpu"] < best[label]["cpu"]):
                    best[label] = run
        self.rows = []
        for group, label, v in CONFIGS:
            run = best[label]
            dt = v.get("dt", SISSM_DT)
            row = dict(group=group, label=label, dt=dt, ok=run["ok"], per_frame=None, wall=None,
                       evaluations=None, unconverged=None, centre=None, lowest=None,
                       note=run["errors"][0] if run["errors"] else "")
            if run["ok"]:
                frames = run["loop_steps"] * dt / self.frame
                row["per_frame"], row["wall"] = run["cpu"] / frames, run["loop"] / frames
                row["centre"], row["lowest"] = cloth.motion_error(
                    cloth.centre_and_lowest(cloth.dump_frames(run)[-1]), self.ref, self.ref0)
                if v.get("solver") == "nve":
                    row["evaluations"] = 1.0
                else:
                    row["evaluations"] = cloth.evaluations(run)[0]
                    row["unconverged"] = int(run["summary"][2]) if run["summary"] else None
            self.rows.append(row)

    # -- output ---------------------------------------------------------------------------------
    def write_csv(self, path):
        keys = ["group", "label", "dt", "per_frame", "wall", "evaluations", "unconverged", "centre",
                "lowest", "note"]
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
            w.writeheader()
            for r in self.rows:
                w.writerow(r)

    def plot(self, path):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharex=True)
        for ax, key, title in ((axes[0], "centre", "centre of mass"),
                               (axes[1], "lowest", "lowest point")):
            for group, (colour, marker) in STYLE.items():
                rows = [r for r in self.rows if r["group"] == group and r["per_frame"]]
                ax.scatter([r["per_frame"] for r in rows], [max(r[key], 1e-9) for r in rows],
                           color=colour, marker=marker, s=50, label=group)
                for j, r in enumerate(rows):    # (labels of near points staggered)
                    ax.annotate(r["label"].replace("fix nve, ", ""), (r["per_frame"],
                                max(r[key], 1e-9)), fontsize=7, xytext=(4, 3 - 8 * (j % 5)),
                                textcoords="offset points")
            points = [(r["per_frame"], r[key]) for r in self.rows if r["per_frame"]]
            front = sorted((points[k] for k in pareto(points)))
            ax.plot([p[0] for p in front], [max(p[1], 1e-9) for p in front], color="0.6",
                    lw=1, zorder=0, label="Pareto front")
            ax.axhline(0.01, color="0.8", ls=":", lw=1)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("CPU time of the loop per frame of 1/60 s (s, 1 rank)")
            ax.set_ylabel(f"{title} error at {self.time:g} s / its motion")
            ax.set_title(f"hanging cloth, 3038 vertices: {title}")
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(path, dpi=110)
        plt.close(fig)

    def section(self, out_rel, command, minutes):
        L = [CLOTH_BEGIN, "", "## Cloth in motion: the hanging cloth", ""]
        runs = [c for v in self.cpu_runs.values() for c in v]
        use = [c / w for c, w in runs]
        spread = [max(c for c, _ in v) / min(c for c, _ in v) - 1
                  for v in self.cpu_runs.values() if len(v) > 1]
        L.append(f"Generated by `{command}` on {datetime.date.today().isoformat()} in "
                 f"{minutes:.1f} minutes ({self.runner.count} LAMMPS runs, one at a time, 1 rank, "
                 f"niced; {describe_build(self.args.lmp)}). The machine has 2 cores and was "
                 "shared with other jobs while it ran: each run's LAMMPS loop got "
                 f"{min(use):.0%} to {max(use):.0%} of a core. The cost plotted is the loop's CPU "
                 "time (LAMMPS's loop time times its \"% CPU use\"), what the loop takes on a "
                 "core of its own; of the rounds the run with the least is kept" +
                 (f". It still differs by {min(spread):.0%} to {max(spread):.0%} between the "
                  "rounds of a configuration (the cores' shared caches and memory)"
                  if spread else "") + "; the errors and evaluations are not affected.")
        L.append("")
        L.append(f"Scene: examples/hanging-cloth (3038 vertices, 2 cm triangles, model xu, "
                 f"`bend auto`), falling and swinging from flat for {self.time:g} s "
                 f"({self.time / self.frame:.3g} frames of 1/60 s). fix sissm at the authors' "
                 f"step, {SISSM_DT * 1e3:g} ms, `scheme genalpha` in every configuration; fix nve "
                 f"at {NVE_DT:g} s (0.9 x its largest measured stable step) and half of it. "
                 f"Reference: fix nve at {REFERENCE_DT:g} s. Error: |x - x_ref| / |x_ref - "
                 "x_ref(0)| at the end, x the mass-weighted centre of all vertices or the lowest "
                 "vertex's z (examples/benchmarks/dynamics/README.md, `cloth.py`). Times: "
                 "per frame, of LAMMPS's loop (setup excluded).")
        L.append("")
        L.append(f"![cloth in motion]({out_rel}/cloth.png)")
        L.append("")
        L.append(f"Points: `{out_rel}/cloth.csv`. Grey line: the Pareto front (no other "
                 "configuration is both faster and more accurate); dotted: 1% of the motion.")
        L.append("")
        L.append("| configuration | fix sissm keywords (beyond `scheme genalpha`) | dt (s) | CPU s "
                 "per frame | wall s per frame | force evaluations per step | unconverged steps "
                 "| centre error | lowest-point error |")
        L.append("|---|---|---|---|---|---|---|---|---|")
        for (group, label, v), r in zip(CONFIGS, self.rows):
            words = v.get("opts", "").replace(GENALPHA, "").strip()
            if "iters" in v:
                words = f"iterations {v['iters']} " + words
            if v.get("solver") == "nve":
                words = "(fix nve)"
            L.append(f"| {group}: {label} | `{words or '(none)'}` | {r['dt']:g} | "
                     f"{fmt(r['per_frame'])} | {fmt(r['wall'])} | {fmt(r['evaluations'])} | "
                     f"{r['unconverged'] if r['unconverged'] is not None else '-'} | "
                     f"{fmt(r['centre'], 2)} | {fmt(r['lowest'], 2)} |")
        failed = [r for r in self.rows if not r["ok"]]
        for r in failed:
            L.append("")
            L.append(f"- {r['label']}: stopped ({r['note']})")
        L += ["", CLOTH_END, ""]
        return "\n".join(L)


def cpu_seconds(run):
    """The loop's CPU time: its wall time times LAMMPS's "% CPU use" (inf for a failed run)."""
    use = CPU_USE.findall(run["log"])
    return run["loop"] * float(use[-1]) / 100 if run["ok"] and use else float("inf")


def replace_section(report: Path, text: str):
    old = report.read_text() if report.exists() else ""
    if CLOTH_BEGIN in old and CLOTH_END in old:
        head, rest = old.split(CLOTH_BEGIN, 1)
        tail = rest.split(CLOTH_END, 1)[1].lstrip("\n")
        new = head + text + tail
    else:
        new = old.rstrip("\n") + "\n\n" + text
    report.write_text(new)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--lmp", type=Path, default=Path(lammps_run.LMP))
    p.add_argument("--time", type=float, default=cloth.SCENES["hanging"]["time"],
                   help="simulated time (s)")
    p.add_argument("--rounds", type=int, default=1, help="rounds (fastest of each kept)")
    p.add_argument("--out", type=Path, default=REPO / "doc" / "reports" / "error-vs-time")
    p.add_argument("--report", type=Path, default=REPO / "doc" / "reports" / "error-vs-time.md")
    p.add_argument("--keep", type=Path, default=None, help="keep the run folders here")
    args = p.parse_args(argv)
    if not args.lmp.exists():
        p.error(f"no LAMMPS wrapper at {args.lmp}")
    t0 = time.time()
    bench = Pareto(args)
    bench.run_all()
    args.out.mkdir(parents=True, exist_ok=True)
    bench.write_csv(args.out / "cloth.csv")
    bench.plot(args.out / "cloth.png")
    command = "/usr/bin/python3 examples/benchmarks/dynamics/pareto.py" + \
        (f" --rounds {args.rounds}" if args.rounds != 1 else "") + \
        (f" --time {args.time:g}" if args.time != cloth.SCENES["hanging"]["time"] else "")
    rel = os.path.relpath(args.out.resolve(), args.report.resolve().parent)
    text = bench.section(rel, command, (time.time() - t0) / 60)
    print(text)
    replace_section(args.report, text)
    bench.runner.progress.done()
    return 0


if __name__ == "__main__":
    sys.exit(main())
