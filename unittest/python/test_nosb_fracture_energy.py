"""Fracture energy (issue 9, item 10): the rigid-halves separation test of
examples/fracture-energy measures the energy per area that a critical stretch dissipates, and
`pair_coeff ... peri/nosb ... s00=NULL ... G0 value` sets peri/nosb's critical stretch from it by
the relation of doc/pair_peri_nosb.rst ("Fracture energy").  Each separation run here has 784
particles and 12 break events (under a second)."""
import importlib.util
import math
import re
from pathlib import Path

import pytest

from lammps_run import LMP, REPO, run_deck
from nosb_block import TWO_TYPE_BLOCK

_spec = importlib.util.spec_from_file_location(
    "fracture_energy_run", REPO / "examples" / "fracture-energy" / "run.py")
fe = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fe)

S00 = 5.0e-4
K = 14.9e9
S00_LINE = re.compile(r"^peri/nosb: types (\d+) (\d+): G0 = (\S+) gives s00 = (\S+) ", re.M)


def test_separation_reproduces_the_pmb_formula(tmp_path):
    """peri/pmb (Silling & Askari 2005): G0 = 9/5 K delta s0^2 in the continuum."""
    m = 3
    res = fe.separate("peri/pmb", fe.coeff_pmb(K, m, S00), m, S00, lmp=LMP, workdir=tmp_path)
    lattice = fe.g0_pmb_lattice_sum(K, m, S00)
    formula = fe.g0_pmb_formula(K, fe.horizon(m), S00)
    # The procedure is exact: every crossing bond breaks at (1 + 1e-7) s0 and its energy
    # c beta s0^2 |xi| V^2 / 2 is released, so the released energy equals the hand-made sum
    # over the lattice bonds to ~1e-7 (round-off of the stretches); the work integral uses
    # the trapezoid rule on a force that is linear in u only to O(s0) = 5e-4 (measured 2e-5).
    assert res["g0_energy"] == pytest.approx(lattice, rel=1e-5)
    assert res["g0_work"] == pytest.approx(lattice, rel=1e-3)
    assert abs(res["residual_pe"]) < 1e-9 * lattice    # every crossing bond broke
    # Against the continuum formula the lattice sum is 0.8729 (horizon 3.0002 a): the family
    # is cut at delta (partial volumes 1/2 .. 1 on the last shell, none beyond) and is a
    # discrete set of bonds.  Over delta/a = 2.5 ... 20 this ratio stays within 0.72 ... 0.97
    # (run.py, g0_pmb_lattice_sum), so 15% is the size of the lattice effect at delta = 3a.
    assert res["g0_work"] == pytest.approx(formula, rel=0.15)
    assert res["g0_work"] / formula == pytest.approx(0.8729, abs=1e-3)


def test_nosb_work_is_the_released_energy(tmp_path):
    """peri/nosb's pe is the potential of its forces: the work done on the upper half equals
    the energy the broken bonds release (both include the stabilization energy)."""
    g = fe.shear_from_nu(K, 0.25)
    res = fe.separate("peri/nosb", fe.coeff_nosb(K, g, 3, S00, 2.0), 3, S00, lmp=LMP,
                      workdir=tmp_path)
    assert res["g0_work"] == pytest.approx(res["g0_energy"], rel=1e-4)  # trapezoid, O(s0)
    assert abs(res["residual_pe"]) < 1e-9 * res["g0_work"]


@pytest.mark.parametrize("model,nu,cs,a", [("linear", 0.3, 1.0, 1.0e-3),
                                            ("neohookean", 0.1, 3.0, 5.0e-4)])
