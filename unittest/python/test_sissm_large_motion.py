"""Steps of fix sissm that move atoms farther than the neighbor skin (issue 40, item 6): with
the defaults and the default short-range contact of peri/nosb, a step whose atoms leave the
reach of the contact candidates does not converge and is cut back; each sub-step that starts
far from the last neighbor list build starts from a new one (doc/fix_sissm.rst, "Contact").
Three scenes whose steps move atoms farther than one neighbor list follows (1.075 spacings with
the decks' skin of one spacing), each on 1 and 2 ranks (on 2 ranks the first two move atoms
from one rank to the other inside the steps):

- a free 5 x 5 x 5 neo-Hookean block whose particles are displaced at random by up to 3
  spacings (each coordinate by up to 1.73 spacings), released at rest, dt = 1e-5 s (about ten
  times the explicit limit of such blocks). It comes back to its rest shape; every pair that
  was never bonded, many of which start inside the contact distance, ends farther apart than
  the contact distance (1.35 spacings).
- a plate of 8 x 8 x 2 particles (1 GPa) released under gravity 5 mm above a floor
  (fix wall/harmonic), dt = 0.01 s: it falls 2 to 3 spacings per step and comes to rest on
  the floor, where the wall holds the two layers' weight with the lower one 1.5 mm into the
  wall's zone.
- the same plate without gravity sliding at 0.2 m/s across the boundary of a box periodic in
  x and y: the sub-steps' neighbor list builds wrap atoms into the box, and the plate ends
  where uniform motion puts it.

Bounds: rest means the largest speed below 1e-4 of the largest speed of the run (the block's
particles reach 400 m/s in its first steps, the plate lands at 0.29 m/s); the damping of
backward Euler at these steps brings both far below that within the steps run (measured: block
~3e-7 m/s, plate ~1e-8 m/s). The rest shape of the block within 1e-3 spacings RMS after the
best rigid alignment (measured ~4e-9); the plate's lower layer at -1.5 mm within 1 um (its
weight over the wall's stiffness; the plate's own compression under it is ~1e-8 of a spacing).
"""

import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from sissm_support import A, BLOCK, DECKS, FIX_DEFAULTS

PLATE = DECKS / "sissm_plate_drop.lmp"
HORIZON = 3.0002 * A
CONTACT = 1.35 * A  # contact distance of pairs never bonded (doc/pair_peri_nosb.rst)

SCRAMBLE = 1.732 * 2 * A  # drand: each coordinate displaced by up to 1.732 spacings


def hashed(ids, k):
    """The deck's pseudo-random number h_k of each atom ID, in [-1/2, 1/2)."""
    t = np.sin(ids * 12.9898 + k * 78.233) * 43758.5453
    return t - np.floor(t) - 0.5


def positions(frame):
    return np.column_stack([frame["x"], frame["y"], frame["z"]])


def speeds(frame):
    return np.linalg.norm(np.column_stack([frame["vx"], frame["vy"], frame["vz"]]), axis=1)


def pair_distances(p):
    d = p[:, None, :] - p[None, :, :]
    return np.sqrt((d ** 2).sum(axis=2))


def aligned_rms(p, q):
    """RMS distance between p and q after the rigid motion of q that fits p best (Kabsch)."""
    pc, qc = p - p.mean(axis=0), q - q.mean(axis=0)
    u, _, vt = np.linalg.svd(qc.T @ pc)
    d = np.sign(np.linalg.det(u @ vt))
    r = u @ np.diag([1.0, 1.0, d]) @ vt
    return float(np.sqrt(((qc @ r - pc) ** 2).sum(axis=1).mean()))


