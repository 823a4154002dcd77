#!/usr/bin/env python3
"""Kalthoff-Winkler plate: runs in.kalthoff.lps and in.kalthoff.nosb (kalthoff.geometry) on one
set-up, measures the cracks from the two notch tips at several times with tools/crack_path.py,
prints one table, and with --pictures draws the mid-plane damage at those times.

    python3 kalthoff_winkler.py [--lmp ../../build/lmp] [--spacing 2|1] [--np N]
        [--pair "peri/nosb keywords"] [--nosb-var NAME VALUE] [--lps-var NAME VALUE]
        [--label NAME] [--styles lps nosb] [--times 30 60 90] [--step NS] [--out DIR]
        [--pictures]

Each style runs in --out (default frames/kalthoff-<spacing>mm) with the decks copied there,
-var a (the spacing), -var dt (--step, default the deck's), -var t_end (the last of --times),
-var dump (every --every us, default 10), and for peri/nosb -var keys (--pair: keywords
appended to its pair_coeff line, e.g. "stabilize 0.1") and the -var of --nosb-var (e.g.
alpha 0), for peri/lps those of --lps-var (e.g. s00 0.0048); --label names the peri/nosb run in
the table and the file names. The table has per style and time the crack's angle to the notch
(0 straight ahead; the experiment's is about 70 degrees) at tip 1 (x = 75 mm) and tip 2
(x = 125 mm), "-" where no crack left the tip, their lengths and widths (particles across the
path), the fraction of the mid-plane's particles damaged beyond 0.4 off both paths (diffuse
damage and cracks that do not start at a tip), the mean damage of the mid-plane, and the wall
time of the run. The pictures (--pictures) are kalthoff-<spacing>mm.png in --out: a row per
style, a column per time, in the current configuration. Needs numpy (and matplotlib for the
pictures).
"""
import argparse
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(HERE))
import crack_path  # noqa: E402
import damage_maps  # noqa: E402

TIPS = [(0.075, 0.05), (0.125, 0.05)]
FILES = ["kalthoff.geometry", "kalthoff.run", "in.kalthoff.lps", "in.kalthoff.nosb"]


def step(args, a):
    """The time step (s): --step in ns, default the deck's 2.5e-5 a (50 ns at 2 mm)."""
    return args.step * 1e-9 if args.step else 2.5e-5 * a


def run(args, style, out, a, name):
    """Run one deck in out; (dump file, wall seconds)."""
    dt = step(args, a)
    every = max(1, round(args.every * 1e-6 / dt))
    cmd = [args.lmp, "-in", f"in.kalthoff.{style}", "-var", "a", f"{a:g}", "-var", "dt",
           f"{dt:g}", "-var", "t_end",
           f"{max(args.times) * 1e-6:g}", "-var", "dump", str(every), "-log", f"log.{name}",
           "-screen", "none"]
    if style == "nosb" and args.pair:
        cmd += ["-var", "keys", args.pair]
    for var, value in args.nosb_var if style == "nosb" else args.lps_var:
        cmd += ["-var", var, value]
    if args.np > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(args.np)] + cmd
    start = time.time()
    proc = subprocess.run(cmd, cwd=out, capture_output=True, text=True)
    wall = time.time() - start
    if proc.returncode:
        tail = (out / f"log.{name}").read_text().splitlines()[-5:] \
            if (out / f"log.{name}").exists() else []
        sys.exit(f"kalthoff_winkler.py: {' '.join(cmd)} failed (exit {proc.returncode}):\n"
                 + "\n".join(tail) + proc.stderr[-500:])
    dump = out / f"dump.kalthoff.{style}"
    if name != style:
        dump = dump.replace(out / f"dump.kalthoff.{name}")
    return dump, wall


