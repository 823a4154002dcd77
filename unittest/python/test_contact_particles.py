"""fix nosb/contact with volumetric particles: non-mesh atoms of the group are points, in
point-point pairs with each other and point-triangle pairs with the group's triangles. The
energy is the barrier summed over those pairs (computed here independently), the forces are
minus its gradient, 1 and 2 ranks give the same forces to the last bit, particles that are or
were bond partners of pair peri/nosb are no pair, and two elastic blocks thrown at each other
(examples/contact/in.two-blocks) bounce off with their total momentum conserved."""
import math
from pathlib import Path

import numpy as np
import pytest

from lammps_run import run_deck
from test_contact import DHAT, DMIN, KAPPA, barrier, barrier_sum, cloth, displaced_runs, \
    dump_frames, gradient_error, mesh_primitives

DECKS = Path(__file__).parent / "decks"
PARTICLES = DECKS / "contact_particles.lmp"
BLOCK = DECKS / "contact_block.lmp"
TWO_BLOCKS = Path(__file__).resolve().parents[2] / "examples" / "contact" / "in.two-blocks"


def atoms_file(points, volumes, density=1000.0):
    """create_atoms and set lines for particles of type 2 at points (after nfirst atoms)."""
    lines = []
    for p in points:
        lines.append("create_atoms 2 single {!r} {!r} {!r} units box".format(*map(float, p)))
    lines.append("variable first equal count(all)-{}".format(len(points)))
    for k, v in enumerate(volumes):
        lines.append(f"set atom $(v_first+{k + 1}) volume {v!r} density {density!r}")
    return "\n".join(lines) + "\n"


def particles_run(workdir, points, volumes, nprocs=1, mesh=False, more=None, check=True,
                  **variables):
    """contact_particles.lmp with the particles at points, over the 10 cm test cloth (cloth(),
    written into workdir) if mesh."""
    files = {"atoms": atoms_file(points, volumes)}
    if more:
        files["more"] = more
        variables["more"] = "more"
    if mesh:
        cloth(workdir)
        variables["mesh"] = "yes"
    return run_deck(PARTICLES, workdir, nprocs=nprocs, variables=variables, files=files,
                    check=check)


def point_point_sum(x, vol, pairs, dmin=DMIN, dhat=DHAT, kappa=KAPPA):
    """(sum of E, sum of the shares E / (2 V_k), active pairs) over the point-point pairs."""
    total = density = 0.0
    active = 0
    for i, j in pairs:
        d = float(np.linalg.norm(x[i] - x[j]))
        if d >= dmin + dhat:
            continue
        E = kappa * barrier(d - dmin, dhat)
        active += 1
        total += E
        density += 0.5 * E / vol[i] + 0.5 * E / vol[j]
    return total, density, active


# Eight particles (volumes 1.0 to 1.7 mm^3) between 3 and 9 mm above the middle of a 10 cm cloth
# (2 cm right triangles, flat at z = 0), at least 2.5 mm apart (dmin = 2 mm, dhat = 5 mm: reach
# 7 mm), drawn with a fixed seed so that they form point-point and point-triangle pairs.
def scene(seed=3, n=8):
    rng = np.random.default_rng(seed)
    points = []
    while len(points) < n:
        p = rng.uniform([-0.01, -0.01, 0.003], [0.01, 0.01, 0.009])
        if all(np.linalg.norm(p - q) > 0.0025 for q in points):
            points.append(p)
    return np.array(points), [1e-9 * (1.0 + 0.1 * k) for k in range(n)]


# The energy is the barrier summed over the pairs: point-point between the particles (the
# distance of their centres), point-triangle between each particle and each triangle of the
# cloth (closest points from tools/mesh_gaps.py), the cloth's own pairs (none in range: a flat
# cloth). Energy, density sum and counts agree to 1e-12 relative (the fix's point-triangle
# distance comes from squared-distance pieces; measured 1e-15) and exactly.
def test_energy_is_the_sum_over_pairs(tmp_path):
    _, vertices, faces = cloth(tmp_path)
    points, volumes = scene()
    run = particles_run(tmp_path, points, volumes, mesh=True)
    t = {k: v[-1] for k, v in run.thermo[-1].items()}
    frame = dump_frames(tmp_path / "dump.contact")[0]
    x, vol = frame[:, 1:4], frame[:, 7]
    n = len(vertices)
    assert np.abs(x[n:] - points).max() < 1e-15
    x0 = x.copy()
    tris, edges = mesh_primitives(faces)
    total, density, npt, nee = barrier_sum(x, x0, tris, edges, vol)
    pairs = [(i, j) for i in range(n, len(x)) for j in range(i + 1, len(x))]
    pp_total, pp_density, npp = point_point_sum(x, vol, pairs)
    assert npt > 0 and npp > 0 and nee == 0
    assert (t["f_c[1]"], t["f_c[2]"], t["f_c[6]"]) == (npt, 0, npp)
    assert abs(t["f_c[4]"] / (total + pp_total) - 1.0) < 1e-12, (t["f_c[4]"], total + pp_total)
    assert abs(t["f_c"] / (density + pp_density) - 1.0) < 1e-12
    d = [np.linalg.norm(x[i] - x[j]) for i, j in pairs] + list(x[n:, 2])
    assert abs(t["f_c[3]"] - min(d)) < 1e-15
    # without pair peri/nosb there are no bond families: the user is told, once
    told = [w for w in run.warnings if "no pair_style peri/nosb" in w]
    assert len(told) == 1, run.warnings
    # the forces sum to zero (sum of V_i f_i) and push the particles up, the cloth down
    F = frame[:, 4:7] * vol[:, None]
    assert np.abs(F.sum(axis=0)).max() < 1e-12 * np.abs(F).max()
    assert F[n:, 2].sum() > 0 and F[:n, 2].sum() < 0


