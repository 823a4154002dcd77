"""The numpy reference values the peri/nosb tests compare against (nosb_reference.py) are
themselves right: no LAMMPS involved."""
import numpy as np
import pytest

from nosb_reference import (first_piola, lame, lps_lattice_young_poisson, nonaffine_measure,
                            rotation, signed_singular_values, strain_energy_density,
                            young_poisson)

MODELS = ["linear", "stvk", "neohookean"]
rng = np.random.default_rng(20251126)
SAMPLES = [np.eye(3) + 0.2 * rng.standard_normal((3, 3)) for _ in range(4)] + [
    np.diag([1.0, 1.0, -0.5]),                                   # inverted
    np.diag([0.3, 0.2, 0.5]) @ rotation([1, 1, 0], 20.0),         # J = 0.03 < J0 = 0.1
]


@pytest.mark.parametrize("model", MODELS)
def test_energy_vanishes_at_rest_and_is_rotation_invariant(model):
    assert strain_energy_density(model, np.eye(3)) == pytest.approx(0.0, abs=1e-6)
    for F in SAMPLES:
        R = rotation([0.2, -0.7, 1.0], 63.0)
        assert strain_energy_density(model, R @ F) == pytest.approx(
            strain_energy_density(model, F), rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
def test_first_piola_is_the_energy_gradient(model):
    # central differences of W with step 1e-6: truncation ~1e-12 |W'''|, round-off
    # ~1e-16 |W| / 1e-6; 1e-7 of |P| is well above both
    for F in SAMPLES:
        P = first_piola(model, F)
        numeric = np.zeros((3, 3))
        for a in range(3):
            for b in range(3):
                d = np.zeros((3, 3))
                d[a, b] = 1e-6
                numeric[a, b] = (strain_energy_density(model, F + d)
                                 - strain_energy_density(model, F - d)) / 2e-6
        assert np.max(np.abs(P - numeric)) < 1e-7 * np.max(np.abs(P))


def test_small_strain_limit_is_linear_elasticity():
    # every model reduces to W = mu eps:eps + lambda/2 tr(eps)^2 for small symmetric strain
    mu, lam = lame()
    eps = 1e-5 * np.array([[1.0, 0.3, -0.2], [0.3, -0.5, 0.1], [-0.2, 0.1, 0.7]])
    W0 = mu * np.sum(eps * eps) + 0.5 * lam * np.trace(eps) ** 2
    for model in MODELS:
        assert strain_energy_density(model, np.eye(3) + eps) == pytest.approx(W0, rel=1e-4)


def test_signed_singular_values():
    assert np.allclose(signed_singular_values(np.diag([2.0, -1.0, 0.5])), [2.0, 1.0, -0.5])
    assert np.allclose(signed_singular_values(np.diag([-2.0, -1.0, 0.5])), [2.0, 1.0, 0.5])


def test_nonaffine_measure_vanishes_for_affine_motion_only():
    g = np.arange(5) * 1e-3
    X = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    V = np.full(len(X), 1e-9)
    F = rotation([1, 2, 3], 10.0) @ np.diag([1.1, 0.9, 1.0])
    assert nonaffine_measure(X, X @ F.T + 0.3, V) < 1e-13
    Y = X.copy()
    Y[:, 0] += 1e-5 * (-1.0) ** np.rint(X.sum(axis=1) / 1e-3)   # checkerboard
    assert nonaffine_measure(X, Y, V) > 1e-3


def test_lps_lattice_constants():
    # the lattice sums converge to the isotropic continuum as the horizon grows (m = 6 is
    # within 2.5% on E and 2.5% on nu) while m = 3 (the decks) is visibly cubic
    E, nu = young_poisson()
    E3, nu3 = lps_lattice_young_poisson(3)
    E6, nu6 = lps_lattice_young_poisson(6)
    assert abs(E6 / E - 1) < 0.025 and abs(nu6 / nu - 1) < 0.025
    assert nu3 == pytest.approx(0.2687, abs=1e-4) and E3 / E == pytest.approx(0.9253, abs=1e-4)
