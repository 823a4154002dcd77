"""Run LAMMPS decks with build/lmp and read what they write.

    run = run_deck(text_or_path, tmp_path, nprocs=2, variables={"nsteps": 200})
    run.ok, run.errors, run.thermo[-1]["PotEng"], read_dump(tmp_path / "dump.atoms")

Thermo tables come from the log file, one per `run`/`minimize`, as numpy columns keyed by the
header names LAMMPS prints (Step, PotEng, KinEng, TotEng, c_ID, f_ID[1], ...).  Dumps are
`dump custom` text files; each frame's columns are sorted by atom id so that runs on different
numbers of ranks compare element by element.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
# PERI_SISSM_LMP points the tests at another wrapper (e.g. a scratch build); default build/lmp.
LMP = Path(os.environ.get("PERI_SISSM_LMP", REPO / "build" / "lmp"))


@dataclass
class Run:
    returncode: int
    stdout: str
    stderr: str
    log: str
    thermo: list = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.returncode == 0 and not self.errors

    @property
    def errors(self) -> list:
        return [ln for ln in (self.stdout + self.log).splitlines() if ln.startswith("ERROR")]

    @property
    def warnings(self) -> list:
        return [ln for ln in self.log.splitlines() if ln.startswith("WARNING")]

    def describe(self) -> str:
        tail = "\n".join((self.stdout + self.stderr).splitlines()[-30:])
        return f"lmp exited with {self.returncode}\n{tail}"


def mpirun_prefix(nprocs: int) -> list:
    if nprocs <= 1:
        return []
    mpirun = shutil.which("mpirun") or "mpirun"
    cmd = [mpirun, "-np", str(nprocs)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    if nprocs > (os.cpu_count() or 1):
        cmd.append("--oversubscribe")
    return cmd


def run_deck(deck, workdir, nprocs: int = 1, variables: dict | None = None,
             files: dict | None = None, timeout: float = 600, check: bool = True,
             env: dict | None = None) -> Run:
    """Run a deck (a path, or the text of one) in workdir and return what it produced.

    variables: -var NAME VALUE pairs; files: extra files {name: text} written into workdir.
    check: raise AssertionError with the run's tail when LAMMPS fails. env: environment
    variables set for this run (on top of the caller's environment).
    """
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    for name, text in (files or {}).items():
        (workdir / name).write_text(text)
    if isinstance(deck, Path):
        infile = deck.resolve()
    else:
        infile = workdir / "in.test"
        infile.write_text(deck)
    logfile = workdir / "log.lammps"
    cmd = mpirun_prefix(nprocs) + [str(LMP), "-in", str(infile), "-log", str(logfile),
                                   "-echo", "log", "-nocite"]
    for name, value in (variables or {}).items():
        cmd += ["-var", name, str(value)]
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, timeout=timeout,
                          stdin=subprocess.DEVNULL,
                          env={**os.environ, **env} if env else None)
    log = logfile.read_text(errors="replace") if logfile.exists() else ""
    run = Run(proc.returncode, proc.stdout, proc.stderr, log, parse_thermo(log))
    if check:
        assert run.ok, run.describe()
    return run


def library_environment() -> dict:
    """Environment for a Python process that drives the same LAMMPS through its library
    interface (`from lammps import lammps`) with the plugin auto-loaded: the variables the
    build/lmp wrapper exports, and PYTHONPATH to the python/ folder of the LAMMPS tree the
    project was built against (LAMMPS_SOURCE_DIR in the build's CMakeCache.txt)."""
    env = dict(os.environ)
    for line in LMP.read_text().splitlines():
        if line.startswith("export ") and "=" in line:
            name, value = line[len("export "):].split("=", 1)
            value = value.strip('"')
            old = os.environ.get(name)
            prefix = "${%s:+$%s:}" % (name, name)
            if value.startswith(prefix):
                # the caller's value first: ${NAME:+$NAME:}VALUE
                value = value[len(prefix):]
                env[name] = (old + ":" if old else "") + value
            else:
                # the caller's value appended: VALUE${NAME:+:$NAME}
                value = value.split("${")[0]
                env[name] = value + (":" + old if old else "")
    cache = (LMP.parent / "CMakeCache.txt").read_text()
    src = next(ln.split("=", 1)[1] for ln in cache.splitlines()
               if ln.startswith("LAMMPS_SOURCE_DIR:"))
    python = str(Path(src).parent / "python")
    env["PYTHONPATH"] = python + (":" + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def _numbers(line: str):
    try:
        return [float(tok) for tok in line.split()]
    except ValueError:
        return None


def parse_thermo(log: str) -> list:
    """Thermo tables of a LAMMPS log: a list (one per run) of {column: np.ndarray}."""
    tables, header, rows = [], None, []
    for line in log.splitlines():
        words = line.split()
        if header is None:
            if words and words[0] == "Step" and len(words) > 1:
                header, rows = words, []
            continue
        if line.startswith("Loop time of") or line.startswith("ERROR"):
            tables.append(_table(header, rows))
            header = None
            continue
        values = _numbers(line)
        if values is not None and len(values) == len(header):
            rows.append(values)
    if header is not None:  # a run that died mid-way keeps what it printed
        tables.append(_table(header, rows))
    return tables


def _table(header, rows) -> dict:
    data = np.array(rows, dtype=float).reshape(len(rows), len(header))
    return {name: data[:, k] for k, name in enumerate(header)}


def read_dump(path) -> list:
    """Frames of a `dump custom` text file: [{"step", "natoms", "box", name: column...}]."""
    frames = []
    lines = Path(path).read_text().splitlines()
    k = 0
    while k < len(lines):
        if not lines[k].startswith("ITEM: TIMESTEP"):
            k += 1
            continue
        step = int(lines[k + 1])
        natoms = int(lines[k + 3])
        box = np.array([[float(v) for v in lines[k + 5 + d].split()[:2]] for d in range(3)])
        names = lines[k + 8].split()[2:]
        data = np.array([[float(v) for v in ln.split()] for ln in lines[k + 9:k + 9 + natoms]])
        data = data.reshape(natoms, len(names))
        if "id" in names:
            data = data[np.argsort(data[:, names.index("id")], kind="stable")]
        frame = {"step": step, "natoms": natoms, "box": box}
        frame.update({name: data[:, j] for j, name in enumerate(names)})
        frames.append(frame)
        k += 9 + natoms
    return frames


def relative_difference(a, b, floor: float = 0.0) -> float:
    """max |a - b| / max(|a|, |b|, floor) over all entries."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = max(np.max(np.abs(a)), np.max(np.abs(b)), floor)
    return float(np.max(np.abs(a - b)) / scale) if scale > 0 else 0.0


def cut_back_steps(run) -> dict:
    """{step: sub-steps} of the steps fix sissm logged as cut back ("Fix sissm ID: step N did
    not converge in M iterations; redone as K sub-steps of H", or "... step N went beyond the
    reach of the contact candidates ...; redone as ...", doc/fix_sissm.rst, "Unconverged
    steps"). With the default `unconverged cutback` a step that misses the tolerance is redone
    as sub-steps (or stops the run), never counted in f_ID[4]: a test that asks for every step
    to converge at its full length checks both."""
    return {int(step): int(k) for step, k in re.findall(
        r"Fix sissm \S+: step (\d+) (?:did not converge in \d+ iterations|went beyond the reach "
        r"of the contact candidates of the last neighbor list build); redone as (\d+) sub-steps",
        run.log)}
