"""Material files (potentials/materials.nosb) read by pair_coeff peri/nosb by name: the impact
example with its material from the file runs exactly as with the numbers it replaces; a cgs
deck gets converted values (a physical check: the same stretch gives the energy density in
erg/cm^3 = 10 x J/m^3); unknown names, missing files and unit styles without a conversion stop
with an error that says what is allowed; the density check and the file's G0."""
import re
import shutil

import numpy as np
import pytest

from lammps_run import REPO, run_deck

IMPACT = REPO / "examples" / "impact"


def impact_run(tmp_path, deck, nsteps=200):
    work = tmp_path / deck
    shutil.copytree(IMPACT, work, ignore=shutil.ignore_patterns("log.*"))
    return run_deck(work / deck, work, variables={"nsteps": nsteps, "thermo_every": 50})


def test_impact_example_with_the_file_material_repeats_the_numbers(tmp_path):
    by_number = impact_run(tmp_path, "in.impact.nosb")
    by_name = impact_run(tmp_path, "in.impact.nosb-material")
    assert by_number.ok, by_number.describe()
    assert by_name.ok, by_name.describe()
    a, b = by_number.thermo[-1], by_name.thermo[-1]
    for column in ("PotEng", "KinEng", "c_dsum"):
        # the same K and G to the last bit: the same trajectory (thermo prints 8 digits)
        np.testing.assert_array_equal(a[column], b[column])
    assert b["KinEng"][-1] > 0 and b["c_dsum"][-1] > 0    # the impact did happen and break bonds
    assert "Material impact-glass from materials.nosb: K = 1.49e+10, G = 8.94e+09" in by_name.log
    assert "source: the glass-like target" in by_name.log


def stretched_block(units, coeff, density, length, extra=""):
    """A 5^3 block; the families are built by a first `run 0`, then the block is stretched
    affinely by 1% in x and a second `run 0` reports pe = N W(F)."""
    a = length
    return f"""
units           {units}
boundary        s s s
atom_style      peri
atom_modify     map array
lattice         sc {a}
region          block block -0.5 4.5 -0.5 4.5 -0.5 4.5
create_box      2 block
create_atoms    1 region block
set             group all density {density}
set             group all volume {a ** 3}
pair_style      peri/nosb
pair_coeff      * * {coeff}
thermo_style    custom step pe
run             0
{extra}
displace_atoms  all ramp x 0.0 {0.01 * 5 * a} x {-0.5 * a} {4.5 * a} units box
run             0
"""


def test_cgs_deck_gets_the_converted_material(tmp_path):
    # the same body in si (m, kg/m^3) and cgs (cm, g/cm^3); steel from the file in both
    si = run_deck(stretched_block("si", "linear material materials.nosb steel 0.0030002 0.1 0.25",
                                  7850, 0.001), tmp_path / "si")
    cgs = run_deck(stretched_block("cgs", "linear material materials.nosb steel 0.30002 0.1 0.25",
                                   7.85, 0.1), tmp_path / "cgs")
    assert si.ok and cgs.ok, si.describe() + cgs.describe()
    assert "Material steel converted from si to cgs units" in cgs.log
    pe_si, pe_cgs = si.thermo[-1]["PotEng"][-1], cgs.thermo[-1]["PotEng"][-1]
    assert pe_si > 0
    # 1 J/m^3 = 10 erg/cm^3; thermo prints 8 significant digits
    assert pe_cgs == pytest.approx(10.0 * pe_si, rel=1e-6)
    # the densities match the file's: no warning from the pair style
    assert not [w for w in si.warnings + cgs.warnings if "peri/nosb" in w.lower()]


@pytest.mark.parametrize("coeff, expected", [
    ("linear material materials.nosb unobtainium 0.003 0.1 0.25",
     ["no material 'unobtainium' in materials.nosb", "steel, aluminium, glass"]),
    ("linear material no-such-file.nosb steel 0.003 0.1 0.25",
     ["cannot open material file no-such-file.nosb", "LAMMPS_POTENTIALS"]),
    ("linear material materials.nosb steel 0.003 0.1",
     ["expected I J MODEL material FILE NAME horizon s00 alpha"]),
    ("linear material materials.nosb steel 0.003 NULL 0.25",
     ["s00 = NULL needs the G0 keyword", "material steel gives no G0"]),
])
def test_bad_material_lookups_name_what_is_wrong(tmp_path, coeff, expected):
    run = run_deck(stretched_block("si", coeff, 7850, 0.001), tmp_path,
                   check=False)
    assert run.returncode > 0 and run.errors, run.describe()
    for text in expected:
        assert text in run.errors[0], run.errors[0]


@pytest.mark.parametrize("units", ["metal", "real", "lj"])
def test_unit_styles_without_a_conversion_are_refused(tmp_path, units):
    run = run_deck(stretched_block(units, "linear material materials.nosb steel 3.0 0.1 0.25",
                                   7.85, 1.0), tmp_path,
                   check=False)
    assert run.returncode > 0 and run.errors, run.describe()
    assert f"cannot be converted to '{units}'" in run.errors[0]
    assert "si, cgs, micro, nano" in run.errors[0]


def test_a_density_other_than_the_files_is_warned_about_once(tmp_path):
    # on 2 ranks: the file is read on one and broadcast, the density range is global
    run = run_deck(stretched_block("si", "linear material materials.nosb glass 0.0030002 0.1 0.25",
                                   2200, 0.001, extra="run 0"), tmp_path, nprocs=2)
    # three runs, one warning
    assert run.ok, run.describe()
    density = [w for w in run.warnings if "density" in w]
    assert len(density) == 1, run.warnings
    assert "type 1" in density[0] and "material glass has 2500" in density[0]
    assert "set type 1 density 2500" in density[0]


def test_s00_null_takes_the_files_G0_as_the_G0_keyword_would(tmp_path):
    from_file = run_deck(stretched_block(
        "si", "linear material materials.nosb glass 0.0030002 NULL 0.25", 2500, 0.001),
        tmp_path / "file")
    keyword = run_deck(stretched_block(
        "si", "linear 3.8889e+10 2.9167e+10 0.0030002 NULL 0.25 G0 7.714", 2500, 0.001),
        tmp_path / "keyword")
    assert from_file.ok and keyword.ok, from_file.describe() + keyword.describe()
    s00 = [re.findall(r"G0 .*?s00 = (\S+)", run.log) for run in (from_file, keyword)]
    assert s00[0] and s00[0] == s00[1], s00
