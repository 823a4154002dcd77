"""kappa auto: fix nosb/contact's barrier stiffness adapted to the implicit steps of fix sissm as
in Incremental Potential Contact (doc/fix_nosb_contact.rst, "Choosing kappa"). IPC's rule compares
the barrier's stiffness with the mass in the step's incremental potential, so it is free of units:
the lower bound is checked against the formula computed here from the scene (bounding box, mean
mass, step), the same throw gives the same motion in SI and in micro units (where a number given
for kappa would have to be converted), the collision-free guarantee holds, the balance raises the
stiffness while two blocks collide and a restart file keeps what it needs; without fix sissm, or
with its forces lagged, kappa auto is an error."""
import math
from pathlib import Path

import numpy as np
import pytest

from lammps_run import run_deck
from test_contact_ccd import DECK, DHAT, DMIN, checker, throw

import mesh_gaps

REPO = Path(__file__).resolve().parents[2]
BLOCKS = REPO / "examples" / "contact" / "in.two-blocks"


def b2(g, dhat):
    """b''(g) of the barrier b(g) = -(g - dhat)^2 ln(g / dhat)."""
    return -2.0 * math.log(g / dhat) - 4.0 * (g - dhat) / g + (g - dhat) ** 2 / g ** 2


def ipc_lower_bound(diagonal, mean_mass, dhat):
    """IPC's kappa_min in the units of the incremental potential: its barrier 1e-8 of the
    scene's diagonal from contact is 1e11 times as stiff as the mean mass."""
    return 1e11 * mean_mass / b2(1e-8 * diagonal, dhat)


def test_lower_bound_is_ipcs(tmp_path):
    """Before the cloths meet the stiffness is IPC's lower bound over c = h^2: 3.563 N/m here."""
    run, lower, upper = throw(tmp_path, kappa="auto", steps=2)
    (vl, _), (vu, _) = lower, upper
    h, dt = 0.01, 1e-3
    vu = vu + np.array([0.0023, 0.0031, h])
    points = np.vstack([vl, vu])
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    # read_mesh: volume t A_k, the vertex areas adding up to the mesh's (0.2^2 and 0.1^2 m^2)
    mean_mass = 400 * 0.0005 * (0.2 ** 2 + 0.1 ** 2) / len(points)
    expected = ipc_lower_bound(diagonal, mean_mass, DHAT) / dt ** 2
    kappa = run.thermo[-1]["f_c[9]"]
    assert np.allclose(kappa, expected, rtol=1e-9, atol=0), (kappa, expected)
    assert expected == pytest.approx(3.563, rel=1e-3)


@pytest.mark.parametrize("nprocs", [1, 2])
def test_thrown_cloth_never_within_dmin(tmp_path, nprocs):
    """The throw of test_contact_ccd.py (3 mm per step onto the held cloth) with kappa auto: no
    pair of the dumps within dmin at any step (independent checker), it bounces, every step
    converges, and the stiffness stays within IPC's bounds (here at the lower one: the balance
    of the impact asks for less, measured)."""
    run, lower, upper = throw(tmp_path, nprocs=nprocs, kappa="auto", steps=10)
    gaps_of, n = checker(lower, upper)
    smallest = np.inf
    for frame in mesh_gaps.read_dump(tmp_path / "dump.ccd"):
        gaps = gaps_of.check(mesh_gaps.mesh_positions(frame, n), radius=0.006, dmin=DMIN)
        assert not gaps.fails, (frame.step, gaps)
        near = [g.distance for g in (gaps.point_triangle, gaps.edge_edge) if g is not None]
        smallest = min([smallest] + near)
    t = run.thermo[-1]
    assert (t["f_c[1]"] > 0).any()                          # the barrier acted
    assert DMIN < smallest < DMIN + DHAT, smallest
    assert t["c_vz"][-1] > 0.1
    assert t["f_integrate[2]"].max() < 1e-6
    kmin = t["f_c[9]"][0]
    assert (t["f_c[9]"] >= kmin * (1 - 1e-12)).all() and (t["f_c[9]"] <= 100 * kmin).all()


def test_same_motion_in_si_and_micro_units(tmp_path):
    """The throw in micro units (um, us, pg): the same motion to 9 digits, and a stiffness that
    is the SI one converted (1 pg/us^2 = 1e-3 N/m). A number for kappa would have had to be
    converted by hand; a rule with a constant in s^-2 would have given another motion."""
    si, _, _ = throw(tmp_path / "si", kappa="auto", steps=6)
    micro, _, _ = throw(tmp_path / "micro", kappa="auto", steps=6, units="micro", L=1e6, T=1e6,
                        M=1e15)
    a, b = si.thermo[-1], micro.thermo[-1]
    assert (a["f_c[1]"] > 0).any()
    for key, scale in (("c_zmin", 1e6), ("f_c[3]", 1e6), ("c_vz", 1.0), ("f_c[9]", 1e3)):
        assert np.allclose(b[key], scale * a[key], rtol=1e-9, atol=1e-9 * np.abs(scale * a[key]).max()), \
            (key, a[key], b[key])
    assert (a["f_integrate[1]"] == b["f_integrate[1]"]).all()