# Forces are minus the gradient of the energy: V_i f_i = -dE/dx_i by central differences
# (h = 1e-8 m) of f_c[4] at three particles and two cloth vertices under them, all directions.
# Round-off and truncation are ~1e-9 of the largest force; allowed 1e-6.
def test_forces_are_minus_the_energy_gradient(tmp_path):
    _, vertices, _ = cloth(tmp_path)
    points, volumes = scene()
    n = len(vertices)
    base = particles_run(tmp_path / "base", points, volumes, mesh=True)
    frame = dump_frames(tmp_path / "base" / "dump.contact")[0]
    below = np.argsort(np.linalg.norm(frame[:n, 1:3], axis=1))[:2] + 1
    ids = [n + 1, n + 4, n + 8] + [int(i) for i in below]
    h = 1e-8
    commands, order = displaced_runs(frame, ids, h)
    run = particles_run(tmp_path / "fd", points, volumes, mesh=True,
                        more="\n".join(commands) + "\n")
    energies = [t["f_c[4]"][-1] for t in run.thermo[1:]]
    worst = gradient_error(frame, ids, order, energies, h)
    assert worst < 1e-6, worst
    assert base.thermo[-1]["f_c[6]"][-1] > 0


@pytest.mark.mpi
def test_two_ranks_agree(tmp_path):
    """Particles on both sides of the rank boundary (x = 0): each pair is evaluated with the
    same vertex order on every rank that owns one of its atoms, each atom sums its pairs in the
    order of their IDs: the forces agree to the last bit."""
    points, volumes = scene()
    one = particles_run(tmp_path / "one", points, volumes, mesh=True)
    two = particles_run(tmp_path / "two", points, volumes, mesh=True, nprocs=2)
    t1 = {k: v[-1] for k, v in one.thermo[-1].items()}
    t2 = {k: v[-1] for k, v in two.thermo[-1].items()}
    for key in ("f_c", "f_c[4]"):
        assert abs(t2[key] / t1[key] - 1.0) < 1e-12, (key, t1[key], t2[key])
    for key in ("f_c[1]", "f_c[3]", "f_c[5]", "f_c[6]"):
        assert t1[key] == t2[key], key
    assert np.any(points[:, 0] < 0) and np.any(points[:, 0] > 0)
    f1 = dump_frames(tmp_path / "one" / "dump.contact")[0][:, 4:7]
    f2 = dump_frames(tmp_path / "two" / "dump.contact")[0][:, 4:7]
    assert np.array_equal(f1, f2)


# One particle 3 mm above the centroid of a triangle of the cloth, with dmin = dhat = 2 mm: the
# other triangles are more than 4 mm away, so there is exactly one pair, of energy
# kappa b(h - dmin); the particle is pushed straight up by kappa |b'(h - dmin)| and each vertex
# of the triangle down by a third of it (the centroid's barycentric weights).
def test_particle_over_a_triangle(tmp_path):
    _, vertices, faces = cloth(tmp_path)
    tri = faces[12]
    c = vertices[list(tri)].mean(axis=0)
    hgt, dmin, dhat = 0.003, 0.002, 0.002
    run = particles_run(tmp_path, [c + [0.0, 0.0, hgt]], [1e-9], mesh=True, dmin=dmin,
                        dhat=dhat)
    t = {k: v[-1] for k, v in run.thermo[-1].items()}
    assert (t["f_c[1]"], t["f_c[2]"], t["f_c[6]"]) == (1, 0, 0)
    g = hgt - dmin
    E = KAPPA * barrier(g, dhat)
    assert abs(t["f_c[4]"] / E - 1.0) < 1e-12
    dE = KAPPA * (2 * (g - dhat) * math.log(g / dhat) + (g - dhat) ** 2 / g)  # -dE/dz > 0
    frame = dump_frames(tmp_path / "dump.contact")[0]
    F = frame[:, 4:7] * frame[:, 7:8]
    n = len(vertices)
    assert abs(F[n, 2] / dE - 1.0) < 1e-10 and np.abs(F[n, :2]).max() < 1e-12 * dE
    for v in tri:
        assert abs(F[v, 2] / (-dE / 3) - 1.0) < 1e-10, (v, F[v])
    assert np.count_nonzero(np.abs(F).sum(axis=1)) == 4