def test_vector_form_g0_keyword_gives_the_measured_fracture_energy(tmp_path, model, nu, cs, a):
    """With `deviation vector`, a type set with `s00 NULL ... G0 value` dissipates G0 per area
    in the separation test (horizon 3.0002 h, where the relation was calibrated).  In the
    small-strain limit the
    dissipated energy is exactly linear in K + 4G/3 and Cs K, and the relation's constants
    (fitted at s00 = 1e-6) have 5 significant digits (1e-4).  At finite s00 the rigid-halves
    G0 is lower by 2.2 s00 (material part) to 5.1 s00 (stabilization part), relative
    (run.py fits at s00 = 1e-6 ... 5e-4); here s00 = 2.7e-4 and 2.4e-4, so the measured G0 must
    lie in [1 - 5.1 s00, 1 - 2.2 s00] G0, widened by 2e-4."""
    g0 = 1.0
    k = 1.0e9
    g = fe.shear_from_nu(k, nu)
    d = fe.horizon(3, a)
    s00 = fe.s00_nosb_relation(g0, k, g, cs, d, a, length=False)
    coeff = f"{model} {k!r} {g!r} {d!r} NULL 0.0 G0 {g0} stabilize {cs} deviation vector"
    res = fe.separate("peri/nosb", coeff, 3, s00, a, lmp=LMP, workdir=tmp_path)
    logged = [float(m[3]) for m in S00_LINE.findall(res["log"])]
    assert logged and logged[0] == pytest.approx(s00, rel=1e-5)  # printed with 6 digits
    ratio = res["g0_work"] / g0
    assert 1.0 - 5.1 * s00 - 2e-4 <= ratio <= 1.0 - 2.2 * s00 + 2e-4, (ratio, s00)


@pytest.mark.parametrize("model,nu,cs", [("linear", 0.3, 2.0), ("stvk", 0.25, 2.0),
                                         ("neohookean", 0.1, 3.0)])
def test_g0_keyword_gives_the_measured_fracture_energy(tmp_path, model, nu, cs):
    """With the default `deviation length` the stabilization's share of G0 is C_L Cs K delta
    s00^2 (doc/pair_peri_nosb.rst): a type set with `s00 NULL ... G0 value` dissipates G0 per
    area in the separation test, for each material model.  The relation is the small-strain limit
    (C_L fitted at s00 = 1e-6, 6 digits); at the s00 here (about 3e-4) the measured G0 is
    lower by less than 5.1 s00 relative, as for the vector form; the vector form's relation
    (stabilization share Cs K delta/h times 1.19) would be off by a factor 2.5 or more."""
    g0, k, a = 1.0, 1.0e9, 1.0e-3
    g = fe.shear_from_nu(k, nu)
    d = fe.horizon(3, a)
    s00 = fe.s00_nosb_relation(g0, k, g, cs, d, a)
    coeff = f"{model} {k!r} {g!r} {d!r} NULL 0.0 G0 {g0} stabilize {cs}"
    res = fe.separate("peri/nosb", coeff, 3, s00, a, lmp=LMP, workdir=tmp_path)
    assert "deviation length" in res["log"]
    logged = [float(m[3]) for m in S00_LINE.findall(res["log"])]
    assert logged and logged[0] == pytest.approx(s00, rel=1e-5)  # printed with 6 digits
    ratio = res["g0_work"] / g0
    assert 1.0 - 5.1 * s00 - 2e-4 <= ratio <= 1.0 + 2e-4, (ratio, s00)
    vector = fe.g0_nosb_relation(k, g, cs, d, s00, a, length=False)
    assert vector > 2.5 * res["g0_work"]


BLOCK = TWO_TYPE_BLOCK + """set             type 1 type/fraction 2 0.5 1234
pair_style      peri/nosb
{coeff}
run             0
run             0
"""


def logged_s00(run):
    return {(int(m[0]), int(m[1])): (float(m[2]), float(m[3]))
            for m in S00_LINE.findall(run.log)}


