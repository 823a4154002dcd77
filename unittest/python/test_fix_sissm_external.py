"""Other fixes' forces under fix sissm's default `external implicit` (issue 9, item 7).

Re-evaluating a fix at every iterate is right only for a fix whose force is a pure function of
positions and velocities. A fix with random numbers or state (fix langevin here) must act once
per step: fix sissm lags its force (the one of the evaluation that ended the previous step)
and says so once in the log, while known pure fixes (gravity) stay implicit. Before the fix,
fix langevin drew new random forces at every evaluation and no step could converge.

decks/sissm_block.lmp, 4x3x3 block (K = 1 GPa) at dt = 1e-5 s (~10 x its explicit limit),
solver krylov. Langevin at 1e20 K: with a density of 1000 as "mass", its random force density
is ~1e6 N/m^3, an acceleration of ~1e3 m/s^2, enough to matter in every step.
"""
import numpy as np

from lammps_run import read_dump, run_deck
from sissm_support import BLOCK, positions

BASE = {"solver": "krylov", "dt": 1.0e-5, "nsteps": 10, "langevin": 1.0e20}
NOTE = "fix heat (langevin) may hold state or random numbers"


def sissm_notes(run):
    return [ln for ln in run.log.splitlines() if ln.startswith("Fix sissm integrate:")]


def test_langevin_is_lagged_and_steps_converge(tmp_path):
    # gravity stays implicit, langevin is lagged: every step meets the default tolerance 1e-6
    # (before: all 10 steps stopped at the 100-evaluation limit, measures 3e-4 to 0.17)
    run = run_deck(BLOCK, tmp_path, variables={**BASE, "grav": 9.81, "iters": 100})
    t = run.thermo[-1]
    assert t["f_integrate[4]"][-1] == 0
    assert np.all(t["f_integrate[2]"][1:] <= 1e-6)
    notes = sissm_notes(run)
    assert len(notes) == 1 and NOTE in notes[0] and "other fixes' forces are implicit" in notes[0]


def test_lagged_langevin_draws_once_per_step(tmp_path):
    # With langevin the only other fix, the mixed treatment solves the same equations as
    # `external lagged` (its force moved into the predictor): converged to 1e-10 of the
    # spacing, the two trajectories agree within a few times that (1e-12 m on 1e-3 m
    # coordinates). Had fix sissm called langevin once more per step (or per evaluation),
    # the random streams would differ and so would the trajectories, by about as much as
    # langevin moves the block (5e-8 m).
    final = {}
    for mode in ("implicit", "lagged"):
        run_deck(BLOCK, tmp_path / mode, variables={**BASE, "external": mode, "iters": 1000,
                                                    "tol": 1.0e-10, "dump_every": 10})
        final[mode] = positions(read_dump(tmp_path / mode / "dump.atoms")[-1])
    start = positions(read_dump(tmp_path / "lagged" / "dump.atoms")[0])
    assert np.abs(final["lagged"] - start).max() > 1e-8  # langevin does move the block
    assert np.abs(final["implicit"] - final["lagged"]).max() < 1e-12


def test_a_rewriting_fix_next_to_langevin_makes_everything_lagged(tmp_path):
    # fix setforce rewrites forces: its order relative to langevin matters, so the forces of
    # all other fixes are lagged, exactly as `external lagged` (same code path: bit-identical)
    runs = {}
    for mode in ("implicit", "lagged"):
        runs[mode] = run_deck(BLOCK, tmp_path / mode,
                              variables={**BASE, "external": mode, "setforce": 1, "grav": 9.81,
                                         "iters": 100, "dump_every": 10})
    notes = sissm_notes(runs["implicit"])
    assert len(notes) == 1 and "the forces of all other fixes are lagged" in notes[0]
    assert not sissm_notes(runs["lagged"])  # asked for: nothing to say
    a = read_dump(tmp_path / "implicit" / "dump.atoms")[-1]
    b = read_dump(tmp_path / "lagged" / "dump.atoms")[-1]
    assert np.array_equal(positions(a), positions(b))


def test_pure_fixes_alone_say_nothing(tmp_path):
    run = run_deck(BLOCK, tmp_path, variables={"solver": "krylov", "dt": 1.0e-5, "nsteps": 2,
                                               "grav": 9.81, "addforce": 1.0e3})
    assert not sissm_notes(run)


# fix restrain (a stiff bond between two opposite corners of the block, 4.12 mm apart: K = 5e10,
# r0 = 4 mm; (h omega)^2 = 2 K h^2 / rho = 0.01): a fix the rule of solvers/external_forces.h re-evaluates from what LAMMPS tells
# about it (it declares a potential: energy_global_flag) without knowing its style name. It is
# added after the deck's first run (run 0), fix sissm defined again next to it; the block
# vibrates (5 m/s between its ends) for 2 steps.
RESTRAIN = """fix pin free restrain bond 1 36 5.0e12 5.0e12 4.12e-3
fix integrate free sissm iterations 1000 tolerance 1.0e-12 solver krylov external {} {}
run 2
"""


def restrained(tmp_path, name, external, opts=""):
    run = run_deck(BLOCK, tmp_path / name, files={"restrain": RESTRAIN.format(external, opts)},
                   variables={"solver": "krylov", "dt": 1.0e-5, "nsteps": 0, "vib": 5.0,
                              "dump_every": 2, "include_after": "restrain"})
    assert run.thermo[-1]["f_integrate[4]"][-1] == 0
    return run, positions(read_dump(tmp_path / name / "dump.atoms")[-1])


def test_a_fix_with_a_potential_is_implicit_and_keyword_lagged_lags_it(tmp_path):
    # Re-evaluated at every iterate, the restraint's force is the one at the end of each step
    # (backward Euler), so the trajectory differs from the lagged one (its force of the start of
    # each step) by O(h^2 K dx / rho): measured 2.7e-9 m. Named in keyword lagged, it is the
    # only lagged fix: the same equations as `external lagged` (measured 2.2e-11 m apart, 0.8%
    # of that gap), and the log says so.
    implicit, y_implicit = restrained(tmp_path, "implicit", "implicit")
    lagged, y_lagged = restrained(tmp_path, "lagged", "lagged")
    named, y_named = restrained(tmp_path, "named", "implicit", "lagged pin")
    assert not sissm_notes(implicit) and not sissm_notes(lagged)
    notes = sissm_notes(named)
    assert len(notes) == 1 and "fix pin (restrain) may hold state" in notes[0]
    gap = np.abs(y_implicit - y_lagged).max()
    assert gap > 1e-9
    assert np.abs(y_named - y_lagged).max() < 0.05 * gap


def test_keyword_lagged_names_fixes_that_exist(tmp_path):
    run = run_deck(BLOCK, tmp_path, check=False,
                   variables={"solver": "krylov", "nsteps": 1, "opts": "lagged nosuch"})
    assert not run.ok
    assert any("Fix sissm integrate lagged: no fix with ID nosuch" in e for e in run.errors)
