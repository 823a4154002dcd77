#!/usr/bin/env python3
"""Speed and memory of the peridynamic styles on the projectile-impact deck (examples/impact),
and the speed goals of the package, from one invocation.

    /usr/bin/python3 examples/benchmarks/speed/bench_impact.py [--quick] [--rounds 3]
        [--steps 500 [100]] [--ranks 1 2] [--sizes small 54k] [--styles lps nosb ...]
        [--csv runs.csv] [--json summary.json] [--lmp build/lmp]

Configurations (--styles keys), each run on every rank count of --ranks:

    pmb, lps            in.impact.pmb, in.impact.lps (built-in peri/pmb, peri/lps; fix nve)
    nosb                in.impact.nosb: peri/nosb linear, fix nve (the bond passes' version
                        the plugin chooses: with fused multiply-adds on x86-64 processors with
                        AVX2 and FMA; the log's "Pair peri/nosb: bond passes" line is printed)
    plain               the same with PERI_SISSM_PASSES=plain: the passes without fused
                        multiply-adds (src/core/linalg/fused.h), for the gain of the other
    beside              peri/nosb linear x2: two serial runs of in.impact.nosb at once, pinned
                        to two cores (taskset), their mean time; only with 1 in --ranks.
                        How much two busy cores slow each other (on a virtual machine two
                        vCPUs may share one physical core's units), which bounds a 2-rank run
    stvk, neohookean    in.impact.nosb with that model in place of linear in pair_coeff (a
                        generated copy of the deck; the deck has no variable for the model)
    jacobi              in.impact.sissm: fix sissm iterations 5 tolerance 0 with -var opts
                        "solver jacobi external lagged" (the deck's default)
    block               the same with "solver krylov precond block external lagged"
    amg                 the same with "solver krylov precond amg external lagged" (information
                        only: its loop time includes the set-ups of PETSc's multigrid hierarchy)
    lockstep            not LAMMPS: lockstep.c (this folder, built with mpicc), the same
                        arithmetic alone and split over 2 ranks that meet in an MPI_Allreduce
                        every 64 chunks (about 10 ms of one rank's work, as often as a 54K force
                        evaluation's halo exchanges), nothing to communicate: its t1 / (2 t2) is
                        the 2-rank efficiency the machine gives perfectly balanced work with
                        free communication in the same minutes as the other runs (1 on two
                        idle cores of their own)

Sizes: small, the deck as it is (3487 particles, --steps default 500); 54k, the same decks with
impact54k.geometry (this folder; 53784 particles, --steps default 100) copied into the work
directory as impact.geometry. 54k runs lps, nosb, plain, beside, jacobi, block and lockstep
only. A second --steps value is the 54k step count; one value sets both. lockstep does 12000
chunks of arithmetic per run with the small size, 24000 with 54k (about 2 and 4 s alone on one
core), 1200 with --quick.

Runs alternate: each of the --rounds rounds (default 3) runs every configuration of every size
on every rank count once, so a slow moment of the shared machine hits them alike. Per
configuration the tables give the median over the rounds and the spread min..max; every ratio
is formed from medians of this invocation, and the efficiencies and goal lines once more
from the minima over the rounds (the best of N: a busy moment of the shared machine only ever
adds time, so with enough rounds the minimum is the undisturbed run). Printed:

- microseconds per particle-step, LAMMPS's "Loop time" / (steps x atoms), and the ratio to
  peri/lps at the same size and rank count;
- LAMMPS's "% CPU use" of every run (CPU time / wall time of the loop, mean over the ranks):
  well below 100 means other jobs took the cores;
- fix sissm: k = iterations per step, fix sissm's output 3 (f_integrate[3], mean over the run),
  its force evaluations inside the solve. The regular force evaluation that ends every step
  (thermo output, next step's lagged external forces) is NOT in k: a step costs k + 1
  evaluations. With t_nve the us per particle-step of peri/nosb linear with fix nve (an
  explicit step, which costs what the step's regular evaluation does), the cost of one
  iteration is given three ways, relative to t_nve: (t - t_nve) / k, what one iteration adds
  (the goal line uses this); t / k, the regular evaluation charged to the iterations;
  t / (k + 1), per force evaluation. jacobi takes exactly 5 iterations per step; krylov may
  take 4 (when CG meets its Eisenstat-Walker target early, one evaluation left is too few for
  a CG product and the check of its Newton iterate: that step ends with a SISSM sweep);
- 2-rank parallel efficiency t1 / (2 t2) where both rank counts ran; with beside, t_x2 / t1
  (1: the cores do not slow each other) and t_x2 / (2 t2), the 2-rank efficiency of peri/nosb
  linear against the rate of two busy cores (what is left is communication, waiting and the
  ranks' extra work); with lockstep, the machine's own ceiling t1 / (2 t2) of the probe and its
  share of the 2-rank time waiting at the meetings, and each configuration's efficiency over
  that ceiling (about 1: the code loses no more than the machine makes any lock-step 2-rank
  code lose); for the 2-rank runs, the share of the loop each rank spent inside MPI
  calls (waiting for the other rank and moving data; mpi_time.c, built with mpicc and preloaded
  into the ranks: mean over the ranks; a run whose loop interval mpi_time.c's report does not
  match has none, and the statistics leave it out) and t1 / own work, own work the sum over the ranks of
  (loop - MPI time): the efficiency is (1 - share) x t1 / own work, what communication and
  waiting cost times how fast the ranks did their halves (work_split.py counts the work itself
  in instructions, free of the machine's noise); the load balance of
  the 2-rank runs: owned atoms ave / max over the ranks (LAMMPS's Nlocal), the efficiency that
  equal work per atom and free communication would give (1 for the 54K cylinder, whose axis
  runs between lattice columns; the small deck's runs through one, so one rank holds it);
- memory per particle: peak resident memory (/usr/bin/time, per rank) summed over the ranks /
  atoms, and LAMMPS's "Per MPI rank memory allocation" avg x ranks / atoms, with the ratios to
  peri/lps;
- the goal lines with PASS/FAIL: peri/nosb linear / peri/lps <= 0.5 (1 and 2
  ranks); one fix sissm iteration / peri/nosb step <= 1.0 (jacobi and krylov block,
  (t - t_nve) / k); 2-rank efficiency at 54K >= 0.95 for nve (peri/nosb linear + fix nve),
  >= 0.9 for fix sissm (jacobi and krylov block), with lockstep followed by the ceiling and
  the efficiencies over it (information: PASS and FAIL judge the efficiencies themselves). A
  goal whose runs were not made says "not measured". Given twice: from the medians, and from
  the minima over the rounds.

--quick: 20 steps, 1 round, small size (a smoke test; explicit options override). --csv writes
one row per run (lockstep's: us per chunk, steps its chunks, atoms 0); --json the figures the
tables and goal lines print, unrounded, per statistic and size (summary()). A run that fails is
reported at the end, and the exit status is 1.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "solver"))
from bench_common import LOOP, REPO, build_info, print_build  # noqa: E402
from lammps_run import LMP, mpirun_prefix, parse_thermo  # noqa: E402
from progress import Progress  # noqa: E402

IMPACT = REPO / "examples" / "impact"
GEOMETRY = {"small": IMPACT / "impact.geometry", "54k": HERE / "impact54k.geometry"}
DEFAULT_STEPS = {"small": 500, "54k": 100}
PARTICLES = {"small": 3487, "54k": 53784}  # for the progress estimate only
QUICK_STEPS = 20

# "99.1% CPU use with 2 MPI tasks x 1 OpenMP threads" after each run
CPU = re.compile(r"([0-9.]+)% CPU use with")
MEMORY = re.compile(r"Per MPI rank memory allocation \(min/avg/max\) = "
                    r"([0-9.eE+-]+) \| ([0-9.eE+-]+) \| ([0-9.eE+-]+) Mbytes")
RSS = re.compile(r"PEAKRSS (\d+)")       # /usr/bin/time -f "PEAKRSS %M": kilobytes, per rank
AMG_SETUPS = re.compile(r"(\d+) set-ups? of the AMG hierarchy")
PASSES = re.compile(r"^Pair peri/nosb: bond passes (.*)$", re.M)
# "Nlocal:        27013.5 ave       27702 max       26325 min" (owned atoms per rank, at the end)
NLOCAL = re.compile(r"^Nlocal:\s+([0-9.eE+-]+) ave\s+([0-9.eE+-]+) max", re.M)
ITERATIONS = "f_integrate[3]"            # fix sissm output 3: mean iterations per step
# mpi_time.c, preloaded into the multi-rank runs, one line per interval between two barriers:
# "MPITIME rank 0 interval 3 loop 4.55 mpi 0.25"
MPI_TIME_SRC = HERE / "mpi_time.c"
MPITIME = re.compile(r"^MPITIME rank (\d+) interval (\d+) loop ([0-9.eE+-]+) mpi ([0-9.eE+-]+)",
                     re.M)
# lockstep.c, the machine's own 2-rank ceiling: "LOCKSTEP ranks 2 chunks 24000 every 64 seconds
# 2.1 mpi 0.2 checksum 1572.1"; chunks per run (about 4 s alone on one core of the 2026 guests at
# 54k), and chunks between two meetings of the ranks (about 10 ms of one rank's work: a 54K force
# evaluation on 2 ranks meets the other rank about as often, in its halo exchanges)
LOCKSTEP_SRC = HERE / "lockstep.c"
LOCKSTEP = re.compile(r"^LOCKSTEP ranks (\d+) chunks (\d+) every (\d+) seconds ([0-9.eE+-]+) "
                      r"mpi ([0-9.eE+-]+)", re.M)
PROBE_CHUNKS = {"small": 12000, "54k": 24000}
QUICK_PROBE_CHUNKS = 1200
PROBE_EVERY = 64


@dataclass(frozen=True)
class Config:
    key: str                 # --styles name
    label: str               # row name in the tables
    deck: str                # file in examples/impact
    model: str = ""          # peri/nosb model replacing linear in the deck's pair_coeff
    opts: str = ""           # fix sissm options (-var opts of in.impact.sissm)
    large: bool = False      # also runs at the 54k size
    env: tuple = ()          # environment variables of the run, (name, value) pairs
    beside: bool = False     # two serial runs at once, one pinned to each of two cores
    probe: bool = False      # lockstep.c, not LAMMPS: the machine's 2-rank ceiling

    def runs_on(self, ranks: int) -> bool:
        """Whether the configuration runs on that rank count (beside: serial runs only)."""
        return not self.beside or ranks == 1


CONFIGS = [
    Config("pmb", "peri/pmb", "in.impact.pmb"),
    Config("lps", "peri/lps", "in.impact.lps", large=True),
    Config("nosb", "peri/nosb linear", "in.impact.nosb", large=True),
    Config("plain", "peri/nosb linear plain", "in.impact.nosb", large=True,
           env=(("PERI_SISSM_PASSES", "plain"),)),
    Config("beside", "peri/nosb linear x2", "in.impact.nosb", large=True, beside=True),
    Config("stvk", "peri/nosb stvk", "in.impact.nosb", model="stvk"),
    Config("neohookean", "peri/nosb neohookean", "in.impact.nosb", model="neohookean"),
    Config("jacobi", "sissm jacobi", "in.impact.sissm", opts="solver jacobi external lagged",
           large=True),
    Config("block", "sissm krylov block", "in.impact.sissm",
           opts="solver krylov precond block external lagged", large=True),
    Config("amg", "sissm krylov amg", "in.impact.sissm",
           opts="solver krylov precond amg external lagged"),
    Config("lockstep", "machine lockstep probe", "", large=True, probe=True),
]
BY_KEY = {c.key: c for c in CONFIGS}
SISSM = ("jacobi", "block", "amg")
ACCEPTED_SISSM = ("jacobi", "block")     # the per-iteration goal line


class RunFailed(Exception):
    pass


def deck_path(config: Config, workdir: Path) -> Path:
    """The deck a configuration runs: the example itself, or a copy with another model."""
    deck = IMPACT / config.deck
    if not config.model:
        return deck
    text = deck.read_text()
    linear = "pair_coeff      * * linear "
    assert text.count(linear) == 1, f"{deck}: no single '{linear}' line"
    copy = workdir / f"{config.deck}-{config.model}"
    copy.write_text(text.replace(linear, f"pair_coeff      * * {config.model} "))
    return copy


def build_mpi_time(tmp: Path):
    """mpi_time.c built as a library to preload (None, with the reason, where it cannot be)."""
    return mpicc(MPI_TIME_SRC, tmp / "libmpi_time.so", ["-shared", "-fPIC"])


def mpicc(source: Path, out: Path, flags: list):
    """source built with mpicc -O2 into out: (out, "") or (None, the reason it could not be)."""
    try:
        done = subprocess.run(["mpicc", *flags, "-O2", "-o", str(out), str(source)],
                              capture_output=True, text=True)
    except OSError as err:
        return None, f"mpicc: {err}"
    if done.returncode != 0:
        return None, "mpicc: " + (done.stderr.strip().splitlines() or ["failed"])[-1]
    return out, ""


def start(config: Config, size: str, ranks: int, steps: int, workdir: Path, lmp: Path,
          prefix: list, preload: Path | None = None,
          launcher: list | None = None) -> subprocess.Popen:
    """Start one run of a configuration in a fresh workdir (prefix: e.g. taskset; preload: the
    library of mpi_time.c, given to the ranks of a multi-rank run; launcher: what runs each
    rank's lmp, by default /usr/bin/time writing the peak memory to rss.txt)."""
    workdir.mkdir(parents=True)
    shutil.copy(GEOMETRY[size], workdir / "impact.geometry")
    mpirun = mpirun_prefix(ranks)
    if mpirun and preload:
        mpirun += ["-x", f"LD_PRELOAD={preload}"]
    if launcher is None:
        launcher = ["/usr/bin/time", "-a", "-o", str(workdir / "rss.txt"), "-f", "PEAKRSS %M"]
    cmd = prefix + mpirun + launcher + [
        str(lmp), "-in", str(deck_path(config, workdir)), "-log", str(workdir / "log.lammps"),
        "-echo", "log", "-nocite", "-var", "nsteps", str(steps), "-var", "thermo_every",
        str(steps)]
    if config.opts:
        cmd += ["-var", "opts", config.opts]
    return subprocess.Popen(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, stdin=subprocess.DEVNULL,
                            env={**os.environ, **dict(config.env)} if config.env else None)


def finish(proc: subprocess.Popen, workdir: Path, ranks: int) -> dict:
    """Wait for a run started by start(); return parse_run() of what it wrote."""
    out, err = proc.communicate()
    log, rss = workdir / "log.lammps", workdir / "rss.txt"
    text = log.read_text(errors="replace") if log.exists() else ""
    errors = [ln for ln in (out + text).splitlines() if ln.startswith("ERROR")]
    if proc.returncode != 0 or errors or not LOOP.search(text):
        tail = errors[:1] or (out + err).splitlines()[-10:]
        raise RunFailed(f"exit {proc.returncode}: " + " | ".join(tail))
    return parse_run(text, rss.read_text() if rss.exists() else "", ranks, err)


def run_once(config: Config, size: str, ranks: int, steps: int, workdir: Path,
             lmp: Path, preload: Path | None = None, probe: tuple = ()) -> dict:
    """Run one configuration once in a fresh workdir; return parse_run() of what it wrote. A
    beside configuration starts two serial runs at once, each pinned to one of the first two
    cores this process may use (unpinned where it may use only one), and returns the first's
    with the mean of the two's times and CPU use. The probe runs lockstep.c instead, probe =
    (its binary, chunks): run_probe()."""
    if config.probe:
        return run_probe(*probe, ranks)
    if not config.beside:
        return finish(start(config, size, ranks, steps, workdir, lmp, [], preload), workdir,
                      ranks)
    cores = sorted(os.sched_getaffinity(0))[:2]
    pins = [["taskset", "-c", str(c)] for c in cores] if len(cores) == 2 else [[], []]
    dirs = [workdir / f"core{k}" for k in (0, 1)]
    procs = [start(config, size, 1, steps, d, lmp, pin) for d, pin in zip(dirs, pins)]
    runs, failed = [], None
    for proc, d in zip(procs, dirs):      # both waited for, even when the first failed
        try:
            runs.append(finish(proc, d, 1))
        except RunFailed as err:
            failed = failed or err
    if failed:
        raise failed
    return {**runs[0], "us": statistics.mean(r["us"] for r in runs),
            "cpu": statistics.mean(r["cpu"] for r in runs)}


def run_probe(binary: Path, chunks: int, ranks: int) -> dict:
    """One run of lockstep.c on that many ranks: the keys of parse_run(), with us the
    microseconds per chunk of the whole (wall time / chunks) and mpi_share the ranks' mean share
    of it spent waiting at the meetings (the rest NaN or empty: no atoms, no LAMMPS log)."""
    done = subprocess.run(mpirun_prefix(ranks) + [str(binary), str(chunks), str(PROBE_EVERY)],
                          capture_output=True, text=True, stdin=subprocess.DEVNULL)
    found = LOCKSTEP.findall(done.stdout)
    if done.returncode != 0 or not found or int(found[-1][0]) != ranks:
        tail = (done.stdout + done.stderr).strip().splitlines()[-3:]
        raise RunFailed(f"lockstep exit {done.returncode}: " + " | ".join(tail))
    seconds, mpi = float(found[-1][3]), float(found[-1][4])
    us = seconds / chunks * 1e6
    nan = float("nan")
    return dict(us=us, atoms=0, mpi_share=mpi / seconds, work_us=ranks * us * (1 - mpi / seconds),
                cpu=nan, iterations=None, amg_setups=None, passes="", nlocal_ave=nan,
                balance=nan, rss_bytes=nan, lammps_bytes=nan)


def parse_run(log: str, rss: str, ranks: int, stderr: str = "") -> dict:
    """What one run's log, /usr/bin/time file and stderr say: microseconds per particle-step,
    atoms, % CPU use, memory (bytes per particle, two ways), for fix sissm the iterations per
    step (None without it) and the set-ups of the AMG hierarchy, and where mpi_time.c reported
    (multi-rank runs) the share of the loop spent inside MPI calls (mean over the ranks) and the
    ranks' own work, the sum over the ranks of (loop - MPI time) per particle-step, i.e. ranks
    x us x (1 - share) (NaN without)."""
    seconds, procs, steps, atoms = LOOP.findall(log)[-1]
    if int(procs) != ranks:
        raise RunFailed(f"ran on {procs} procs, not {ranks}")
    atoms = int(atoms)
    cpu = CPU.findall(log)
    table = parse_thermo(log)[-1]
    rss_kb = [int(v) for v in RSS.findall(rss)]
    setups = AMG_SETUPS.findall(log)
    passes = PASSES.findall(log)
    nlocal = NLOCAL.findall(log)
    ave, most = (float(v) for v in nlocal[-1]) if nlocal else (float("nan"), float("nan"))
    us = float(seconds) / (int(steps) * atoms) * 1e6
    loop = run_loop_intervals(MPITIME.findall(stderr), ranks, float(seconds))
    # each rank's share of its own loop interval (the ranks leave the closing barrier a moment
    # apart), applied to LAMMPS's loop time
    share = statistics.mean(mpi / t for t, mpi in loop) if loop else float("nan")
    return dict(
        us=us, atoms=atoms, mpi_share=share, work_us=ranks * us * (1 - share),
        cpu=float(cpu[-1]) if cpu else float("nan"),
        iterations=float(table[ITERATIONS][-1]) if ITERATIONS in table else None,
        amg_setups=int(setups[-1]) if setups else None,
        passes=passes[0] if passes else "",
        nlocal_ave=ave, balance=ave / most if nlocal else float("nan"),
        rss_bytes=sum(rss_kb) * 1024 / atoms if len(rss_kb) == ranks else float("nan"),
        lammps_bytes=float(MEMORY.findall(log)[-1][1]) * 2**20 * ranks / atoms)


def run_loop_intervals(found: list, ranks: int, seconds: float) -> list:
    """[(loop, mpi)] of each rank in the run loop, from mpi_time.c's intervals [(rank,
    interval, loop, mpi)]: the interval, the same on every rank (every barrier is collective),
    whose loop time averaged over the ranks is LAMMPS's loop time (its average of the same
    per-rank times) within 1 %, the closest one; [] where none is (no report, or a barrier
    inside the loop cut it)."""
    by = {}
    for rank, k, loop, mpi in found:
        by.setdefault(int(k), {})[int(rank)] = (float(loop), float(mpi))
    whole = [k for k, per in by.items() if len(per) == ranks]
    if ranks < 2 or not whole:
        return []
    def off(k):
        return abs(statistics.mean(t for t, _ in by[k].values()) / seconds - 1)
    best = min(whole, key=off)
    return list(by[best].values()) if off(best) < 0.01 else []


def finite(runs: list, name: str) -> list:
    """The values of name over the runs that have a finite one (mpi_time.c's figures are NaN in
    a run whose loop interval its report did not match)."""
    return [r[name] for r in runs if r[name] is not None and math.isfinite(r[name])]


class Results:
    """The runs of one invocation, {(size, key, ranks): [parse_run() of each round]}, and the
    medians (or, from best(), the minima) and ratios formed from them (None where a run is
    missing)."""

    def __init__(self, stat=statistics.median):
        self.runs = {}
        self.stat = stat

    def best(self) -> "Results":
        """The same runs, every statistic the minimum over the rounds instead of the median."""
        other = Results(min)
        other.runs = self.runs
        return other

    def get(self, size, key, ranks) -> list:
        return self.runs.get((size, key, ranks), [])

    def med(self, size, key, ranks, name="us"):
        """The statistic of this view (median, or minimum from best()) over the rounds' finite
        values (None without one)."""
        values = finite(self.get(size, key, ranks), name)
        return self.stat(values) if values else None

    def ratio(self, size, key, ranks, name="us"):
        """key over peri/lps, each by med()."""
        a, b = self.med(size, key, ranks, name), self.med(size, "lps", ranks, name)
        return a / b if a and b else None

    def per_iteration(self, size, key, ranks, extra=0, marginal=False):
        """(us per particle-step / (k + extra)) / us per particle-step of peri/nosb + nve; with
        marginal, ((us per particle-step - that of peri/nosb + nve) / k) / the latter: what one
        iteration adds to the step's regular evaluation, which costs an explicit step."""
        t, k, base = (self.med(size, key, ranks), self.med(size, key, ranks, "iterations"),
                      self.med(size, "nosb", ranks))
        if not (t and k and base):
            return None
        return (t - base) / k / base if marginal else t / (k + extra) / base

    def efficiency(self, size, key):
        t1, t2 = self.med(size, key, 1), self.med(size, key, 2)
        return t1 / (2 * t2) if t1 and t2 else None

    def split(self, size, key):
        """(share of the 2-rank loop inside MPI calls, t1 / own work): the 2-rank efficiency
        t1 / (2 t2) is (1 - share) x t1 / own work, where own work is the sum over the ranks
        of (loop - MPI time) per particle-step. The first factor is what waiting for the other
        rank and moving data cost; the second, how fast the ranks
        did their halves against the serial run doing the whole (less than 1: extra work on 2
        ranks, or two busy cores slowing each other). None without mpi_time.c's report."""
        t1, share, work = (self.med(size, key, 1), self.med(size, key, 2, "mpi_share"),
                           self.med(size, key, 2, "work_us"))
        if not (t1 and share is not None and work):
            return None
        return share, t1 / work

    def split_text(self, size, keys) -> str:
        """"label share % / t1 over own work" of split() for each key that has it, joined."""
        return ", ".join(f"{BY_KEY[k].label} {100 * sp[0]:.1f} % / {sp[1]:.2f}" for k in keys
                         if (sp := self.split(size, k)))

    def beside(self, size):
        """(t_x2 / t1, t_x2 / (2 t2)) of peri/nosb linear, t_x2 from two serial runs at once:
        how much the two cores slow each other, and the 2-rank efficiency against the rate of
        two busy cores (None without those runs)."""
        tx, t1, t2 = (self.med(size, "beside", 1), self.med(size, "nosb", 1),
                      self.med(size, "nosb", 2))
        return (tx / t1, tx / (2 * t2)) if tx and t1 and t2 else None

    def ceiling(self, size):
        """(t1 / (2 t2), 2-rank share waiting) of lockstep.c in the rounds of this size: the
        2-rank efficiency the machine gave perfectly balanced arithmetic with free communication
        in the same minutes (None without the probe's runs)."""
        eff = self.efficiency(size, "lockstep")
        return (eff, self.med(size, "lockstep", 2, "mpi_share")) if eff else None

    def against_ceiling(self, size, keys) -> str:
        """"label efficiency / ceiling" for each key with both, joined."""
        top = self.ceiling(size)
        return ", ".join(f"{BY_KEY[k].label} {e / top[0]:.2f}" for k in keys
                         if top and (e := self.efficiency(size, k)))


W = 32          # width of a table cell


def rank_text(r: int) -> str:
    return f"{r} rank" + "s" * (r > 1)


def table(title: str, labels: list, ranks: list, text, width: int = W) -> None:
    """A table with one row per label and one column per rank count; text(label, ranks) gives
    a cell."""
    print("\n" + title)
    print(f"{'configuration':<22}" + "".join(f"  {rank_text(r):>{width}}" for r in ranks))
    for label, key in labels:
        print(f"{label:<22}" + "".join(f"  {text(key, r):>{width}}" for r in ranks))


def missing(key: str, r: int) -> str:
    """A table cell without runs: empty where the configuration does not run, else failed."""
    return "failed" if BY_KEY[key].runs_on(r) else ""


def print_size(res: Results, size: str, configs: list, ranks: list, steps: int) -> None:
    """The tables of one size."""
    atoms = next((r[0]["atoms"] for (s, k, _), r in res.runs.items()
                  if s == size and not BY_KEY[k].probe), "?")
    print(f"\n== {size}: {atoms} atoms, {steps} steps ==")
    probe = [c for c in configs if c.probe]
    configs = [c for c in configs if not c.probe]
    rows = [(c.label, c.key) for c in configs]
    for c in configs:
        versions = sorted({x["passes"] for r in ranks for x in res.get(size, c.key, r)} - {""})
        if versions:
            print(f"{c.label}: bond passes {' / '.join(versions)}")

    def speed(key, r):
        found = res.get(size, key, r)
        if not found:
            return missing(key, r)
        lo, hi = min(x["us"] for x in found), max(x["us"] for x in found)
        ratio = res.ratio(size, key, r)
        return (f"{res.med(size, key, r):.3f} ({lo:.3f}..{hi:.3f})"
                + (f" {ratio:5.2f}x" if ratio else ""))
    table("us per particle-step: median (min..max), ratio to peri/lps", rows, ranks, speed, 34)
    table("% CPU use of each run (LAMMPS; well below 100: the machine was busy)", rows, ranks,
          lambda key, r: " ".join(f"{x['cpu']:.1f}" for x in res.get(size, key, r)))

    solvers = [(c.label, c.key) for c in configs if c.key in SISSM]
    if solvers:
        def sissm(key, r):
            k, one = res.med(size, key, r, "iterations"), res.per_iteration(size, key, r)
            if k is None:
                return "failed"
            if one is None:
                return f"k {k:.2f}, no peri/nosb run"
            return (f"k {k:.2f}: {res.per_iteration(size, key, r, marginal=True):.2f}x | "
                    f"{one:.2f}x / {res.per_iteration(size, key, r, 1):.2f}x")
        table("fix sissm iterations 5 tolerance 0: k = iterations per step (" + ITERATIONS
              + ", mean over the run), WITHOUT\nthe regular force evaluation that ends each "
              "step (a step costs k + 1 evaluations). Cost of one iteration, relative to\n"
              "t_nve, the us per particle-step of peri/nosb linear + nve: (t - t_nve) / k, what "
              "an iteration adds to the\nstep's regular evaluation (which costs an explicit "
              "step) | t / k, the regular evaluation charged to the\niterations / t / (k + 1), "
              "per force evaluation", solvers, ranks, sissm, 40)
        if "amg" in [key for _, key in solvers]:
            setups = sorted({x["amg_setups"] for r in ranks for x in res.get(size, "amg", r)})
            print(f"(sissm krylov amg: information only; its loop time includes the set-ups of "
                  f"the AMG hierarchy, {setups} per run)")

    if 1 in ranks and 2 in ranks:
        print()
        views = (("medians", res), ("minima", res.best()))
        for which, stats in views:
            print(f"2-rank parallel efficiency t1 / (2 t2) of the {which}: " + ", ".join(
                f"{c.label} {e:.2f}" for c in configs if (e := stats.efficiency(size, c.key))))
        for which, stats in views:
            if (parts := stats.split_text(size, [c.key for c in configs + probe])):
                print(f"2 ranks ({which}): % of the loop inside MPI calls, waits and transfers "
                      f"(mean over the ranks) / t1 / (own work: sum over the ranks of loop - "
                      f"MPI time): " + parts)
        for which, stats in views:
            if probe and (top := stats.ceiling(size)):
                base = stats.med(size, "lockstep", 1)
                print(f"the machine's own 2-rank ceiling ({which}; lockstep.c: the same "
                      f"arithmetic alone and split over 2 ranks that meet every {PROBE_EVERY} "
                      f"chunks, {base * PROBE_EVERY / 1000:.1f} ms of one rank's work, no data to "
                      f"move): t1 / (2 t2) {top[0]:.2f}, {100 * top[1]:.1f} % of the 2-rank time "
                      f"waiting; each efficiency over it: "
                      + stats.against_ceiling(size, [c.key for c in configs]))
        for which, stats in views:
            if (both := stats.beside(size)):
                print(f"both cores busy ({which}): two serial peri/nosb linear runs at once, "
                      f"one per core, each take {both[0]:.2f} x a lone one; the 2-rank "
                      f"efficiency of peri/nosb linear against that rate, t_x2 / (2 t2): "
                      f"{both[1]:.2f}")
    balance = sorted({x["balance"] for c in configs for x in res.get(size, c.key, 2)})
    if balance:
        print("load balance on 2 ranks, owned atoms ave / max (LAMMPS's Nlocal at the end of the "
              "run; the efficiency that equal work per atom and free communication would "
              "give): " + ", ".join(f"{b:.4f}" for b in balance))

    def memory(key, r):
        if not res.get(size, key, r):
            return missing(key, r)
        parts = []
        for name in ("rss_bytes", "lammps_bytes"):
            ratio = res.ratio(size, key, r, name)
            parts.append(f"{res.med(size, key, r, name):.0f}"
                         + (f" ({ratio:.2f}x)" if ratio else ""))
        return " | ".join(parts)
    table("memory, bytes per particle (ratio to peri/lps): peak RSS summed over the ranks / "
          "atoms | LAMMPS's\nper-rank allocation avg x ranks / atoms", rows, ranks, memory, 36)


def goal(text: str, values: list, limit: float, expected: int, above: bool = False) -> dict:
    """One goal line: values [(name, value)] against <= limit (>= with above); "not measured"
    unless all expected values are there."""
    if len(values) < expected:
        outcome = "not measured"
    else:
        ok = all(v >= limit if above else v <= limit for _, v in values)
        outcome = "PASS" if ok else "FAIL"
    return dict(text=text, values=values, limit=limit, above=above, outcome=outcome)


def goals(res: Results, sizes: list, ranks: list) -> list:
    """The goal lines of one statistic (goal() of each)."""
    both = [r for r in (1, 2) if r in ranks]
    found = []
    for size in sizes:
        found.append(goal(f"[{size}] peri/nosb linear / peri/lps <= 0.5 (1 and 2 ranks)",
                          [(rank_text(r), v) for r in both if (v := res.ratio(size, "nosb", r))],
                          0.5, 2))
        found.append(goal(
            f"[{size}] one fix sissm iteration / peri/nosb step <= 1.0 (jacobi and krylov "
            "block; (t - t_nve) / k)",
            [(f"{BY_KEY[k].label} {rank_text(r)}", v) for k in ACCEPTED_SISSM for r in both
             if (v := res.per_iteration(size, k, r, marginal=True))], 1.0, 4))
    nve = [("nve", e) for e in [res.efficiency("54k", "nosb")] if e]
    sissm = [(BY_KEY[k].label, e) for k in ACCEPTED_SISSM if (e := res.efficiency("54k", k))]
    found.append(goal("[54k] 2-rank efficiency >= 0.95 nve (peri/nosb linear)", nve, 0.95, 1,
                      above=True))
    found.append(goal("[54k] 2-rank efficiency >= 0.9 sissm (jacobi and krylov block)", sissm,
                      0.9, 2, above=True))
    return found


def print_goal(line: dict) -> None:
    shown = ", ".join(f"{n} {v:.2f}" for n, v in line["values"]) or "(not run)"
    print(f"  {line['text']}: {shown} -> {line['outcome']}")


def print_goals(res: Results, sizes: list, ranks: list, which: str) -> None:
    print(f"\ngoals ({which}):")
    lines = goals(res, sizes, ranks)
    for line in lines[:-1]:
        print_goal(line)
    if (both := res.beside("54k")):
        print(f"    (both cores busy: two serial runs at once each take {both[0]:.2f} x a lone "
              f"one; the nve efficiency against that rate {both[1]:.2f})")
    print_goal(lines[-1])
    if (top := res.ceiling("54k")):
        print(f"    (the machine's own ceiling in these rounds, lockstep.c: {top[0]:.2f}; each "
              f"efficiency over it: "
              + res.against_ceiling("54k", ("nosb",) + ACCEPTED_SISSM) + ")")
    if (parts := res.split_text("54k", ("nosb",) + ACCEPTED_SISSM + ("lockstep",))):
        print("    (2 ranks, % of the loop inside MPI calls / the ranks' own work against the "
              "serial run: " + parts + ")")


def summary(res: Results, sizes: list, configs: dict, ranks: list) -> dict:
    """What the tables and goal lines print, unrounded, for --json: per statistic ("medians",
    "minima") and size, per configuration and rank count the us per particle-step ("us"), its
    ratio to peri/lps ("ratio"), for fix sissm the iterations per step ("k") and
    (t - t_nve) / k / t_nve ("iteration"); per configuration the 2-rank efficiency t1 / (2 t2)
    ("efficiency") and [share inside MPI, t1 / own work] ("split"); "ceiling" [lockstep.c's
    t1 / (2 t2), its share waiting] and "beside" [t_x2 / t1, t_x2 / (2 t2)] (null where not
    measured); and the goal lines ("goals")."""
    out = {}
    for which, stats in (("medians", res), ("minima", res.best())):
        view = {}
        for size in sizes:
            keys = [c.key for c in configs[size]]
            per = {k: {str(r): dict(us=stats.med(size, k, r), ratio=stats.ratio(size, k, r),
                                    k=stats.med(size, k, r, "iterations"),
                                    iteration=stats.per_iteration(size, k, r, marginal=True))
                       for r in ranks if stats.get(size, k, r)} for k in keys}
            view[size] = dict(
                runs=per, efficiency={k: stats.efficiency(size, k) for k in keys},
                split={k: stats.split(size, k) for k in keys}, ceiling=stats.ceiling(size),
                beside=stats.beside(size))
        view["goals"] = goals(stats, sizes, ranks)
        out[which] = view
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help=f"smoke test: {QUICK_STEPS} steps, 1 round, small size")
    ap.add_argument("--rounds", type=int, default=None, help="alternating rounds (default 3)")
    ap.add_argument("--steps", type=int, nargs="+", default=None,
                    help="steps of the small size [and of 54k] (default 500 100)")
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--sizes", nargs="+", choices=list(GEOMETRY), default=None)
    ap.add_argument("--styles", nargs="+", choices=list(BY_KEY), default=list(BY_KEY))
    ap.add_argument("--csv", type=Path, help="write one row per run here")
    ap.add_argument("--json", type=Path, help="write the printed figures, unrounded, here")
    ap.add_argument("--lmp", type=Path, default=LMP)
    args = ap.parse_args()
    rounds = args.rounds or (1 if args.quick else 3)
    sizes = args.sizes or (["small"] if args.quick else list(GEOMETRY))
    given = args.steps or ([QUICK_STEPS] if args.quick else None)
    steps = ({s: given[min(k, len(given) - 1)] for k, s in enumerate(GEOMETRY)} if given
             else DEFAULT_STEPS)
    configs = {s: [c for c in CONFIGS if c.key in args.styles and (s == "small" or c.large)]
               for s in sizes}
    start = build_info()

    # rounds x (size, configuration, ranks), round-robin; progress weighted by particle-steps
    # (x6 for fix sissm's evaluations)
    order = [(s, c, r) for s in sizes for c in configs[s] for r in args.ranks if c.runs_on(r)]
    chunks = {s: QUICK_PROBE_CHUNKS if args.quick else PROBE_CHUNKS[s] for s in sizes}
    # (a chunk of the probe takes about as long as 80 particle-steps)
    weight = {(s, c): (80 * chunks[s] if c.probe else steps[s] * PARTICLES[s])
              * (6 if c.opts else 1) * (2 if c.beside else 1) for s, c, _ in order}
    res, failures, rows = Results(), [], []
    with tempfile.TemporaryDirectory(prefix="bench_impact-") as tmp:
        preload, why = build_mpi_time(Path(tmp)) if max(args.ranks) > 1 else (None, "")
        lockstep = None
        if any(c.probe for _, c, _ in order):
            lockstep, no_probe = mpicc(LOCKSTEP_SRC, Path(tmp) / "lockstep", [])
            if not lockstep:
                failures.append(f"machine lockstep probe: {no_probe}")
                order = [(s, c, r) for s, c, r in order if not c.probe]
        progress = Progress(rounds * sum(weight[s, c] for s, c, _ in order), "bench_impact")
        for n in range(1, rounds + 1):
            for size, config, ranks in order:
                what = f"{size} {config.label} on {ranks} rank(s), round {n}"
                try:
                    run = run_once(config, size, ranks, steps[size],
                                   Path(tmp) / f"{size}-{config.key}-{ranks}-{n}", args.lmp,
                                   preload, (lockstep, chunks[size]))
                except RunFailed as err:
                    failures.append(f"{what}: {err}")
                else:
                    res.runs.setdefault((size, config.key, ranks), []).append(run)
                    rows.append(dict(round=n, size=size, config=config.key, ranks=ranks,
                                     steps=chunks[size] if config.probe else steps[size],
                                     **run))
                progress.step(what, weight[size, config])
    progress.done()
    if args.csv and rows:
        with open(args.csv, "w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)

    print("Projectile impact (examples/impact): microseconds per particle-step = LAMMPS loop "
          "time / (steps x atoms);")
    print(f"median of {rounds} alternating round(s) (min..max); ratios of medians to peri/lps at "
          "the same size and rank count")
    print_build(start)
    if why:
        print(f"(no MPI timing of the multi-rank runs: {why})")
    for size in sizes:
        print_size(res, size, configs[size], args.ranks, steps[size])
    print_goals(res, sizes, args.ranks, "medians of this invocation")
    print_goals(res.best(), sizes, args.ranks, "minima over the rounds of this invocation; "
                     "a busy machine only adds time")
    if args.json:
        args.json.write_text(json.dumps(summary(res, sizes, configs, args.ranks), indent=1))
    if failures:
        print("\nfailed runs:")
        for line in failures:
            print("  " + line)
        sys.exit(1)


if __name__ == "__main__":
    main()
