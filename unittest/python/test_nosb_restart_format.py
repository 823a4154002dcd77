"""Restart files of peri/nosb (issue 9, item 9): the model is stored by name, the pair and
bond-family data carry a format version that is checked, and compute nosb/atom after
read_restart, when the pair has not evaluated the atoms, stops with an error instead of
reading state that does not exist (it crashed with a segmentation fault)."""
import struct

import numpy as np

from lammps_run import read_dump, run_deck

WRITE = """
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
lattice         sc 0.001
region          block block -0.5 3.5 -0.5 2.5 -0.5 2.5
create_box      1 block
create_atoms    1 region block
set             group all density 1000
set             group all volume 1.0e-9
pair_style      peri/nosb
pair_coeff      * * stvk 1.0e9 0.6e9 0.0030002 0.01 0.25
velocity        all set 0.0 0.0 0.0
compute         nosb all nosb/atom
fix             1 all nve
timestep        1.0e-7
run             0
displace_atoms  all ramp x 0.0 3.0e-5 x 0.0 0.003 units box
run             0
write_dump      all custom dump.before id c_nosb[2] c_nosb[3] modify format float %.17g
write_restart   restart.nosb
"""

READ = """
read_restart    restart.nosb
compute         nosb all nosb/atom
{before_run}
fix             1 all nve
run             0
write_dump      all custom dump.after id c_nosb[2] c_nosb[3] modify format float %.17g
"""


def written(tmp_path):
    run_deck(WRITE, tmp_path / "write")
    return (tmp_path / "write" / "restart.nosb").read_bytes()


def read_back(tmp_path, name, data, before_run=""):
    work = tmp_path / name
    work.mkdir()
    (work / "restart.nosb").write_bytes(data)
    return run_deck(READ.format(before_run=before_run), work, check=False)


def test_restart_keeps_the_model_and_state(tmp_path):
    data = written(tmp_path)
    run = read_back(tmp_path, "plain", data)
    assert run.ok, run.describe()
    before = read_dump(tmp_path / "write" / "dump.before")[0]
    after = read_dump(tmp_path / "plain" / "dump.after")[0]
    assert np.any(before["c_nosb[2]"] > 0)  # a strained state with energy
    for col in ("c_nosb[2]", "c_nosb[3]"):
        assert np.array_equal(before[col], after[col]), col


def test_compute_before_the_first_evaluation_is_an_error(tmp_path):
    # after read_restart the bond families exist, the pair's per-atom state does not; with
    # pair_modify compute no the run never makes it, and a dump of compute nosb/atom read it
    # (LAMMPS itself refuses write_dump and variables of computes before the first run)
    run = read_back(tmp_path, "early", written(tmp_path),
                    before_run="pair_modify compute no\n"
                               "dump early all custom 1 dump.early id c_nosb[2]")
    assert run.returncode > 0  # an error exit, not a signal (it was -11)
    assert any("Compute nosb/atom" in e and "run 0" in e for e in run.errors), run.errors


def test_unknown_model_name_and_other_versions_are_refused(tmp_path):
    data = written(tmp_path)
    # the pair data: version 5, setflag 1, the model name with its length (5 = "stvk\0")
    pair = struct.pack("iii", 5, 1, 5) + b"stvk\0"
    assert data.count(pair) == 1
    run = read_back(tmp_path, "name", data.replace(pair, struct.pack("iii", 5, 1, 5) + b"stvq\0"))
    assert any("model 'stvq'" in e and "allowed: linear, stvk, neohookean" in e
               for e in run.errors), run.errors
    run = read_back(tmp_path, "pairversion", data.replace(pair, struct.pack("iii", 1, 1, 5) +
                                                          b"stvk\0"))
    assert any("pair data of format version 1" in e for e in run.errors), run.errors
    # the bond families' global data: its size (13 doubles), then version 2.0, built 1.0
    family = struct.pack("i", 13 * 8) + struct.pack("dd", 2.0, 1.0)
    assert data.count(family) == 1
    run = read_back(tmp_path, "familyversion",
                    data.replace(family, struct.pack("i", 13 * 8) + struct.pack("dd", 1.0, 1.0)))
    assert any("bond families of another format version" in e for e in run.errors), run.errors
