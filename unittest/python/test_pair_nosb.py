"""pair_style peri/nosb (issue 3): affine deformations, momentum, energy conservation and
zero-energy-mode stabilization, against values computed independently in numpy
(nosb_reference.py) from the formulas of doc/pair_peri_nosb.rst and doc/theory.rst."""
from pathlib import Path

import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from nosb_reference import (A_TEST, affine_force_vectors, bond_weights, first_piola,
                            lattice_index, nonaffine_measure, rotation, strain_energy_density,
                            surface_depth)

DECKS = Path(__file__).parent / "decks"
AFFINE = DECKS / "nosb_affine.lmp"
BLOCK = DECKS / "nosb_block.lmp"

MODELS = ["linear", "stvk", "neohookean"]
N_AFFINE = 14  # 14^3 = 2744 particles: 8 of them are two horizons deep inside

# deformation gradients y = F X (moderate, so that every model stays far from its limits)
GRADIENTS = {
    "uniaxial-stretch": np.diag([1.2, 1.0, 1.0]),
    "triaxial": np.diag([1.1, 0.95, 1.05]),
    "simple-shear": np.array([[1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
    "compression": np.diag([0.85, 0.85, 0.9]),
    "rotation+stretch": rotation([1.0, 2.0, 3.0], 30.0)
    @ np.array([[1.1, 0.05, 0.0], [0.05, 0.9, 0.0], [0.0, 0.0, 1.0]]),
    # det F < 0: one signed singular value is negative; neo-Hookean is on its continuation
    "inverted": np.diag([1.0, 1.0, -0.5]),
}


def gradient_variables(F) -> dict:
    return {f"F{r + 1}{c + 1}": repr(float(F[r, c])) for r in range(3) for c in range(3)}


@pytest.fixture(scope="module")
def affine_runs(tmp_path_factory):
    """One run of nosb_affine.lmp per (model, F); kept for the several checks below."""
    runs = {}

    def get(model, name):
        if (model, name) not in runs:
            work = tmp_path_factory.mktemp(f"affine-{model}-{name}")
            variables = {"model": model, "n": N_AFFINE, **gradient_variables(GRADIENTS[name])}
            run = run_deck(AFFINE, work, variables=variables)
            runs[model, name] = (run, read_dump(work / "dump.affine")[0])
        return runs[model, name]

    return get


@pytest.mark.parametrize("name", list(GRADIENTS))
@pytest.mark.parametrize("model", MODELS)
def test_affine_energy_is_n_times_w(affine_runs, model, name):
    # For y = F X every particle's F_i is F (also near surfaces, doc/theory.rst), so
    # pe = N W(F). F_i = M_i K_i^-1 is reproduced to ~1e-15 relative (sums of ~100 bonds, a
    # 3x3 inverse); W's relative round-off is at most eps / |s - 1| ~ 1e-13 for these strains,
    # and the sum over N adds ~sqrt(N) eps: 1e-9 leaves four orders of margin and would still
    # catch a wrong weight, factor or formula (those give O(1) or O(h/delta) errors).
    run, frame = affine_runs(model, name)
    F = GRADIENTS[name]
    W = strain_energy_density(model, F)
    natoms = frame["natoms"]
    assert natoms == N_AFFINE ** 3
    undeformed, deformed, unstabilized = (t["PotEng"][0] for t in run.thermo)
    assert abs(undeformed) <= 1e-12 * natoms * W  # the reference state stores no energy
    assert deformed == pytest.approx(natoms * W, rel=1e-9)
    # stabilization acts on eta - F_i xi only, which vanishes for affine motion: the energy
    # with Cs = 0.1 and with Cs = 0 agree to round-off of the (zero) residual sum
    assert unstabilized == pytest.approx(deformed, rel=1e-12)
    # per-atom energy density (compute nosb/atom column 2) and J = det F (column 3)
    assert np.allclose(frame["c_nosb[2]"], W, rtol=1e-9, atol=0.0)
    J = np.linalg.det(F)
    assert np.allclose(frame["c_nosb[3]"], J, rtol=1e-12, atol=1e-13)
    assert not np.any(frame["c_nosb[1]"])  # no bond broke


@pytest.fixture(scope="module")
def affine_geometry(affine_runs):
    """d_i of nosb_reference.affine_force_vectors for the reference lattice of the decks."""
    _, frame = affine_runs("linear", "uniaxial-stretch")
    X = np.stack([frame[f"f_ref[{k}]"] for k in (1, 2, 3)], axis=1)
    return X, affine_force_vectors(X, np.full(len(X), A_TEST ** 3))


@pytest.mark.parametrize("name", list(GRADIENTS))
@pytest.mark.parametrize("model", MODELS)
def test_affine_forces(affine_runs, affine_geometry, model, name):
    # Under y = F X all particles have the same P = P(F) and
    # f_i = sum_j omega (P K_i^-1 + P K_j^-1) xi (doc/theory.rst), computed here in numpy
    # from the reference lattice (nosb_reference.affine_force_vectors). Both sides sum the
    # same ~100 terms of the size of the surface force, so 1e-9 of the largest force is a
    # thousandfold margin over round-off; a wrong weight (beta, V_j), a transposed K^-1 or a
    # missing partner term gives errors of 1e-2 or more.
    _, frame = affine_runs(model, name)
    X, d = affine_geometry
    assert np.array_equal(X, np.stack([frame[f"f_ref[{k}]"] for k in (1, 2, 3)], axis=1))
    P = first_piola(model, GRADIENTS[name])
    expected = d @ P.T
    force = np.stack([frame["fx"], frame["fy"], frame["fz"]], axis=1)
    fmax = np.max(np.linalg.norm(expected, axis=1))
    assert fmax > 0.0
    assert np.max(np.linalg.norm(force - expected, axis=1)) < 1e-9 * fmax

    # Where i and all its partners have complete families (>= 6 spacings, i.e. two horizons,
    # from every face: 8 particles of the 14^3 block) the sum of omega xi over a complete
    # family vanishes by symmetry and so does the force, to the same round-off.
    depth = surface_depth(X, N_AFFINE)
    magnitude = np.linalg.norm(force, axis=1)
    assert np.count_nonzero(depth >= 6) == 8
    assert np.max(magnitude[depth >= 6]) < 1e-9 * fmax

    # The particles at a face carry its traction P n: at the middle of each face (in-plane
    # depth >= 6, where the neighbourhood is mirror-symmetric) d_i is along the normal, so
    # f_i is parallel to P n and non-zero exactly when the traction is (the triaxial F has
    # P_yy = 0 for the linear model: no traction on the y faces).
    idx = lattice_index(X)
    for axis in range(3):
        others = [k for k in range(3) if k != axis]
        middle = np.all(np.minimum(idx[:, others], N_AFFINE - 1 - idx[:, others]) >= 6, axis=1)
        for side, normal_sign in ((0, -1.0), (N_AFFINE - 1, 1.0)):
            sel = middle & (idx[:, axis] == side)
            assert np.count_nonzero(sel) == 4
            traction = normal_sign * P[:, axis]
            if np.linalg.norm(traction) < 1e-6 * np.max(np.abs(P)):
                assert np.max(magnitude[sel]) < 1e-9 * fmax
                continue
            t_unit = traction / np.linalg.norm(traction)
            for f in force[sel]:
                assert np.linalg.norm(f) > 1e-2 * fmax
                # f = -c P n with c > 0: the surface particle is pulled back towards the body
                # when the traction points out of it
                assert np.linalg.norm(np.cross(f, t_unit)) < 1e-9 * fmax
                assert np.dot(f, t_unit) < 0.0


def test_affine_rotation_stores_no_energy(tmp_path):
    # a rigid rotation is F = R: W(R) = 0 for every model; forces vanish everywhere (round-off
    # relative to the force scale of a 1% strain, computed in the same deck geometry)
    F = rotation([0.3, -1.0, 0.5], 40.0)
    run = run_deck(AFFINE, tmp_path, variables={"model": "neohookean", "n": 8,
                                                **gradient_variables(F)})
    frame = read_dump(tmp_path / "dump.affine")[0]
    scale_energy = frame["natoms"] * strain_energy_density("linear", np.diag([1.01, 1, 1]))
    assert abs(run.thermo[1]["PotEng"][0]) < 1e-9 * scale_energy
    assert np.allclose(frame["c_nosb[3]"], 1.0, rtol=0, atol=1e-12)
    # force density of a 1% stretch at a surface ~ E * 0.01 / a
    fscale = 1.5e9 * 0.01 / A_TEST
    assert np.max(np.abs([frame["fx"], frame["fy"], frame["fz"]])) < 1e-9 * fscale


PERIODIC = DECKS / "nosb_periodic.lmp"


@pytest.mark.parametrize("nprocs", [1, pytest.param(2, marks=pytest.mark.mpi)])
@pytest.mark.parametrize("model", MODELS)
def test_affine_periodic_lattice(tmp_path, model, nprocs):
    # A periodic 8^3 lattice deformed with change_box ... remap (stretch, then an xy tilt):
    # every family is complete and crosses the periodic boundaries, so the bonds must be
    # taken to the right (closest) images, on one rank (images of local atoms) and on two
    # (ghost images). pe = N W(F) to 1e-9 and J = det F as in the free block; every particle
    # is an interior one, so all forces vanish to round-off: ~100 bond terms of the size
    # P/a ~ 1e11 each cancel to ~1e-3 (measured), bounded by 1e-12 of P / a.
    sx, sy, sz, gxy = 1.1, 0.95, 1.02, 0.1
    F = np.array([[1.0, gxy, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]) @ np.diag([sx, sy, sz])
    run = run_deck(PERIODIC, tmp_path, nprocs=nprocs,
                   variables={"model": model, "sx": sx, "sy": sy, "sz": sz, "gxy": gxy})
    frame = read_dump(tmp_path / "dump.periodic")[-1]
    assert frame["natoms"] == 512
    W = strain_energy_density(model, F)
    assert run.thermo[-1]["PotEng"][0] == pytest.approx(512 * W, rel=1e-9)
    assert np.allclose(frame["c_nosb[3]"], np.linalg.det(F), rtol=1e-12, atol=0)
    assert np.allclose(frame["c_nosb[2]"], W, rtol=1e-9, atol=0)
    fscale = np.abs(first_piola(model, F)).max() / A_TEST
    assert np.max(np.abs([frame["fx"], frame["fy"], frame["fz"]])) < 1e-12 * fscale


# ----------------------------------------------------------------------------------------
# momentum


def momentum_columns(run, k=0):
    t = run.thermo[-1]
    p = np.array([t[f"c_mom[{d}]"][k] for d in (1, 2, 3)])
    return p, t["c_momabs"][k]


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("vrel", [0.0, 0.4])
def test_internal_forces_conserve_momentum(tmp_path, model, vrel):
    # Each bond ij adds V_i V_j omega-terms to V_i f_i and the same with opposite sign to
    # V_j f_j (doc/theory.rst; beta is symmetric in i, j), so sum_i V_i f_i = 0 for any
    # positions and also for unequal volumes (vrel: V_i = a^3 (1 + vrel h_i)). Random
    # displacements of 0.3 spacings make every F_i different and far from the identity.
    # The sum cancels terms of size sum_i |V_i f_i|; round-off leaves ~1e-16 of that per term
    # summed, so 1e-12 of sum_i |V_i f_i| is a wide but still meaningful bound (one missing
    # or unequal bond term would be ~1e-3 of it).
    run = run_deck(BLOCK, tmp_path, variables={"model": model, "n": 7, "drand": 0.3 * A_TEST,
                                               "vrel": vrel, "momentum": 1, "nsteps": 0})
    p, pabs = momentum_columns(run)
    assert pabs > 0.0
    assert np.max(np.abs(p)) < 1e-12 * pabs, (p, pabs)


# ----------------------------------------------------------------------------------------
# energy conservation


def energy_error(run):
    e = run.thermo[-1]["TotEng"]
    return float(np.max(np.abs(e - e[0])) / e[0])


@pytest.mark.parametrize("model", MODELS)
def test_elastic_vibration_conserves_energy(tmp_path, model):
    # etotal = sum_i (rho v^2/2 + W_i) on a uniform lattice (doc/pair_peri_nosb.rst) is conserved by
    # velocity Verlet up to its O(dt^2) error, when the forces are the exact gradient of pe.
    # Block of 6^3, vibration of ~1.5% strain (nonlinear regime) plus a random velocity
    # pattern (excites the short waves and the stabilization), bonds unbreakable.
    # dt = 2.5e-8 s is "small": this block still runs stably at 8e-7 s. The largest deviation
    # of etotal from its start measured at 2.5e-8 s is ~8e-5, below the 1e-4 the issue asks
    # for; halving dt must cut it by ~4 (3 to 5), which an energy/force inconsistency (an
    # error that does not shrink with dt) would not do.
    common = {"model": model, "n": 6, "vib": 20.0, "vrand": 2.0, "thermo_every": 1}
    coarse = run_deck(BLOCK, tmp_path / "dt", variables={**common, "dt": 2.5e-8,
                                                         "nsteps": 1000})
    fine = run_deck(BLOCK, tmp_path / "dt2", variables={**common, "dt": 1.25e-8,
                                                        "nsteps": 2000})
    t = coarse.thermo[-1]
    assert t["KinEng"][0] > 0.0 and np.max(t["PotEng"]) > 0.5 * t["TotEng"][0]
    assert energy_error(coarse) < 1e-4
    ratio = energy_error(coarse) / energy_error(fine)
    assert 3.0 < ratio < 5.0, ratio


# ----------------------------------------------------------------------------------------
# zero-energy modes


def nonaffine_history(workdir):
    frames = read_dump(workdir / "dump.atoms")
    history = []
    for fr in frames:
        X = np.stack([fr[f"f_ref[{k}]"] for k in (1, 2, 3)], axis=1)
        Y = np.stack([fr[c] for c in "xyz"], axis=1)
        history.append((fr["step"], nonaffine_measure(X, Y, np.full(len(X), A_TEST ** 3))))
    return np.array(history)


def test_stabilization_controls_zero_energy_modes(tmp_path):
    # A checkerboard velocity v_x = v0 (-1)^(i+j+k) is a zero-energy mode of the interior of a
    # correspondence body: it leaves every interior F_i unchanged. Without stabilization nothing
    # resists it and the non-affine measure |eta - F xi| (nosb_reference.nonaffine_measure)
    # keeps growing (measured: x8 from step 50 to step 1000, monotonic); with the default
    # Cs = 0.1 it oscillates at a bounded amplitude (measured ~5e-4, 30x smaller at the end).
    common = {"n": 8, "vcheck": 1.0, "nsteps": 1000, "dt": 1e-7, "dump_every": 50,
              "thermo_every": 100}
    run_deck(BLOCK, tmp_path / "off", variables={**common, "Cs": 0.0})
    run_deck(BLOCK, tmp_path / "on", variables=common)  # default stabilization
    off = nonaffine_history(tmp_path / "off")
    on = nonaffine_history(tmp_path / "on")
    assert off[0, 1] < 1e-14 and on[0, 1] < 1e-14  # the lattice itself is affine
    grows = off[1:, 1]
    assert np.all(np.diff(grows) > 0.0), grows            # keeps growing ...
    assert grows[-1] > 4.0 * grows[0], grows              # ... by a lot
    bounded = on[1:, 1]
    half = len(bounded) // 2
    assert np.max(bounded[half:]) < 1.5 * np.max(bounded[:half]), bounded
    assert bounded[-1] < 0.1 * grows[-1]


def test_singular_families_stay_finite(tmp_path):
    # A single layer of particles: every family is coplanar, K_i is singular for every
    # particle (doc/pair_peri_nosb.rst: handled explicitly, never with NaN). The documented fallback
    # (compute_nosb_atom.cpp, src/core/peri/elastic.cpp) reports F = I (J = 1, W = 0) and gives the
    # particle no force state of its own; the run must stay finite.
    deck = (DECKS / "nosb_plate.lmp")
    run = run_deck(deck, tmp_path, variables={"nsteps": 20})
    assert "atoms with a singular shape tensor = 64" in run.log
    frame = read_dump(tmp_path / "dump.plate")[-1]
    for col in ("x", "y", "z", "fx", "fy", "fz", "c_nosb[2]", "c_nosb[3]"):
        assert np.all(np.isfinite(frame[col])), col
    assert np.all(frame["c_nosb[3]"] == 1.0) and not np.any(frame["c_nosb[2]"])
    assert np.all(np.isfinite(run.thermo[-1]["PotEng"]))


DELETE = """
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
lattice         sc 0.001
region          block block -0.5 7.5 -0.5 5.5 -0.5 5.5
create_box      1 block
create_atoms    1 region block
set             group all density 1000
set             group all volume 1.0e-9
pair_style      peri/nosb
pair_coeff      * * linear 1.0e9 0.6e9 0.0030002 0.5 0.25
compute         nosb all nosb/atom
thermo_style    custom step pe
thermo_modify   format float %.17g
run             0
region          cut block INF 0.0025 INF INF INF INF units box
delete_atoms    region cut compress no
dump            d all custom 1 dump.cut id x y z fx fy fz c_nosb[1] c_nosb[2] c_nosb[3]
dump_modify     d format float %.17g
run             0
"""


def test_deleted_partners_are_broken_bonds(tmp_path):
    # delete_atoms (without renumbering) after the families exist: a partner that no longer
    # exists counts as a broken bond, as in the built-in PERI styles. The remaining block is
    # undeformed, so it stays at rest: pe and forces are round-off (F_i = I for any family),
    # particles within one horizon of the cut (x < 2.5 + 3 spacings) are damaged, the others
    # are not.
    run = run_deck(DELETE, tmp_path)
    frame = read_dump(tmp_path / "dump.cut")[-1]
    assert frame["natoms"] == 5 * 36
    pe = run.thermo[-1]["PotEng"][0]
    assert abs(pe) < 1e-6   # a 1e-3 strain would store ~1e2 per particle
    # surface force density of a 1e-3 strain ~ E 1e-3 / a = 1.5e9; round-off measured 5e-4
    assert np.max(np.abs([frame["fx"], frame["fy"], frame["fz"]])) < 1e-9 * 1.5e9
    damage = frame["c_nosb[1]"]
    ix = lattice_index(frame["x"])
    assert np.all(damage[ix <= 5] > 0.0) and not np.any(damage[ix >= 6])
    assert np.allclose(frame["c_nosb[3]"], 1.0, rtol=0, atol=1e-12)


# ----------------------------------------------------------------------------------------
# per-type coefficients

TWO_TYPES = DECKS / "nosb_two_types.lmp"
# decks/nosb_two_types.lmp: (model, K, G, s00, alpha) of types 1, 2 and of the 1-2 bonds
TYPE_COEFFS = {(1, 1): ("linear", 1.0e9, 0.6e9, 0.05, 0.25),
               (2, 2): ("neohookean", 2.0e9, 0.5e9, 0.5, 0.25),
               (1, 2): ("linear", 1.5e9, 0.55e9, 0.08, 0.25)}


def expected_damage(X, Y, types, horizon=3.0002 * A_TEST, coeffs=TYPE_COEFFS):
    """Damage after the first breaking evaluation of peri/nosb for positions Y held since the
    setup evaluation (doc/pair_peri_nosb.rst: a bond between types I and J breaks when its
    stretch exceeds s00_IJ - alpha_IJ max(s_min,i, s_min,j), s_min,i the smallest stretch
    among i's bonds, here from the setup evaluation at the same positions); damage = broken
    fraction of the family weighted by the bond weights omega = beta V_j (fix_nosb_family.h;
    uniform volumes here)."""
    xi = X[None, :, :] - X[:, None, :]
    r0 = np.linalg.norm(xi, axis=2)
    bonded = (r0 > 0) & (r0 <= horizon)
    r = np.linalg.norm(Y[None, :, :] - Y[:, None, :], axis=2)
    stretch = np.where(bonded, r / np.where(bonded, r0, 1.0) - 1.0, 0.0)
    lo, hi = np.minimum.outer(types, types), np.maximum.outer(types, types)
    s00 = np.empty_like(r0)
    alpha = np.empty_like(r0)
    for (a, b), c in coeffs.items():
        pair = (lo == a) & (hi == b)
        s00[pair], alpha[pair] = c[3], c[4]
    smin = np.min(np.where(bonded, stretch, np.inf), axis=1)
    broken = bonded & (stretch > s00 - alpha * np.maximum.outer(smin, smin))
    _, omega = bond_weights(X, np.full(len(X), A_TEST ** 3), horizon)
    return np.sum(omega * broken, axis=1) / np.sum(omega, axis=1)


def test_per_type_coefficients_apply_per_type(tmp_path):
    # Type 1 (x < 4.5 a): linear, K = 1 GPa, s00 = 0.05; type 2: neo-Hookean, K = 2 GPa,
    # s00 = 0.5; 1-2 bonds s00 = 0.08. A uniaxial stretch of 10% (F11 = 1.1) then
    # 1) gives pe = N1 W_linear(F; K1, G1) + N2 W_neohookean(F; K2, G2): each particle's energy
    #    uses its own type's model and moduli (1e-9 as in test_affine_energy_is_n_times_w);
    # 2) breaks exactly the bonds the critical-stretch rule with per-type s00 predicts
    #    (LAMMPS's built-in styles ignore per-type s00: LAMMPS issue 984): each bond at the
    #    s00 and alpha of its own type pair; some of every type-1 family, none of the bonds
    #    between type-2 particles. The per-particle
    #    damage is a ratio of sums of ~100 bond weights, compared to 1e-12;
    # 3) breaks each bond at both ends in the same evaluation: momentum stays zero (1e-12 of
    #    sum |V f| as in test_internal_forces_conserve_momentum) after the families changed;
    # 4) does not change the energy: F_i of an affine deformation is F for any family, so pe
    #    after breaking equals pe before to round-off.
    run = run_deck(TWO_TYPES, tmp_path)
    frame0, frame1 = read_dump(tmp_path / "dump.types")
    F = np.diag([1.1, 1.0, 1.0])
    types = frame0["type"].astype(int)
    n1, n2 = np.count_nonzero(types == 1), np.count_nonzero(types == 2)
    assert n1 == 500 and n2 == 500
    W1 = strain_energy_density("linear", F, K=1.0e9, G=0.6e9)
    W2 = strain_energy_density("neohookean", F, K=2.0e9, G=0.5e9)
    before, after = run.thermo[-1]["PotEng"]
    assert before == pytest.approx(n1 * W1 + n2 * W2, rel=1e-9)
    assert after == pytest.approx(before, rel=1e-12)
    assert np.allclose(frame0["c_nosb[2]"], np.where(types == 1, W1, W2), rtol=1e-9, atol=0)

    X = np.stack([frame1[f"f_ref[{k}]"] for k in (1, 2, 3)], axis=1)
    Y = np.stack([frame1[c] for c in "xyz"], axis=1)
    damage = frame1["c_nosb[1]"]
    assert not np.any(frame0["c_nosb[1]"])  # nothing breaks in the setup evaluation
    assert np.allclose(damage, expected_damage(X, Y, types), rtol=0, atol=1e-12)
    deep2 = (types == 2) & (lattice_index(X)[:, 0] >= 8)  # type-2 partners only
    assert np.count_nonzero(deep2) == 200 and not np.any(damage[deep2])
    assert np.all(damage[types == 1] > 0.1)

    t = run.thermo[-1]
    for k in (0, 1):
        p = np.array([t[f"c_mom[{d}]"][k] for d in (1, 2, 3)])
        assert np.max(np.abs(p)) < 1e-12 * t["c_momabs"][k]