# ---- bonds: particles that are or were bond partners are no contact pair ----

def block(workdir, **variables):
    return run_deck(BLOCK, workdir, variables=variables)


def test_block_at_rest_has_no_contact(tmp_path):
    """A 4^3 block (spacing 1 mm) whose horizon (3 mm) covers dmin + dhat (1 + 0.5 mm): every
    particle within reach is a bond partner, so no pair is even a candidate. With dmin = the
    spacing, an unexcluded neighbour would be an infinite barrier (an error)."""
    run = block(tmp_path)
    t = {k: v[-1] for k, v in run.thermo[-1].items()}
    assert t["f_c"] == 0.0 and t["f_c[4]"] == 0.0 and t["f_c[6]"] == 0 and t["f_c[5]"] == 0
    assert "total # of bonds = 2712" in run.log


def test_unbonded_neighbours_are_pairs(tmp_path):
    """With the horizon at 1.0002 spacings only the face neighbours are bonded (288 bond ends:
    the families are built although the fix's list is longer than the pair's): the face
    neighbours (at dmin) are excluded, the 216 face diagonals (sqrt 2 mm, within dmin + dhat =
    1.5 mm) repel with the barrier's energy each."""
    run = block(tmp_path, hfac=1.0002)
    assert "total # of bonds = 288" in run.log
    t = {k: v[-1] for k, v in run.thermo[-1].items()}
    assert t["f_c[6]"] == 216 and t["f_c[1]"] == 0
    E = 1.0 * barrier(math.sqrt(2) * 1e-3 - 1e-3, 0.5e-3)
    assert abs(t["f_c[4]"] / (216 * E) - 1.0) < 1e-12
    assert abs(t["f_c"] / (216 * E / 1e-9) - 1.0) < 1e-12


def test_broken_bonds_stay_excluded(tmp_path):
    """The same block stretched by 10% along x (critical stretch 2%): its x bonds break. Put
    back at rest, the former x partners are at dmin again, and still no pair (else the barrier
    would be infinite): the same contact as before the stretch, to the last bit."""
    run = block(tmp_path, hfac=1.0002, stretch=0.1)
    first, broken, back = (run.thermo[k] for k in (0, 1, 2))
    assert first["c_damage"][-1] == 0.0 and back["c_damage"][-1] > 0.3
    for key in ("f_c", "f_c[4]", "f_c[5]", "f_c[6]"):
        assert back[key][-1] == first[key][-1], key
    assert broken["f_c[6]"][-1] > 0


# ---- two blocks thrown at each other (examples/contact/in.two-blocks) ----

# Two 5^3 blocks at 20 m/s each under fix nve, only the barrier between them (kappa = 1e4 J/m^2,
# dmin = 1 mm, dhat = 0.5 mm), every step printed. No external force: the total momentum sum
# m v (m = rmass vfrac) stays zero to round-off, allowed 1e-10 of one block's (measured 1e-15);
# the blocks touch (25 point-point pairs active, smallest distance 1.134 mm > dmin), separate
# again and leave with their momenta reversed (measured 99.96% of it: the rest vibrates them).
def test_two_blocks_bounce_with_momentum_conserved(tmp_path):
    run = run_deck(TWO_BLOCKS, tmp_path, variables={"every": 1})
    t = run.thermo[-1]
    p0 = t["c_pxleft"][0]
    assert abs(p0 - 20.0 * 125 * 1e-9 * 1000.0) < 1e-12
    assert np.abs(t["c_px"]).max() < 1e-10 * p0, np.abs(t["c_px"]).max()
    assert t["f_contact[6]"].max() > 0
    assert t["f_contact[3]"].min() > 0.001
    assert t["f_contact[6]"][-1] == 0 and t["v_gap"][-1] > t["v_gap"][-2] > 0.0015
    assert -1.0 < t["c_pxleft"][-1] / p0 < -0.95


# ---- bad input ----

def test_empty_group_is_refused(tmp_path):
    run = particles_run(tmp_path, [[0.0, 0.0, 0.0]], [1e-9], check=False, group="empty")
    assert any("group empty holds no atom" in e for e in run.errors), run.errors


def test_short_ghost_cutoff_without_mesh(tmp_path):
    """Particles alone: the other particle of a pair must be a ghost atom, dmin + dhat + skin =
    0.012 here."""
    run = particles_run(tmp_path, [[0.0, 0.0, 0.0]], [1e-9], check=False, comm=0.0119)
    assert any("dmin + dhat + skin = 0.012" in e and "comm_modify cutoff 0.012" in e
               for e in run.errors), run.errors


def test_particles_within_dmin_are_an_error(tmp_path):
    run = particles_run(tmp_path, [[0.0, 0.0, 0.0], [0.0015, 0.0, 0.0]], [1e-9, 1e-9],
                        check=False)
    assert any("point-point pair of atoms 1 2 is 0.0015 apart" in e for e in run.errors), \
        run.errors
