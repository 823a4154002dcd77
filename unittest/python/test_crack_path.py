"""tools/crack_path.py on synthetic damage fields on a lattice plate (spacing 1, 100 x 50 x 3
particles): a straight damaged band from a tip at a known angle, no damage, random diffuse
damage, a band off the mid-plane, and the command line on a written dump."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
import crack_path  # noqa: E402

TIP = (40.5, 15.5)
OTHER_TIP = (80.5, 15.5)


def plate(layers=3):
    i, j, k = np.meshgrid(np.arange(100), np.arange(50), np.arange(layers), indexing="ij")
    return np.stack([i.ravel() + 0.5, j.ravel() + 0.5, k.ravel() + 0.5], axis=1)


def band(points, angle_deg, length=30.0, half_width=1.0, tip=TIP):
    """Mask of the particles within half_width of the segment from tip, angle_deg from +y
    turning toward +x."""
    t = math.radians(angle_deg)
    direction = np.array([math.sin(t), math.cos(t)])
    rel = points[:, :2] - np.array(tip)
    s = rel @ direction
    n = np.abs(rel @ np.array([-direction[1], direction[0]]))
    return (s >= 0) & (s <= length) & (n <= half_width)


@pytest.mark.parametrize("angle", [0.0, 30.0, 70.0, -70.0])
def test_a_straight_band_gives_its_angle_length_and_width(angle):
    points = plate()
    damage = np.where(band(points, angle), 0.6, 0.05)
    tips, stats = crack_path.analyse(points, damage, [TIP, OTHER_TIP], (0.0, 1.0), h=1.0)
    assert tips[0]["crack"]
    assert tips[0]["angle"] == pytest.approx(abs(angle), abs=2.0)
    assert np.sign(tips[0]["dir"][0]) == np.sign(angle) or angle == 0.0
    assert tips[0]["length"] == pytest.approx(30.0, abs=1.5)
    assert 1.5 <= tips[0]["width"] <= 3.0
    assert not tips[1]["crack"] and tips[1]["length"] == 0.0 and tips[1]["particles"] == 0
    assert stats["off_path"] == 0.0
    assert stats["layer"] == 100 * 50


def test_a_wider_band_is_wider():
    points = plate()
    narrow = crack_path.analyse(points, np.where(band(points, 70.0), 0.6, 0.0), [TIP],
                                (0.0, 1.0), h=1.0)[0][0]
    wide = crack_path.analyse(points, np.where(band(points, 70.0, half_width=3.0), 0.6, 0.0),
                              [TIP], (0.0, 1.0), h=1.0)[0][0]
    assert wide["width"] >= narrow["width"] + 3.0
    assert wide["angle"] == pytest.approx(70.0, abs=2.0)


def test_no_damage_no_crack():
    points = plate()
    tips, stats = crack_path.analyse(points, np.zeros(len(points)), [TIP], (0.0, 1.0), h=1.0)
    assert not tips[0]["crack"] and math.isnan(tips[0]["angle"]) and tips[0]["width"] == 0.0
    assert stats["off_path"] == 0.0 and stats["mean_all"] == 0.0 and stats["touched"] == 0.0


def test_a_short_damaged_spot_at_the_tip_is_no_crack():
    points = plate()
    damage = np.where(band(points, 70.0, length=4.0), 0.6, 0.0)
    tip = crack_path.analyse(points, damage, [TIP], (0.0, 1.0), h=1.0)[0][0]
    assert not tip["crack"] and 0.0 < tip["length"] < 6.0


def test_diffuse_random_damage_is_off_path():
    points = plate()
    rng = np.random.default_rng(7)
    hot = rng.random(len(points)) < 0.15
    damage = np.where(hot, 0.5, 0.2)
    tips, stats = crack_path.analyse(points, damage, [TIP, OTHER_TIP], (0.0, 1.0), h=1.0)
    assert not any(t["crack"] for t in tips)
    assert stats["off_path"] == pytest.approx(0.15, abs=0.02)
    assert stats["touched"] == 1.0
    assert stats["mean_all"] == pytest.approx(0.2 + 0.3 * 0.15, abs=0.01)


def test_only_the_mid_plane_counts():
    points = plate()
    top = points[:, 2] > 2.0
    damage = np.where(band(points, 70.0) & top, 0.6, 0.0)
    tips, stats = crack_path.analyse(points, damage, [TIP], (0.0, 1.0), h=1.0)
    assert not tips[0]["crack"] and stats["off_path"] == 0.0
    assert stats["mean_all"] > 0.0 and stats["mean_layer"] == 0.0


def test_the_measured_spacing_is_the_lattice_constant():
    assert crack_path.spacing(plate() * 0.002) == pytest.approx(0.002)


def write_dump(path, frames):
    with open(path, "w") as f:
        for step, points, damage in frames:
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(points)}\n")
            f.write("ITEM: BOX BOUNDS ss ss ss\n0 1\n0 1\n0 1\n")
            f.write("ITEM: ATOMS id x y z v_damage\n")
            for k, (p, d) in enumerate(zip(points, damage), 1):
                f.write(f"{k} {p[0]:.6g} {p[1]:.6g} {p[2]:.6g} {d:.4g}\n")


def test_the_command_line_prints_a_row_per_frame_and_tip(tmp_path, capsys):
    points = plate() * 0.002
    dump = tmp_path / "dump.plate"
    write_dump(dump, [(0, points, np.zeros(len(points))),
                      (300, points, np.where(band(points / 0.002, 70.0), 0.6, 0.0))])
    tips = ["--tip", str(TIP[0] * 0.002), str(TIP[1] * 0.002),
            "--tip", str(OTHER_TIP[0] * 0.002), str(OTHER_TIP[1] * 0.002)]
    assert crack_path.main([str(dump), *tips, "--scale", "1000", "--unit", "mm"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 1 + 2 * 2 and "length (mm)" in lines[0]
    crack = lines[3].split()
    assert crack[1:4] == ["300", "1", "yes"]
    assert float(crack[4]) == pytest.approx(60.0, abs=3.0)
    assert float(crack[5]) == pytest.approx(70.0, abs=2.0)
    assert lines[1].split()[3] == "no" and lines[4].split()[3] == "no"
    assert crack_path.main([str(dump), *tips, "--last"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 3


def test_a_missing_column_is_an_error(tmp_path, capsys):
    points = plate()
    dump = tmp_path / "dump.plate"
    write_dump(dump, [(0, points, np.zeros(len(points)))])
    assert crack_path.main([str(dump), "--tip", "1", "1", "--column", "c_damage"]) == 1
    assert "no column c_damage" in capsys.readouterr().err


def test_a_forked_path_is_fitted_along_its_main_branch():
    points = plate()
    fork = band(points, 70.0) | band(points, -80.0, length=12.0)
    tip = crack_path.analyse(points, np.where(fork, 0.6, 0.0), [TIP], (0.0, 1.0), h=1.0)[0][0]
    assert tip["crack"] and tip["angle"] == pytest.approx(70.0, abs=2.0) and tip["dir"][0] > 0
    assert 1.5 <= tip["width"] <= 3.0


def test_a_crack_found_earlier_is_followed_when_more_damage_joins_it():
    points = plate()
    first = np.where(band(points, 70.0, length=20.0), 0.6, 0.0)
    later = np.where(band(points, 70.0, length=20.0) | band(points, -60.0, half_width=3.0),
                     0.6, 0.0)
    alone = crack_path.analyse(points, later, [TIP], (0.0, 1.0), h=1.0)[0][0]
    assert alone["angle"] == pytest.approx(60.0, abs=3.0) and alone["dir"][0] < 0
    early = crack_path.analyse(points, first, [TIP], (0.0, 1.0), h=1.0)[0][0]
    followed = crack_path.analyse(points, later, [TIP], (0.0, 1.0), h=1.0,
                                  previous=[early["dir"]])[0][0]
    assert followed["angle"] == pytest.approx(70.0, abs=2.0) and followed["dir"][0] > 0
