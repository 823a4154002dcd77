"""Collision-free implicit steps: fix nosb/contact under fix sissm limits every move of the atoms
by continuous collision detection (doc/fix_nosb_contact.rst, "Collision-free steps under fix
sissm"). A 10 cm cloth thrown at 3 m/s onto a held 20 cm cloth with 1 ms steps moves 3 mm per
step, more than dmin + dhat = 3 mm of barrier range: the independent checker (tools/mesh_gaps.py)
finds no non-adjacent point-triangle or edge-edge pair of the two cloths within dmin in any
step's dump, on 1 and 2 ranks; the same throw with `ccd no` ends in the barrier's error (an
iterate went through); a step farther than the candidates reach is redone as sub-steps, and
without them (unconverged warn) it is an error naming the skin."""
import sys
from pathlib import Path

import numpy as np
import pytest

from lammps_run import run_deck

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
import make_sheet  # noqa: E402
import mesh_gaps  # noqa: E402

DECK = Path(__file__).parent / "decks" / "contact_ccd.lmp"
DMIN, DHAT = 0.001, 0.002


def write_cloth(path, size):
    vertices, faces = make_sheet.rectangle(size, size, 0.01, "alternate", 0.0, 1)
    make_sheet.write_obj(path, vertices, faces, ["cloth for test_contact_ccd.py"])
    return np.array(vertices, dtype=float), [tuple(t) for t in faces]


def throw(workdir, nprocs=1, check=True, **variables):
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    lower = write_cloth(workdir / "lower.obj", 0.2)
    upper = write_cloth(workdir / "upper.obj", 0.1)
    run = run_deck(DECK, workdir, nprocs=nprocs, check=check, variables=variables)
    return run, lower, upper


def checker(lower, upper):
    (vl, fl), (vu, fu) = lower, upper
    n = len(vl)
    vertices = np.vstack([vl, vu])
    faces = fl + [tuple(v + n for v in t) for t in fu]
    return mesh_gaps.MeshGaps(vertices, faces, 1, 1), len(vertices)


@pytest.mark.parametrize("nprocs", [1, 2])
def test_thrown_cloth_never_within_dmin(tmp_path, nprocs):
    run, lower, upper = throw(tmp_path, nprocs=nprocs, steps=12)
    gaps_of, n = checker(lower, upper)
    smallest = np.inf
    frames = list(mesh_gaps.read_dump(tmp_path / "dump.ccd"))
    assert len(frames) == 13
    for frame in frames:
        gaps = gaps_of.check(mesh_gaps.mesh_positions(frame, n), radius=0.006, dmin=DMIN)
        assert not gaps.fails, (frame.step, gaps)
        near = [g.distance for g in (gaps.point_triangle, gaps.edge_edge) if g is not None]
        smallest = min([smallest] + near)
    t = run.thermo[-1]
    # it reached the barrier (within a tenth of dhat of dmin) and stayed out of dmin...
    assert DMIN < smallest < DMIN + 0.1 * DHAT, smallest
    assert t["f_c[3]"].min() > DMIN
    assert abs(t["f_c[3]"].min() - smallest) < 1e-9
    # ...in steps that move the cloth by more than the barrier's range (3 mm at 3 m/s)
    assert t["c_zmin"][1] - t["c_zmin"][2] > DMIN + DHAT - 1e-12
    # and it bounced: moving up at the end; every step converged
    assert t["c_vz"][-1] > 0.1
    assert t["f_integrate[2]"].max() < 1e-6
    # the default (ccd yes) says nothing about collision-free steps
    assert not [w for w in run.warnings if "collision-free" in w], run.warnings


def test_one_and_two_ranks_agree(tmp_path):
    one, _, _ = throw(tmp_path / "one", steps=6)
    two, _, _ = throw(tmp_path / "two", nprocs=2, steps=6)
    # the solves converge to 1e-6 of a particle size, 1e-8 m on 1 cm particles: positions agree
    # to 10x that, velocities ((y - y^n) / h, h = 1 ms) to 10x that / h
    for key, tol in (("c_zmin", 1e-7), ("f_c[3]", 1e-7), ("c_vz", 1e-4)):
        a, b = one.thermo[-1][key], two.thermo[-1][key]
        assert np.abs(a - b).max() < tol, (key, a, b)


