"""Regressions of peri/nosb found in review: the force kernel's template switch (periodic
reference images and the virial) and the mixing of the critical stretch with 'break no'."""
from pathlib import Path

import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from nosb_reference import A_TEST, first_piola

DECKS = Path(__file__).parent / "decks"


def kirchhoff_volume_sum(model, F, natoms):
    tau = first_piola(model, F) @ F.T
    return natoms * A_TEST ** 3 * np.array([tau[0, 0], tau[1, 1], tau[2, 2], tau[0, 1],
                                            tau[0, 2], tau[1, 2]])


@pytest.mark.parametrize("nprocs", [1, pytest.param(2, marks=pytest.mark.mpi)])
@pytest.mark.parametrize("model,cs", [("linear", 2.0), ("stvk", 0.0), ("neohookean", 2.0)])
def test_deformed_periodic_lattice_stays_at_rest_and_carries_its_stress(tmp_path, model, cs,
                                                                        nprocs):
    # A periodic lattice under a uniform F has zero force on every particle: under fix nve
    # (steps without any virial request, so the plain force kernel runs) it must not move.
    # Forces of ~100 bonds of size P/a ~ 1e10 cancel to ~1e-3 (round-off), so ke after 10
    # steps of 1e-7 s stays far below 1e-12 (a bond taken to the wrong periodic image gives
    # forces ~1e10 and ke ~1e5 within one step). With a virial request, the per-atom virial
    # (compute stress/atom, half of each bond at each end) sums to N V tau, tau = P F^T.
    sx, gxy, n = 1.01, 0.05, 7
    F = np.array([[1.0, gxy, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]) @ np.diag([sx, 1, 1])
    run = run_deck(DECKS / "nosb_periodic_run.lmp", tmp_path, nprocs=nprocs,
                   variables={"model": model, "sx": sx, "gxy": gxy, "cs": cs, "n": n})
    assert np.max(run.thermo[-2]["KinEng"]) < 1e-12
    t = run.thermo[-1]
    expect = kirchhoff_volume_sum(model, F, n ** 3)
    for k in range(6):
        col = t[f"c_ssum[{k + 1}]"]
        assert np.max(np.abs(col - expect[k])) < 1e-9 * np.max(np.abs(expect)), (k, col)


def test_virial_of_a_free_block_is_tallied_on_every_step(tmp_path):
    # A free (shrink-wrapped) block under the same affine F: every F_i = F, so the per-atom
    # virial again sums to N V tau; checked on the steps after setup, where the kernel
    # without periodic images runs.
    sx, n = 1.01, 6
    F = np.diag([sx, 1.0, 1.0])
    run = run_deck(DECKS / "nosb_periodic_run.lmp", tmp_path,
                   variables={"bnd": "s", "sx": sx, "n": n, "nsteps": 0})
    t = run.thermo[-1]
    expect = kirchhoff_volume_sum("linear", F, int(t["Atoms"][0]))
    assert t["Step"][-1] == 2
    for k in range(3):
        col = t[f"c_ssum[{k + 1}]"]
        assert np.max(np.abs(col - expect[k])) < 1e-9 * np.max(np.abs(expect)), (k, col)


def test_mixed_bonds_take_the_critical_stretch_of_the_breaking_type(tmp_path):
    # Type 1 has 'break no' (its s00 = 0 means nothing); type 2 breaks at 2% stretch. Without
    # a pair_coeff 1 2 line, the 1-2 bonds must break at 2% too: a 1% affine stretch breaks
    # nothing anywhere, a 3% stretch breaks the 1-2 and 2-2 bonds but no 1-1 bond.
    def damage(stretch, sub):
        run_deck(DECKS / "nosb_mixed_break.lmp", tmp_path / sub,
                 variables={"n": 8, "F11": stretch, "model1": "linear", "model2": "linear"})
        frame = read_dump(tmp_path / sub / "dump.types")[-1]
        return frame["type"], frame["c_nosb[1]"], frame["f_ref[1]"]

    _, dmg, _ = damage(1.01, "small")
    assert np.all(dmg == 0.0)
    types, dmg, x = damage(1.03, "large")
    assert np.all(dmg[types == 2] > 0.0)
    # type-1 particles farther than a horizon from type 2 keep every bond
    far = (types == 1) & (x < (4.5 - 3.0002) * A_TEST - 1e-12)
    assert far.any() and np.all(dmg[far] == 0.0)
    # type-1 particles within a horizon of type 2 lose their 1-2 bonds
    near = (types == 1) & (x > 3.5 * A_TEST)
    assert near.any() and np.all(dmg[near] > 0.0)
