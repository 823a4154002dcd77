"""The damage maps of the fracture scripts (kalthoff_winkler.py, branching.py): one picture
with a row per run and a column per time, the damage in the mid-plane slice of each run's dump,
drawn by tools/render_particles.py."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent.parent


def draw(runs, times, dt, spacing, window, cell, picture):
    """runs: (label, dump file) per row; times in us; dt the time step (s) that turns a time
    into a dump step; spacing (m) the slice's thickness; window (xlo, xhi, ylo, yhi) in m;
    cell (width, height) in inches per panel. Exits with render_particles's message if it
    fails; returns the picture's path."""
    dumps, steps, labels = [], [], []
    for label, dump in runs:
        for t in times:
            dumps.append(str(dump))
            steps.append(str(round(t * 1e-6 / dt)))
            labels.append(f"{label} {t:g} us")
    cmd = [sys.executable, str(ROOT / "tools" / "render_particles.py"), *dumps,
           "--column", "v_damage", "--steps", *steps, "--rows", str(len(runs)),
           "--labels", *labels, "--thickness", f"{spacing:g}", "--range", "0", "1",
           "--window", *(f"{w:g}" for w in window),
           "--label", "damage", "--size", str(cell[0] * len(times) + 1.5),
           str(cell[1] * len(runs) + 0.4), "-o", str(picture)]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode:
        sys.exit(proc.stderr)
    return picture
