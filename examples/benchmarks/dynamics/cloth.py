#!/usr/bin/env python3
"""Cloth in motion: fix sissm at the authors' step against fix nve at its stable step, wall time
per frame, force evaluations per step and an accuracy check, in one invocation with the runs
alternating so that both see the same machine (README.md, "Cloth in motion").

    /usr/bin/python3 examples/benchmarks/dynamics/cloth.py --scene hanging [--full] [--halve]
    /usr/bin/python3 examples/benchmarks/dynamics/cloth.py --scene ball [--layers 1 3 6]
    /usr/bin/python3 examples/benchmarks/dynamics/cloth.py --scene twist
    /usr/bin/python3 examples/benchmarks/dynamics/cloth.py --scene thrown [--friction 0.3]

Every scene: --sissm "OPTIONS" (fix sissm's keywords, appended to the deck's; default "scheme
genalpha"), --lmp PATH (default $PERI_SISSM_LMP, else build/lmp), --np 1 2 (MPI ranks, each
measured), --time T (simulated seconds) or --frames N (simulated frames), --rounds R (alternating
rounds, the fastest of each kept), --keep DIR (keep the run folders). Prints markdown tables on
standard output (progress on standard error); no result depends on the wall time but the
times themselves.

The scenes run their own decks (examples/hanging-cloth/in.hanging,
examples/cloth-on-ball/in.cloth-on-ball, examples/twisting-cloth/in.twisting-cloth,
examples/contact/in.thrown-cloth) with -var settings only:
  hanging  1 m cloth held at two corners, falling and swinging (3038 vertices; --full: 33418).
           fix sissm at 2 ms; fix nve at 2e-4 s (6.3e-5 s at --full), 0.9 x the largest step
           measured stable (README.md), shortened to fit the same time exactly. Accuracy: the
           centre of mass and the lowest point at the end against fix nve's (the small-step
           reference), relative to the reference's own displacement since the start; --halve
           also runs fix nve at half its step to show that the reference is converged. Frame
           1/60 s.
  ball     1, 3 or 6 layers of cloth falling onto a ball, one frame (33 steps of fix sissm). fix
           sissm at 1 ms (skin 10 mm, 4 to 6 times a step's move, ghost cutoff 10.5 cm: the
           steps that go beyond the candidates' reach stop at once and are cut back, which
           costs less than the wider lists of 12 mm; 6 layers keep 8 mm and 9 cm, faster there);
           fix nve at 20 us. Frame 1/30 s.
  twist    a strip twisted by its ends. fix sissm at 1 ms (kappa 10, the deck's); fix nve at
           20 us with kappa 100 (at 10 the explicit run goes through the barrier after the
           buckle: examples/twisting-cloth/README.md); both with the deck's skin, 16 mm.
           Frame 1/30 s.
  (ball and twist: the smallest distance between primitives at the end, tools/mesh_gaps.py on
  the final dump, and the smallest candidate distance printed over the run, f_contact[3],
  against dmin = 1 mm.)
  thrown   a 10 cm cloth thrown at 3 m/s onto a held one, fix sissm at 1 ms only (kappa auto
           needs it), friction --friction and kappa --kappa: did it finish, the evaluations of
           the dearest step and of the first step in contact.
fix sissm's iterations, tolerance and error rule are its defaults (100, 1e-6, error 1e-3 with
--sissm's scheme genalpha) in every scene.
"""
from __future__ import annotations

import argparse
import contextlib
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
EXAMPLES = REPO / "examples"
sys.path.insert(0, str(HERE.parent))
from deck_runs import DeckRunner, describe_build, fmt, lammps_run  # noqa: E402
from make_sheet import read_obj  # noqa: E402  (tools/ is on the path through deck_runs)
import mesh_gaps  # noqa: E402

DMIN, DHAT = 0.001, 0.002          # the contact decks' barrier (in.cloth-on-ball, twisting)
# fix nve's step on the hanging cloth: 0.9 x the largest step measured stable (3038 vertices:
# 0.3 s at 2.25e-4 s runs, 2.5e-4 s blows up; 33418 vertices: 400 steps at 7e-5 s run, 8e-5 s
# blows up), rounded down
HANGING_FULL = dict(mesh=EXAMPLES / "hanging-cloth" / "cloth_full.obj", a=0.00593, nve_dt=6.3e-5)
HANGING = dict(mesh=EXAMPLES / "hanging-cloth" / "cloth.obj", a=0.02, nve_dt=2e-4)

