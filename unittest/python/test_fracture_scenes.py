"""examples/fracture: the decks build the plates they describe and leave out the bonds across the
notches and the crack (the families have fewer bonds than the same plate without the
neigh_modify exclude line), and edge_crack.py's LEFM reference is the Brown-Srawley / Tada
shape factor."""
import itertools
import math
import re
import shutil
import sys

import numpy as np
import pytest

from lammps_run import REPO, run_deck

SCENES = REPO / "examples" / "fracture"
sys.path.insert(0, str(SCENES))
import edge_crack  # noqa: E402


def test_the_shape_factor_is_the_handbooks():
    assert edge_crack.shape_factor(0.0) == pytest.approx(1.12)
    assert edge_crack.shape_factor(0.5) == pytest.approx(2.83, rel=5e-3)    # Tada's table
    assert edge_crack.shape_factor(0.6) == pytest.approx(4.03, rel=5e-3)
    # sigma sqrt(pi c) F(c/W) = sqrt(G0 E) at the stress printed as sigma_LEFM
    target = edge_crack.sigma_lefm(60)
    assert target * math.sqrt(math.pi * 0.03) * edge_crack.shape_factor(0.5) == pytest.approx(
        math.sqrt(22170 * 190e9))
    assert edge_crack.sigma_lefm(30) / target == pytest.approx(math.sqrt(2))


def bonds_per_atom(run):
    return float(re.search(r"bonds/atom = ([0-9.]+)", run.stdout + run.log).group(1))


@pytest.mark.parametrize("deck, files, counts, variables", [
    ("in.kalthoff.nosb", ["kalthoff.geometry", "kalthoff.run"],
     ["Created 25000 atoms", "new total = 24750", "120 atoms in group struck"], {"t_end": 0}),
    ("in.edge.nosb", ["edge.geometry", "edge.run"],
     ["Created 5400 atoms", "90 atoms in group top", "90 atoms in group ligament"],
     {"t_end": 0}),
])
def test_the_decks_cut_the_bonds_across_notches_and_cracks(tmp_path, deck, files, counts,
                                                          variables):
    runs = {}
    for cut in (True, False):
        wd = tmp_path / ("cut" if cut else "whole")
        wd.mkdir()
        for name in [deck] + files:
            shutil.copy(SCENES / name, wd / name)
        geometry = wd / files[0]
        if not cut:
            text = geometry.read_text()
            assert "neigh_modify    exclude" in text
            geometry.write_text(re.sub(r"^neigh_modify\s+exclude.*$", "", text, flags=re.M))
        runs[cut] = run_deck(wd / deck, wd, variables=variables)
    for line in counts:
        assert line in runs[True].stdout + runs[True].log, line
    assert bonds_per_atom(runs[True]) < bonds_per_atom(runs[False]) - 0.1


def edge_plate_bonds(nw, nz, periodic_z, crack_rule, horizon=3.0002):
    """Bonds (pairs within the horizon) of edge.geometry's plate, nw x 2 nw x nz spacings, less
    those the crack cuts: crack_rule "crossing" cuts every bond that crosses the plane y = nw
    at x < nw / 2, "blocks" only those with both ends at x < nw / 2."""
    points = np.array(list(itertools.product(range(nw), range(2 * nw), range(nz)))) + 0.5
    offsets = [d for d in itertools.product(range(-3, 4), repeat=3)
               if d > (0, 0, 0) and sum(c * c for c in d) <= horizon**2]
    total = 0
    for offset in offsets:
        other = points + offset
        inside = (other[:, 0] < nw) & (other[:, 1] > 0) & (other[:, 1] < 2 * nw)
        if periodic_z:
            other[:, 2] %= nz
        else:
            inside &= (other[:, 2] > 0) & (other[:, 2] < nz)
        p, q = points[inside], other[inside]
        crosses = (p[:, 1] - nw) * (q[:, 1] - nw) < 0
        if crack_rule == "crossing":
            rise = np.where(crosses, q[:, 1] - p[:, 1], 1.0)
            at = p[:, 0] + (q[:, 0] - p[:, 0]) * (nw - p[:, 1]) / rise
            cut = crosses & (at < nw / 2)
        else:
            cut = crosses & (p[:, 0] < nw / 2) & (q[:, 0] < nw / 2)
        total += int(np.count_nonzero(~cut))
    return total


@pytest.mark.parametrize("cut_tip, nz, zb", [(1, 3, "s"), (0, 3, "s"), (1, 7, "p")])
def test_the_edge_crack_cuts_the_bonds_that_cross_it_short_of_the_tip(tmp_path, cut_tip, nz,
                                                                      zb):
    """edge.geometry's bond families against a count of the lattice's pairs within the horizon:
    with cut_tip 1 every bond crossing the crack plane short of the tip is cut (50 more than
    the two blocks' exclusion at nw = 12, nz = 3), with cut_tip 0 only those between the
    blocks; periodic in z with 7 layers (more than two horizons) no particle bonds to its own
    image."""
    for name in ("in.edge.nosb", "edge.geometry", "edge.run"):
        shutil.copy(SCENES / name, tmp_path / name)
    run = run_deck(tmp_path / "in.edge.nosb", tmp_path,
                   variables={"t_end": 0, "nw": 12, "nz": nz, "zb": zb, "cut_tip": cut_tip})
    total = int(re.search(r"total # of bonds = ([0-9]+)", run.stdout + run.log).group(1))
    rule = "crossing" if cut_tip else "blocks"
    assert total == 2 * edge_plate_bonds(12, nz, zb == "p", rule)
    if cut_tip and zb == "s":
        assert edge_plate_bonds(12, 3, False, "blocks") - total // 2 == 50


