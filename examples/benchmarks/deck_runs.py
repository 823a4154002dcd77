"""Shared by the benchmark drivers (error-vs-time/run.py, dynamics/run.py, dynamics/cloth.py):
running one LAMMPS deck of a benchmark or example folder in a numbered work folder, and the
small helpers of their reports (the build measured, Pareto fronts, number formatting)."""
from __future__ import annotations

import math
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "unittest" / "python"))
import lammps_run  # noqa: E402  (parse_thermo; LMP default honours PERI_SISSM_LMP)

sys.path.insert(0, str(REPO / "tools"))
from progress import Progress  # noqa: E402

LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
# the summary line fix sissm writes at the end of every run it completes (doc/fix_sissm.rst)
SUMMARY = re.compile(r"Fix sissm \S+ run: (\d+) steps, ([0-9.eE+-]+) iterations per step, "
                     r"(\d+) unconverged, (\d+) cut back, (\d+) preconditioner switches"
                     r"(?:, \d+ ended by the error estimate)?"
                     r"(?:; (\d+) set-ups? of the AMG hierarchy)?")


class DeckRunner:
    """Runs decks of one benchmark folder (`folder`), each in work/runNNNN with the folder's
    `shared` files copied beside it, serial and niced; progress on stderr (tools/progress.py)."""

    # a guard against a hung lmp only (runs are capped in steps or force evaluations); a hit
    # stops the benchmark with an error that names the run
    HANG_GUARD_S = 3600

    def __init__(self, lmp: Path, work: Path, folder: Path, shared: list, name: str,
                 expected=None):
        self.lmp, self.work, self.folder, self.shared = lmp, work, folder, shared
        self.count, self.total_wall = 0, 0.0
        self.progress = Progress(expected, name, approximate=expected is not None)

    def run(self, deck: str, variables: dict, check=True, label="", nprocs=1):
        """ok, log, thermo (last table), errors (ERROR lines), summary (fix sissm's), loop time,
        loop steps, atoms and the run folder of one run, on nprocs MPI ranks."""
        self.count += 1
        wd = self.work / f"run{self.count:04d}"
        wd.mkdir(parents=True)
        for name in self.shared:
            shutil.copy(self.folder / name, wd)
        cmd = ["nice", *lammps_run.mpirun_prefix(nprocs), str(self.lmp), "-in",
               str(self.folder / deck), "-log", "log.lammps", "-nocite", "-screen", "none"]
        for k, v in variables.items():
            cmd += ["-var", k, str(v)]
        t0 = time.time()
        try:
            proc = subprocess.run(cmd, cwd=wd, capture_output=True, text=True,
                                  timeout=self.HANG_GUARD_S, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired:
            raise RuntimeError(f"{deck} {variables} in {wd} did not finish within the "
                               f"{self.HANG_GUARD_S} s hang guard") from None
        self.total_wall += time.time() - t0
        self.progress.step(f"{deck}{' ' + label if label else ''}, {time.time() - t0:.1f} s")
        log = (wd / "log.lammps").read_text(errors="replace") if (wd / "log.lammps").exists() \
            else ""
        errors = [ln for ln in (proc.stdout + log).splitlines() if ln.startswith("ERROR")]
        if not log and proc.returncode != 0:   # LAMMPS did not even start its log
            errors = errors or [ln for ln in (proc.stdout + proc.stderr).splitlines()
                                if ln.strip()][-3:]
        ok = proc.returncode == 0 and not errors
        if check and not ok:
            raise RuntimeError(f"{deck} {variables} failed in {wd}:\n" + "\n".join(
                (proc.stdout + proc.stderr + log).splitlines()[-15:]))
        tables = lammps_run.parse_thermo(log)
        loop = LOOP.findall(log)
        summary = SUMMARY.findall(log)
        return dict(ok=ok, log=log, thermo=tables[-1] if tables else {}, errors=errors,
                    summary=summary[-1] if summary else None,
                    loop=float(loop[-1][0]) if loop else float("nan"),
                    loop_steps=int(loop[-1][2]) if loop else 0,
                    atoms=int(loop[-1][3]) if loop else 0, dir=wd)


def describe_build(lmp):
    """The commit of the checkout, whether src/ has uncommitted changes, and the plugin's
    modification time (the build changes while fix sissm is being worked on)."""
    def git(*a):
        try:
            return subprocess.run(["git", "-C", str(REPO), *a], capture_output=True,
                                  text=True).stdout.strip()
        except OSError:
            return ""
    head = git("rev-parse", "--short", "HEAD") or "?"
    dirty = git("status", "--porcelain", "--", "src")
    plugins = sorted(Path(lmp).resolve().parent.glob("*plugin*.so"))
    stamp = (time.strftime("%Y-%m-%d %H:%M", time.localtime(plugins[0].stat().st_mtime))
             if plugins else "?")
    return (f"commit {head}" + (" with uncommitted changes under src/" if dirty else "")
            + f", plugin built {stamp}")


def pareto(points):
    """Indices of the non-dominated (cost, error) points: cost ascending, error strictly
    decreasing."""
    order = sorted(range(len(points)), key=lambda k: (points[k][0], points[k][1]))
    front, best = [], math.inf
    for k in order:
        if points[k][1] < best:
            front.append(k)
            best = points[k][1]
    return front


def fmt(x, digits=3):
    """x to `digits` significant digits; '-' for None and non-finite values."""
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{x:.{digits}g}"
