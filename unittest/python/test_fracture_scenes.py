"""examples/fracture: the decks build the plates they describe and leave out the bonds across the
notches and the crack (the families have fewer bonds than the same plate without the
neigh_modify exclude line), and edge_crack.py's LEFM reference is the Brown-Srawley / Tada
shape factor."""
import math
import re
import shutil
import sys

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