# per scene: the example folder, its deck, the files it reads, the length of a frame (s), the
# step of fix sissm and the largest step of fix nve (s), the default simulated time (s; the 3K
# scenes take under 2 minutes each on the project's 2-core machine) and the -var settings of
# each integrator beyond steps, dt and output
SCENES = {
    "hanging": dict(folder="hanging-cloth", deck="in.hanging", files=[], frame=1 / 60,
                    sissm_dt=2e-3, nve_dt=None, time=0.3, sissm={}, nve={"solver": "nve"}),
    "ball": dict(folder="cloth-on-ball", deck="in.cloth-on-ball",
                 files=["cloth.obj", "ball.obj"], frame=1 / 30, sissm_dt=1e-3, nve_dt=2e-5,
                 time=1 / 30, sissm={"solver": "sissm", "skin": 0.010, "comm": 0.105},
                 nve={"solver": "nve"}),
    "twist": dict(folder="twisting-cloth", deck="in.twisting-cloth", files=["strip.obj"],
                  frame=1 / 30, sissm_dt=1e-3, nve_dt=2e-5, time=0.2,
                  sissm={"solver": "sissm", "iters": 100}, nve={"solver": "nve", "kappa": 100}),
    "thrown": dict(folder="contact", deck="in.thrown-cloth", files=["cloth.obj", "small.obj"],
                   frame=1 / 30, sissm_dt=1e-3, nve_dt=None, time=0.03, sissm={}, nve=None),
}


def step_counts(total, sissm_dt, nve_dt):
    """Steps of fix sissm (total rounded to its step, at least 1), and fix nve's step count
    and step: the least number of steps no longer than nve_dt that cover the same time."""
    n_sissm = max(1, round(total / sissm_dt))
    if nve_dt is None:
        return n_sissm, None, None
    time = n_sissm * sissm_dt
    n_nve = math.ceil(time / nve_dt - 1e-9)
    return n_sissm, n_nve, time / n_nve


def evaluations(run):
    """Force evaluations per step of a fix sissm run: mean (the run summary's; of the printed
    steps when the run stopped before its summary), largest (the thermo's f_integrate[1], a row
    every step) and the step where it was largest."""
    col = run["thermo"].get("f_integrate[1]")
    steps = run["thermo"].get("Step")
    if col is None or len(col) < 2:
        return None, None, None
    mean = float(run["summary"][1]) if run["summary"] else float(col[1:].mean())
    k = 1 + int(np.argmax(col[1:]))           # row 0 is the start of the run
    return mean, int(col[k]), int(steps[k])


def dump_frames(run):
    """The frames of the run's dump (dump.run: the start and the end): [{"id", "x", ...}]."""
    return lammps_run.read_dump(run["dir"] / "dump.run")


