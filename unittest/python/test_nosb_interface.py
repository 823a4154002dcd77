"""Per-type critical stretch (issue 9, item 4): a bond between types I and J breaks at the
critical stretch that `pair_coeff I J` gives it, s00_IJ - alpha_IJ max(s_min,i, s_min,j).

The bar of decks/nosb_interface.lmp: type 1 (x < 7.5 mm, s00 = 2e-3) and type 2 (s00 = 3e-3)
joined by an interface whose pair_coeff 1 2 has s00 = 5e-4, below both. (Before the fix s0
was folded per particle as the largest over its bonds, so an interface particle carried its
bulk s00 into its interface bonds: the interface could not break before the weaker bulk.)"""
from pathlib import Path

import numpy as np

from lammps_run import read_dump, run_deck
from nosb_reference import A_TEST, bond_weights

DECK = Path(__file__).parent / "decks" / "nosb_interface.lmp"
HORIZON = 3.0002 * A_TEST


def bar(tmp_path, **variables):
    run_deck(DECK, tmp_path, variables=variables)
    frame = read_dump(tmp_path / "dump.bar")[0]
    X = np.stack([frame[f"f_ref[{k}]"] for k in (1, 2, 3)], axis=1)
    Y = np.stack([frame[c] for c in "xyz"], axis=1)
    return X, Y, frame["type"].astype(int), frame["c_nosb[1]"]


def interface_share(X, types):
    """Weight of each particle's interface (1-2) bonds relative to its whole family: its damage
    when exactly the interface bonds are broken (omega = beta V_j, uniform volumes)."""
    _, omega = bond_weights(X, np.full(len(X), A_TEST ** 3), HORIZON)
    cross = (omega > 0) & (types[:, None] != types[None, :])
    return np.sum(omega * cross, axis=1) / np.sum(omega, axis=1)


def test_interface_bonds_break_at_their_own_critical_stretch(tmp_path):
    # Uniaxial strain 1e-3 held: a bond at angle theta to the bar stretches by 1e-3 cos^2
    # theta (+ O(1e-6)), and s_min = 0 (bonds across the bar do not stretch), so exactly the
    # interface bonds within ~45 degrees of the axis exceed their 5e-4 and break, and no bulk
    # bond reaches 2e-3 or 3e-3. Damage (ratios of sums of ~100 bond weights) compared to
    # 1e-12 with the prediction from the exact stretches; before the fix nothing broke.
    X, Y, types, damage = bar(tmp_path, mode="static", eps=1.0e-3)
    r0 = np.linalg.norm(X[None, :, :] - X[:, None, :], axis=2)
    r = np.linalg.norm(Y[None, :, :] - Y[:, None, :], axis=2)
    _, omega = bond_weights(X, np.full(len(X), A_TEST ** 3), HORIZON)
    bonded = omega > 0
    stretch = np.where(bonded, r / np.where(bonded, r0, 1.0) - 1.0, 0.0)
    cross = types[:, None] != types[None, :]
    assert stretch[bonded & ~cross].max() < 2.0e-3  # no bulk bond can break
    broken = bonded & cross & (stretch > 5.0e-4)
    expected = np.sum(omega * broken, axis=1) / np.sum(omega, axis=1)
    assert np.count_nonzero(expected) > 0.25 * len(X)
    assert np.allclose(damage, expected, rtol=0, atol=1e-12)


def test_pulled_bar_breaks_at_the_weak_interface_and_nowhere_else(tmp_path):
    # The bar pulled apart (ends at 0.05 m/s for 1.2 ms, ~5 wave transits: a strain of 4e-3
    # if it held, beyond both bulks' 2e-3 and 3e-3) under fix nve. It must separate at the
    # interface: every interface bond broken, no other (each particle's damage equals its
    # interface share to 1e-12), and a gap there. Before the fix the bar fragmented through
    # type 1 (damaged particles from x = 0 to 14 mm, none with its interface share).
    X, Y, types, damage = bar(tmp_path, mode="pull")
    assert np.allclose(damage, interface_share(X, types), rtol=0, atol=1e-12)
    u = Y[:, 0] - X[:, 0]
    left, right = u[types == 1], u[types == 2]
    gap = right.min() - left.max()  # opening of the interface beyond the bodies' own stretch
    assert gap > 0.5 * 0.05 * 1.2e-3, (gap, left.max(), right.min())
