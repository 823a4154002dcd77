"""fix sissm on a gravity-loaded cantilever (issue 4): the static equilibrium is a fixed point of
the step for any iteration count, converged steps far beyond the explicit limit bring the beam
to the rest deflection of the explicit damped run, and a beam that is not at rest is not
reported as converged."""
from pathlib import Path

import numpy as np
import pytest

from lammps_run import cut_back_steps, read_dump, run_deck
from sissm_support import CANTILEVER, EXPLICIT_LIMIT, positions

GRAV = 100.0  # m/s^2 (the beams are linear-elastic: the deflection is just proportional to g)
# viscous damping of the explicit relaxation: critical for the fundamental bending mode of the
# 16x4x4 beam (period ~4e-4 s, gamma_c = 2 rho omega ~ 3e7); every mode then decays at least
# at gamma / (2 rho) = 2e4 / s, so 3000 steps of 5e-7 s (1.5e-3 s) reduce it by e^-30
GAMMA = 4.0e7


def cantilever(name):
    nx, ny, nz = (int(d) for d in name.split()[1].split("x"))
    return {"nx": nx, "ny": ny, "nz": nz, "held": 3, "grav": GRAV}


def explicit_limit_brackets(name, workdir):
    """fix nve (undamped, from rest under gravity) runs 3000 steps at 0.9x the tabulated
    limit, and blows up (etotal = pe + ke above 100 J, ~40 times the stable maximum) at
    1.15x."""
    def stable(dt, tag):
        run = run_deck(CANTILEVER, Path(workdir) / tag, check=False,
                       variables={**cantilever(name), "nrelax": 3000, "gamma": 0.0,
                                  "dt_nve": dt, "halt": 100.0})
        t = run.thermo[0] if run.thermo else {"Step": [0]}
        return run.ok and t["Step"][-1] == 3000
    dt = EXPLICIT_LIMIT[name]
    return stable(0.9 * dt, "below") and not stable(1.15 * dt, "above")


@pytest.mark.parametrize("solver", ["jacobi", "krylov"])
def test_static_equilibrium_is_a_fixed_point(tmp_path, solver):
    name = "cantilever 16x4x4"
    assert explicit_limit_brackets(name, tmp_path / "limit")
    run = run_deck(CANTILEVER, tmp_path / "run", variables={
        **cantilever(name), "nrelax": 3000, "gamma": GAMMA, "dt_nve": 0.7 * EXPLICIT_LIMIT[name],
        "nsissm": 20, "dt_sissm": 100.0 * EXPLICIT_LIMIT[name], "iters": 5,
        "solver": solver, "thermo_every": 100, "dump_every": 1})
    relax, sissm = run.thermo[0], run.thermo[1]
    # the explicit relaxation is at rest: the tip moved by less than 1e-6 of its deflection
    # over the last 1000 steps (measured 1e-9)
    tip = relax["c_tipdz"]
    assert tip[-1] < 0
    assert abs(tip[-1] - tip[-11]) < 1e-6 * abs(tip[-1])
    relaxed = read_dump(tmp_path / "run/dump.relaxed")[0]
    frames = read_dump(tmp_path / "run/dump.sissm")
    assert [f["step"] for f in frames] == list(range(3000, 3021))
    deflection = abs(tip[-1])
    # From an equilibrium with v = 0 the first residual is h^2 (f_int + f_ext) ~ 0, whatever
    # the number of sweeps, so the beam must stay. The 0.1 % of the tip deflection asked for
    # is ~1.4e-10 m; what is left of the explicit relaxation (1e-9 relative) moves it by far
    # less (measured 2e-10 relative over the 20 steps).
    drift = max(np.abs(positions(f) - positions(relaxed)).max() for f in frames)
    assert drift < 1e-3 * deflection, drift / deflection
    assert np.all(sissm["f_integrate[4]"] == 0) and not cut_back_steps(run)