class Cloth:
    def __init__(self, args):
        self.args = args
        self.scene = SCENES[args.scene]
        self.folder = EXAMPLES / self.scene["folder"]
        work = args.keep or Path(tempfile.mkdtemp(prefix=f"cloth-{args.scene}-"))
        work.mkdir(parents=True, exist_ok=True)
        self.runner = DeckRunner(args.lmp, work, self.folder, self.scene["files"],
                                 f"cloth {args.scene}")
        total = args.frames * self.scene["frame"] if args.frames else \
            args.time if args.time else self.scene["time"]
        nve_dt = args.nve_dt or self.scene["nve_dt"]
        if args.scene == "hanging":
            size = HANGING_FULL if args.full else HANGING
            nve_dt = args.nve_dt or size["nve_dt"]
            self.size = size
        self.n_sissm, self.n_nve, self.dt_nve = step_counts(total, self.scene["sissm_dt"],
                                                            nve_dt)
        self.time = self.n_sissm * self.scene["sissm_dt"]
        self.notes = []

    # -- the runs -------------------------------------------------------------------------------
    def sissm_vars(self, extra=None):
        v = {"steps": self.n_sissm, "every": 1, **self.scene["sissm"], **(extra or {})}
        if self.args.scene != "thrown":
            v.update(dt=self.scene["sissm_dt"], dump=self.n_sissm, name="run")
        if self.args.sissm.strip():
            v["opts"] = self.args.sissm
        return v

    def nve_vars(self, extra=None, halve=False):
        n, dt = (2 * self.n_nve, self.dt_nve / 2) if halve else (self.n_nve, self.dt_nve)
        every = max(1, n // self.n_sissm)          # a thermo row per fix sissm step
        return {"steps": n, "dt": repr(dt), "every": every, "dump": n, "name": "run",
                **self.scene["nve"], **(extra or {})}

    def alternate(self, configs, nprocs, what=""):
        """Runs each (key, variables) of configs in turn, --rounds times; per key the run with
        the shortest loop time (every round gives the same physics)."""
        best = {}
        for r in range(self.args.rounds):
            for key, variables in configs:
                run = self.runner.run(self.scene["deck"], variables, check=False, nprocs=nprocs,
                                      label=f"{key}, {what}{nprocs} rank(s), round {r + 1}")
                if key not in best or (run["ok"] and run["loop"] < best[key]["loop"]):
                    best[key] = run
        return best

    def per_frame(self, run, dt):
        """Seconds of the run's loop per simulated frame; None for a run that stopped."""
        if not run["ok"]:
            return None
        return run["loop"] / (run["loop_steps"] * dt / self.scene["frame"])

    def failed(self, what, run):
        if not run["ok"]:
            self.notes.append(f"{what}: " + (run["errors"][0] if run["errors"] else
                                             "lmp failed") + f" (run folder {run['dir']})")
            return True
        return False

    # -- hanging cloth --------------------------------------------------------------------------
    def hanging(self):
        mesh = self.size["mesh"]
        if not mesh.exists():          # the authors' size is not shipped (hanging-cloth/README)
            import make_sheet
            with contextlib.redirect_stdout(sys.stderr):     # its summary line: not the table's
                make_sheet.main(["rectangle", "1.0", "1.0", "--spacing", str(self.size["a"]),
                                 "--pattern", "equilateral", "-o", str(mesh)])
        common = {"mesh": mesh, "a": self.size["a"]}
        rows, checks, positions = [], [], []
        for nprocs in self.args.np:
            best = self.alternate([("sissm", self.sissm_vars(common)),
                                   ("nve", self.nve_vars(common))], nprocs)
            s, n = best["sissm"], best["nve"]
            failed = self.failed(f"fix sissm, {nprocs} rank(s)", s)
            if self.failed(f"fix nve, {nprocs} rank(s)", n):
                raise RuntimeError("the reference run failed: " + self.notes[-1])
            frames = dump_frames(n)
            ref0, ref = centre_and_lowest(frames[0]), centre_and_lowest(frames[-1])
            err = (None, None) if failed else motion_error(
                centre_and_lowest(dump_frames(s)[-1]), ref, ref0)
            mean, most, at = evaluations(s)
            sf, nf = self.per_frame(s, self.scene["sissm_dt"]), self.per_frame(n, self.dt_nve)
            rows.append([n["atoms"], nprocs, frame_cell(s, sf), fmt(nf),
                         fmt(sf / nf if sf else None),
                         fmt(mean), most if most is not None else "-", cut_back(s),
                         amg_setups(s), fmt(err[0], 2), fmt(err[1], 2)])
            positions += [[f"fix sissm, {nprocs} rank(s)", *position_cells(s)],
                          [f"fix nve, {nprocs} rank(s)", *position_cells(n)]]
            if self.args.halve:
                half = self.runner.run(self.scene["deck"], self.nve_vars(common, halve=True),
                                       nprocs=nprocs, label=f"nve dt/2, {nprocs} rank(s)")
                e = motion_error(centre_and_lowest(dump_frames(half)[-1]), ref, ref0)
                checks.append([nprocs, f"{self.dt_nve:.4g}", f"{self.dt_nve / 2:.4g}",
                               fmt(e[0], 2), fmt(e[1], 2)])
                positions.append([f"fix nve dt/2, {nprocs} rank(s)", *position_cells(half)])
        print(f"Hanging cloth ({self.describe()}; fix nve at dt {self.dt_nve:.4g} s, "
              f"{self.n_nve} steps):\n")
        table(["vertices", "ranks", "sissm s/frame", "nve s/frame", "sissm / nve",
               "evaluations per step", "most in a step", "cut back", "AMG set-ups",
               "centre error", "lowest-point error"], rows)
        if checks:
            print("\nThe reference: fix nve at dt against dt/2 (differences relative to the "
                  "motion, as above):\n")
            table(["ranks", "nve dt (s)", "dt/2 (s)", "centre difference",
                   "lowest-point difference"], checks)
        print("\nAt the end (m):\n")
        table(["run", "centre of mass x", "y", "z", "lowest point z"], positions)

    # -- cloth on a ball, twisting cloth --------------------------------------------------------
    def contact_scene(self):
        layer_counts = self.args.layers if self.args.scene == "ball" else [None]
        rows = []
        for layers in layer_counts:
            extra = {"layers": layers} if layers else {}
            mesh = self.contact_mesh(layers)
            # (6 layers: 10 mm took 1.1 x the loop time of 8 mm, 2026-12-01)
            sissm_extra = {**extra, "skin": 0.008, "comm": 0.09} if layers and layers > 3 else extra
            for nprocs in self.args.np:
                best = self.alternate([("sissm", self.sissm_vars(sissm_extra)),
                                       ("nve", self.nve_vars(extra))], nprocs,
                                      f"{layers} layer(s), " if layers else "")
                s, n = best["sissm"], best["nve"]
                what = (f"{layers} layer(s), " if layers else "") + f"{nprocs} rank(s)"
                self.failed(f"fix sissm, {what}", s)
                self.failed(f"fix nve, {what}", n)
                mean, most, at = evaluations(s)
                sf, nf = self.per_frame(s, self.scene["sissm_dt"]), self.per_frame(n, self.dt_nve)
                rows.append(([layers] if layers else []) + [
                    len(mesh.vertices), nprocs, frame_cell(s, sf), frame_cell(n, nf),
                    fmt(sf / nf if sf and nf else None), fmt(mean),
                    most if most is not None else "-", cut_back(s),
                    f"{gap_text(mesh, s)} / {gap_text(mesh, n)}",
                    f"{smallest_candidate(s)} / {smallest_candidate(n)}"])
        name = "Cloth on a ball" if self.args.scene == "ball" else "Twisting cloth"
        print(f"{name} ({self.describe()}; fix nve at dt {self.dt_nve:.4g} s, {self.n_nve} "
              f"steps; dmin {DMIN * 1e3:g} mm):\n")
        table((["layers"] if self.args.scene == "ball" else []) + [
            "vertices", "ranks", "sissm s/frame", "nve s/frame", "sissm / nve",
            "evaluations per step", "most in a step", "cut back",
            "gap at the end (mm): sissm / nve", "smallest candidate distance (mm): sissm / nve"],
            rows)

    def contact_mesh(self, layers):
        """mesh_gaps's view of the scene: the meshes in atom-ID order (read_mesh numbers each
        file's vertices after the atoms already there)."""
        if layers is None:
            vertices, faces = read_obj(self.folder / "strip.obj")
        else:
            vertices, faces = (list(part) for part in read_obj(self.folder / "ball.obj"))
            cv, cf = read_obj(self.folder / "cloth.obj")
            for _ in range(layers):
                first = len(vertices)
                vertices += cv
                faces += [tuple(i + first for i in f) for f in cf]
        return mesh_gaps.MeshGaps(vertices, faces, 1, 1)

    # -- thrown cloth ---------------------------------------------------------------------------
    def thrown(self):
        extra = {"kappa": self.args.kappa, "friction": self.args.friction}
        rows = []
        for nprocs in self.args.np:
            run = self.alternate([("sissm", self.sissm_vars(extra))], nprocs)["sissm"]
            done = not self.failed(f"fix sissm, {nprocs} rank(s)", run)
            mean, most, at = evaluations(run)
            th = run["thermo"]
            pairs = th.get("f_contact[1]", np.zeros(0)) + th.get("f_contact[2]", np.zeros(0))
            touch = np.nonzero(pairs > 0)[0]
            first = (f"{int(th['f_integrate[1]'][touch[0]])} (step {int(th['Step'][touch[0]])})"
                     if len(touch) else "no contact")
            rows.append([nprocs, "yes" if done else "no", f"{last_step(run)} of {self.n_sissm}",
                         fmt(mean), f"{most} (step {at})" if most is not None else "-", first,
                         cut_back(run), unconverged(run),
                         smallest_candidate(run)])
        print(f"Thrown cloth (kappa {self.args.kappa}, friction {self.args.friction}; "
              f"{self.describe()}):\n")
        table(["ranks", "finished", "steps", "evaluations per step", "most in a step",
               "in the first step in contact", "cut back", "unconverged",
               "smallest candidate distance (mm)"], rows)

    def describe(self):
        return (f"fix sissm {self.args.sissm!r} at dt {self.scene['sissm_dt']:g} s, "
                f"{self.n_sissm} steps, {self.time:g} s = {self.time / self.scene['frame']:.3g}"
                f" frames of {self.scene['frame']:.4g} s")

    def report(self):
        print(f"# cloth.py --scene {self.args.scene}: {describe_build(self.args.lmp)}\n")
        {"hanging": self.hanging, "ball": self.contact_scene, "twist": self.contact_scene,
         "thrown": self.thrown}[self.args.scene]()
        for note in self.notes:
            print(f"\n- {note}")
        self.runner.progress.done()


def centre_and_lowest(frame):
    """The mass-weighted centre of a dump frame (all atoms) and its lowest z."""
    m = frame["mass"]
    x = np.column_stack([frame["x"], frame["y"], frame["z"]])
    return m @ x / m.sum(), float(x[:, 2].min())


def motion_error(run, ref, start):
    """|run - ref| / |ref - start| of the centre (a vector) and of the lowest point."""
    (c, z), (cr, zr), (c0, z0) = run, ref, start
    return (float(np.linalg.norm(c - cr) / np.linalg.norm(cr - c0)), abs(z - zr) / abs(zr - z0))


def position_cells(run):
    if not run["ok"]:
        return ["-"] * 4
    c, z = centre_and_lowest(dump_frames(run)[-1])
    return [f"{v:.7g}" for v in (*c, z)]


def last_step(run):
    steps = run["thermo"].get("Step")
    return int(steps[-1]) if steps is not None and len(steps) else 0


def frame_cell(run, seconds):
    """Seconds per frame, or where a run that ended in an ERROR stopped."""
    return fmt(seconds) if run["ok"] else f"stopped after step {last_step(run)}"


def gap_text(mesh, run):
    """The smallest point-triangle or edge-edge distance (mm) in the run's last dump frame,
    with the crossing triangle pairs when there are any; '-' for a failed run."""
    if not run["ok"]:
        return "-"
    frame = dump_frames(run)[-1]
    x = np.column_stack([frame["x"], frame["y"], frame["z"]])[:len(mesh.vertices)]
    radius = DMIN + DHAT
    gaps = mesh.check(x, radius=radius, dmin=DMIN)
    found = [p.distance for p in (gaps.point_triangle, gaps.edge_edge) if p is not None]
    text = f"{min(found) * 1e3:.3g}" if found else f"> {radius * 1e3:g}"
    return text + (f" ({gaps.intersections} crossing)" if gaps.intersections else "")


def smallest_candidate(run):
    """The smallest f_contact[3] (mm) over the printed steps."""
    col = run["thermo"].get("f_contact[3]")
    return "-" if col is None or not len(col) else f"{col.min() * 1e3:.3g}"


def cut_back(run):
    return run["summary"][3] if run["summary"] else "-"


def unconverged(run):
    return run["summary"][2] if run["summary"] else "-"


def amg_setups(run):
    return (run["summary"][5] or "-") if run["summary"] else "-"


def table(header, rows):
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for r in rows:
        print("| " + " | ".join(str(c) for c in r) + " |")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", required=True, choices=sorted(SCENES))
    p.add_argument("--sissm", default="scheme genalpha",
                   help="fix sissm keywords, appended to the deck's (default: scheme genalpha)")
    p.add_argument("--lmp", type=Path, default=Path(lammps_run.LMP))
    p.add_argument("--np", type=int, nargs="+", default=[1], help="MPI ranks (each measured)")
    p.add_argument("--time", type=float, default=None, help="simulated time (s)")
    p.add_argument("--frames", type=float, default=None,
                   help="simulated time in frames (1/60 s hanging, 1/30 s the others)")
    p.add_argument("--rounds", type=int, default=1, help="alternating rounds (fastest kept)")
    p.add_argument("--keep", type=Path, default=None, help="keep the run folders here")
    p.add_argument("--nve-dt", type=float, default=None, help="fix nve's largest step (s)")
    p.add_argument("--full", action="store_true", help="hanging: the authors' size (33418 "
                   "vertices, a = 5.93 mm; hanging-cloth/cloth_full.obj, made when missing)")
    p.add_argument("--halve", action="store_true",
                   help="hanging: also fix nve at half its step, against the reference")
    p.add_argument("--layers", type=int, nargs="+", default=[1, 3, 6], help="ball: layers")
    p.add_argument("--friction", type=float, default=0.3, help="thrown: friction coefficient")
    p.add_argument("--kappa", default="auto", help="thrown: barrier stiffness (J/m^2) or auto")
    args = p.parse_args(argv)
    if args.time is not None and args.frames is not None:
        p.error("give --time or --frames, not both")
    if not args.lmp.exists():
        p.error(f"no LAMMPS wrapper at {args.lmp}")
    Cloth(args).report()
    return 0


if __name__ == "__main__":
    sys.exit(main())
