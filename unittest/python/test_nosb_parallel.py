"""peri/nosb on several MPI ranks and across restart files (issue 3, doc/pair_peri_nosb.rst 'Restart and
parallel runs'): results do not depend on the number of ranks beyond round-off, and a run split
by write_restart/read_restart continues as if it had not been split."""
from pathlib import Path

import numpy as np
import pytest

from lammps_run import read_dump, relative_difference, run_deck

DECKS = Path(__file__).parent / "decks"
BLOCK = DECKS / "nosb_block.lmp"
CONTINUE = DECKS / "nosb_continue.lmp"

# A 10^3 block vibrating at ~3% strain with a random velocity pattern on top: every particle
# moves differently, so every bond is exercised.
ELASTIC = {"n": 10, "vib": 40.0, "vrand": 4.0, "nsteps": 200, "dt": 1e-7,
           "thermo_every": 10, "dump_every": 100}
# The same with breakable bonds (s00 = 1%): about 650 of the 1000 particles lose bonds, so
# the families, s0 and the shape tensors change during the run.
FRACTURE = {**ELASTIC, "brk": "yes", "s00": 0.01}
SUMS = ("PotEng", "KinEng", "TotEng")   # thermo sums over atoms (nosb_block.lmp: %.17g)
DUMPED = ("id", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "c_nosb[1]", "c_nosb[2]",
          "c_nosb[3]")                  # dump_modify format float %.17g: round-trips a double
# A sum of n terms of one sign (energy densities, kinetic energies, contact energies) changes
# by at most 2 (n - 1) 2^-53 of itself when its terms are added in another order; n is at most
# a few thousand here (1000 atoms and their contact pairs), so 1e-12.
REORDERED_SUM = 1e-12


def damage_column(frame):
    return frame["c_nosb[1]"]


@pytest.mark.mpi
@pytest.mark.parametrize("case", ["elastic", "fracture"])
def test_one_and_two_ranks_agree(tmp_path, case):
    # Families are sorted by atom ID and each owned atom sums its own bonds, so the per-atom
    # arithmetic is the same on any number of ranks: positions, velocities, forces and damage
    # are bit-identical (the issue asked for 1e-8; exact is what the design gives, even in
    # the chaotic fracture case). Only the global sums of the thermo output are reduced in
    # another order: by REORDERED_SUM at most (measured 1.5e-15).
    args = ELASTIC if case == "elastic" else FRACTURE
    one = run_deck(BLOCK, tmp_path / "np1", nprocs=1, variables=args)
    two = run_deck(BLOCK, tmp_path / "np2", nprocs=2, variables=args)
    assert "with 2 MPI tasks" in two.log
    t1, t2 = one.thermo[-1], two.thermo[-1]
    assert np.array_equal(t1["Step"], t2["Step"]) and t1["Step"][-1] == 200
    for col in SUMS:
        assert relative_difference(t1[col], t2[col]) < REORDERED_SUM, col
    d1, d2 = read_dump(tmp_path / "np1/dump.atoms"), read_dump(tmp_path / "np2/dump.atoms")
    assert [f["step"] for f in d1] == [0, 100, 200] == [f["step"] for f in d2]
    for frame1, frame2 in zip(d1, d2):
        for col in DUMPED:
            assert np.array_equal(frame1[col], frame2[col]), (frame1["step"], col)
    damage = damage_column(d1[-1])
    if case == "fracture":
        assert np.count_nonzero(damage) > 100  # bonds did break, on both rank counts alike
    else:
        assert not np.any(damage)


