#!/usr/bin/env python3
"""Mode-I edge-cracked plate: runs in.edge.lps and in.edge.nosb (edge.geometry) under a slowly
rising tension and compares the stress at crack growth with linear elastic fracture mechanics.

    python3 edge_crack.py [--lmp ../../build/lmp] [--nw 60 30] [--np N] [--pair "keywords"]
        [--nosb-var NAME VALUE] [--styles lps nosb] [--transits 32] [--damp 3]
        [--max-load 2.5] [--hold X] [--hold-time 10] [--nz 3] [--periodic-z]
        [--keep-tip-bonds] [--broken 0.3] [--sissm-step 0.125] [--sissm "keywords"] [--out DIR]

LEFM: a single edge crack of length c in a strip of width W under a remote tension sigma has
K_I = sigma sqrt(pi c) F(c/W), F = 1.12 - 0.231 r + 10.55 r^2 - 21.72 r^3 + 30.39 r^4 (r = c/W;
Brown and Srawley 1966, as given by Tada, Paris and Irwin, The Stress Analysis of Cracks
Handbook: within 0.5% for r <= 0.6, ends free to rotate, a long strip). The crack grows when
K_I = K_Ic = sqrt(G0 E'), E' = E for a plane-stress plate (3 layers of particles, 3 mm in a
60 mm wide plate at the default 1 mm spacing; E / (1 - nu^2) with --periodic-z, plane strain),
so sigma_LEFM = sqrt(G0 E') / (F sqrt(pi c)). The tension rises at sigma_LEFM per --transits
times (default 32) the time a P wave takes to cross the plate's height, after a smooth start
over 1.33 of those transit times, under a viscous damping with a decay time of --damp transit
times (default 3); with --hold X it stays at X sigma_LEFM once reached, for --hold-time transit
times. The crack cuts every bond that crosses its plane short of the tip (--keep-tip-bonds:
only those between the blocks beside it). Loaded in 8 transit times with damping 1 the plate's
opening lags the tension by 30% at half sigma_LEFM; at the defaults by 1 to 2% (README, "Where
the factor came from"). Per style and width (--nw, in spacings; the crack is half of it): sigma
at crack growth (2 nz ligament particles beyond --broken damage, default 0.3, per spacing of
growth: the first thermo row with growth of one horizon, 3 spacings), sigma when half the
ligament is broken, both over sigma_LEFM, the wall time; with --hold, when the crack grew
after the tension reached the held value.
Style sissm: in.edge.nosb with `fix sissm` (keywords from --sissm) instead of `fix nve`, at a
step of --sissm-step transit times (default 1/8: 28 times the explicit step at W = 30), the same
loading and damping; its bonds break at the end of each step (doc/fix_sissm.rst, "Bond
breaking"), and the run prints the evaluations per step.
Runs in --out (default frames/edge), decks copied there.
"""
import argparse
import math
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
FILES = ["edge.geometry", "edge.run", "in.edge.lps", "in.edge.nosb"]
E, NU, RHO, G0 = 190e9, 0.25, 8000.0, 22170.0
A = 0.001          # lattice spacing (m)
NZ = 3


def shape_factor(r):
    """F(c/W) of a single edge crack in a strip under tension (Brown-Srawley / Tada)."""
    return 1.12 - 0.231 * r + 10.55 * r**2 - 21.72 * r**3 + 30.39 * r**4


def sigma_lefm(nw, ratio=0.5, plane_strain=False):
    crack = ratio * nw * A
    modulus = E / (1 - NU**2) if plane_strain else E
    return math.sqrt(G0 * modulus) / (shape_factor(ratio) * math.sqrt(math.pi * crack))


def thermo(log):
    """Rows (dicts) of the last thermo table of a LAMMPS log."""
    header, rows = None, []
    for line in Path(log).read_text().splitlines():
        words = line.split()
        if words and words[0] == "Step":
            header, rows = words, []
        elif header and len(words) == len(header) and words[0].isdigit():
            rows.append(dict(zip(header, map(float, words))))
        elif line.startswith("Loop time"):
            header = None
    return rows


