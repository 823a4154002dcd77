"""Friction of fix nosb/contact (keywords friction mu, epsv v): IPC's lagged smooth friction on
the barrier's active pairs, lagged at each step's start under fix sissm, from the velocities
(u = v dt) under fix nve. Issue 15's acceptance: a block on an incline (examples/contact/
in.incline) slides with acceleration g (sin theta - mu cos theta) within 2% for mu < tan theta
and sticks for mu > tan theta; friction 0 is the frictionless fix; one particle sliding over a
triangle feels Coulomb's force against an independent evaluation; 1 and 2 ranks agree."""
import math
import re
from pathlib import Path

import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from test_contact import CLOTHS, barrier, cloth

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "contact"
INCLINE = EXAMPLE / "in.incline"
G, THETA, EPSV = 9.81, math.radians(30.0), 1.0e-3
DMIN = 0.0005    # in.incline's thickness (m)


def incline(workdir, nprocs=1, deck=INCLINE, **variables):
    """in.incline run in workdir (incline.obj copied there): its last thermo table."""
    files = {"incline.obj": (EXAMPLE / "incline.obj").read_text()}
    run = run_deck(deck, workdir, nprocs=nprocs, variables=variables, files=files)
    return run.thermo[-1]


def acceleration(t, start, end):
    """Least-squares slope of the downhill velocity v_vs over start <= time <= end."""
    m = (t["Time"] >= start - 1e-12) & (t["Time"] <= end + 1e-12)
    return np.polyfit(t["Time"][m], t["v_vs"][m], 1)[0], m


# Sliding under fix sissm (backward Euler, 1 ms steps, 150 steps): the block starts at rest with
# its bottom layer at dmin + dhat above the sheet, lands within a few steps (backward Euler damps
# the bounce) and then slides. The acceleration is the slope of the downhill velocity over
# 50-150 ms (v^{n+1} = (x^{n+1} - x^n) / h): measured 3.2062 against 3.2059 m/s^2 (mu 0.2) and
# 1.5052 against 1.5067 (mu 0.4), within 0.1%; issue 15 asks for 2%. The block stays on the
# sheet (friction pairs at every output, the smallest distance above dmin).
@pytest.mark.parametrize("mu", [0.2, 0.4])
def test_incline_slides_under_fix_sissm(tmp_path, mu):
    t = incline(tmp_path, mu=mu, steps=150, every=5)
    expected = G * (math.sin(THETA) - mu * math.cos(THETA))
    a, window = acceleration(t, 0.05, 0.15)
    assert abs(a - expected) <= 0.02 * expected, (a, expected)
    assert (t["f_contact[7]"][window] >= 16).all()
    assert t["f_contact[3]"].min() > DMIN
    # the friction work over a step: mu N times the step's slip v h (the normal force N =
    # m g cos theta; m = 64 mg), summed over the window's outputs within 3% (measured 1.1% and
    # 1.8%; one output alone is off by up to 12%: the normal force jolts as particles cross the
    # sheet's edges, where two triangles' pairs are active, and after a list build the work is
    # taken with lambda at x^{n+1})
    work = mu * 64e-6 * G * math.cos(THETA) * t["v_vs"][window] * 1e-3
    total = t["f_contact[8]"][window].sum()
    assert abs(total - work.sum()) <= 0.03 * work.sum(), (total, work.sum())


# mu = 0.8 > tan 30 = 0.577: the block sticks up to the regularisation. The smoothed static
# regime creeps at the speed where f1(y) = tan(theta) / mu, y = v h, eps = epsv h
# (core/contact/friction.h): v = epsv (1 - sqrt(1 - tan(theta) / mu)) = 0.4725 epsv; measured
# 0.4727 epsv at the end. The speed stays below epsv over 50-150 ms, the displacement below
# epsv times the window.
def test_incline_sticks_under_fix_sissm(tmp_path):
    mu = 0.8
    t = incline(tmp_path, mu=mu, steps=150, every=5)
    m = t["Time"] >= 0.05 - 1e-12
    assert np.abs(t["v_vs"][m]).max() < EPSV
    moved = t["v_pos"][m][-1] - t["v_pos"][m][0]
    assert abs(moved) < EPSV * 0.1, moved
    creep = EPSV * (1.0 - math.sqrt(1.0 - math.tan(THETA) / mu))
    assert abs(t["v_vs"][-1] - creep) <= 0.02 * creep, (t["v_vs"][-1], creep)


# Under fix nve (1 us steps, the explicit recipe u = v dt): the block first rests 10 ms with
# friction 2 under a viscous drag (the deck's settle), so that it starts at its equilibrium gap
# (fix nve does not damp its bounce on the barrier), then slides for 40 ms. Measured 3.2043
# against 3.2059 m/s^2 over 20-60 ms (0.05%).
def test_incline_slides_under_fix_nve(tmp_path):
    mu = 0.2
    t = incline(tmp_path, mu=mu, integrator="nve", dt=1e-6, settle=10000, steps=60000,
                every=1000)
    expected = G * (math.sin(THETA) - mu * math.cos(THETA))
    a, _ = acceleration(t, 0.02, 0.06)
    assert abs(a - expected) <= 0.02 * expected, (a, expected)


