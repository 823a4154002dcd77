"""Membranes (pair_coeff ... membrane yes) through LAMMPS: a strip hanging under its own weight
stretches by rho g L^2 / (2 E) (plane stress: the same for nu = 0 and nu = 0.3, while plane
strain would give (1 - nu^2) of it), contracts sideways by nu times its strain, and stays in its
plane; 1 and 2 ranks agree; bad input is refused with a clear message."""
import sys
from pathlib import Path

import pytest

from lammps_run import run_deck

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
import make_sheet  # noqa: E402

STRIP = Path(__file__).parent / "decks" / "membrane_strip.lmp"
RHO, GRAV, E = 1000.0, 9.81, 1.0e7


def strip_mesh(workdir, L=1.5, W=0.06, a=0.01, jitter=0.0):
    vertices, faces = make_sheet.rectangle(W, L, a, "alternate", jitter, 1)
    path = Path(workdir) / "strip.obj"
    path.parent.mkdir(parents=True, exist_ok=True)
    make_sheet.write_obj(path, vertices, faces, ["strip for test_membrane.py"])
    return path


def hang(tmp_path, nu, model="linear", nprocs=1, steps=12, **extra):
    mesh = strip_mesh(tmp_path)
    run = run_deck(STRIP, tmp_path, nprocs=nprocs, variables={
        "mesh": mesh, "nu": nu, "model": model, "steps": steps, "E": E, **extra})
    t = run.thermo[-1]
    return run, {k: v[-1] for k, v in t.items()}, t


# Elongation of a strip of length L hanging from its top edge: the strain at distance s from the
# top is rho g (L - s) / E (uniaxial stress: plane stress and free sides), so the bottom moves by
# rho g L^2 / (2E) = 1.104e-3 m here (strain at most 1.5e-3: geometric nonlinearity ~0.1%). The
# model's own error is a boundary layer about a horizon deep at the clamp, where the one-sided
# families of the held row and its neighbours are softer (the zero-energy-mode control, Cs = 2 by
# default, keeps it small; without it the strip is 9% too long at L = 1 m): measured +1.8%
# (nu = 0) and +0.7% (nu = 0.3) at L = 1 m with spacing 1 cm, +0.9% at 5 mm (it scales like
# delta / L), so +1.2% / +0.4% here against the 2% allowed. The clamped row cannot contract
# sideways, which stiffens a zone about a width long by up to 1/(1 - nu^2) (~nu^2 W / L = 0.4%).
# Backward Euler steps of 0.02 s (the slowest axial period is 0.06 s) reach the static state to
# 1e-5 in 12 steps. Plane strain would make it 9% short at nu = 0.3.
@pytest.mark.parametrize("nu", [0.0, 0.3])
def test_hanging_strip_elongation(tmp_path, nu):
    run, last, t = hang(tmp_path, nu)
    L = 1.5
    expected = RHO * GRAV * L * L / (2.0 * E)
    elongation = -last["c_tipdy"]
    assert abs(elongation / expected - 1.0) < 0.02, (elongation, expected)
    # no step of fix sissm stopped at its iteration limit
    assert last["f_integrate[4]"] == 0
    # in-plane loading keeps the strip in its plane (to round-off)
    assert abs(last["c_zmean"]) < 1e-12


def test_plane_stress_contracts_sideways(tmp_path):
    """The strip's sides move in by nu times its axial strain: the mean axial strain is
    rho g L / (2E), so the right edge (half the width from the middle) moves in by
    nu (W/2) rho g L / (2E) on average. The clamp holds the top of the edge (about a width of it
    contracts less): the mean is checked to 10% (measured -2.5%)."""
    nu, W, L = 0.3, 0.06, 1.5
    run, last, t = hang(tmp_path, nu)
    expected = -nu * (W / 2) * RHO * GRAV * L / (2.0 * E)
    assert abs(last["c_edgedx"] / expected - 1.0) < 0.10, (last["c_edgedx"], expected)


def test_xu_model_is_linear_at_small_strain(tmp_path):
    """The authors' model xu with s0 = E/2 has E and nu = 0 at small strain: the strip stretches
    as the linear model's with nu = 0 (the same discretization, to 1e-3: the strain of 1.5e-3
    brings the models' cubic terms in at that order)."""
    _, xu, _ = hang(tmp_path / "xu", 0.0, model="xu", E=E)
    # the deck passes K = E / (3 (1 - 2 nu)) = E / 3 in the place of s0: scale E so that
    # s0 = E_deck / 3 = E / 2
    _, xu2, _ = hang(tmp_path / "xu2", 0.0, model="xu", E=1.5 * E)
    _, lin, _ = hang(tmp_path / "lin", 0.0)
    assert abs(xu2["c_tipdy"] / lin["c_tipdy"] - 1.0) < 1e-3, (xu2["c_tipdy"], lin["c_tipdy"])
    # and with s0 = E/3 it is 1.5 x softer
    assert abs(xu["c_tipdy"] / lin["c_tipdy"] - 1.5) < 2e-3


@pytest.mark.mpi
def test_two_ranks_agree(tmp_path):
    """Forces do not depend on how the particles are spread over ranks; the solver sums in
    another order: the elongation agrees to 1e-9 relative (measured ~1e-12)."""
    _, one, _ = hang(tmp_path / "one", 0.3)
    _, two, _ = hang(tmp_path / "two", 0.3, nprocs=2)
    assert abs(two["c_tipdy"] / one["c_tipdy"] - 1.0) < 1e-9, (one["c_tipdy"], two["c_tipdy"])
    assert abs(two["c_edgedx"] / one["c_edgedx"] - 1.0) < 1e-6


def test_membrane_type_needs_a_mesh(tmp_path):
    deck = """
units si
atom_style peri
atom_modify map array
lattice sc 0.01
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
set group all density 1000
set group all volume 1e-6
pair_style peri/nosb
pair_coeff * * linear 1e7 5e6 0.03 0 0 break no membrane yes
run 0
"""
    run = run_deck(deck, tmp_path, check=False)
    assert not run.ok
    assert any("membrane type" in e and "read_mesh" in e for e in run.errors), run.errors


def test_xu_needs_positive_s0(tmp_path):
    mesh = strip_mesh(tmp_path)
    run = run_deck(STRIP, tmp_path, check=False, variables={"mesh": mesh, "model": "xu",
                                                            "E": -1.0, "steps": 0})
    assert any("xu modulus s0 must be > 0" in e for e in run.errors), run.errors