@pytest.mark.parametrize("solver", ["jacobi", "krylov"])
def test_converged_steps_reach_the_explicit_rest_deflection(tmp_path, solver):
    # The 10x3x3 beam (the 16x4x4 one costs ~1.7e5 sweeps of 256 particles to settle). Each
    # SISSM step is converged (residual tolerance 1e-10 of the spacing): backward Euler at 100x damps the fundamental
    # (omega h ~ 3) by ~8 per step, so 4 steps reach the rest deflection to ~1e-3 (measured
    # 8e-4); each takes ~1e4 sweeps (the bending mode contracts by ~1 - 3.6e-4 per sweep).
    # Same force, same equilibrium: 1 % (the criterion) is a loose bound.
    name = "cantilever 10x3x3"
    assert explicit_limit_brackets(name, tmp_path / "limit")
    explicit = run_deck(CANTILEVER, tmp_path / "nve", variables={
        **cantilever(name), "nrelax": 4000, "gamma": GAMMA,
        "dt_nve": 0.7 * EXPLICIT_LIMIT[name], "thermo_every": 100})
    tip = explicit.thermo[0]["c_tipdz"]
    assert abs(tip[-1] - tip[-11]) < 1e-6 * abs(tip[-1])
    sissm = run_deck(CANTILEVER, tmp_path / "sissm", variables={
        **cantilever(name), "nsissm": 4, "dt_sissm": 100.0 * EXPLICIT_LIMIT[name],
        "iters": 1000000, "tol": 1e-10, "solver": solver, "thermo_every": 1})
    t = sissm.thermo[0]
    assert np.all(t["f_integrate[4]"] == 0) and not cut_back_steps(sissm)
    assert t["c_tipdz"][-1] == pytest.approx(tip[-1], rel=0.01)


def test_a_beam_that_is_not_at_rest_is_not_reported_converged(tmp_path):
    # BUG (reported): with solver jacobi, `iterations 5` and tolerance 1e-6 at 100x the limit,
    # every step stops after ONE sweep as "converged" (measure ~2e-9: the first correction of
    # the slow bending mode is tiny, though the iterate is far from the step's solution), and
    # the beam swings with a period ~2000 steps (about 25 times the physical one) between
    # 0.2 and 1.6 times its rest deflection, still swinging after 3000 steps, with
    # f_ID[4] = 0 and no warning. Contract: either the beam settles (within 1 % of the
    # explicit rest deflection over the last 500 steps) or the steps are counted as
    # unconverged. The steps kept at the iteration limit are the subject, so they are kept
    # (unconverged warn; with the default cutback, 16 sub-steps of 5 sweeps do not converge
    # step 1 either and the run stops with an error). Measured now: 2672 of 3000 steps
    # counted, with the warning, and the tip within 0.2 % of the rest deflection at the end.
    name = "cantilever 10x3x3"
    run = run_deck(CANTILEVER, tmp_path, variables={
        **cantilever(name), "nsissm": 3000, "dt_sissm": 100.0 * EXPLICIT_LIMIT[name],
        "iters": 5, "solver": "jacobi", "opts": "unconverged warn", "thermo_every": 50})
    t = run.thermo[0]
    rest = -1.344e-8  # explicit rest deflection of this beam (previous test: -1.34397e-8 m)
    settled = np.all(np.abs(t["c_tipdz"][-11:] - rest) < 0.01 * abs(rest))
    reported = t["f_integrate[4]"][-1] > 0 and any("Fix sissm" in w for w in run.warnings)
    assert settled or reported, (
        f"tip over the last 500 steps {t['c_tipdz'][-11:].min():.3g} .. "
        f"{t['c_tipdz'][-11:].max():.3g} m (rest {rest:.4g} m), f_integrate[4] = "
        f"{t['f_integrate[4]'][-1]:g}, mean iterations {t['f_integrate[3]'][-1]:g}")
