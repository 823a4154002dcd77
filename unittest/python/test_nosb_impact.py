"""The impact example (examples/impact/in.impact.nosb, issue 3): the projectile fractures the
cylinder, and early in the impact the damage stays near the indenter."""
import re

import numpy as np
import pytest

from lammps_run import REPO, read_dump, run_deck

IMPACT = REPO / "examples" / "impact"

# impact.geometry: cylinder of radius 5 mm along y, top face at y = 0, bottom at y = -5 mm;
# spherical indenter of radius R = 1.5 mm, centre at y0 = 1.55 mm moving at -100 m/s,
# dt = 1e-7 s; horizon delta = 1.5 mm.
RADIUS = 0.0015
HORIZON = 0.0015
STEPS = 300  # the indenter tip is then 2.95 mm deep; 1000 steps take the sphere through


def indenter_centre_y(step: int) -> float:
    return 0.00155 - 100.0 * step * 1.0e-7


def run_impact(tmp_path, deck_name, damage_column, steps=STEPS):
    text = (IMPACT / deck_name).read_text()
    # reference positions (fragments fly: damage is judged where the material came from)
    dump = ("fix             ref all store/state 0 x y z\n"
            f"dump            damage all custom {steps} dump.damage id f_ref[1] f_ref[2] "
            f"f_ref[3] x y z {damage_column}\n"
            "dump_modify     damage format float %.17g\n")
    text, count = re.subn(r"(?m)^run\s", dump + "run ", text)
    assert count == 1
    run = run_deck(text, tmp_path, variables={"nsteps": steps, "thermo_every": 100},
                   files={"impact.geometry": (IMPACT / "impact.geometry").read_text()})
    frame = read_dump(tmp_path / "dump.damage")[-1]
    assert frame["step"] == steps and frame["natoms"] == 3487
    return run, frame, frame[damage_column]


def assert_localized(frame, damage, steps):
    x, y, z = (frame[f"f_ref[{k}]"] for k in (1, 2, 3))
    yc = indenter_centre_y(steps)
    tip = yc - RADIUS
    r = np.sqrt(x ** 2 + (y - yc) ** 2 + z ** 2)
    damaged = damage > 0.0
    # it fractures: dozens of particles lose bonds, some lose most of them
    assert np.count_nonzero(damaged) >= 20 and damage.max() > 0.5
    # the heavily damaged particles are at the impact: within one horizon of the sphere
    heavy = damage > 0.5
    assert np.max(r[heavy]) < RADIUS + HORIZON, np.max(r[heavy])
    # nothing is damaged more than one horizon below the indenter's tip ...
    assert np.min(y[damaged]) > tip - HORIZON, (np.min(y[damaged]), tip)
    # ... and the far bottom (the last 1 mm, 2 horizons below the tip) is intact
    assert not np.any(damage[y < -0.004]), np.max(damage[y < -0.004])


def test_impact_damage_criterion_holds_for_peri_lps(tmp_path):
    # control: the built-in peri/lps on the same deck meets the localization criterion at
    # the same step (measured: 382 particles damaged, deepest at y = -2.5 mm for a tip at
    # -2.95 mm, bottom intact), so the criterion is a fair one for the same material and
    # critical stretch
    _, frame, damage = run_impact(tmp_path, "in.impact.lps", "c_damage")
    assert_localized(frame, damage, STEPS)


def test_impact_deck_fractures_near_the_indenter(tmp_path):
    run, frame, damage = run_impact(tmp_path, "in.impact.nosb", "c_nosb[1]")
    thermo = run.thermo[-1]
    assert np.all(np.isfinite(thermo["TotEng"]))
    assert thermo["c_dmax"][-1] == pytest.approx(damage.max(), rel=1e-6)
    assert thermo["c_dsum"][-1] == pytest.approx(damage.sum(), rel=1e-6)
    assert_localized(frame, damage, STEPS)