BLOCKS_AFTER_RESTART = """
read_restart    blocks.restart
pair_style      peri/nosb
pair_coeff      * * linear 1.0e9 0.6e9 $(3.0002*0.001) 0 0 break no contact no
neighbor        0.001 bin
fix             contact all nosb/contact dhat 0.0005 dmin 0.001 kappa auto
fix             integrate all sissm
thermo_style    custom step f_contact[3] f_contact[9]
thermo_modify   format float %.12g
thermo          1
run             4
"""


def test_colliding_blocks_raise_it_and_a_restart_keeps_it(tmp_path):
    """Two free blocks at 20 m/s each under fix sissm with 10 us steps (test_contact_ccd.py):
    with kappa auto the balance of the first iterate raises the stiffness above the lower bound
    while they are in contact (measured 1.13 x), back to it when no pair is active; momentum is
    kept and they stay apart. A restart file written in the contact keeps the stiffness (and the
    box and mass its bounds come from): the restarted run starts and goes on as the whole run."""
    whole = run_deck(BLOCKS, tmp_path / "whole", variables={
        "integrator": "sissm", "dt": 1e-5, "steps": 12, "every": 1, "kappa": "auto"})
    t = whole.thermo[-1]
    kmin = t["f_contact[9]"][0]
    active = t["f_contact[6]"] > 0
    assert active.any() and not active[0]
    assert t["f_contact[9]"][active].max() > 1.05 * kmin
    assert (t["f_contact[9]"] <= 100 * kmin).all() and (t["f_contact[9]"] >= kmin).all()
    assert (t["f_contact[9]"][~active] == kmin).all()
    assert np.abs(t["c_px"]).max() < 1e-12 * t["c_pxleft"][0]
    assert t["f_contact[3]"].min() > 0.001

    first = run_deck(f"include {BLOCKS}\nwrite_restart blocks.restart\n", tmp_path / "restart",
                     variables={"integrator": "sissm", "dt": 1e-5, "steps": 8, "every": 1,
                                "kappa": "auto"})
    assert first.thermo[-1]["f_contact[9]"][-1] > 1.05 * kmin     # written while raised
    second = run_deck(BLOCKS_AFTER_RESTART, tmp_path / "restart")
    r = second.thermo[-1]
    rows = {int(s): i for i, s in enumerate(t["Step"])}
    for k, step in enumerate(r["Step"]):
        i = rows[int(step)]
        assert r["f_contact[9]"][k] == pytest.approx(t["f_contact[9]"][i], rel=1e-9), step
        # the restarted run sets its multigrid up anew, so its Newton iterates differ: each
        # step lands within the tolerance (1e-6 of the 1 mm spacing) of the implicit step
        # (measured 3e-12 m at step 12)
        assert r["f_contact[3]"][k] == pytest.approx(t["f_contact[3]"][i], abs=1e-9), step


def test_kappa_auto_needs_fix_sissm(tmp_path):
    run = run_deck(BLOCKS, tmp_path, check=False, variables={"kappa": "auto", "steps": 1})
    assert any("kappa auto needs fix sissm" in e for e in run.errors), run.errors


def test_kappa_auto_with_lagged_forces_is_refused(tmp_path):
    run, _, _ = throw(tmp_path, check=False, kappa="auto", ccd="no", more="external lagged",
                      steps=1)
    assert any("adapts its stiffness" in e and "external lagged" in e for e in run.errors), \
        run.errors


def test_setup_uses_the_schemes_force_factor(tmp_path):
    """Before the first step the stiffness is the lower bound over the force factor c of fix
    sissm's scheme at the run's time step, the c of its steps: generalized-alpha's c is not h^2
    (the setup force starts its acceleration)."""
    run, _, _ = throw(tmp_path, kappa="auto", scheme="genalpha", steps=2)
    k = run.thermo[-1]["f_c[9]"]
    assert k[0] == pytest.approx(k[1], rel=1e-12) and k[1] == pytest.approx(k[2], rel=1e-12)
    euler, _, _ = throw(tmp_path / "euler", kappa="auto", steps=0)
    assert abs(k[0] / euler.thermo[-1]["f_c[9]"][0] - 1.0) > 0.1


def copy_meshes(workdir):
    """The two cloths of the throw in workdir (for a deck edited from test_contact_ccd.py's)."""
    throw(workdir / "meshes", steps=0)
    for name in ("lower.obj", "upper.obj"):
        (workdir / name).write_text((workdir / "meshes" / name).read_text())


def test_mixed_external_forces(tmp_path):
    """A lagged fix beside the contact (fix langevin: external mixed, the contact still
    re-evaluated at every iterate): kappa auto runs and the throw stays collision-free."""
    deck = DECK.read_text().replace(
        "fix             integrate upper sissm",
        "fix             lang upper langevin 0.0 0.0 1.0 48279\n"
        "fix             integrate upper sissm")
    copy_meshes(tmp_path)
    run = run_deck(deck, tmp_path, variables={"kappa": "auto", "steps": 6})
    t = run.thermo[-1]
    assert (t["f_c[1]"] > 0).any()
    assert t["f_c[3]"].min() > DMIN
    assert "lagged" in run.log


def test_kappa_auto_with_two_fix_sissm_is_refused(tmp_path):
    deck = DECK.read_text().replace(
        "fix             integrate upper sissm scheme ${scheme} ${more}",
        "fix             integrate upper sissm\nfix             other lower sissm")
    copy_meshes(tmp_path)
    run = run_deck(deck, tmp_path, check=False, variables={"kappa": "auto", "steps": 1})
    assert any("more than one fix sissm" in e for e in run.errors), run.errors