@pytest.mark.parametrize("case,write_ranks,read_ranks", [
    ("elastic", 1, 1),
    ("fracture", 1, 1),
    pytest.param("fracture", 2, 1, marks=pytest.mark.mpi),
    pytest.param("fracture", 1, 2, marks=pytest.mark.mpi),
])
def test_restart_continues_the_run(tmp_path, case, write_ranks, read_ranks):
    # Unsplit: 200 steps. Split: 100 steps, write_restart, then a new LAMMPS reads the file
    # and runs up to step 200. Families, broken bonds, s0, x0, velocities and the time step
    # all come from the file, so the continued run repeats the unsplit one operation by
    # operation, bit for bit, also when the file was written on another rank count (per-atom
    # arithmetic does not depend on it, test_one_and_two_ranks_agree). On 1 rank the thermo
    # sums are bit-identical too. On 2 ranks an atom that migrated to the other rank before
    # the split is appended to that rank's atoms, while the continued run sorts them at its
    # setup (atom_modify sort): the sums add the same values in another order (REORDERED_SUM),
    # and the short-range contact forces of particles that touch after their bonds broke are
    # summed in the neighbor list's order (measured: 1 ulp of the largest force at step 200,
    # "fracture 1 2"; positions and velocities bit-identical; without contact the forces are
    # bit-identical too, test_length_form_per_atom_results_do_not_depend_on_ranks_or_restarts).
    args = ELASTIC if case == "elastic" else FRACTURE
    unsplit = run_deck(BLOCK, tmp_path / "unsplit", nprocs=read_ranks, variables=args)
    first = run_deck(BLOCK, tmp_path / "split", nprocs=write_ranks,
                     variables={**args, "restart_at": 100})
    assert (tmp_path / "split/restart.block").exists()
    assert first.thermo[-1]["Step"][-1] == 100
    (tmp_path / "split/dump.atoms").rename(tmp_path / "split/dump.first")
    second = run_deck(CONTINUE, tmp_path / "split", nprocs=read_ranks,
                      variables={"nsteps": 200, "thermo_every": 10, "dump_every": 100})
    t_all, t_cont = unsplit.thermo[-1], second.thermo[-1]
    assert t_cont["Step"][0] == 100 and t_cont["Step"][-1] == 200
    rows = np.searchsorted(t_all["Step"], t_cont["Step"])
    assert np.array_equal(t_all["Step"][rows], t_cont["Step"])
    for col in SUMS:
        if read_ranks == 1:
            assert np.array_equal(t_all[col][rows], t_cont[col]), col
        else:
            assert relative_difference(t_all[col][rows], t_cont[col]) < REORDERED_SUM, col
    whole = read_dump(tmp_path / "unsplit/dump.atoms")[-1]
    cont = read_dump(tmp_path / "split/dump.atoms")[-1]
    assert whole["step"] == cont["step"] == 200
    for col in DUMPED:
        if read_ranks == 1 or col not in ("fx", "fy", "fz"):
            assert np.array_equal(whole[col], cont[col]), col
        else:
            scale = np.abs(whole[col]).max()
            assert np.abs(whole[col] - cont[col]).max() <= 1e-14 * scale, col
    if case == "fracture":
        assert np.count_nonzero(damage_column(cont)) > 100


@pytest.mark.mpi
def test_length_form_per_atom_results_do_not_depend_on_ranks_or_restarts(tmp_path):
    # The fracture case with `deviation length` (doc/pair_peri_nosb.rst, "Stabilization and
    # fracture"), short-range contact off: on 2 ranks, and split by a restart written on 1 rank
    # and read on 2, every particle's position, velocity, force and damage is bit-identical to
    # the unsplit 1-rank run (the thermo sums only to REORDERED_SUM: another summation order).
    # With contact on, the forces of particles that touch after their bonds broke are summed in
    # the neighbor list's order, which the restart changes: measured 2e-16 of the force, not
    # visible in the positions at step 200.
    args = {**FRACTURE, "keys": "deviation length contact no"}
    one = run_deck(BLOCK, tmp_path / "np1", nprocs=1, variables=args)
    two = run_deck(BLOCK, tmp_path / "np2", nprocs=2, variables=args)
    first = run_deck(BLOCK, tmp_path / "split", nprocs=1, variables={**args, "restart_at": 100})
    (tmp_path / "split/dump.atoms").rename(tmp_path / "split/dump.first")
    second = run_deck(CONTINUE, tmp_path / "split", nprocs=2,
                      variables={"nsteps": 200, "thermo_every": 10, "dump_every": 100})
    assert "deviation length" in one.log and first.thermo[-1]["Step"][-1] == 100
    for other in (two, second):
        t1, t2 = one.thermo[-1], other.thermo[-1]
        assert t2["Step"][-1] == 200
        rows = np.searchsorted(t1["Step"], t2["Step"])
        for col in SUMS:
            assert relative_difference(t1[col][rows], t2[col]) < REORDERED_SUM, col
    whole = read_dump(tmp_path / "np1/dump.atoms")[-1]
    for path in ("np2/dump.atoms", "split/dump.atoms"):
        other = read_dump(tmp_path / path)[-1]
        assert other["step"] == whole["step"] == 200
        for col in DUMPED:
            assert np.array_equal(whole[col], other[col]), (path, col)
    assert np.count_nonzero(damage_column(whole)) > 100
