"""Short-range contact of peri/nosb inside large fix sissm steps (issue 9, item 8).

Contact candidates come from the neighbor list, which LAMMPS rebuilds between steps; one
implicit step can move atoms farther than the skin, and two blocks approaching at such a step
used to meet pairs the candidates did not hold: the contact missed them within the step. Now
fix sissm re-selects the candidates inside the step when atoms moved beyond their margin
(PairPeriNosb::contact_follow_motion); a step that moves atoms farther than the neighbor list
covers does not converge and is cut back into sub-steps that start from new neighbor lists,
and where it is not cut back (unconverged warn) it is refused with an error that says what to
change.

decks/sissm_two_blocks.lmp: two 3x3x3 blocks (spacing 1 mm, K = 1 GPa) approach at v each,
fix sissm with its defaults at dt = 1e-4 s (~100 x the explicit limit); contact distance
1.35 mm; neighbor skin 1 mm.
"""
from pathlib import Path

import numpy as np

from lammps_run import run_deck

DECK = Path(__file__).parent / "decks" / "sissm_two_blocks.lmp"
TOUCH = 1.35e-3  # contact distance 1.35 x particle size (pair_peri_nosb.rst)


def test_contact_within_a_step_is_seen(tmp_path):
    # 6 m/s at 1e-4 s: 0.6 mm per block per step. The facing layers start a step 2.4 mm apart,
    # beyond the candidates of the neighbor list build (contact distance + skin = 2.35 mm), and
    # the first iterate y^n + h v^n brings them to 1.2 mm, inside the contact distance. Before
    # the fix that step did not see the contact (one iteration, gap 1.2 mm) and the next one
    # failed to converge (measure 17) and threw the blocks apart at 0.73 m/s. Now every step
    # converges, the gap never closes below the contact distance (backward Euler with the
    # stiff contact spring stops the layers at it; 1 % margin) and the blocks come to rest
    # against each other (inelastic: backward Euler at 100 x damps the bounce).
    run = run_deck(DECK, tmp_path, variables={"gap": 0.0036, "v": 6.0, "nsteps": 10})
    t = run.thermo[-1]
    assert t["f_integrate[4]"][-1] == 0
    assert t["v_gapnow"][2] < 2.35e-3 + 1e-12 < t["v_gapnow"][1]  # the case described
    assert np.min(t["v_gapnow"]) > 0.99 * TOUCH
    assert abs(t["v_vl"][-1]) < 0.01 * 6.0 and abs(t["v_vr"][-1]) < 0.01 * 6.0


def test_a_step_beyond_the_neighbor_list_is_cut_back(tmp_path):
    # 15 m/s: 1.5 mm per block per step, more than a step can move atoms with a skin of 1 mm
    # ((horizon - contact distance)/2 + skin/4 = 1.075 mm). The step's iterates are evaluated
    # with the candidates they can have and do not count as converged: the step is cut back
    # into sub-steps, each starting from a new neighbor list when the atoms have moved far
    # from the last one (issue 40). Step 1 brings the layers to 1.5 mm, step 2 meets the
    # contact (8 sub-steps); the gap never closes below the contact distance and the blocks
    # part at 0.2 m/s (backward Euler damps the bounce). Without contact candidates that
    # follow the iterates the blocks pass through each other unhindered (gap 4.5, 1.5, -1.5,
    # -4.5 mm, one iteration per step, "converged").
    run = run_deck(DECK, tmp_path, variables={"gap": 0.0045, "v": 15.0})
    t = run.thermo[-1]
    assert ("step 1 went beyond the reach of the contact candidates of the last neighbor list "
            "build; redone as") in run.log
    assert t["f_integrate[4]"][-1] == 0
    assert np.min(t["v_gapnow"]) > 0.99 * TOUCH
    assert abs(t["v_vl"][-1]) < 0.02 * 15.0 and abs(t["v_vr"][-1]) < 0.02 * 15.0


def test_a_step_beyond_the_neighbor_list_is_refused(tmp_path):
    # The same step where it is not cut back (unconverged warn): its result is that far, and
    # the run stops in step 1 with an error naming the step, the atom, and the skin that would
    # do.
    run = run_deck(DECK, tmp_path, variables={"gap": 0.0045, "v": 15.0,
                                              "opts": "unconverged warn"}, check=False)
    assert run.returncode > 0  # an error exit, not a signal
    assert len(run.errors) >= 1
    error = run.errors[0]
    assert "implicit step 1 moved atom" in error and "by 0.0015" in error
    assert "neighbor skin of at least 0.0027" in error
    # with that skin the candidates follow the motion: the step runs
    run = run_deck(DECK, tmp_path / "skin", variables={"gap": 0.0045, "v": 15.0, "nsteps": 1,
                                                      "skin": 0.0027,
                                                      "opts": "unconverged warn"})
    assert run.thermo[-1]["Step"][-1] == 1
