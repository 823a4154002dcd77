#!/usr/bin/env python3
"""Wall time per simulated frame (1/60 s) of the hanging cloth: fix sissm at the authors' 2 ms
against explicit peri/nosb (fix nve) below its stable step, measured in one invocation,
alternating the two so that both see the same machine (README.md, "Cost per frame").

    python3 per_frame.py                          # shipped mesh (3038 vertices), dt 1.5e-4
    python3 per_frame.py --full                   # the authors' size (makes cloth_full.obj)
    python3 per_frame.py --full --np 2

Both simulate the same TIME (default 0.06 s: 30 steps of 2 ms); printed per method: steps,
loop time, seconds per frame, the lowest vertex at the end (backward Euler at 2 ms falls
(n + 1) / n further than the exact free fall in the first steps), and the ratio sissm / nve.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
LMP = Path(os.environ.get("PERI_SISSM_LMP", HERE.parents[1] / "build" / "lmp"))
FRAME = 1.0 / 60.0


def run(method, args, work):
    """One run of in.hanging; returns (steps, loop seconds, lowest vertex)."""
    if method == "sissm":
        dt, extra = 2e-3, []
    else:
        dt, extra = args.dt, ["-var", "solver", "nve"]
    steps = round(args.time / dt)
    cmd = [str(LMP), "-in", str(HERE / "in.hanging"), "-var", "mesh", str(Path(args.mesh).resolve()),
           "-var", "a", str(args.a), "-var", "steps", str(steps), "-var", "dt", repr(dt),
           "-var", "every", str(steps), "-log", "log." + method, "-screen", "none"] + extra
    if args.np > 1:
        cmd = ["mpirun", "-np", str(args.np)] + (["--allow-run-as-root"] if os.geteuid() == 0
                                                 else []) + cmd
    subprocess.run(cmd, cwd=work, check=True)
    log = (Path(work) / ("log." + method)).read_text()
    loop = float(re.search(r"Loop time of (\S+) on", log).group(1))
    head = log.index("c_zmin", log.index("Step "))
    rows = [ln.split() for ln in log[head:].splitlines()[1:] if re.match(r"\s*\d+ ", ln)]
    header = log[log.rindex("\n", 0, head) + 1:].split("\n", 1)[0].split()
    zmin = float(rows[-1][header.index("c_zmin")])
    return steps, loop, zmin


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--mesh", default=str(HERE / "cloth.obj"))
    p.add_argument("--a", type=float, default=0.02, help="the mesh's spacing (m)")
    p.add_argument("--dt", type=float, default=1.5e-4, help="fix nve's step (s)")
    p.add_argument("--time", type=float, default=0.06, help="simulated time (s)")
    p.add_argument("--rounds", type=int, default=1, help="alternating rounds (best of)")
    p.add_argument("--np", type=int, default=1, help="MPI ranks")
    p.add_argument("--full", action="store_true",
                   help="the authors' size: cloth_full.obj (33418 vertices, made here when "
                   "missing), a = 0.00593 m, dt = 4e-5 s")
    args = p.parse_args()
    if args.full:
        args.mesh, args.a, args.dt = str(HERE / "cloth_full.obj"), 0.00593, 4e-5
        if not Path(args.mesh).exists():
            subprocess.run([sys.executable, str(HERE.parents[1] / "tools" / "make_sheet.py"),
                            "rectangle", "1.0", "1.0", "--spacing", "0.00593", "--pattern",
                            "equilateral", "-o", args.mesh], check=True)
    work = tempfile.mkdtemp(prefix="per_frame.")
    best = {}
    for _ in range(args.rounds):
        for method in ("sissm", "nve"):
            steps, loop, zmin = run(method, args, work)
            if method not in best or loop < best[method][1]:
                best[method] = (steps, loop, zmin)
    shutil.rmtree(work)
    frames = args.time / FRAME
    print(f"mesh {args.mesh}, {args.np} rank(s), {args.time} s simulated ({frames:.2f} frames)")
    print(f"{'method':<22} {'steps':>6} {'loop s':>9} {'s/frame':>9} {'lowest vertex (m)':>19}")
    for method, label in (("sissm", "fix sissm, dt 2e-3"), ("nve", f"fix nve, dt {args.dt:g}")):
        steps, loop, zmin = best[method]
        print(f"{label:<22} {steps:>6} {loop:>9.2f} {loop / frames:>9.3f} {zmin:>19.10g}")
    print(f"sissm / nve wall time: {best['sissm'][1] / best['nve'][1]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
