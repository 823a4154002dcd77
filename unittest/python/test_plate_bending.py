"""The plate bending energy of membranes (pair_coeff ... bend D|auto bending plate) through
LAMMPS: a sheet bent without stretching into a cylinder stores D kappa^2 / 2 per area whatever
the triangulation and the direction of the axis (where the hinges give 1.5 times that about the
diagonals of right triangles); a simply supported plate and a narrow strip bring in Poisson's
ratio as plate theory does; forces are the energy's gradient; 1 and 2 ranks agree; the list
follows the atoms through periodic boundaries and rank changes; a split run continues exactly;
meshes it cannot serve are refused with a message that names the way out."""
import math
import sys
from pathlib import Path

import pytest

from lammps_run import run_deck

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
import make_sheet  # noqa: E402

DECKS = Path(__file__).parent / "decks"
CYLINDER = DECKS / "membrane_cylinder.lmp"
PLATE = DECKS / "membrane_plate.lmp"


def sheet(tmp_path, pattern="alternate", a=0.01, side=0.3, **kw):
    vertices, faces = make_sheet.rectangle(side, side, a, pattern, kw.get("jitter", 0.0),
                                           kw.get("seed", 1))
    path = Path(tmp_path) / "sheet.obj"
    path.parent.mkdir(parents=True, exist_ok=True)
    make_sheet.write_obj(path, vertices, faces, ["sheet"])
    return vertices, faces, path


def cylinder_ratio(tmp_path, pattern, angle, bending, nu=0.0, jitter=0.0):
    """Energy of the sheet bent into a cylinder of curvature 2 / m about an axis at `angle`
    degrees to x, over D kappa^2 / 2 times its area (D = 1 N m, a membrane of 1 Pa)."""
    vertices, faces, path = sheet(tmp_path, pattern, jitter=jitter, seed=3)
    area = make_sheet.mesh_stats(vertices, faces)["area"]
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    R = 0.5
    E = 1.0
    deck = f"""units si
boundary f f f
atom_style peri
atom_modify map array
region box block -0.4 0.4 -0.4 0.4 -0.2 0.4
create_box 1 box
read_mesh sheet.obj type 1 thickness 0.001 density 1000
pair_style peri/nosb
pair_coeff * * linear {E / (3 * (1 - 2 * nu))} {E / (2 * (1 + nu))} 0.030006 0 0 break no &
  membrane yes bend 1.0 bending {bending}
neighbor 0.01 bin
run 0 post no
fix ref all store/state 0 x y
variable u atom -f_ref[1]*{s}+f_ref[2]*{c}
variable v atom f_ref[1]*{c}+f_ref[2]*{s}
variable nx atom v_v*{c}-{R}*sin(v_u/{R})*{s}
variable ny atom v_v*{s}+{R}*sin(v_u/{R})*{c}
variable nz atom {R}*(1-cos(v_u/{R}))
set group all x v_nx y v_ny z v_nz
compute pea all pe/atom
compute vol all property/atom vfrac
variable ev atom c_pea*c_vol
compute etot all reduce sum v_ev
thermo_style custom step pe c_etot
thermo_modify format float %.17g
run 0 post no
"""
    run = run_deck(deck, tmp_path, files={"sheet.obj": path.read_text()})
    energy = run.thermo[-1]["c_etot"][-1]
    return energy / (0.5 * (1.0 / R) ** 2 * area), run


# The plate energy is exact on quadratic deflections (core test Curvature.*); on a cylinder of
# kappa h = 0.02 the chords' departure from the arcs costs (kappa h)^2 ~ 4e-4 at most (measured
# 0.9997-0.9998 at kappa = 4, validate_bending.py): asked, 1e-3 on every mesh kind and axis,
# with nu = 0 and 0.3 (a cylinder has det k = 0: nu does not enter). The hinges on the same
# alternate mesh store 1.5 times as much about a diagonal (membrane/hinge.h).
@pytest.mark.parametrize("pattern,angle,nu,jitter", [
    ("alternate", 0, 0.0, 0.0), ("alternate", 45, 0.3, 0.0), ("right", 45, 0.0, 0.0),
    ("alternate", 30, 0.0, 0.25), ("equilateral", 60, 0.3, 0.0)])
def test_cylinder_stores_d_kappa_squared_over_two(tmp_path, pattern, angle, nu, jitter):
    ratio, run = cylinder_ratio(tmp_path, pattern, angle, "plate", nu=nu, jitter=jitter)
    assert abs(ratio - 1.0) < 1e-3, ratio
    assert "Pair peri/nosb bending plate: ghost cutoff at least" in run.log


def test_hinges_are_stiffer_about_a_diagonal_of_right_triangles(tmp_path):
    ratio, _ = cylinder_ratio(tmp_path, "alternate", 45, "hinge")
    assert 1.4 < ratio < 1.6, ratio


