"""What the solver benchmarks (cantilever.py, scaling.py, setup_cost.py, cube.py) share: the
repository's paths on sys.path (unittest/python for lammps_run, tools for progress), which build
ran, and the pattern of LAMMPS's loop-time line."""
import datetime
import re
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
for _p in (REPO / "unittest" / "python", REPO / "tools"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

# "Loop time of T on P procs for S steps with N atoms": T, P, S, N
LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")


def build_info() -> str:
    """Which build ran: the commit, whether src/ differs from it, and the plugin's time stamp
    (the numbers belong to that build)."""
    def git(*a):
        return subprocess.run(["git", "-C", str(REPO), *a], capture_output=True,
                              text=True).stdout.strip()
    so = REPO / "build" / "perisissmplugin.so"
    stamp = (datetime.datetime.fromtimestamp(so.stat().st_mtime).strftime("%Y-%m-%d %H:%M")
             if so.exists() else "?")
    dirty = " + uncommitted changes in src/" if git("status", "--porcelain", "src") else ""
    return f"build: commit {git('rev-parse', '--short', 'HEAD')}{dirty}, plugin built {stamp}"


def print_build(start: str) -> None:
    """Print the build an invocation started with (build_info() then), and a note when the
    build changed before its end (the numbers then mix two builds)."""
    end = build_info()
    print(start)
    if end != start:
        print(f"NOTE: the build changed during this invocation; at its end: {end}")