# 1 and 2 ranks: the same steps up to the solver's tolerance (measured: positions 1e-11 m,
# velocities 7e-10 m/s apart after 60 ms, the counts equal); asserted: 1e-8 m and 1e-6 m/s
# (the velocities are displacements over h = 1 ms).
def test_incline_two_ranks_agree(tmp_path):
    one = incline(tmp_path / "one", mu=0.2, steps=60, every=5)
    two = incline(tmp_path / "two", nprocs=2, mu=0.2, steps=60, every=5)
    assert np.abs(one["v_pos"] - two["v_pos"]).max() < 1e-8
    assert np.abs(one["v_vs"] - two["v_vs"]).max() < 1e-6
    assert np.abs(one["v_vn"] - two["v_vn"]).max() < 1e-6
    for col in ("f_contact[1]", "f_contact[7]"):
        assert (one[col] == two[col]).all(), col


# friction 0 (the default) is the frictionless fix: the same thermo, to the last printed digit,
# as the deck without the keyword
def test_friction_zero_is_frictionless(tmp_path):
    text = INCLINE.read_text()
    plain = text.replace(" friction ${mu}", "")
    assert plain != text
    zero = incline(tmp_path / "zero", mu=0, steps=40, every=5)
    none = incline(tmp_path / "none", deck=plain, steps=40, every=5)
    for col in zero:
        assert (zero[col] == none[col]).all(), col
    assert (zero["f_contact[7]"] == 0).all() and (zero["f_contact[8]"] == 0).all()
    # and the block slides down without friction: g sin theta
    a, _ = acceleration(zero, 0.01, 0.04)
    assert abs(a - G * math.sin(THETA)) <= 0.02 * G * math.sin(THETA), a


# One particle over one held triangle in the plane z = 0 (legs 2 cm), 4 mm above it (dmin 2 mm,
# dhat 5 mm), moving with velocity v: the explicit recipe (no fix sissm) gives it the barrier's
# normal force lambda = kappa |b'(d - dmin)| and the friction -mu lambda s(|v_T| / epsv) v_T /
# |v_T| with s(r) = 2 r - r^2 below 1, 1 beyond, whatever the normal velocity; the triangle's
# vertices take the opposite (the forces sum to zero). Computed here from the closed form.
PARTICLE = """
units           si
boundary        f f f
atom_style      peri
atom_modify     map array
region          box block -0.05 0.05 -0.05 0.05 -0.05 0.05
create_box      2 box
read_mesh       tri.obj type 1 thickness 0.001 density 1000 group sheet
create_atoms    2 single 0.005 0.005 0.004 units box
group           p type 2
set             group p volume 1e-9 density 1000
velocity        p set ${vx} ${vy} ${vz} units box
neighbor        0.005 bin
comm_modify     cutoff 0.12
fix             c all nosb/contact dhat 0.005 dmin 0.002 kappa 10 friction 0.3 epsv 0.01
timestep        1e-4
compute         vol all property/atom vfrac
thermo_style    custom step f_c[1] f_c[7] f_c[8]
thermo_modify   format float %.17g
dump            d all custom 1 dump.f id x y z fx fy fz c_vol
dump_modify     d sort id format float %.17g
run             0
"""


@pytest.mark.parametrize("v", [(0.3, -0.1, 0.05), (0.004, 0.0, -0.02), (0.0, 0.0, 0.1)])
def test_one_particle_against_closed_form(tmp_path, v):
    tri = "v 0 0 0\nv 0.02 0 0\nv 0 0.02 0\nf 1 2 3\n"
    run = run_deck(PARTICLE, tmp_path, files={"tri.obj": tri},
                   variables={"vx": v[0], "vy": v[1], "vz": v[2]})
    frame = read_dump(tmp_path / "dump.f")[0]
    F = np.stack([frame["fx"], frame["fy"], frame["fz"]], axis=1) * frame["c_vol"][:, None]
    mu, epsv, kappa, dhat, dmin = 0.3, 0.01, 10.0, 0.005, 0.002
    lam = kappa * abs(barrier_derivative(0.004 - dmin, dhat))
    vt = np.array([v[0], v[1], 0.0])
    speed = np.linalg.norm(vt)
    r = speed / epsv
    s = 1.0 if r >= 1.0 else 2.0 * r - r * r
    friction = -mu * lam * s * vt / speed if speed > 0 else np.zeros(3)
    expected = friction + np.array([0.0, 0.0, lam])
    scale = lam
    assert np.abs(F[3] - expected).max() <= 1e-9 * scale, (F[3], expected)
    assert np.abs(F.sum(axis=0)).max() <= 1e-12 * scale
    t = run.thermo[-1]
    assert t["f_c[7]"][0] == 1
    # the work over the step: mu lambda s |v_T| dt
    assert abs(t["f_c[8]"][0] - mu * lam * s * speed * 1e-4) <= 1e-12 * scale * 1e-4


