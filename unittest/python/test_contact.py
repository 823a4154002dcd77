"""fix nosb/contact (barrier contact between mesh primitives) through LAMMPS: its energy is the sum
of the barrier over the non-adjacent point-triangle and edge-edge pairs, computed here
independently; its forces are minus the energy's gradient; it vanishes beyond dmin + dhat; a
cloth dropped onto another one under fix nve never comes within dmin of it (checked by
tools/mesh_gaps.py); 1 and 2 ranks agree; bad input is refused with a clear message."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from lammps_run import run_deck

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools"))
import make_sheet  # noqa: E402
import mesh_gaps  # noqa: E402

CLOTHS = Path(__file__).parent / "decks" / "contact_cloths.lmp"
DROP = Path(__file__).parent / "decks" / "contact_drop.lmp"
DHAT, DMIN, KAPPA = 0.005, 0.002, 10.0
OFFSET = (0.0037, 0.0051)


def cloth(workdir, size=0.1, a=0.02, name="cloth.obj"):
    vertices, faces = make_sheet.rectangle(size, size, a, "alternate", 0.0, 1)
    path = Path(workdir) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    make_sheet.write_obj(path, vertices, faces, ["cloth for test_contact.py"])
    return path, np.array(vertices, dtype=float), [tuple(t) for t in faces]


def two_cloths(workdir, gap, nprocs=1, more=None, **extra):
    mesh, _, _ = cloth(workdir)
    files = {}
    variables = {"mesh": mesh, "gap": gap, "dhat": DHAT, "dmin": DMIN, "kappa": KAPPA, **extra}
    if more:
        files["more"] = more
        variables["more"] = "more"
    return run_deck(CLOTHS, workdir, nprocs=nprocs, variables=variables, files=files)


def dump_frames(path):
    """Frames of a dump custom file with columns id x y z fx fy fz c_vol, sorted by id."""
    frames = []
    lines = Path(path).read_text().splitlines()
    k = 0
    while k < len(lines):
        if lines[k].startswith("ITEM: NUMBER OF ATOMS"):
            n = int(lines[k + 1])
        if lines[k].startswith("ITEM: ATOMS"):
            table = np.array([[float(v) for v in ln.split()] for ln in lines[k + 1:k + 1 + n]])
            frames.append(table[np.argsort(table[:, 0])])
            k += n
        k += 1
    return frames


# ---- forces against central differences of the energy ----

def displaced_runs(frame, ids, h):
    """LAMMPS commands that move each atom of ids (1-based IDs; frame sorted by id, columns
    id x y z ...) by +h and -h along x, y, z in turn, with a `run 0` after each move and the atom
    put back after each direction; and the (id, direction, sign) of each run, in order."""
    commands, order = [], []
    for i in ids:
        for k, name in enumerate("xyz"):
            for sign in (1, -1):
                commands += [f"set atom {i} {name} {frame[i - 1, 1 + k] + sign * h!r}", "run 0"]
                order.append((i, k, sign))
            commands.append(f"set atom {i} {name} {frame[i - 1, 1 + k]!r}")
    return commands, order


def gradient_error(frame, ids, order, energies, h):
    """The largest |-dE/dx (central differences of the runs' energies) - V f| over ids and
    directions, relative to the largest V f of the frame (columns 4-6 f, 7 V)."""
    assert len(energies) == len(order)
    E = dict(zip(order, energies))
    V = frame[:, 7]
    scale = np.abs(frame[:, 4:7] * V[:, None]).max()
    worst = 0.0
    for i in ids:
        for k in range(3):
            fd = -(E[(i, k, 1)] - E[(i, k, -1)]) / (2 * h)
            worst = max(worst, abs(fd - frame[i - 1, 4 + k] * V[i - 1]) / scale)
    return worst


# ---- an independent sum of the barrier (doc/fix_nosb_contact.rst, src/core/contact) ----

def barrier(g, dhat):
    return 0.0 if g >= dhat else -(g - dhat) ** 2 * math.log(g / dhat)


def mesh_primitives(faces, offset=0):
    tris = [tuple(v + offset for v in t) for t in faces]
    edges = sorted({tuple(sorted((t[k], t[(k + 1) % 3]))) for t in tris for k in range(3)})
    return tris, edges


def barrier_sum(x, x0, tris, edges, vol):
    """Pair energies kappa b(d - dmin) (edge-edge times IPC's mollifier from the rest shape x0)
    over every point-triangle and edge-edge pair sharing no vertex: (sum of E, sum of the
    vertices' shares E / (4 V_k), active point-triangle pairs, active edge-edge pairs)."""
    reach = DMIN + DHAT
    total = density = 0.0
    npt = nee = 0
    for t in tris:
        a, b, c = (x[t[0]], x[t[1]], x[t[2]])
        lo, hi = np.minimum(np.minimum(a, b), c) - reach, np.maximum(np.maximum(a, b), c) + reach
        for p in range(len(x)):
            if p in t or np.any(x[p] < lo) or np.any(x[p] > hi):
                continue
            d = float(mesh_gaps.point_triangle_distance(x[p], a, b, c)[0])
            if d >= reach:
                continue
            E = KAPPA * barrier(d - DMIN, DHAT)
            npt += 1
            total += E
            density += sum(0.25 * E / vol[k] for k in (p,) + t)
    for i, e in enumerate(edges):
        for f in edges[i + 1:]:
            if set(e) & set(f):
                continue
            d = float(mesh_gaps.segment_segment_distance(x[e[0]], x[e[1]], x[f[0]], x[f[1]])[0])
            if d >= reach:
                continue
            u, v = x[e[1]] - x[e[0]], x[f[1]] - x[f[0]]
            U, V = x0[e[1]] - x0[e[0]], x0[f[1]] - x0[f[0]]
            eps = 1e-3 * U.dot(U) * V.dot(V)
            cr = np.cross(u, v)
            c = cr.dot(cr)
            moll = 1.0 if c >= eps else (2.0 - c / eps) * c / eps
            E = moll * KAPPA * barrier(d - DMIN, DHAT)
            nee += 1
            total += E
            density += sum(0.25 * E / vol[k] for k in e + f)
    return total, density, npt, nee


# The energy is the barrier summed over the pairs: the two cloths (6 x 6 vertices, 2 cm right
# triangles, the upper one shifted sideways by (3.7, 5.1) mm so that no vertex sits on a feature
# of the other) 6 mm apart with dmin = 2 mm and dhat = 5 mm. The sum here uses the closest points
# directly (mesh_gaps), the fix the smooth squared-distance pieces: agreement to 1e-9 relative
# (measured 2e-15 for the energy, 1e-14 for the sum of densities); the active pair counts agree exactly (76 point-triangle, 251 edge-edge; the
# in-plane pairs of a flat cloth are 1.4 cm apart, beyond dmin + dhat).
def test_energy_is_the_sum_over_pairs(tmp_path):
    gap = 0.006
    run = two_cloths(tmp_path, gap)
    t = {k: v[-1] for k, v in run.thermo[-1].items()}
    frame = dump_frames(tmp_path / "dump.contact")[0]
    x, vol = frame[:, 1:4], frame[:, 7]
    _, vertices, faces = cloth(tmp_path)
    n = len(vertices)
    x0 = np.vstack([vertices, vertices + np.array([OFFSET[0], OFFSET[1], gap])])
    tris, edges = mesh_primitives(faces)
    tris2, edges2 = mesh_primitives(faces, n)
    total, density, npt, nee = barrier_sum(x, x0, tris + tris2, edges + edges2, vol)
    assert npt > 0 and nee > 0
    assert (t["f_c[1]"], t["f_c[2]"]) == (npt, nee)
    assert abs(t["f_c[4]"] / total - 1.0) < 1e-9, (t["f_c[4]"], total)
    assert abs(t["f_c"] / density - 1.0) < 1e-9, (t["f_c"], density)
    assert abs(t["f_c[3]"] - gap) < 1e-12
    # the forces push the cloths apart, equal and opposite (sum of V_i f_i = 0)
    F = frame[:, 4:7] * vol[:, None]
    lower, upper = F[:n].sum(axis=0), F[n:].sum(axis=0)
    assert upper[2] > 0 and lower[2] < 0
    assert np.abs(lower + upper).max() < 1e-12 * np.abs(upper).max()


def test_nothing_beyond_dmin_plus_dhat(tmp_path):
    """Just beyond dmin + dhat the energy and every force are exactly zero; just inside they
    are not."""
    out = two_cloths(tmp_path / "out", DMIN + DHAT + 1e-9)
    t = {k: v[-1] for k, v in out.thermo[-1].items()}
    assert t["f_c"] == 0.0 and t["f_c[4]"] == 0.0 and t["f_c[1]"] == 0 and t["f_c[2]"] == 0
    assert t["f_c[5]"] > 0    # the pairs are candidates all the same
    assert np.all(dump_frames(tmp_path / "out" / "dump.contact")[0][:, 4:7] == 0.0)
    inside = two_cloths(tmp_path / "in", DMIN + DHAT - 1e-4)
    assert inside.thermo[-1]["f_c[4]"][-1] > 0.0


# Forces are minus the gradient of the energy: V_i f_i = -dE/dx_i (E = f_c[4], the energy in
# energy units; f a force density), by central differences with h = 1e-8 m at a few atoms and
# all three directions, the cloths 4 mm apart (deep in the barrier's range). Round-off in E
# (~1e-16 E / h) and the h^2 truncation are both ~1e-9 of the largest force; allowed 1e-6 of it
# (measured 1.8e-10). Atoms with in-plane forces from edge-edge pairs, both cloths, a corner.
def test_forces_are_minus_the_energy_gradient(tmp_path):
    gap, h = 0.004, 1e-8
    base = two_cloths(tmp_path / "base", gap)
    frame = dump_frames(tmp_path / "base" / "dump.contact")[0]
    ids = [8, 10, 1, 44, 51]
    commands, order = displaced_runs(frame, ids, h)
    run = two_cloths(tmp_path / "fd", gap, more="\n".join(commands) + "\n")
    energies = [t["f_c[4]"][-1] for t in run.thermo[1:]]
    worst = gradient_error(frame, ids, order, energies, h)
    assert worst < 1e-6, worst
    assert base.thermo[-1]["f_c[4]"][-1] > 0


@pytest.mark.mpi
def test_two_ranks_agree(tmp_path):
    """Each pair is evaluated with the same vertex order on every rank holding a vertex of it,
    and a vertex sums its pairs in the order of their IDs: energy and forces agree to 1e-10
    relative (measured: energies to 1.4e-14, forces to the last bit)."""
    one = two_cloths(tmp_path / "one", 0.0045)
    two = two_cloths(tmp_path / "two", 0.0045, nprocs=2)
    t1 = {k: v[-1] for k, v in one.thermo[-1].items()}
    t2 = {k: v[-1] for k, v in two.thermo[-1].items()}
    for key in ("f_c", "f_c[4]"):
        assert abs(t2[key] / t1[key] - 1.0) < 1e-10, (key, t1[key], t2[key])
    for key in ("f_c[1]", "f_c[2]", "f_c[3]", "f_c[5]"):
        assert t1[key] == t2[key], key
    f1 = dump_frames(tmp_path / "one" / "dump.contact")[0][:, 4:7]
    f2 = dump_frames(tmp_path / "two" / "dump.contact")[0][:, 4:7]
    assert np.abs(f1 - f2).max() <= 1e-10 * np.abs(f1).max()


# A 10 cm cloth (1 cm right triangles) dropped from 8 mm onto a held copy under fix nve
# (dt = 10 us, 4500 steps: the fall, the impact at 0.03 s and the bounce), dmin = 1 mm,
# dhat = 2 mm. The independent checker measures every non-adjacent point-triangle and edge-edge
# distance of both cloths in the dumps (every 20 steps) and finds none below dmin; the fix's own
# smallest candidate distance agrees with it wherever the layers are within the checker's
# radius. Smallest distance reached (fix, every step): 2.36 mm at kappa = 1, 1.71 mm at 0.1,
# 1.001 mm at 0.01 (the barrier nearly pierced: below that kappa the run stops with the
# barrier's error). Explicit steps carry no guarantee (doc: Restrictions).
@pytest.mark.parametrize("kappa", [1.0, 0.1])
def test_dropped_cloth_stays_above_dmin(tmp_path, kappa):
    _, vertices, faces = cloth(tmp_path, a=0.01)
    n = len(vertices)
    both = np.vstack([vertices, vertices])
    faces2 = faces + [tuple(v + n for v in t) for t in faces]
    run = run_deck(DROP, tmp_path, variables={
        "mesh": tmp_path / "cloth.obj", "kappa": kappa, "steps": 4500, "every": 20})
    checker = mesh_gaps.MeshGaps(both, faces2, 1, 1)
    smallest = np.inf
    fix_min = dict(zip(run.thermo[-1]["Step"], run.thermo[-1]["f_c[3]"]))
    compared = 0
    for frame in mesh_gaps.read_dump(tmp_path / "dump.drop"):
        x = mesh_gaps.mesh_positions(frame, 2 * n)
        gaps = checker.check(x, radius=0.006, dmin=0.001)
        assert not gaps.fails, (frame.step, gaps)
        d = min(g.distance for g in (gaps.point_triangle, gaps.edge_edge) if g is not None) \
            if (gaps.point_triangle or gaps.edge_edge) else np.inf
        smallest = min(smallest, d)
        if d < 0.003:      # within dmin + dhat: the fix's candidates hold the closest pair
            assert abs(fix_min[frame.step] - d) < 1e-9, (frame.step, fix_min[frame.step], d)
            compared += 1
    assert compared > 0    # the cloth did reach the barrier
    assert smallest > 0.001
    # it bounced: the lowest vertex of the upper cloth rises again at the end
    zmin = run.thermo[-1]["c_zmin"]
    assert zmin[-1] > zmin.min()
    # under fix nve there is no implicit step to warn about
    assert not [w for w in run.warnings if "collision-free" in w], run.warnings


# Under fix sissm (backward Euler, 0.2 ms steps) the barrier is part of the implicit step and
# every move is limited by continuous collision detection (test_contact_ccd.py has the steps that
# need it): the same drop lands and leaves again without an error, lists are built again after
# steps that moved atoms skin/8 (LAMMPS checks only between steps), and the layers stay apart.
def test_implicit_drop_under_fix_sissm(tmp_path):
    cloth(tmp_path, a=0.01)
    run = run_deck(DROP, tmp_path, variables={
        "mesh": tmp_path / "cloth.obj", "kappa": 0.1, "steps": 220, "every": 1, "dt": 2e-4,
        "integrator": "sissm"})
    t = run.thermo[-1]
    assert t["f_c[1]"].max() > 0                      # it reached the barrier
    assert t["f_c[3]"].min() > 0.001
    assert t["c_zmin"][-1] > t["c_zmin"].min()        # and left it
    builds = int(run.log.split("Neighbor list builds =")[1].split()[0])
    assert builds >= 5, builds
    # collision-free by default: nothing to warn about
    assert not [w for w in run.warnings if "collision-free" in w], run.warnings


# ---- bad input ----

@pytest.mark.parametrize("args, message", [
    ("kappa 1", "keyword dhat is required"),
    ("dhat 0.005", "keyword kappa is required"),
    ("dhat -0.005 kappa 1", "dhat must be > 0"),
    ("dhat 0.005 dmin -1 kappa 1", "dmin must be >= 0"),
    ("dhat 0.005 kappa 0", "kappa must be > 0"),
    ("dhat 0.005 kappa auto", "kappa auto needs fix sissm"),
    ("dhat 0.005 kappa 1 ccd maybe", "Expected boolean parameter instead of 'maybe'"),
    ("dhat 0.005 kappa 1 stiff 3", "unknown keyword 'stiff'"),
    ("dhat 0.005 kappa", "fix nosb/contact kappa"),
])
def test_bad_arguments(tmp_path, args, message):
    mesh, _, _ = cloth(tmp_path)
    run = run_deck(CLOTHS, tmp_path, check=False,
                   variables={"mesh": mesh, "custom": "yes", "args": args})
    assert any(message in e for e in run.errors), (args, run.errors)


def test_short_ghost_cutoff_is_refused(tmp_path):
    """The other vertices of a pair must be ghost atoms: dmin + dhat + skin + 2.5 x 1.5 x the
    longest edge (2 cm x sqrt 2) = 0.118066 here."""
    mesh, _, _ = cloth(tmp_path)
    run = run_deck(CLOTHS, tmp_path, check=False, variables={"mesh": mesh, "comm": 0.118})
    assert any("comm_modify cutoff 0.118066" in e for e in run.errors), run.errors
    ok = run_deck(CLOTHS, tmp_path / "ok", variables={"mesh": mesh, "comm": 0.1181})
    assert ok.ok


def test_barrier_crossed_is_an_error(tmp_path):
    """Cloths placed within dmin of each other: the barrier is infinite there; the error names
    the pair."""
    mesh, _, _ = cloth(tmp_path)
    run = run_deck(CLOTHS, tmp_path, check=False, variables={"mesh": mesh, "gap": 0.0015})
    assert any("not more than dmin" in e and "barrier is infinite" in e for e in run.errors), \
        run.errors