def edge_growth(wd, variables):
    """in.edge.nosb as it is (W = 30 spacings, the tension reaching sigma_LEFM in 32 transit
    times, damping over 3) with `deviation length`, alpha 0 and `variables`, on two ranks: the
    tension at which the crack has grown by one horizon, over sigma_LEFM."""
    for name in ("in.edge.nosb", "edge.geometry", "edge.run"):
        shutil.copy(SCENES / name, wd / name)
    run = run_deck(wd / "in.edge.nosb", wd, nprocs=2,
                   variables={"keys": "deviation length", "alpha": 0, **variables})
    table = run.thermo[-1]
    grown = np.flatnonzero(table["c_broken"] >= 2 * 3 * 3)
    assert grown.size, "the crack did not grow by one horizon"
    return table["v_sigma"][grown[0]] / edge_crack.sigma_lefm(30)


@pytest.fixture(scope="module")
def explicit_growth(tmp_path_factory):
    return edge_growth(tmp_path_factory.mktemp("edge_nve"), {})


@pytest.mark.slow
def test_the_edge_crack_grows_within_ten_percent_of_the_lefm_stress(explicit_growth):
    """fix nve at the deck's 50 ns: the crack has grown by one horizon at 1.014 sigma_LEFM on
    one rank (README, "Mode-I edge-cracked plate"; a held tension grows it at 0.89 and not at
    0.86 sigma_LEFM, the rest is the loading rate's); within 10%."""
    assert 0.9 <= explicit_growth <= 1.1, explicit_growth


@pytest.mark.slow
def test_fix_sissm_at_28_explicit_steps_grows_the_crack_within_five_percent_of_fix_nve(
        tmp_path, explicit_growth):
    """The same plate and loading with fix sissm (defaults) at 1.405 us, an eighth of the P
    wave's transit time and 28 times the explicit step; its bonds break at the end of each
    step. Measured (README, "fix sissm with breaking", 1 and 2 ranks, 2026-11-30): growth at
    1.057 sigma_LEFM, 4.2% above fix nve's 1.014 (steps of 1/2, 1/4, 1/16 transit: 1.135,
    1.089, 1.040, converging to fix nve's value); within 5% (the issue's bound), and above it:
    the backward-Euler step slows the opening that runs the crack. Bonds that break keep the
    multigrid hierarchy: 5 set-ups on two ranks, where a new one whenever bonds broke made 90;
    at most 20."""
    ratio = edge_growth(tmp_path, {"integrate": "sissm", "dt": 1.405e-6, "thermo_every": 1})
    assert explicit_growth <= ratio <= 1.05 * explicit_growth, (ratio, explicit_growth)
    log = (tmp_path / "log.lammps").read_text()
    setups = int(re.search(r"([0-9]+) set-ups? of the AMG hierarchy", log).group(1))
    assert setups <= 20, setups


def cracks(tmp_path, name, keys):
    """The Kalthoff-Winkler plate at 2 mm to 60 us (1200 steps of the deck's 50 ns) with alpha 0
    and the peri/nosb keywords `keys`; crack_path's result per tip at 60 us."""
    wd = tmp_path / name
    wd.mkdir()
    for f in ("in.kalthoff.nosb", "kalthoff.geometry", "kalthoff.run"):
        shutil.copy(SCENES / f, wd / f)
    run_deck(wd / "in.kalthoff.nosb", wd, variables={"t_end": 60e-6, "alpha": 0, "keys": keys,
                                                      "dump": 1200})
    sys.path.insert(0, str(REPO / "tools"))
    import crack_path
    step, points, damage = crack_path.frames(wd / "dump.kalthoff.nosb", "v_damage")[-1]
    assert step == 1200
    tips, _ = crack_path.analyse(points, damage, [(0.075, 0.05), (0.125, 0.05)], (0.0, 1.0))
    return tips


@pytest.mark.parametrize("form", ["length", "vector"])
def test_the_length_form_cracks_from_both_notch_tips_and_the_vector_form_does_not(tmp_path,
                                                                                  form):
    """doc/pair_peri_nosb.rst, "Stabilization and fracture": with `deviation length` a crack
    leaves each notch tip away from the struck middle, at 60 to 75 degrees to the notch (the
    experiment: about 70; measured 64.2, README table), at most three particles wide; with the
    default vector form no damaged path reaches two horizons from a tip."""
    tips = cracks(tmp_path, form, f"deviation {form}")
    for tip, sign in zip(tips, (-1.0, 1.0)):
        if form == "vector":
            assert not tip["crack"], tip
            continue
        assert tip["crack"], tip
        assert 60.0 <= tip["angle"] <= 75.0, tip
        assert sign * tip["dir"][0] > 0.0, tip      # away from the struck middle
        assert tip["width"] <= 3.0, tip