def test_g0_keyword_s00_is_the_documented_relation(tmp_path):
    """s00 = sqrt(G0 / (delta (C_M (K + 4G/3) + C_L Cs K))) (deviation length, the default) or
    sqrt(G0 / (delta (C_M (K + 4G/3) + C_S Cs K delta/h))) (deviation vector), with K, G, Cs,
    the horizon and the deviation form of the same pair_coeff line wherever its keywords are,
    h = V^(1/3); logged once per type pair (two runs here)."""
    coeff = "\n".join([
        # stabilize after G0, default Cs = 2 on the cross pair, stabilize before G0
        "pair_coeff      1 1 linear 1.0e9 0.6e9 0.0030002 NULL 0.25 G0 3.0 stabilize 0.5",
        "pair_coeff      1 2 stvk 2.0e9 0.5e9 0.0040002 NULL 0.25 G0 7.0 deviation vector",
        "pair_coeff      2 2 neohookean 3.0e9 1.0e9 0.0030002 NULL 0.25 stabilize 0 G0 1.0",
    ])
    run = run_deck(BLOCK.format(coeff=coeff), tmp_path)
    s00 = logged_s00(run)
    h = 1.0e-3
    expected = {(1, 1): fe.s00_nosb_relation(3.0, 1.0e9, 0.6e9, 0.5, 0.0030002, h),
                (1, 2): fe.s00_nosb_relation(7.0, 2.0e9, 0.5e9, 2.0, 0.0040002, h, length=False),
                (2, 2): fe.s00_nosb_relation(1.0, 3.0e9, 1.0e9, 0.0, 0.0030002, h)}
    assert set(s00) == set(expected)
    for pair, value in expected.items():
        assert s00[pair][1] == pytest.approx(value, rel=1e-5), pair   # 6 printed digits
    assert len(S00_LINE.findall(run.log)) == 3    # not again at the second run
    # the relation itself, with the constants of the documentation
    doc = (REPO / "doc" / "pair_peri_nosb.rst").read_text()
    assert f"{fe.C_M}" in doc and f"{fe.C_S}" in doc and f"{fe.C_L}" in doc
    assert expected[(1, 1)] == pytest.approx(
        math.sqrt(3.0 / (0.0030002 * (0.58376 * (1.0e9 + 4.0 / 3.0 * 0.6e9)
                                      + 1.00391 * 0.5 * 1.0e9))), rel=1e-12)
    assert expected[(1, 2)] == pytest.approx(
        math.sqrt(7.0 / (0.0040002 * (0.58376 * (2.0e9 + 4.0 / 3.0 * 0.5e9)
                                      + 1.19321 * 2.0 * 2.0e9 * 4.0002))), rel=1e-12)


def test_g0_keyword_keeps_a_type_pair_without_g0_alone(tmp_path):
    coeff = "\n".join([
        "pair_coeff      1 1 linear 1.0e9 0.6e9 0.0030002 NULL 0.25 G0 3.0",
        "pair_coeff      2 2 linear 1.0e9 0.6e9 0.0030002 0.001 0.25",
    ])
    run = run_deck(BLOCK.format(coeff=coeff), tmp_path)
    assert set(logged_s00(run)) == {(1, 1)}


COEFF = "linear 1.0e9 0.6e9 0.0030002"
BAD_G0 = [
    ("s00-and-G0", f"{COEFF} 0.001 0.25 G0 3.0", ["pair_coeff peri/nosb", "0.001", "G0", "3"]),
    ("G0-zero", f"{COEFF} NULL 0.25 G0 0", ["pair_coeff peri/nosb", "G0", "> 0", "got 0"]),
    ("G0-negative", f"{COEFF} NULL 0.25 G0 -2.5", ["pair_coeff peri/nosb", "G0", "-2.5"]),
    ("G0-break-no", f"{COEFF} NULL 0.25 G0 3.5 break no",
     ["pair_coeff peri/nosb", "G0", "3.5", "break no"]),
    ("G0-break-no-first", f"{COEFF} NULL 0.25 break no G0 3.5",
     ["pair_coeff peri/nosb", "G0", "3.5", "break no"]),
    ("G0-missing-value", f"{COEFF} NULL 0.25 G0", ["pair_coeff peri/nosb", "G0", "missing"]),
    ("G0-not-a-number", f"{COEFF} NULL 0.25 G0 tough", ["pair_coeff peri/nosb", "G0", "tough"]),
    ("s00-NULL-without-G0", f"{COEFF} NULL 0.25", ["pair_coeff peri/nosb", "NULL", "G0"]),
    ("deviation-unknown", f"{COEFF} 0.001 0.25 deviation sideways",
     ["pair_coeff peri/nosb", "deviation", "length or vector", "sideways"]),
    ("deviation-length-membrane", f"{COEFF} 0.001 0.25 membrane yes deviation length",
     ["pair_coeff peri/nosb", "deviation length", "membranes", "vector"]),
]


@pytest.mark.parametrize("case,args,expected", BAD_G0, ids=[c[0] for c in BAD_G0])
def test_bad_g0_input_is_an_error(tmp_path, case, args, expected):
    run = run_deck(BLOCK.format(coeff=f"pair_coeff      * * {args}"), tmp_path, check=False)
    assert run.returncode > 0, run.describe()
    assert run.errors, run.describe()
    line = run.errors[0]
    for word in expected:
        assert word.lower() in line.lower(), (word, line)