def test_bending_force_is_the_energy_gradient(tmp_path):
    """The z force on an interior vertex of the bent and turned plate (all terms) against central
    differences of the energy (step 1e-7 m on a 1 cm mesh; the plate term is quadratic, so the
    truncation is the membrane's ~1e-14; round-off ~1e-8 N): to 1e-5 relative."""
    _, _, path = sheet(tmp_path / "mesh")
    probe = 16 * 31 + 14
    common = {"mesh": path, "dir": "y", "kappa": 2.0, "turn": 30.0, "probe": probe,
              "extra": "bend auto bending plate"}
    out = {}
    for name, step in (("0", 0.0), ("p", 1e-7), ("m", -1e-7)):
        run = run_deck(CYLINDER, tmp_path / name, variables={**common, "step": step})
        out[name] = {k: v[-1] for k, v in run.thermo[-1].items()}
    fd = -(out["p"]["c_energy"] - out["m"]["c_energy"]) / 2e-7
    fz = out["0"]["v_fz"]
    assert abs(fz) > 1e-3
    assert abs(fz - fd) < 1e-5 * abs(fz), (fz, fd)


@pytest.mark.mpi
def test_two_ranks_agree_and_the_list_follows_the_atoms(tmp_path):
    """The cylinder travels rigidly 1.5 box widths through periodic x on 2 ranks with a neighbor
    list build every step and the atoms sorted every 5: the stencils' vertices change ranks,
    local rows and periodic images, and the energy stays that of the first step to round-off;
    the first step's energy equals the one-rank run's."""
    _, _, path = sheet(tmp_path / "mesh")
    deck = CYLINDER.read_text().replace("boundary        f f f",
                                        "boundary        p f f\nprocessors      * 1 1")
    head, tail = deck.rsplit("run             0 post no", 1)
    deck = head + """
atom_modify     sort 5 0.05
neighbor        0.001 bin
neigh_modify    every 1 delay 0 check no
timestep        0.01
fix             travel all move linear 1.2 0.0 0.0
thermo_style    custom step pe c_energy
thermo_modify   format float %.17g
thermo          10
run             100
""" + tail
    energies = []
    for n in (1, 2):
        run = run_deck(deck, tmp_path / str(n), nprocs=n, variables={
            "mesh": path, "kappa": 2.0, "extra": "bend auto bending plate stabilize 0"})
        t = run.thermo[-1]
        assert t["Step"][-1] == 100
        e = t["c_energy"]
        assert e[0] > 10.0
        assert max(abs(v / e[0] - 1.0) for v in e) < 1e-9, list(e)
        energies.append(e[0])
    assert abs(energies[1] / energies[0] - 1.0) < 1e-12, energies


def test_split_run_continues_exactly(tmp_path):
    """write_restart / read_restart keep the keyword (restart format 5); the stencils are made
    again from the reference positions and the triangles, in the same order, and fix sissm's
    forcing term is in the restart file: the continuation takes the same iterations and
    reaches the same state. The thermo's sums add the atoms in the order of the continued
    run's setup, which sorts them again (atom_modify sort): an atom that crossed a sort bin
    since step 0 adds elsewhere, so they agree to a reordered sum's round-off (measured 4e-16
    for KinEng, 2026-12-01), and to the last bit only by chance."""
    _, _, path = sheet(tmp_path / "mesh", pattern="alternate", a=0.02)
    variables = {"mesh": path, "a": 0.02, "extra": "bending plate"}
    full = run_deck(PLATE, tmp_path / "full", variables={**variables, "steps": 4})
    first = PLATE.read_text() + "\nwrite_restart plate.restart\n"
    run_deck(first, tmp_path / "split", variables={**variables, "steps": 2})
    rest = run_deck(DECKS / "membrane_plate_continue.lmp", tmp_path / "split")
    a = {k: v[-1] for k, v in full.thermo[-1].items()}
    b = {k: v[-1] for k, v in rest.thermo[-1].items()}
    assert a["Step"] == b["Step"] == 4
    assert a["c_tipz"] < -1e-4    # it sags
    for key in ("f_integrate[1]", "f_integrate[2]"):
        assert a[key] == b[key], (key, a[key], b[key])
    for key in ("PotEng", "KinEng", "c_tipz"):
        assert abs(a[key] - b[key]) <= 1e-14 * abs(a[key]), (key, a[key], b[key])


def test_curved_rest_shape_is_refused(tmp_path):
    from test_membrane import curved_patch
    run = run_deck(DECKS / "membrane_curved_patch.lmp", tmp_path, check=False,
                   variables={"bend": "bend auto bending plate"},
                   files={"patch.obj": curved_patch()})
    assert not run.ok
    assert any("the mesh is not flat at rest" in e and "'bending hinge'" in e
               for e in run.errors), run.errors


