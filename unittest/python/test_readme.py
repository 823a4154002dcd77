"""The README's first deck is examples/first-deck/in.first, line for line, and running it prints
what the README says it prints: every step converged (f_step[4] = 0, the measure below the
default tolerance 1e-6, none cut back) and the same potential energy at the rows the README
shows."""
import re

import numpy as np

from lammps_run import REPO, run_deck

README = (REPO / "README.md").read_text()
DECK = REPO / "examples" / "first-deck" / "in.first"


def first_deck_section():
    return README.split("## A first deck", 1)[1].split("\n## ", 1)[0]


def indented_blocks(text):
    blocks, current = [], []
    for line in text.splitlines():
        if line.startswith("    "):
            current.append(line[4:].rstrip())
        elif current and line.strip() == "":
            continue
        elif current:
            blocks.append(current)
            current = []
    if current:
        blocks.append(current)
    return blocks


def test_the_readme_deck_is_the_example_deck():
    deck = [ln.rstrip() for ln in DECK.read_text().splitlines()
            if ln.strip() and not ln.startswith("#")]
    assert indented_blocks(first_deck_section())[0] == deck


def test_the_deck_prints_what_the_readme_says(tmp_path):
    shown = {}
    for line in indented_blocks(first_deck_section())[1]:
        words = line.split()
        if words and re.fullmatch(r"\d+", words[0]) and len(words) == 6:
            shown[int(words[0])] = [float(w) for w in words[1:]]
    assert {0, 2, 4, 20} <= set(shown)
    run = run_deck(DECK, tmp_path)
    table = run.thermo[-1]
    steps = list(table["Step"].astype(int))
    for step, (time, pe, iters, measure, unconverged) in shown.items():
        row = steps.index(step)
        assert table["Time"][row] == time
        # the same trajectory; 1e-6 leaves room for another compiler's round-off
        assert abs(table["PotEng"][row] - pe) <= 1e-6 * max(abs(pe), 1e-3)
        assert table["f_step[4]"][row] == unconverged == 0
    assert np.all(table["f_step[2]"][1:] < 1e-6)     # converged: below the default tolerance
    assert np.all(table["f_step[4]"] == 0)
    # and none was cut back into sub-steps (the default unconverged cutback would log it)
    assert "redone as" not in run.log and " 0 cut back" in run.log