def barrier_derivative(g, dhat):
    """b'(g) of b(g) = -(g - dhat)^2 ln(g / dhat), checked against a central difference of
    test_contact's barrier()."""
    d = -2.0 * (g - dhat) * math.log(g / dhat) - (g - dhat) ** 2 / g
    step = 1e-7 * dhat
    fd = (barrier(g + step, dhat) - barrier(g - step, dhat)) / (2 * step)
    assert abs(d - fd) <= 1e-6 * abs(d)
    return d


# ---- bad input ----

@pytest.mark.parametrize("args, message", [
    ("dhat 0.005 kappa 1 friction -1", "friction mu must be >= 0, got '-1'"),
    ("dhat 0.005 kappa 1 friction 0.3 epsv 0", "epsv must be > 0, got '0'"),
    ("dhat 0.005 kappa 1 epsv", "fix nosb/contact epsv"),
])
def test_bad_friction_arguments(tmp_path, args, message):
    mesh, _, _ = cloth(tmp_path)
    run = run_deck(CLOTHS, tmp_path, check=False,
                   variables={"mesh": mesh, "custom": "yes", "args": args})
    assert any(message in e for e in run.errors), (args, run.errors)


# ---- the default slip speed ----

def test_default_slip_speed_is_ipcs_in_any_units(tmp_path):
    """Without epsv the slip speed is IPC's 1e-3 m/s in the deck's units: the thrown cloth of
    test_contact_ccd.py with friction 0.1 (kappa auto) in SI and in cgs units gives the same
    motion and friction work (1 J = 1e7 erg), and in cgs the same as epsv given as 0.1 (cm/s).
    (The work depends on epsv only through the vertices that slip slower than it, so how much
    the number 1e-3 in cgs, 1e-3 cm/s, changes the work depends on the run: measured 1e-9
    relative on this one, 2026-11-29; the exact comparison with 0.1 cm/s fails on that.)
    (iterations 200: with the plate bending energy the impact step 4 takes 132 force
    evaluations, above fix sissm's default cap of 100; 87 with the hinges; measured 2026-11-30.)"""
    from test_contact_ccd import throw
    cgs = {"units": "cgs", "L": 100, "T": 1, "M": 1000}
    more = {"more": "iterations 200"}
    si, _, _ = throw(tmp_path / "si", kappa="auto", friction=0.1, steps=4, **more)
    cm, _, _ = throw(tmp_path / "cgs", kappa="auto", friction=0.1, steps=4, **cgs, **more)
    given, _, _ = throw(tmp_path / "given", kappa="auto", friction="0.1 epsv 0.1", steps=4,
                        **cgs, **more)
    a, b, c = si.thermo[-1], cm.thermo[-1], given.thermo[-1]
    assert a["f_c[7]"].max() > 0 and a["f_c[8]"][-1] > 0        # friction acted
    assert np.allclose(b["c_zmin"], 100 * a["c_zmin"], rtol=1e-10, atol=0)
    assert np.allclose(b["f_c[8]"], 1e7 * a["f_c[8]"], rtol=1e-9, atol=0)
    assert np.allclose(c["f_c[8]"], b["f_c[8]"], rtol=1e-12, atol=0)
    assert np.allclose(c["c_zmin"], b["c_zmin"], rtol=1e-12, atol=0)


def test_friction_in_lj_units_needs_epsv(tmp_path):
    deck = PARTICLE.replace("units           si", "units           lj").replace(" epsv 0.01", "")
    tri = "v 0 0 0\nv 0.02 0 0\nv 0 0.02 0\nf 1 2 3\n"
    run = run_deck(deck, tmp_path, check=False, files={"tri.obj": tri},
                   variables={"vx": 0, "vy": 0, "vz": 0})
    assert any("with friction in lj units give the slip speed epsv" in e for e in run.errors), \
        run.errors


def test_thrown_cloth_with_friction_converges_under_genalpha(tmp_path):
    """The thrown cloth of test_contact_ccd.py with friction 0.3 and kappa auto under scheme
    genalpha (with the contact fix: its Wood-Bossak-Zienkiewicz member, the forces at the end
    positions): the 10 steps through the impact all converge, none cut back, and no candidate
    pair comes within dmin (measured 20.7 evaluations per step, 2026-11-29; the same throw under
    bdf2 stops at step 4, not converged even as 16 sub-steps)."""
    from test_contact_ccd import DMIN as CCD_DMIN, throw
    run, _, _ = throw(tmp_path, kappa="auto", friction=0.3, scheme="genalpha", steps=10)
    t = run.thermo[-1]
    assert t["Step"][-1] == 10
    assert t["f_c[7]"].max() > 0                                   # friction acted
    assert t["f_c[3]"].min() > CCD_DMIN
    summary = re.search(r"run: 10 steps, [\d.]+ iterations per step, (\d+) unconverged, "
                        r"(\d+) cut back", run.log)
    assert summary and summary.groups() == ("0", "0"), run.log[-2000:]
