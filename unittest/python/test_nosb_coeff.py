"""pair_coeff of peri/nosb with type labels (labelmap): the types of a line may be given by
label, and the run is the run with the types given by number, bit for bit (the types
parsed by LAMMPS's utils::bounds_typelabel, src/lammps/pair_peri_nosb_coeff.cpp)."""
import numpy as np

from lammps_run import run_deck
from nosb_block import TWO_TYPE_BLOCK

DECK = TWO_TYPE_BLOCK + """
region          upper block INF INF INF INF 2.5 INF
labelmap        atom 1 soft 2 stiff
set             region upper type 2
velocity        all set 0.0 0.0 0.0
velocity        all ramp vz -2.0 2.0 z -0.5 5.5 units box
pair_style      peri/nosb
pair_coeff      {one} {one} linear 1.0e9 0.6e9 0.0030002 0.5 0.25 break no
pair_coeff      {two} {two} neohookean 2.0e9 1.0e9 0.0030002 0.5 0.25 break no
pair_coeff      {one} {two} stvk 1.5e9 0.8e9 0.0030002 0.5 0.25 break no
fix             1 all nve
thermo          5
thermo_style    custom step pe ke
run             20
"""


def test_type_labels_give_the_run_of_type_numbers(tmp_path):
    numbers = run_deck(DECK.format(one="1", two="2"), tmp_path / "numbers")
    labels = run_deck(DECK.format(one="soft", two="stiff"), tmp_path / "labels")
    assert numbers.thermo[-1]["PotEng"][-1] != 0.0
    assert len(labels.thermo) == len(numbers.thermo)
    for a, b in zip(labels.thermo, numbers.thermo):
        assert a.keys() == b.keys()
        for key in a:
            assert np.array_equal(a[key], b[key]), key


def test_an_unknown_label_is_an_error_that_names_it(tmp_path):
    run = run_deck(DECK.format(one="soft", two="hard"), tmp_path, check=False, timeout=120)
    assert run.returncode > 0, run.describe()
    assert "hard" in run.stdout + run.log