@pytest.mark.parametrize("nprocs", [1, 2])
def test_scrambled_block_recovers(tmp_path, nprocs):
    nsteps = 60
    run = run_deck(BLOCK, tmp_path, nprocs=nprocs, variables={
        **FIX_DEFAULTS, "nx": 5, "ny": 5, "nz": 5, "model": "neohookean", "drand": SCRAMBLE,
        "dt": 1.0e-5, "nsteps": nsteps, "thermo_every": 1, "dump_every": 1})
    assert "redone as" in run.log  # steps were cut back
    frames = read_dump(tmp_path / "dump.atoms")
    first, last = frames[0], frames[-1]
    ids = first["id"]
    # the lattice the families were built on, from the deck's displacement
    ref = positions(first) - SCRAMBLE * np.column_stack([hashed(ids, k) for k in (1, 2, 3)])
    never_bonded = pair_distances(ref) > HORIZON
    start = pair_distances(positions(first))[never_bonded]
    assert start.min() < 0.5 * CONTACT  # the scramble pushes such pairs deep into contact
    end = pair_distances(positions(last))[never_bonded]
    print(f"{nprocs} ranks: closest pair never bonded {start.min() / A:.3f} a at the start, "
          f"{end.min() / A:.3f} a at the end")
    assert end.min() > CONTACT
    rms = aligned_rms(ref, positions(last))
    peak = max(speeds(f).max() for f in frames)
    vmax = speeds(last).max()
    print(f"rest shape within {rms / A:.2e} a RMS, largest speed {vmax:.2e} m/s "
          f"(largest of the run {peak:.3g} m/s)")
    assert rms < 1e-3 * A
    assert vmax < 1e-4 * peak


@pytest.mark.parametrize("nprocs", [1, 2])
def test_plate_falls_to_rest_on_the_floor(tmp_path, nprocs):
    run = run_deck(PLATE, tmp_path, nprocs=nprocs, variables={"nsteps": 50})
    t = run.thermo[-1]
    assert t["f_integrate[6]"][-1] >= 1  # steps were cut back
    landing = max(-t["c_vmin[3]"].min(), t["c_vmax[3]"].max())
    assert 0.2 < landing < 0.4  # it fell: sqrt(2 g 5 mm) = 0.31 m/s
    (last,) = read_dump(tmp_path / "dump.final")
    vmax = speeds(last).max()
    zlow = last["z"].min()
    print(f"{nprocs} ranks: landed at {landing:.3f} m/s; at rest {vmax:.2e} m/s, lowest z "
          f"{zlow * 1e3:.6f} mm")
    assert vmax < 1e-4 * landing
    assert abs(zlow - (-1.5e-3)) < 1e-6
    # the plate kept its shape: nearest neighbours one spacing apart, to 1e-6
    d = pair_distances(positions(last))
    np.fill_diagonal(d, np.inf)
    assert np.abs(d.min(axis=1) / A - 1.0).max() < 1e-6


@pytest.mark.parametrize("nprocs", [1, 2])
def test_plate_slides_across_a_periodic_boundary(tmp_path, nprocs):
    # no gravity, 0.2 m/s along x in a box periodic in x and y (12 spacings): 2 mm per step,
    # every step cut back, and the sub-steps' neighbor list builds wrap the atoms that leave
    # the box (their rows of the step move with them). A free plate in uniform motion: backward
    # Euler keeps it exactly, so every atom ends where it started plus v t (to 1e-12 m, the
    # round-off of positions of a few mm) and the plate is undeformed.
    nsteps, v, dt = 4, 0.2, 0.01
    run = run_deck(PLATE, tmp_path, nprocs=nprocs, variables={
        "nsteps": nsteps, "g": 0, "vx": v, "bxy": "p", "dt": dt})
    assert run.thermo[-1]["f_integrate[6]"][-1] == nsteps
    (last,) = read_dump(tmp_path / "dump.final")
    # 8 mm in a box of 12 mm: the leading 6 columns were wrapped, the last 2 not
    wraps = np.round((last["xu"] - last["x"]) / (12 * A)).astype(int)
    assert set(wraps) == {0, 1}
    unwrapped = np.column_stack([last["xu"], last["yu"], last["zu"]])
    moved = unwrapped - np.array([v * nsteps * dt, 0.0, 0.0])
    lattice = np.round(moved / A) * A
    print(f"{nprocs} ranks: off the moved lattice by {np.abs(moved - lattice).max():.2e} m, "
          f"velocities off by {np.abs(last['vx'] - v).max():.2e} m/s")
    assert np.abs(moved - lattice).max() < 1e-12
    assert len({tuple(p) for p in np.round(lattice / A).astype(int)}) == len(lattice)
    assert np.abs(last["vx"] - v).max() < 1e-9
    assert np.abs(last["vy"]).max() < 1e-9 and np.abs(last["vz"]).max() < 1e-9
