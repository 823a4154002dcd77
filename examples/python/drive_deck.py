#!/usr/bin/env python3
"""Drive a deck from Python with LAMMPS's own module: run the README's first deck (a PMMA
cantilever under gravity, fix sissm, examples/first-deck/in.first), read the particles'
positions, reference positions and compute nosb/atom's von Mises stress into numpy, and plot
the deflection along the beam, coloured by the stress, to a PNG.

    python3 examples/python/drive_deck.py [-o cantilever.png]

Needs bash tools/setup.sh (it links LAMMPS's Python module and library into build/python);
in your own scripts:

    PYTHONPATH=build/python python3 your_script.py
    ... lmp = lammps(); lmp.command("plugin load build/perisissmplugin.so")
"""
import argparse
import os
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "build" / "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from lammps import LMP_STYLE_ATOM, LMP_TYPE_ARRAY, lammps  # noqa: E402


def run_deck():
    """The cantilever after 20 steps: reference x (mm), deflection uz (um), von Mises (Pa)."""
    # the deck's material file (potentials/materials.nosb), as build/lmp finds it
    os.environ["LAMMPS_POTENTIALS"] = os.pathsep.join(
        p for p in (os.environ.get("LAMMPS_POTENTIALS"), str(REPO / "potentials")) if p)
    lmp = lammps(cmdargs=["-screen", "none", "-log", "none", "-nocite"])
    try:
        lmp.command(f"plugin load {REPO / 'build' / 'perisissmplugin.so'}")
        lmp.file(str(REPO / "examples" / "first-deck" / "in.first"))
        lmp.commands_list(["compute s all nosb/atom", "run 0"])
        x = lmp.numpy.extract_atom("x").copy()
        x0 = lmp.numpy.extract_atom("x0").copy()
        stress = lmp.numpy.extract_compute("s", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)[:, 3].copy()
    finally:
        lmp.close()
    return x0[:, 0] * 1e3, (x[:, 2] - x0[:, 2]) * 1e6, stress


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--output", default="cantilever.png", help="the picture (PNG)")
    args = ap.parse_args()
    xmm, uz, stress = run_deck()
    fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=120)
    dots = ax.scatter(xmm, uz, c=stress / 1e3, s=8, cmap="viridis")
    fig.colorbar(dots, ax=ax, label="von Mises stress (kPa)")
    ax.set_xlabel("x along the beam (mm)")
    ax.set_ylabel("deflection $u_z$ ($\\mu$m)")
    ax.set_title("PMMA cantilever under gravity after 20 steps of fix sissm")
    fig.tight_layout()
    fig.savefig(args.output)
    print(f"{len(xmm)} particles; tip deflection {uz.min():.6g} um; largest von Mises stress "
          f"{stress.max():.6g} Pa; picture {args.output}")


if __name__ == "__main__":
    main()