def test_keyword_errors(tmp_path):
    _, _, path = sheet(tmp_path / "mesh", a=0.02)
    for extra, message in (("bend auto bending flat", "bending must be plate or hinge, got flat"),
                           ("bending plate", "bending chooses the energy of bend")):
        run = run_deck(CYLINDER, tmp_path / extra.split()[-1], check=False,
                       variables={"mesh": path, "extra": extra})
        assert any(message in e for e in run.errors), run.errors


def clamped_sag(tmp_path, pattern, precond):
    """The plate of membrane_plate.lmp (30 cm, 2 cm cells, t = 2 cm, two top rows held) sagging
    under its weight with bending plate: the free edge's sag over q L^4 / (8 D), L from the inner
    held row (the plate's clamp), and the run's fix sissm summary line."""
    vertices, faces, path = sheet(tmp_path / "mesh", pattern, a=0.02)
    run = run_deck(PLATE, tmp_path / precond, variables={
        "mesh": path, "a": 0.02, "extra": "bending plate", "precond": precond})
    last = {k: v[-1] for k, v in run.thermo[-1].items()}
    assert last["f_integrate[4]"] == 0    # every step converged
    rows = sorted({round(v[1], 12) for v in vertices})
    L = rows[-2] - rows[0]
    D = 1.0e8 * 0.02 ** 3 / 12.0
    summary = next(ln for ln in run.log.splitlines() if "iterations per step" in ln)
    return -last["c_tipz"] / (1000.0 * 9.81 * 0.02 * L ** 4 / (8.0 * D)), summary


# The sag hardly depends on the triangulation (measured 1.0454 equilateral, 1.0533 alternate,
# 1.0541 right at 2 cm, 2026-11-30; 1.020-1.034 at 1 cm, validate_bending.py), where the hinges
# differ by 11-19%; precond amg serves the plate's static steps without falling back to the
# blocks (the plate edges' hinges and, at these steps, the plate couplings in its matrix).
def test_clamped_plate_sags_alike_on_every_triangulation(tmp_path):
    sags = {}
    for pattern in ("equilateral", "alternate", "right"):
        sags[pattern], summary = clamped_sag(tmp_path / pattern, pattern, "amg")
        assert "0 preconditioner switches" in summary, summary
        assert 1.0 < sags[pattern] < 1.07, sags
    assert max(sags.values()) / min(sags.values()) < 1.015, sags


def validate_bending(*args):
    """Rows of examples/membranes/validate_bending.py (build/lmp runs) as {label: [values]}."""
    import subprocess
    script = REPO / "examples" / "membranes" / "validate_bending.py"
    out = subprocess.run([sys.executable, str(script), "--lmp", str(REPO / "build" / "lmp"),
                          *args], capture_output=True, text=True, timeout=900, check=True)
    rows = {}
    for line in out.stdout.splitlines():
        words = line.split()
        numbers = []
        for w in reversed(words):
            try:
                numbers.insert(0, float(w))
            except ValueError:
                break
        if numbers:
            rows[" ".join(words[:len(words) - len(numbers)])] = numbers
    return rows


# Poisson's ratio in bending, wide: a square plate (30 cm, 1 cm cells, nu = 0.3) with its rim held
# under its weight deflects by Timoshenko's 0.00406 q a^4 / D with the plate modulus
# D = E t^3 / (12 (1 - nu^2)) (measured 2026-11-30: 1.0020 on right, 1.0028 on alternating right
# triangles; 1.0009-1.0012 at 5 mm on the five kinds). Asked: 1% (the target is 5%).
def test_simply_supported_plate_against_timoshenko():
    rows = validate_bending("--only", "simply", "--cells", "0.01", "--kinds", "right",
                            "alternate")
    ratios = rows["10 mm cells"]
    assert all(abs(r - 1.0) < 0.01 for r in ratios), rows


# Poisson's ratio in bending, narrow: a 6 cm x 30 cm strip (1 cm cells) clamped at one end, at
# nu = 0.3, curls across its width (anticlastic curvature -nu times the curvature along it at
# mid-length; measured -0.3154 and -0.3140) and so bends with the beam's E t^3 / 12, not the
# plate modulus (9% stiffer): sag 0.9925 and 0.9979 of q L^4 / (8 E t^3 / 12) (L from the inner
# held row). At nu = 0 it does not curl (|ratio| < 1e-3). Asked: curvature ratio within 0.03 of
# -nu, sag within 2.5% of the beam's.
def test_narrow_strip_curls_anticlastically():
    rows = validate_bending("--only", "strip", "--kinds", "equilateral", "alternate")
    assert all(abs(r + 0.3) < 0.03 for r in rows["nu = 0.3, curvatures"]), rows
    assert all(abs(r - 1.0) < 0.025 for r in rows["nu = 0.3, sag, L inner"]), rows
    assert all(abs(r) < 1e-3 for r in rows["nu = 0.0, curvatures"]), rows