def test_without_ccd_an_iterate_goes_through_the_barrier(tmp_path):
    """ccd no (with a skin wide enough for the motion): the first step that reaches the held
    cloth moves it 3 mm, past the barrier's 2 mm range, and the barrier reports the crossing; the
    user was warned once that steps are not collision-free."""
    run, _, _ = throw(tmp_path, check=False, ccd="no", skin=0.03, comm=0.22, steps=8)
    assert any("not more than dmin" in e and "at step 3" in e for e in run.errors), run.errors
    told = [w for w in run.warnings if "not collision-free" in w]
    assert len(told) == 1, run.warnings


@pytest.mark.parametrize("nprocs", [1, 2])
def test_step_beyond_the_candidates_reach_is_redone_as_substeps(tmp_path, nprocs):
    """A 4 mm skin lets a step move atoms 1.5 mm at least (3/8 of the skin); at 3 mm per step the
    first step already needs more: it is redone as sub-steps (the default unconverged cutback),
    each of which may start from new candidates, and the throw goes on, every frame outside dmin
    (mesh_gaps) and every step converged. The whole step stops where the reach stops it (its
    moves cut to nothing: NonlinearSystem::stalled()) instead of spending its 100 evaluations
    there: measured 4, 4 and 53 evaluations for the three steps with all their sub-steps (52 on
    2 ranks), 102, 102 and 143 when the whole step ran to its budget. All ranks stop alike."""
    run, lower, upper = throw(tmp_path, nprocs=nprocs, skin=0.004, steps=3)
    assert run.thermo[-1]["Step"][-1] == 3
    assert run.thermo[-1]["f_integrate[1]"].max() < 100
    assert ("Fix sissm integrate: step 1 went beyond the reach of the contact candidates of the "
            "last neighbor list build; redone as") in run.log
    assert run.thermo[-1]["f_integrate[2]"].max() < 1e-6
    gaps_of, n = checker(lower, upper)
    for frame in mesh_gaps.read_dump(tmp_path / "dump.ccd"):
        gaps = gaps_of.check(mesh_gaps.mesh_positions(frame, n), radius=0.006, dmin=DMIN)
        assert not gaps.fails, (frame.step, gaps)


def test_step_beyond_the_candidates_reach_is_an_error_without_cutback(tmp_path):
    """The same throw with unconverged warn (no sub-steps): the first step ends in an error that
    says what to change."""
    run, _, _ = throw(tmp_path, check=False, skin=0.004, steps=3, more="unconverged warn")
    assert any("fix sissm step 1 needs atom" in e and "half the neighbor skin (0.002)" in e
               and "larger neighbor skin" in e for e in run.errors), run.errors


def test_lagged_contact_is_refused(tmp_path):
    run, _, _ = throw(tmp_path, check=False, more="external lagged", steps=1)
    assert any("makes the implicit step collision-free" in e and "external lagged" in e
               for e in run.errors), run.errors


# Two free elastic blocks (examples/contact/in.two-blocks: 5x5x5 particles each, 20 m/s each way)
# collide under fix sissm with 10 us steps, 100 times the explicit example's step: each step
# closes the gap by 0.4 mm, most of the barrier's range (dhat = 0.5 mm). No external force: the
# total momentum stays at round-off of one block's (measured 2e-17 kg m/s against 2.5e-3; the
# momentum balance of fix sissm keeps a free group's momentum to round-off whatever the
# solver's tolerance), they stay more than dmin apart (closest 1.254 mm, dmin = 1 mm) and leave
# each other (backward Euler at this step keeps 22% of the momentum in the rebound).
def test_colliding_blocks_keep_their_momentum(tmp_path):
    run = run_deck(REPO / "examples" / "contact" / "in.two-blocks", tmp_path, variables={
        "integrator": "sissm", "dt": 1e-5, "steps": 25, "every": 1})
    t = run.thermo[-1]
    p_block = t["c_pxleft"][0]
    assert p_block == pytest.approx(0.0025, rel=1e-12)
    assert np.abs(t["c_px"]).max() < 1e-12 * p_block
    assert t["f_contact[6]"].max() > 0                    # the blocks met through the barrier
    assert 0.001 < t["f_contact[3]"].min() < 0.0015
    assert t["c_pxleft"][-1] < -0.1 * p_block             # and bounced
    assert t["v_gap"][-1] > t["v_gap"].min() + 0.001