def measure(dump, a, dt, times):
    """{time in us: (tips, stats)} at the dump's frames closest to the given times."""
    series = crack_path.frames(dump, "v_damage")
    previous = [None] * len(TIPS)
    found = {}
    for n, points, damage in series:
        tips, stats = crack_path.analyse(points, damage, TIPS, (0.0, 1.0), h=a,
                                         fit_length=0.04 / a, previous=previous)
        previous = [t["dir"] if t["crack"] else p for t, p in zip(tips, previous)]
        found[n * dt * 1e6] = (tips, stats)
    return {t: found[min(found, key=lambda s: abs(s - t))] for t in times}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=str(ROOT / "build" / "lmp"), help="LAMMPS with the plugin")
    ap.add_argument("--spacing", type=float, default=2.0, help="lattice spacing in mm (2 or 1)")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks")
    ap.add_argument("--pair", default="", help="keywords appended to peri/nosb's pair_coeff")
    ap.add_argument("--nosb-var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a -var for the peri/nosb run only, e.g. alpha 0 (repeat)")
    ap.add_argument("--lps-var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a -var for the peri/lps run only, e.g. s00 0.0048 (repeat)")
    ap.add_argument("--label", help="the name of the peri/nosb run (default nosb)")
    ap.add_argument("--styles", nargs="+", default=["lps", "nosb"], choices=["lps", "nosb"])
    ap.add_argument("--times", type=float, nargs="+", default=[30.0, 60.0, 90.0],
                    help="times (us) of the table and the pictures")
    ap.add_argument("--every", type=float, default=10.0, help="dump interval (us)")
    ap.add_argument("--step", type=float, help="time step in ns (default 25 per mm of spacing)")
    ap.add_argument("--out", help="the working folder (default frames/kalthoff-<spacing>mm)")
    ap.add_argument("--pictures", action="store_true", help="draw the damage maps")
    args = ap.parse_args(argv)
    args.lmp = str(Path(args.lmp).resolve())
    a = args.spacing * 1e-3
    out = Path(args.out) if args.out else HERE / "frames" / f"kalthoff-{args.spacing:g}mm"
    out.mkdir(parents=True, exist_ok=True)
    for name in FILES:
        shutil.copy(HERE / name, out / name)
    names = {"lps": "lps", "nosb": args.label or "nosb"}
    results = {}
    for style in args.styles:
        dump, wall = run(args, style, out, a, names[style])
        results[style] = (dump, wall, measure(dump, a, step(args, a), args.times))
    print(f"Kalthoff-Winkler plate, spacing {args.spacing:g} mm, {args.np} rank(s), "
          f"peri/nosb keywords: {args.pair or '(none)'}")
    print(f"{'style':>10s} {'t (us)':>6s} {'angle 1':>7s} {'angle 2':>7s} {'len 1':>6s} "
          f"{'len 2':>6s} {'width':>5s} {'off-path':>8s} {'mean d':>6s} {'wall (s)':>8s}")
    for style in args.styles:
        dump, wall, rows = results[style]
        for t in args.times:
            tips, stats = rows[t]
            angles = [f"{tip['angle']:7.1f}" if tip["crack"] else f"{'-':>7s}" for tip in tips]
            widths = [tip["width"] for tip in tips if tip["crack"]]
            width = f"{max(widths):5.1f}" if widths else f"{'-':>5s}"
            print(f"{names[style]:>10s} {t:6.0f} {angles[0]} {angles[1]} "
                  f"{tips[0]['length'] * 1e3:6.1f} {tips[1]['length'] * 1e3:6.1f} {width} "
                  f"{stats['off_path']:8.4f} {stats['mean_layer']:6.3f} {wall:8.0f}")
    if args.pictures:
        picture = damage_maps.draw([(names[s], results[s][0]) for s in args.styles], args.times,
                                   step(args, a), a, (-0.005, 0.205, -0.005, 0.105), (3.2, 1.9),
                                   out / f"kalthoff-{args.spacing:g}mm.png")
        print(f"pictures: {picture}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
