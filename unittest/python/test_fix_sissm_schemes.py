"""fix sissm time schemes (issue 12): `scheme euler|bdf2|genalpha [rho_inf]` through LAMMPS.

The schemes' properties on toy systems (order, the linear oscillator's amplitude and period,
generalized-alpha's energy and spectral radius, variable-step BDF2, the momentum balance) are
tested in the core (unittest/core/solvers/test_time_schemes.cpp). Here: the glue around them
(the per-atom history that travels with the atoms and through restart files, the start from
the forces at y^n, cut-back sub-steps restoring the history, the forces of generalized-alpha
at t^{n+1-alpha_f}), checked on decks: free fall exact, the order of convergence of a vibrating
block, 1 and 2 ranks, a run split by a restart file, bad input."""
import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from sissm_support import BLOCK, CONTINUE, EXPLICIT_LIMIT, PRESCRIBED, explicit_limit_brackets

G = 9.81
SECOND_ORDER = ["bdf2", "genalpha", "genalpha 1.0", "genalpha 0.0"]
DUMPED = ("id", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz")


def fall_error(run_dir, h, nsteps):
    """Largest deviation from exact free fall z = z0 - g t^2 / 2, v = -g t (v0 = 0), relative to
    the fall of that step's time / its velocity."""
    frames = read_dump(run_dir / "dump.atoms")
    assert [f["step"] for f in frames] == list(range(nsteps + 1))
    z0 = frames[0]["z"]
    ez = ev = 0.0
    for f in frames[1:]:
        t = f["step"] * h
        fall = 0.5 * G * t * t
        ez = max(ez, np.abs(f["z"] - (z0 - fall)).max() / fall)
        ev = max(ev, np.abs(f["vz"] + G * t).max() / (G * t))
    return ez, ev


@pytest.mark.parametrize("scheme", SECOND_ORDER)
def test_free_fall_is_exact(tmp_path, scheme):
    # Both second-order schemes integrate a constant acceleration exactly: BDF2 from the history
    # it starts from a^0 = f(y^0)/rho (fix gravity's force, read at the start of the step), and
    # generalized-alpha from a^0. Backward Euler would be off by h/t (10 % at step 10;
    # test_fix_sissm.py checks its own closed form). Tolerance: the solve stops at
    # tol a = 1e-15 m, 2e-7 of the smallest fall (g h^2 / 2 at 10x the limit: 4e-9 m); the
    # error of a missing or doubled start term is O(1).
    system = "block 3x3x3"
    assert explicit_limit_brackets(system)
    h = 10 * EXPLICIT_LIMIT[system]
    run = run_deck(BLOCK, tmp_path, variables={"nx": 3, "ny": 3, "nz": 3, "grav": G, "dt": h,
                                               "nsteps": 10, "iters": 200, "tol": 1e-12,
                                               "solver": "krylov", "dump_every": 1,
                                               "opts": f"scheme {scheme}"})
    assert np.all(run.thermo[-1]["f_integrate[4]"] == 0)
    ez, ev = fall_error(tmp_path, h, 10)
    assert ez < 1e-5 and ev < 1e-5, (ez, ev)


def test_cut_back_steps_restore_the_history(tmp_path):
    # Steps that cannot converge in 12 evaluations are redone as sub-steps (measured: every
    # step, as 4 sub-steps); the history of the start of the step is restored before each
    # attempt, the sub-steps are variable BDF2 steps, and the step after them (4x the last
    # sub-step) starts its history again from a^n: a free fall stays exact (a history left by
    # a failed attempt, or used at the wrong step ratio, would not be).
    h = 10 * EXPLICIT_LIMIT["block 3x3x3"]
    run = run_deck(BLOCK, tmp_path, variables={"nx": 3, "ny": 3, "nz": 3, "grav": G, "dt": h,
                                               "nsteps": 10, "iters": 12, "tol": 1e-12,
                                               "solver": "krylov", "dump_every": 1,
                                               "opts": "scheme bdf2 precond block"})
    assert "redone as" in run.log
    assert run.thermo[-1]["f_integrate[4]"][-1] == 0
    ez, ev = fall_error(tmp_path, h, 10)
    assert ez < 1e-5 and ev < 1e-5, (ez, ev)


@pytest.mark.parametrize("scheme", ["euler", "bdf2", "genalpha", "genalpha 0.0"])
def test_prescribed_atoms_where_the_forces_are_evaluated(tmp_path, scheme):
    # A block moving rigidly at 1 m/s, its first two layers driven by fix move at the same
    # speed: no bond is ever stretched, and every scheme carries the free atoms along exactly.
    # Generalized-alpha evaluates the forces at t^{n+1-alpha_f}: the driven layers must be
    # placed there too while the step is solved (at t^{n+1} they would lead by alpha_f h v =
    # 9e-6 m, 1 % of a spacing, and pull the block ahead: measured 1.1e-5 m). 20 steps of
    # 2e-5 s (35x the explicit limit). Tolerance: the solve's 1e-12 spacings, 1e-15 m.
    run_deck(PRESCRIBED, tmp_path, variables={"drive": "move", "vdrive": 1.0, "vfree": 1.0,
                                              "dt": 2e-5, "nsteps": 20, "dump_every": 20,
                                              "solver": "krylov", "iters": 100, "tol": 1e-12,
                                              "opts": f"scheme {scheme}"})
    first, last = read_dump(tmp_path / "dump.atoms")
    assert np.abs(last["x"] - first["x"] - 4e-4).max() < 1e-13
    assert np.abs(last["vx"] - 1.0).max() < 1e-9
    assert np.abs(last["y"] - first["y"]).max() < 1e-13


def drag_decay(tmp_path, scheme, steps=20):
    """A free 3x3x3 block moving rigidly at 1 m/s under fix viscous (rho dv/dt = -gamma v,
    gamma h / rho = 0.1): its velocity after 20 steps, the exact one being exp(-2)."""
    deck = "\n".join([
        "units si", "boundary s s s", "atom_style peri", "atom_modify map array",
        "lattice sc 0.001", "region block block -0.5 2.5 -0.5 2.5 -0.5 2.5",
        "create_box 1 block", "create_atoms 1 region block",
        "set group all density 1000", "set group all volume 1.0e-9",
        "pair_style peri/nosb", "pair_coeff * * linear 1.0e9 0.6e9 0.0030002 0.5 0.25",
        "velocity all set 1.0 0.0 0.0 units box", "fix drag all viscous 1.0e9",
        f"fix 1 all sissm tolerance 1e-13 precond block scheme {scheme}", "timestep 1.0e-7",
        "compute vx all reduce ave vx", "thermo_style custom step c_vx f_1[4]",
        "thermo_modify format float %.15g", f"thermo {steps}", f"run {steps}"]) + "\n"
    run = run_deck(deck, tmp_path)
    assert run.thermo[-1]["f_1[4]"][-1] == 0
    return run.thermo[-1]["c_vx"][-1]


def test_velocity_dependent_forces_at_the_schemes_order(tmp_path):
    # fix viscous is re-evaluated at every iterate with the velocity the scheme gives that
    # iterate (BDF2's, generalized-alpha's at t^{n+1-alpha_f}): the decay exp(-gamma t / rho)
    # is then met to second order. Backward Euler: (1/1.1)^20 = 0.1486 against exp(-2) =
    # 0.1353 (10 %); the second-order schemes 10x closer at least (measured: bdf2 0.42 %,
    # genalpha 0.8 0.17 %, genalpha 1.0 0.17 %).
    exact = np.exp(-2.0)
    euler = drag_decay(tmp_path / "euler", "euler")
    assert euler == pytest.approx(1.1 ** -20, rel=1e-7)  # the solve: 1e-16 m / h per step
    for scheme in ("bdf2", "genalpha", "genalpha 1.0"):
        v = drag_decay(tmp_path / scheme.replace(" ", "_"), scheme)
        assert abs(v - exact) < 0.1 * abs(euler - exact), (scheme, v)


def tip_x(run_dir):
    """x of the atoms of the last dump frame, sorted by id."""
    f = read_dump(run_dir / "dump.atoms")[-1]
    return f["x"][np.argsort(f["id"])]


@pytest.mark.parametrize("scheme,order", [("euler", 1), ("bdf2", 2), ("genalpha", 2),
                                          ("genalpha 1.0", 2)])
def test_order_of_convergence(tmp_path, scheme, order):
    # A 4x3x3 block (K = 1 GPa, neo-Hookean) released with a stretching velocity field
    # (v_x = 2 m/s (X - xc)/L: a few 1e-3 strain) vibrates, mostly in its lowest axial mode;
    # positions at t = 60 h0 (h0 = 0.2x the explicit limit: the steps resolve every mode that
    # moves; at 5x the limit backward Euler damps it all away, and at 0.5x the errors are not
    # yet in their asymptotic range) from steps h0, h0/2, h0/4 against the same scheme at
    # h0/32. The error falls by 2^order per halving (within 25 %; measured: euler 1.85, 2.23;
    # bdf2 3.49, 3.82; genalpha 0.8 3.88, 4.01; genalpha 1.0 3.89, 4.02), so the history, the
    # start from f^0 and the velocity update are all of the scheme's order.
    h0 = 0.2 * EXPLICIT_LIMIT["block 4x3x3"]
    base = {"model": "neohookean", "vib": 2.0, "iters": 200, "tol": 1e-13, "solver": "krylov",
            "opts": f"scheme {scheme} precond block", "thermo_every": 1000}

    def end(k):
        d = tmp_path / f"h{k}"
        n = 60 * k
        run_deck(BLOCK, d, variables={**base, "dt": h0 / k, "nsteps": n, "dump_every": n})
        return tip_x(d)

    ref = end(32)
    err = [np.abs(end(k) - ref).max() for k in (1, 2, 4)]
    ratios = [err[0] / err[1], err[1] / err[2]]
    expected = 2.0 ** order
    assert all(abs(r - expected) < 0.25 * expected for r in ratios), (err, ratios)


@pytest.mark.mpi
@pytest.mark.parametrize("scheme", ["bdf2", "genalpha 0.8"])
def test_one_and_two_ranks_agree(tmp_path, scheme):
    # With precond block every per-atom value is bit-identical on 1 and 2 ranks (as for
    # backward Euler, test_fix_sissm_parallel.py): the history moves with its atoms.
    args = {"nx": 6, "ny": 6, "nz": 6, "dt": 1.5e-5, "vib": 20.0, "vrand": 2.0, "grav": 1000.0,
            "held": 1, "nsteps": 40, "thermo_every": 10, "solver": "krylov",
            "dump_every": 40, "opts": f"scheme {scheme} precond block unconverged warn"}
    run_deck(BLOCK, tmp_path / "np1", nprocs=1, variables=args)
    two = run_deck(BLOCK, tmp_path / "np2", nprocs=2, variables=args)
    assert "with 2 MPI tasks" in two.log
    d1, d2 = read_dump(tmp_path / "np1/dump.atoms")[-1], read_dump(tmp_path / "np2/dump.atoms")[-1]
    for col in DUMPED:
        assert np.array_equal(d1[col], d2[col]), col


@pytest.mark.parametrize("scheme,ranks", [("bdf2", 1), ("genalpha 0.8", 1),
                                          pytest.param("bdf2", 2, marks=pytest.mark.mpi)])
def test_restart_continues_the_run(tmp_path, scheme, ranks):
    # The history (BDF2: the last step's changes, its acceleration and length; generalized-
    # alpha: the acceleration) is in the restart file: the continued run is the unsplit one,
    # bit for bit (without it the continued run would start a new history and differ at 1e-3).
    args = {"nx": 6, "ny": 6, "nz": 6, "dt": 1.5e-5, "vib": 20.0, "vrand": 2.0, "grav": 1000.0,
            "held": 1, "nsteps": 40, "thermo_every": 10, "solver": "krylov",
            "opts": f"scheme {scheme} precond block unconverged warn"}
    run_deck(BLOCK, tmp_path / "full", nprocs=ranks, variables={**args, "dump_every": 20})
    run_deck(BLOCK, tmp_path / "split", nprocs=ranks, variables={**args, "restart_at": 20})
    keep = {k: args[k] for k in ("nsteps", "grav", "thermo_every", "solver", "opts")}
    cont = run_deck(CONTINUE, tmp_path / "split", nprocs=ranks,
                    variables={**keep, "dump_every": 20})
    assert "holds no history" not in cont.log
    fa = read_dump(tmp_path / "full/dump.atoms")[-1]
    fb = read_dump(tmp_path / "split/dump.atoms")[-1]
    assert fa["step"] == fb["step"] == 40
    for col in DUMPED:
        assert np.array_equal(fa[col], fb[col]), col


def test_restart_with_another_scheme_starts_anew(tmp_path):
    args = {"nx": 4, "ny": 3, "nz": 3, "dt": 1e-5, "vib": 2.0, "nsteps": 10, "solver": "krylov",
            "opts": "scheme bdf2"}
    run_deck(BLOCK, tmp_path, variables={**args, "restart_at": 5})
    cont = run_deck(CONTINUE, tmp_path, variables={"nsteps": 10, "solver": "krylov",
                                                    "opts": "scheme genalpha"})
    assert "holds no history of scheme genalpha" in cont.log


@pytest.mark.parametrize("opts,message", [
    ("scheme newmark", "scheme must be euler, bdf2 or genalpha, got 'newmark'"),
    ("scheme genalpha 1.5", "scheme genalpha rho_inf must be 0 to 1, got 1.5"),
    ("scheme", "fix sissm scheme"),
])
def test_bad_scheme(tmp_path, opts, message):
    run = run_deck(BLOCK, tmp_path, variables={"nsteps": 1, "opts": opts}, check=False)
    assert not run.ok and message in run.log + run.stdout + run.stderr
