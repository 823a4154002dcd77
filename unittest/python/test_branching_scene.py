"""examples/fracture/in.branching.nosb (peri/nosb, deviation length, 1 mm spacing) under the
tension of 4 MPa at which its crack runs and branches (README, "Dynamic crack branching"), to
24 us: the crack leaves the notch tip, runs below the Rayleigh speed, branches near the middle
of the ligament, and no damage forms off it (branching.py's measurement)."""
import shutil
import sys

from lammps_run import REPO, run_deck

SCENES = REPO / "examples" / "fracture"
sys.path.insert(0, str(SCENES))
import branching  # noqa: E402

A = 0.001
DT = 25e-9
# Rayleigh speed of E = 72 GPa, nu = 0.22, 2440 kg/m^3: (0.862 + 1.14 nu) / (1 + nu) sqrt(G/rho)
RAYLEIGH = 3170.0


def test_the_crack_runs_from_the_notch_tip_and_branches_below_the_rayleigh_speed(tmp_path):
    for name in ("in.branching.nosb", "branching.geometry", "branching.run"):
        shutil.copy(SCENES / name, tmp_path / name)
    run_deck(tmp_path / "in.branching.nosb", tmp_path,
             variables={"sigma": 4e6, "t_end": 24e-6, "dump": 40})
    rows = branching.analyse(tmp_path / "dump.branching.nosb", A, DT, 2.0)
    assert len(rows) == 25 and rows[-1]["time"] == 24.0
    cracked = [r for r in rows if r["tip_x"] == r["tip_x"]]
    # measured: the first damaged path at 6 us, tip x 52.5 mm; 82.5 mm at 22 us
    assert 4.0 <= cracked[0]["time"] <= 8.0 and cracked[0]["tip_x"] <= 0.055
    tips = [r["tip_x"] for r in cracked]
    assert all(b >= a for a, b in zip(tips, tips[1:]))
    assert 0.075 <= tips[-1] <= 0.095
    s = branching.summary(rows)
    # measured: largest speeds 2800 m/s (tip x) and 3000 m/s (along the path)
    assert 1000.0 < s["v_x"] < RAYLEIGH
    # measured: branched at 20 us, at x = 73.5 mm, 25.8 degrees between the branches
    assert s["branched"] and 0.065 <= s["branch_x"] <= 0.082
    assert 10.0 <= s["angle"] <= 45.0
    assert s["right"] is None
    # measured: at most 0.1% of the mid-plane damaged off the crack
    assert max(r["off_path"] for r in rows) < 0.01
