"""Small-strain tension of a bar (issue 3): peri/nosb reproduces the continuum's E and nu in
the interior and matches the built-in peri/lps at equal material on the same lattice."""
from pathlib import Path

import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from nosb_reference import A_TEST, lps_lattice_young_poisson, young_poisson

BAR = Path(__file__).parent / "decks" / "nosb_bar.lmp"
NX, NY = 24, 12   # 3456 particles; the cross-section is 4 horizons wide


def relaxed_bar(run, workdir):
    frame = read_dump(Path(workdir) / "dump.bar")[-1]
    X = np.stack([frame[f"f_ref[{k}]"] for k in (1, 2, 3)], axis=1)
    u = np.stack([frame[c] for c in "xyz"], axis=1) - X
    pull = [t for t in run.thermo if "f_holdl[1]" in t][-1]["f_holdl[1]"][-1]
    return X, u, pull


def interior_moduli(X, u, pull):
    """E and nu of the middle half of the bar: strains from least-squares slopes of the
    displacement there (u_x against X over the whole cross-section; u_y against Y and u_z
    against Z using the particles at least one horizon from the side faces, where the lateral
    field is that of the bulk), stress = pulling force / cross-section."""
    L = X[:, 0].max()
    mid = np.abs(X[:, 0] - 0.5 * L) < 0.25 * L
    c = 0.5 * X[:, 1].max()
    core = mid & np.all(np.abs(X[:, 1:] - c) < c - 2.9 * A_TEST, axis=1)
    exx = np.polyfit(X[mid, 0], u[mid, 0], 1)[0]
    eyy = np.polyfit(X[core, 1], u[core, 1], 1)[0]
    ezz = np.polyfit(X[core, 2], u[core, 2], 1)[0]
    # force density summed over the held slab, times the particle volume; area = NY^2 a^2
    stress = abs(pull) * A_TEST ** 3 / (NY * A_TEST) ** 2
    return stress / exx, -0.5 * (eyy + ezz) / exx, exx


@pytest.fixture(scope="module")
def bars(tmp_path_factory):
    out = {}
    for style in ("nosb", "lps"):
        work = tmp_path_factory.mktemp(f"bar-{style}")
        run = run_deck(BAR, work, variables={"style": style, "nx": NX, "ny": NY})
        assert "Stopping criterion = force tolerance" in run.log
        out[style] = relaxed_bar(run, work)
    return out


def test_nosb_bar_interior_has_the_continuum_moduli(bars):
    # A uniaxial affine field is an exact equilibrium of the correspondence model away from
    # the held ends (F_i = F everywhere, P = diag(E e, 0, 0) exactly for the linear model, and
    # the sum over a family cut only by the side faces has no axial part). So E and nu come
    # out exact up to the end effects of the grips: measured E 0.04% and nu 0.4% off.
    # 1% on each is the bound (ten times the St-Venant/end-effect error measured at
    # NX = 24, NX = 32 halves it).
    E, nu = young_poisson()
    E_bar, nu_bar, exx = interior_moduli(*bars["nosb"])
    assert exx == pytest.approx(1.0e-3, rel=0.05)  # the grips impose ~1e-3
    assert E_bar == pytest.approx(E, rel=0.01)
    assert nu_bar == pytest.approx(nu, rel=0.01)


def test_nosb_matches_lps_displacement_field(bars):
    # Both styles are calibrated to the same K and G; on a simple cubic lattice with horizon
    # 3a, peri/lps's discrete fourth moment is not isotropic, so its bulk Poisson ratio along
    # a cube axis is 0.2687, not 0.25 (nosb_reference.lps_lattice_young_poisson), and its side
    # faces add a surface effect. The displacement fields therefore agree to a few percent of
    # the largest displacement (measured 3.6%; bound 5%), with the difference concentrated
    # in the lateral contraction, and peri/lps's interior nu is the one its lattice predicts
    # (measured 0.2698; 1.5% allows the remaining surface influence), which shows that the
    # remaining difference is the lps discretization, not a nosb error.
    X1, u_nosb, _ = bars["nosb"]
    X2, u_lps, _ = bars["lps"]
    assert np.array_equal(X1, X2)
    umax = np.max(np.linalg.norm(u_lps, axis=1))
    assert np.max(np.linalg.norm(u_nosb - u_lps, axis=1)) < 0.05 * umax
    # axial displacement alone: same bound relative to its own maximum
    assert np.max(np.abs(u_nosb[:, 0] - u_lps[:, 0])) < 0.05 * np.max(np.abs(u_lps[:, 0]))
    _, nu_lattice = lps_lattice_young_poisson(3)
    _, nu_lps, _ = interior_moduli(*bars["lps"])
    assert nu_lps == pytest.approx(nu_lattice, rel=0.015)
