"""The two versions of peri/nosb's bond passes (src/core/linalg/fused.h, doc/theory.rst
"Parallel evaluation"): plain, and on x86-64 processors with AVX2 and FMA a version whose
products and sums are fused multiply-adds, chosen at the pair style's init. The environment
variable PERI_SISSM_PASSES=plain selects the plain version on any processor. The log names the
version that ran, which every rank of a run shares (the fused one only where every rank can run
it); the two agree to round-off, and the plain one is the arithmetic of the builds without the
fused version, bit for bit."""
import subprocess
from pathlib import Path

import numpy as np
import pytest

from lammps_run import LMP, mpirun_prefix, parse_thermo, read_dump, run_deck

DECKS = Path(__file__).parent / "decks"
BLOCK = DECKS / "nosb_block.lmp"
# a vibrating 10^3 block (the elastic case of test_nosb_parallel.py): 200 steps of 0.1 us
ELASTIC = {"n": 10, "vib": 40.0, "vrand": 4.0, "nsteps": 200, "dt": 1e-7,
           "thermo_every": 10, "dump_every": 200}
PLAIN = {"PERI_SISSM_PASSES": "plain"}


def fused_expected() -> bool:
    """The build has both versions and this processor runs the fused one."""
    cache = (LMP.parent / "CMakeCache.txt").read_text()
    if "PERISISSM_CPU_DISPATCH:BOOL=ON" not in cache:
        return False
    flags = set()
    for line in Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("flags"):
            flags = set(line.split(":", 1)[1].split())
            break
    return {"avx2", "fma"} <= flags


def version_line(log: str) -> str:
    lines = [ln for ln in log.splitlines() if ln.startswith("Pair peri/nosb: bond passes")]
    assert len(lines) == 1, lines    # once per LAMMPS instance, not once per run
    return lines[0]


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("fused")
    default = run_deck(BLOCK, base / "default", variables=ELASTIC)
    plain = run_deck(BLOCK, base / "plain", variables=ELASTIC, env=PLAIN)
    return (default, read_dump(base / "default/dump.atoms")[-1],
            plain, read_dump(base / "plain/dump.atoms")[-1])


def test_the_log_names_the_version(runs):
    default, _, plain, _ = runs
    assert "without fused multiply-add" in version_line(plain.log)
    expected = "with fused multiply-add" if fused_expected() else "without fused multiply-add"
    assert expected in version_line(default.log)


def test_the_versions_agree_to_round_off(runs):
    default, fd, plain, fp = runs
    assert fd["step"] == fp["step"] == 200
    assert np.array_equal(fd["id"], fp["id"])
    if not fused_expected():
        # both ran the plain version: the same arithmetic, bit for bit
        for col in ("x", "y", "z", "vx", "vy", "vz"):
            assert np.array_equal(fd[col], fp[col]), col
        return
    # The block vibrates with displacements of up to 22 um and speeds of up to 13 m/s; one
    # rounding less per fused operation moves each force by ~1e-16 relative, and 200 steps of
    # an elastic vibration keep the difference small: bound 1e-11 of the motion (measured:
    # 7.9e-13 of the largest displacement, 8.9e-13 of the largest speed; PotEng 1.2e-14).
    disp = max(np.abs(fp[c] - fp["f_ref[" + str(k + 1) + "]"]).max()
               for k, c in enumerate("xyz"))
    speed = max(np.abs(fp[c]).max() for c in ("vx", "vy", "vz"))
    dx = max(np.abs(fd[c] - fp[c]).max() for c in "xyz")
    dv = max(np.abs(fd[c] - fp[c]).max() for c in ("vx", "vy", "vz"))
    assert dx < 1e-11 * disp and dv < 1e-11 * speed, (dx / disp, dv / speed)
    # and they are not the same run (the fused version did run)
    assert dx > 0.0 or dv > 0.0
    pe_d, pe_p = default.thermo[-1]["PotEng"][-1], plain.thermo[-1]["PotEng"][-1]
    assert abs(pe_d - pe_p) < 1e-10 * abs(pe_p)


def test_the_ranks_agree_on_the_version(tmp_path):
    """Rank 1 alone told PERI_SISSM_PASSES=plain (two programs of one MPI job, each with its
    own environment): every rank runs the plain version, as the log of rank 0 says, and the run
    is the plain 2-rank run bit for bit (a rank that ran the other version would give forces
    that differ in round-off)."""
    short = {**ELASTIC, "nsteps": 20, "thermo_every": 5, "dump_every": 20}
    plain = run_deck(BLOCK, tmp_path / "plain", nprocs=2, variables=short, env=PLAIN)
    work = tmp_path / "mixed"
    work.mkdir()
    lmp = [str(LMP), "-in", str(BLOCK.resolve()), "-log", "log.lammps", "-echo", "log",
           "-nocite"]
    for name, value in short.items():
        lmp += ["-var", name, str(value)]
    mpirun = mpirun_prefix(2)
    cmd = (mpirun[:1] + mpirun[3:] + ["-np", "1"] + lmp + [":", "-np", "1", "env",
                                                             "PERI_SISSM_PASSES=plain"] + lmp)
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=600,
                          stdin=subprocess.DEVNULL)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    log = (work / "log.lammps").read_text()
    assert "with 2 MPI tasks" in log or "2 by 1 by 1" in log + proc.stdout
    assert "without fused multiply-add" in version_line(log)
    mixed, ref = read_dump(work / "dump.atoms")[-1], read_dump(tmp_path / "plain/dump.atoms")[-1]
    assert mixed["step"] == ref["step"] == 20
    for col in ("id", "x", "y", "z", "vx", "vy", "vz"):
        assert np.array_equal(mixed[col], ref[col]), col
    assert np.array_equal(parse_thermo(log)[-1]["PotEng"], plain.thermo[-1]["PotEng"])