def evaluations(log):
    """Force evaluations of the run in a log: its steps (fix nve), or fix sissm's iterations
    per step times its steps plus one per step (the evaluation that ends each step)."""
    lines = Path(log).read_text().splitlines()
    for line in lines:
        if line.startswith("Fix sissm") and " run: " in line:
            words = line.split(" run: ")[1].split()
            return round(float(words[0]) * (float(words[2]) + 1))
    for line in lines:
        if line.startswith("Loop time of"):
            return int(line.split(" steps")[0].split()[-1]) + 1
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=str(ROOT / "build" / "lmp"))
    ap.add_argument("--nw", type=int, nargs="+", default=[60], help="plate widths (spacings)")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--pair", default="", help="keywords appended to peri/nosb's pair_coeff")
    ap.add_argument("--nosb-var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                    help="a -var for the peri/nosb runs only, e.g. alpha 0 (repeat)")
    ap.add_argument("--nz", type=int, default=NZ, help="layers of particles (z)")
    ap.add_argument("--periodic-z", action="store_true",
                    help="periodic in z (plane strain; needs nz > 2 horizons / a = 6)")
    ap.add_argument("--broken", type=float, default=0.3,
                    help="a ligament particle counts as broken beyond this damage")
    ap.add_argument("--keep-tip-bonds", action="store_true",
                    help="cut only the bonds between the blocks beside the crack (-var cut_tip 0)")
    ap.add_argument("--styles", nargs="+", default=["lps", "nosb"],
                    choices=["lps", "nosb", "sissm"])
    ap.add_argument("--sissm-step", type=float, default=0.125,
                    help="style sissm: the time step in transit times")
    ap.add_argument("--sissm", default="", help="style sissm: keywords of its fix sissm")
    ap.add_argument("--transits", type=float, default=32.0)
    ap.add_argument("--max-load", type=float, default=2.5,
                    help="the run ends at this multiple of sigma_LEFM (or when the ligament "
                    "is broken through)")
    ap.add_argument("--hold", type=float,
                    help="hold the tension at this multiple of sigma_LEFM once reached")
    ap.add_argument("--hold-time", type=float, default=10.0,
                    help="with --hold: the run goes on for this many transit times at it")
    ap.add_argument("--damp", type=float, default=3.0,
                    help="damping time in transit times (0: undamped)")
    ap.add_argument("--out", help="working folder (default frames/edge)")
    args = ap.parse_args(argv)
    lmp = str(Path(args.lmp).resolve())
    out = Path(args.out) if args.out else HERE / "frames" / "edge"
    out.mkdir(parents=True, exist_ok=True)
    for name in FILES:
        shutil.copy(HERE / name, out / name)
    wave = math.sqrt((E / (3 * (1 - 2 * NU)) + 4 / 3 * E / (2 * (1 + NU))) / RHO)
    lines, held = [], []
    for nw in args.nw:
        target = sigma_lefm(nw, plane_strain=args.periodic_z)
        transit = 2 * nw * A / wave
        rate = target / (args.transits * transit)
        t_start = 1.33 * transit
        t_end = args.max_load * target / rate + 0.5 * t_start
        if args.hold:
            t_reach = args.hold * target / rate + 0.5 * t_start
            t_end = t_reach + args.hold_time * transit
        t_damp = args.damp * transit
        for style in args.styles:
            log = f"log.{style}.{nw}"
            deck = "nosb" if style == "sissm" else style
            sig_max = f"{args.hold * target:.6g}" if args.hold else "1e30"
            cmd = [lmp, "-in", f"in.edge.{deck}", "-var", "nw", str(nw), "-var", "sig_rate",
                   f"{rate:.6g}", "-var", "sig_max", sig_max, "-var", "t_start",
                   f"{t_start:.6g}", "-var", "t_damp", f"{t_damp:.6g}", "-var", "t_end",
                   f"{t_end:.6g}", "-var", "nz", str(args.nz), "-var", "zb",
                   "p" if args.periodic_z else "s", "-var", "cut_tip",
                   "0" if args.keep_tip_bonds else "1", "-var", "broken", f"{args.broken:g}",
                   "-log", log, "-screen", "none"]
            if deck == "nosb" and args.pair:
                cmd += ["-var", "keys", args.pair]
            if deck == "nosb":
                for var, value in args.nosb_var:
                    cmd += ["-var", var, value]
            if style == "sissm":
                dt = args.sissm_step * transit
                cmd += ["-var", "integrate", f"sissm {args.sissm}".strip(), "-var", "dt",
                        f"{dt:.6g}", "-var", "thermo_every", "1"]
            if args.np > 1:
                cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np",
                       str(args.np)] + cmd
            start = time.time()
            proc = subprocess.run(cmd, cwd=out, capture_output=True, text=True)
            wall = time.time() - start
            if proc.returncode:
                sys.exit(f"edge_crack.py: {' '.join(cmd)} failed: {proc.stderr[-500:]}")
            rows = thermo(out / log)
            grown = next((r for r in rows if r["c_broken"] >= 2 * args.nz * 3), None)
            growth = grown["v_sigma"] if grown else None
            if args.hold and grown:
                held.append(f"{style} W/a {nw}: grown {(grown['Time'] - t_reach) / transit:.2f} "
                            f"transit times after the tension reached {args.hold:g} sigma_LEFM")
            elif args.hold:
                held.append(f"{style} W/a {nw}: not grown within {args.hold_time:g} transit "
                            f"times at {args.hold:g} sigma_LEFM")
            half = next((r["v_sigma"] for r in rows
                         if r["c_broken"] >= args.nz * (nw - nw // 2)), None)
            lines.append((style, nw, target, growth, half, rows[-1]["c_dmax"], wall,
                          evaluations(out / log)))
    layers = f"{args.nz} layers" + (", periodic" if args.periodic_z else "")
    print(f"Edge-cracked plate (crack = W/2, H = 2W, {layers}, spacing {A * 1e3:g} mm), "
          f"loaded to sigma_LEFM in {args.transits:g} transit times; peri/nosb keywords: "
          f"{args.pair or '(none)'}")
    print(f"{'style':>6s} {'W/a':>4s} {'crack/delta':>11s} {'sigma_LEFM (MPa)':>16s} "
          f"{'growth/LEFM':>11s} {'half/LEFM':>9s} {'max d':>6s} {'wall (s)':>8s} "
          f"{'evaluations':>11s}")
    for style, nw, target, growth, half, dmax, wall, evals in lines:
        ratio = [f"{s / target:.3f}" if s is not None else "none" for s in (growth, half)]
        print(f"{style:>6s} {nw:4d} {nw / 2 / 3.0002:11.1f} {target / 1e6:16.2f} {ratio[0]:>11s} "
              f"{ratio[1]:>9s} {dmax:6.3f} {wall:8.0f} {evals:11d}")
    for line in held:
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
