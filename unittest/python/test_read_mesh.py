"""read_mesh and fix nosb/mesh (doc/read_mesh.rst): one peri particle per vertex of an OBJ file
with the right IDs, types, volumes, densities, groups and placement; mesh ids; reference
normals of flat, folded and curved meshes against hand computations; the same per-atom data on
1 and 2 ranks; the triangles through write_restart/read_restart and write_data/read_data;
deleted vertices; and an error naming the problem for every bad input."""
import math
import re

import pytest

from lammps_run import read_dump, run_deck

H = 0.25            # grid spacing of the test meshes
T = 0.01            # thickness
RHO = 1000.0        # density


def grid_obj(nx=5, ny=4, h=H, height=None, reverse=False, header="# test grid\n"):
    """nx x ny vertices at (i h, j h, height(i, j)) (vertex k = j nx + i is line k + 2 of the
    file), two counterclockwise triangles per cell (diagonal (i,j)-(i+1,j+1)), or clockwise ones
    with reverse=True."""
    lines = [header.rstrip("\n")] if header else []
    for j in range(ny):
        for i in range(nx):
            z = height(i, j) if height else 0.0
            lines.append(f"v {i * h!r} {j * h!r} {z!r}")
    for j in range(ny - 1):
        for i in range(nx - 1):
            a = j * nx + i + 1
            for face in ((a, a + 1, a + nx + 1), (a, a + nx + 1, a + nx)):
                lines.append("f " + " ".join(str(v) for v in (reversed(face) if reverse else face)))
    return "\n".join(lines) + "\n"


def grid_triangles(nx=5, ny=4):
    """The triangles of grid_obj as 0-based vertex indices in file orientation."""
    tris = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            a = j * nx + i
            tris += [(a, a + 1, a + nx + 1), (a, a + nx + 1, a + nx)]
    return tris


def deck(read, box="-1 2 -1 2 -1 1", boundary="p p f", before="", after="", cutoff=0.6,
         normals=True, run="run 0", dump=True):
    """A 2-type peri box, the read_mesh lines, the ghost cutoff (no pair style: the mesh alone),
    fix_modify NOSB_MESH normals yes, and a dump of everything per atom at run 0."""
    parts = [
        "units           si",
        "atom_style      peri",
        "atom_modify     map array",
        f"boundary        {boundary}",
        f"region          box block {box}",
        "create_box      2 box",
        before,
        read,
        after,
        f"comm_modify     cutoff {cutoff}" if cutoff else "",
        "fix_modify      NOSB_MESH normals yes" if normals else "",
    ]
    if dump:
        parts += [
            "compute         vf all property/atom vfrac",
            "dump            d all custom 1 dump.mesh id type x y z c_vf mass ix iy iz "
            "f_NOSB_MESH[*]",
            "dump_modify     d sort id format float %.17g",
        ]
    parts.append(run)
    return "\n".join(p for p in parts if p) + "\n"


def read_mesh_line(name="grid.obj", kind=2, t=T, rho=RHO, extra=""):
    return f"read_mesh       {name} type {kind} thickness {t} density {rho} {extra}".rstrip()


def frame(workdir):
    return read_dump(workdir / "dump.mesh")[0]


def normal(f, k):
    return [f[f"f_NOSB_MESH[{c}]"][k] for c in (4, 5, 6)]


def angle_weighted_normal(x, i, triangles):
    """Independent reference: sum over the triangles (i, a, b) at vertex i of the interior angle
    at i times the unit normal (x_a - x_i) x (x_b - x_i) / |...|, normalized."""
    n = [0.0, 0.0, 0.0]
    for tri in triangles:
        if i not in tri:
            continue
        c = tri.index(i)
        a, b = tri[(c + 1) % 3], tri[(c + 2) % 3]
        e1 = [x[a][d] - x[i][d] for d in range(3)]
        e2 = [x[b][d] - x[i][d] for d in range(3)]
        cr = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
              e1[0] * e2[1] - e1[1] * e2[0]]
        length = math.sqrt(sum(v * v for v in cr))
        angle = math.acos(sum(e1[d] * e2[d] for d in range(3)) /
                          math.sqrt(sum(v * v for v in e1) * sum(v * v for v in e2)))
        n = [n[d] + angle * cr[d] / length for d in range(3)]
    length = math.sqrt(sum(v * v for v in n))
    return [v / length for v in n]


# ----------------------------------------------------------------------------------------------
# atoms, volumes, densities, groups


def test_grid_atoms_ids_types_volumes_and_groups(tmp_path):
    # three atoms exist before: the mesh's IDs continue after the largest (vertex k -> 4 + k)
    before = "\n".join(f"create_atoms    1 single {x} 1.5 0.0" for x in (-0.5, 0.0, 0.5))
    run = run_deck(deck(read_mesh_line(extra="group sheet"), before=before,
                        after="variable nsheet equal count(sheet)\nprint \"SHEET ${nsheet}\""),
                   tmp_path, files={"grid.obj": grid_obj()})
    assert ("Read mesh grid.obj: 20 vertices, 24 triangles, area 0.75, thickness 0.01, "
            "mesh id 1") in run.log
    assert "SHEET 20" in run.log    # the group holds the 20 vertices, not the 3 other atoms
    f = frame(tmp_path)
    assert f["natoms"] == 23
    ids = [int(v) for v in f["id"]]
    assert ids == list(range(1, 24))
    tri = H * H / 2
    for k in range(20):
        row = 3 + k    # atom ID 4 + k
        i, j = k % 5, k // 5
        assert (f["x"][row], f["y"][row], f["z"][row]) == (i * H, j * H, 0.0)
        assert f["type"][row] == 2
        assert f["mass"][row] == RHO
        # triangles at a vertex of this grid: 6 inside, 3 on an edge, 2 or 1 at a corner
        on_x_edge, on_y_edge = i in (0, 4), j in (0, 3)
        if on_x_edge and on_y_edge:
            count = 2 if (i, j) in ((0, 0), (4, 3)) else 1
        elif on_x_edge or on_y_edge:
            count = 3
        else:
            count = 6
        assert f["c_vf"][row] == pytest.approx(T * count * tri / 3, rel=1e-14), k
        assert f["f_NOSB_MESH[3]"][row] == count
        assert f["f_NOSB_MESH[1]"][row] == 1 and f["f_NOSB_MESH[2]"][row] == T
    # the particles' volumes add up to the sheet's: area x thickness
    assert sum(f["c_vf"][3:]) == pytest.approx(0.75 * T, rel=1e-14)
    # atoms that are no vertices: mesh 0, thickness 0, no triangles, no normal
    for row in range(3):
        assert [f[f"f_NOSB_MESH[{c}]"][row] for c in range(1, 7)] == [0] * 6


def test_placement_scale_then_rotate_then_offset(tmp_path):
    # unit square; scale 2, then 120 degrees about (1,1,1) (x -> y -> z -> x), then offset
    square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
    run = run_deck(deck(read_mesh_line("square.obj", extra="scale 2 rotate 120 1 1 1 "
                                       "offset 0.5 0.25 -1"), box="-2 3 -2 3 -2 3",
                        boundary="f f f", cutoff=3.0),
                   tmp_path, files={"square.obj": square})
    assert "2 triangles, area 4," in run.log    # a quad is two triangles; area scales by 4
    f = frame(tmp_path)
    expected = [(0, 0, 0), (0, 2, 0), (0, 2, 2), (0, 0, 2)]    # (2x, 2y, 0) rotated: (0, 2x, 2y)
    for k, (x, y, z) in enumerate(expected):
        assert f["x"][k] == pytest.approx(x + 0.5, abs=1e-14)
        assert f["y"][k] == pytest.approx(y + 0.25, abs=1e-14)
        assert f["z"][k] == pytest.approx(z - 1.0, abs=1e-14)
        # the square's normal +z rotated with it: +x
        assert normal(f, k) == pytest.approx([1.0, 0.0, 0.0], abs=1e-14)
    # vertices 1 and 3 are in both triangles: half the area each; 2 and 4 a quarter
    assert [f["c_vf"][k] / T for k in range(4)] == pytest.approx([4 / 3, 2 / 3, 4 / 3, 2 / 3],
                                                                 rel=1e-14)


def test_two_meshes_get_ids_one_and_two(tmp_path):
    reads = "\n".join([read_mesh_line(extra="offset 0 0 0.5"),
                       read_mesh_line(kind=1, t=0.02, rho=500, extra="offset 0 0 -0.5")])
    run = run_deck(deck(reads), tmp_path, files={"grid.obj": grid_obj()})
    assert "mesh id 1" in run.log and "mesh id 2" in run.log
    f = frame(tmp_path)
    assert list(f["f_NOSB_MESH[1]"]) == [1] * 20 + [2] * 20
    assert list(f["f_NOSB_MESH[2]"]) == [T] * 20 + [0.02] * 20
    assert list(f["type"]) == [2] * 20 + [1] * 20
    assert list(f["mass"]) == [RHO] * 20 + [500] * 20
    assert list(f["id"]) == list(range(1, 41))


def test_type_label(tmp_path):
    # labelmap atom: read_mesh takes the label wherever it takes a type number
    reads = "\n".join(["labelmap        atom 1 cloth 2 body",
                       read_mesh_line(kind="body", extra="offset 0 0 0.5"),
                       read_mesh_line(kind="cloth", extra="offset 0 0 -0.5")])
    run = run_deck(deck(reads), tmp_path, files={"grid.obj": grid_obj()})
    assert "type 2" in run.log and "type 1" in run.log
    assert list(frame(tmp_path)["type"]) == [2] * 20 + [1] * 20


# ----------------------------------------------------------------------------------------------
# reference normals


@pytest.mark.parametrize("reverse,sign", [(False, 1.0), (True, -1.0)])
def test_flat_sheet_normals_follow_the_face_order(tmp_path, reverse, sign):
    run_deck(deck(read_mesh_line()), tmp_path, files={"grid.obj": grid_obj(reverse=reverse)})
    f = frame(tmp_path)
    for k in range(20):
        assert normal(f, k) == [0.0, 0.0, sign]


def test_normals_are_zero_until_asked_for(tmp_path):
    run_deck(deck(read_mesh_line(), normals=False), tmp_path, files={"grid.obj": grid_obj()})
    f = frame(tmp_path)
    assert all(normal(f, k) == [0.0, 0.0, 0.0] for k in range(20))


def test_folded_mesh_normals_by_hand(tmp_path):
    # a 3 x 2 strip folded along x = H: the cells at x < H lie flat, the cells at x > H rise at
    # 60 degrees (vertex 2 = (2H, 0, sqrt(3) H))
    rise = lambda i, j: (i - 1) * H * math.tan(math.pi / 3) if i > 1 else 0.0
    run_deck(deck(read_mesh_line()), tmp_path,
             files={"grid.obj": grid_obj(nx=3, ny=2, height=rise)})
    f = frame(tmp_path)
    # vertex 0 lies only in the flat part, vertex 2 only in the tilted one
    assert normal(f, 0) == pytest.approx([0.0, 0.0, 1.0], abs=1e-15)
    assert normal(f, 2) == pytest.approx([-math.sin(math.pi / 3), 0.0, 0.5], abs=1e-14)
    # vertex 1 = (H, 0, 0) on the fold is in the file's triangles (0 1 4), (1 2 5), (1 5 4):
    #   (1 4 0): flat, angle 90 deg at vertex 1, unit normal +z
    #   (1 2 5): tilted, e1 = (H, 0, sqrt3 H), e2 = (H, H, sqrt3 H): angle acos(2/sqrt5),
    #            unit normal e1 x e2 / |.| = (-sqrt3/2, 0, 1/2)
    #   (1 5 4): tilted, e1 = (H, H, sqrt3 H), e2 = (0, H, 0): angle acos(1/sqrt5), same normal
    # The tilted angles add up to 90 deg as well, so the normal bisects the fold: 30 degrees
    # from +z towards -x
    assert math.acos(2 / math.sqrt(5)) + math.acos(1 / math.sqrt(5)) == pytest.approx(
        math.pi / 2, abs=1e-15)
    assert normal(f, 1) == pytest.approx([-0.5, 0.0, math.sqrt(3) / 2], abs=1e-14)
    # and every vertex against the independent reference
    x = [(f["x"][k], f["y"][k], f["z"][k]) for k in range(6)]
    for k in range(6):
        assert normal(f, k) == pytest.approx(angle_weighted_normal(x, k, grid_triangles(3, 2)),
                                             abs=1e-14), k


def test_curved_mesh_normals_are_radial(tmp_path):
    # a quarter cylinder of radius R about the y axis: x = R sin(phi), z = R cos(phi). The mesh
    # around an interior vertex is symmetric under the half turn about its radius, so the
    # angle-weighted normal is exactly radial there (the boundary vertices are checked against
    # the reference)
    R, n = 1.0, 7
    phi = lambda i: (i - 3) * math.pi / 12
    lines = []
    for j in range(3):
        for i in range(n):
            lines.append(f"v {R * math.sin(phi(i))!r} {j * H!r} {R * math.cos(phi(i))!r}")
    for j in range(2):
        for i in range(n - 1):
            a = j * n + i + 1
            lines += [f"f {a} {a + 1} {a + n + 1}", f"f {a} {a + n + 1} {a + n}"]
    run_deck(deck(read_mesh_line("arc.obj"), box="-2 2 -1 2 -2 2", boundary="f f f", cutoff=0.7),
             tmp_path, files={"arc.obj": "\n".join(lines) + "\n"})
    f = frame(tmp_path)
    x = [(f["x"][k], f["y"][k], f["z"][k]) for k in range(3 * n)]
    tris = []
    for j in range(2):
        for i in range(n - 1):
            a = j * n + i
            tris += [(a, a + 1, a + n + 1), (a, a + n + 1, a + n)]
    for k in range(3 * n):
        assert normal(f, k) == pytest.approx(angle_weighted_normal(x, k, tris), abs=1e-14), k
    for i in range(1, n - 1):
        k = n + i    # middle row, interior
        assert normal(f, k) == pytest.approx([math.sin(phi(i)), 0.0, math.cos(phi(i))],
                                             abs=1e-14), k


# ----------------------------------------------------------------------------------------------
# parallel runs, periodic and shrink-wrapped boxes

COLUMNS = ["id", "type", "x", "y", "z", "c_vf", "mass", "ix", "iy", "iz"] + \
          [f"f_NOSB_MESH[{c}]" for c in range(1, 7)]


@pytest.mark.mpi
def test_one_and_two_ranks_give_the_same_per_atom_data(tmp_path):
    # two meshes, one rotated so that its triangles cross the sub-domain boundary obliquely
    reads = "\n".join([read_mesh_line(extra="offset -0.1 0.3 0.1"),
                       read_mesh_line(kind=1, t=0.02, extra="rotate 30 1 2 3 offset 0.2 0.1 -0.4")])
    frames, logs = [], []
    for np_ in (1, 2):
        run = run_deck(deck(reads), tmp_path / f"np{np_}", nprocs=np_,
                       files={"grid.obj": grid_obj(height=lambda i, j: 0.05 * i * j)})
        if np_ == 2:
            assert "with 2 MPI tasks" in run.log
        frames.append(frame(tmp_path / f"np{np_}"))
        logs.append([ln for ln in run.log.splitlines()
                     if ln.startswith(("Read mesh", "  atom IDs"))])
    for col in COLUMNS:
        assert list(frames[0][col]) == list(frames[1][col]), col
    assert len(logs[0]) == 4 and logs[0] == logs[1]
    assert any(frames[0]["f_NOSB_MESH[4]"] != 0.0)    # the normals are not all trivial


@pytest.mark.mpi
def test_periodic_box_wraps_vertices_and_normals_use_the_closest_image(tmp_path):
    # x periodic from 0 to 0.8: the grid (x 0..1) sticks out by one column, which wraps
    run = run_deck(deck(read_mesh_line(extra="offset 0 0.1 0"), box="0 0.8 0 1 -0.5 0.5",
                        boundary="p f f", cutoff=0.4),
                   tmp_path, nprocs=2, files={"grid.obj": grid_obj()})
    f = frame(tmp_path)
    for k in range(20):
        i = k % 5
        assert f["x"][k] == pytest.approx(i * H - (0.8 if i == 4 else 0.0), abs=1e-15)
        assert (f["ix"][k], f["iy"][k], f["iz"][k]) == (0, 0, 0)
        assert normal(f, k) == [0.0, 0.0, 1.0]
    assert f["natoms"] == 20 and "ERROR" not in run.log


def test_shrink_wrapped_box_grows_around_the_mesh(tmp_path):
    run = run_deck(deck(read_mesh_line(extra="offset 0 0 0.3"), box="0 0.5 0 0.5 0 0.1",
                        boundary="s s s") + "print \"BOX $(xhi) $(yhi) $(zlo)\"\n",
                   tmp_path, files={"grid.obj": grid_obj()})
    f = frame(tmp_path)
    assert f["natoms"] == 20
    assert max(f["x"]) == 1.0 and max(f["y"]) == 0.75 and min(f["z"]) == 0.3
    m = re.search(r"^BOX (\S+) (\S+) (\S+)$", run.log, re.M)
    assert float(m.group(1)) >= 1.0 and float(m.group(2)) >= 0.75
    assert float(m.group(3)) == pytest.approx(0.3, abs=1e-3)


# ----------------------------------------------------------------------------------------------
# restart files and data files


def triangles_of(data_file):
    """The Mesh Triangles section of a data file as a sorted list of (mesh, thickness, v1 v2 v3)
    with the vertices rotated to start at the smallest ID (the same triangle, orientation
    kept)."""
    lines = data_file.read_text().splitlines()
    header = [ln for ln in lines if ln.endswith("mesh triangles")]
    start = lines.index("Mesh Triangles") + 2
    out = []
    for ln in lines[start:]:
        if not ln.strip():
            break
        w = ln.split()
        v = [int(x) for x in w[3:6]]
        r = v.index(min(v))
        out.append((int(w[1]), float(w[2]), tuple(v[r:] + v[:r])))
    assert int(header[0].split()[0]) == len(out)
    return sorted(out)


TWO_MESHES = "\n".join([read_mesh_line(extra="offset 0 0 0.5"),
                        read_mesh_line(kind=1, t=0.02, rho=500,
                                       extra="rotate 90 1 0 0 offset 0 -0.5 -0.5")])


def test_restart_keeps_meshes_normals_and_triangles(tmp_path):
    first = tmp_path / "first"
    run_deck(deck(TWO_MESHES) + "write_restart   mesh.restart\nwrite_data      first.data\n",
             first, files={"grid.obj": grid_obj(height=lambda i, j: 0.02 * i * i)})
    second = tmp_path / "second"
    second.mkdir()
    (second / "mesh.restart").write_bytes((first / "mesh.restart").read_bytes())
    (second / "grid.obj").write_text(grid_obj())
    # the fix is re-specified (as any fix with restart data) before the first run; the normals
    # come from the file (fix_modify normals is not given here)
    run = run_deck("read_restart    mesh.restart\n"
                   "fix             NOSB_MESH all nosb/mesh\n"
                   "compute         vf all property/atom vfrac\n"
                   "dump            d all custom 1 dump.mesh id type x y z c_vf mass ix iy iz "
                   "f_NOSB_MESH[*]\n"
                   "dump_modify     d sort id format float %.17g\n"
                   "comm_modify     cutoff 0.6\n"
                   "run             0\n"
                   "write_data      second.data\n"
                   + read_mesh_line(extra="offset 0.1 0.1 0.1") + "\n"
                   "run             0\n", second)
    assert "Resetting peratom fix info from restart file" in run.log
    assert "mesh id 3" in run.log    # the restart file had meshes 1 and 2
    before, after = frame(first), read_dump(second / "dump.mesh")[0]
    for col in COLUMNS:
        assert list(before[col]) == list(after[col]), col
    assert triangles_of(first / "first.data") == triangles_of(second / "second.data")
    assert len(triangles_of(second / "second.data")) == 48


def test_read_mesh_after_read_restart_needs_a_run_first(tmp_path):
    first = tmp_path / "first"
    run_deck(deck(read_mesh_line(), dump=False) + "write_restart   mesh.restart\n", first,
             files={"grid.obj": grid_obj()})
    second = tmp_path / "second"
    second.mkdir()
    (second / "mesh.restart").write_bytes((first / "mesh.restart").read_bytes())
    (second / "grid.obj").write_text(grid_obj())
    run = run_deck("read_restart    mesh.restart\n" + read_mesh_line() + "\n", second,
                   check=False)
    assert not run.ok
    # the message says what to do, and (the mesh fix of the file was found) how to keep it
    assert any("run 0" in e and "fix NOSB_MESH all nosb/mesh" in e for e in run.errors), run.errors

    # a restart file with per-atom fix data (peri/nosb's bond families) but no mesh: the same
    # error, without the advice about the mesh fix
    nomesh = tmp_path / "nomesh"
    run_deck("\n".join(["units si", "atom_style peri", "atom_modify map array",
                        "region box block 0 1 0 1 0 1", "create_box 1 box",
                        "create_atoms 1 single 0.5 0.5 0.5", "pair_style peri/nosb",
                        "pair_coeff * * linear 1.0e9 0.6e9 0.1 0.5 0.25", "run 0",
                        "write_restart nomesh.restart", ""]), nomesh)
    (nomesh / "grid.obj").write_text(grid_obj())
    run = run_deck("read_restart    nomesh.restart\n" +
                   read_mesh_line(kind=1, extra="scale 0.1 offset 0.2 0.2 0.2") + "\n", nomesh,
                   check=False)
    assert any("run 0" in e for e in run.errors), run.errors
    assert not any("NOSB_MESH" in e for e in run.errors), run.errors


def test_write_data_and_read_data_round_trip(tmp_path):
    first = tmp_path / "first"
    run_deck(deck(TWO_MESHES) + "write_data      mesh.data\n", first,
             files={"grid.obj": grid_obj(height=lambda i, j: 0.02 * i * i)})
    second = tmp_path / "second"
    second.mkdir()
    (second / "mesh.data").write_text((first / "mesh.data").read_text())
    # the documented route: a box inside the data file's, the fix, read_data add append
    read = ('fix             NOSB_MESH all nosb/mesh\n'
            'read_data       mesh.data add append fix NOSB_MESH "mesh triangles" '
            '"Mesh Triangles"')
    run_deck(deck(read, box="-1 2 -1 2 -1 1"), second)
    before, after = frame(first), frame(second)
    # LAMMPS writes the data file's doubles (volumes, positions) with 16 significant digits:
    # they come back to within 1e-16 relative, and the normals computed from the positions
    # within a few 1e-16; everything else exactly
    for col in COLUMNS:
        if col in ("c_vf", "x", "y", "z") or col in [f"f_NOSB_MESH[{c}]" for c in (4, 5, 6)]:
            assert list(after[col]) == pytest.approx(list(before[col]), rel=1e-15, abs=1e-15), col
        else:
            assert list(before[col]) == list(after[col]), col
    run_deck(deck(read, box="-1 2 -1 2 -1 1", run="run 0\nwrite_data mesh2.data"),
             tmp_path / "third", files={"mesh.data": (first / "mesh.data").read_text()})
    assert triangles_of(first / "mesh.data") == triangles_of(tmp_path / "third" / "mesh2.data")


def test_read_data_appends_meshes_after_those_of_the_deck(tmp_path):
    first = tmp_path / "first"
    run_deck(deck(TWO_MESHES) + "write_data      mesh.data\n", first,
             files={"grid.obj": grid_obj()})
    read = "\n".join([read_mesh_line(extra="offset 0 0 0.8"),
                      'read_data       mesh.data add append fix NOSB_MESH "mesh triangles" '
                      '"Mesh Triangles"',
                      read_mesh_line(extra="offset 0 0 -0.8")])
    run = run_deck(deck(read, run="run 0\nwrite_data out.data"), tmp_path / "second",
                   files={"grid.obj": grid_obj(), "mesh.data": (first / "mesh.data").read_text()})
    assert "mesh id 1" in run.log and "mesh id 4" in run.log
    f = frame(tmp_path / "second")
    assert list(f["f_NOSB_MESH[1]"]) == [1] * 20 + [2] * 20 + [3] * 20 + [4] * 20
    tris = triangles_of(tmp_path / "second" / "out.data")
    # the data file's triangles, with IDs after the deck's 20 atoms and mesh ids after its 1
    old = triangles_of(first / "mesh.data")
    shifted = sorted((m + 1, t, tuple(v + 20 for v in vs)) for m, t, vs in old)
    assert [tr for tr in tris if tr[0] in (2, 3)] == shifted


def test_read_data_needs_the_header_keyword(tmp_path):
    first = tmp_path / "first"
    run_deck(deck(read_mesh_line(), dump=False) + "write_data      mesh.data\n", first,
             files={"grid.obj": grid_obj()})
    data = (first / "mesh.data").read_text()
    read = ('fix             NOSB_MESH all nosb/mesh\n'
            'read_data       mesh.data add append fix NOSB_MESH NULL "Mesh Triangles"')
    # the header line is there, but nothing reads it: LAMMPS names it
    run = run_deck(deck(read, dump=False), tmp_path / "second", check=False,
                   files={"mesh.data": data})
    assert any("24 mesh triangles" in e for e in run.errors), run.errors
    # without the header line the fix cannot know the section's length: it says how to read it
    run = run_deck(deck(read, dump=False), tmp_path / "third", check=False,
                   files={"mesh.data": data.replace("24 mesh triangles\n", "")})
    assert any("header line 'N mesh triangles'" in e and '"mesh triangles"' in e
               for e in run.errors), run.errors


# ----------------------------------------------------------------------------------------------
# deleted atoms


def test_deleted_vertex_drops_its_triangles(tmp_path):
    # delete the interior vertex (1,1) (atom 7): its six triangles go, the rest stays a mesh
    after = ("group           gone id 7\n"
             "delete_atoms    group gone compress no")
    run = run_deck(deck(read_mesh_line(), after=after, run="run 0\nwrite_data out.data"),
                   tmp_path, files={"grid.obj": grid_obj()})
    assert any("6 mesh triangles lost a vertex" in w and "18 remain" in w
               for w in run.warnings), run.warnings
    f = frame(tmp_path)
    ntri = dict(zip([int(i) for i in f["id"]], f["f_NOSB_MESH[3]"]))
    assert 7 not in ntri
    # triangles left at the vertices around (1,1): (0,0) 2 -> 0, (1,0) 3 -> 1, (0,1) 3 -> 1,
    # (2,1), (1,2), (2,2) 6 -> 4; (2,0) and (0,2) keep their 3
    assert ntri[1] == 0 and ntri[2] == 1 and ntri[6] == 1
    assert ntri[8] == 4 and ntri[12] == 4 and ntri[13] == 4
    assert ntri[3] == 3 and ntri[11] == 3
    assert sum(f["f_NOSB_MESH[3]"]) == 3 * 18
    assert len(triangles_of(tmp_path / "out.data")) == 18
    # still a mesh atom, without triangles and so without a normal
    assert f["f_NOSB_MESH[1]"][0] == 1 and normal(f, 0) == [0.0, 0.0, 0.0]
    assert all(normal(f, k) == [0.0, 0.0, 1.0] for k in range(1, 19))


def test_reused_id_of_a_deleted_vertex_is_no_vertex(tmp_path):
    # the corner (4,3) has the largest ID (20): deleted, create_atoms gives 20 to a new atom,
    # which is no vertex of the mesh; the two triangles at the corner are dropped
    after = ("group           gone id 20\n"
             "delete_atoms    group gone compress no\n"
             "create_atoms    1 single 1.5 1.5 0.0")
    run = run_deck(deck(read_mesh_line(), after=after), tmp_path,
                   files={"grid.obj": grid_obj()})
    assert any("2 mesh triangles lost a vertex" in w for w in run.warnings), run.warnings
    f = frame(tmp_path)
    assert f["id"][19] == 20 and f["x"][19] == 1.5
    assert [f[f"f_NOSB_MESH[{c}]"][19] for c in range(1, 7)] == [0] * 6
    # (3,3) and (4,2) lose one each, (3,2) loses both of its triangles with the corner
    assert (f["f_NOSB_MESH[3]"][18], f["f_NOSB_MESH[3]"][14], f["f_NOSB_MESH[3]"][13]) == \
        (2, 2, 4)


def test_renumbered_atoms_are_an_error(tmp_path):
    after = ("group           gone id 7\n"
             "delete_atoms    group gone compress yes")
    run = run_deck(deck(read_mesh_line(), after=after), tmp_path, check=False,
                   files={"grid.obj": grid_obj()})
    assert any("atom IDs changed" in e and "compress no" in e for e in run.errors), run.errors


# ----------------------------------------------------------------------------------------------
# errors

GOOD = grid_obj()
DISK17 = "v 0 0 0\n" + "".join(
    f"v {0.3 * math.cos(2 * math.pi * k / 17)!r} {0.3 * math.sin(2 * math.pi * k / 17)!r} 0\n"
    for k in range(17)) + "".join(f"f 1 {2 + k} {2 + (k + 1) % 17}\n" for k in range(17))
SQUARE = "v 0 0 0\nv 0.5 0 0\nv 0.5 0.5 0\nv 0 0.5 0\n"

# (case, deck arguments, mesh file text, parts of the ERROR line)
BAD = [
    ("no-box", dict(read=read_mesh_line(), before=None), GOOD,
     ["read_mesh", "before the simulation box"]),
    ("atom-style", dict(atom_style="atomic"), GOOD, ["read_mesh", "atom_style peri"]),
    ("atom-map", dict(atom_map=""), GOOD, ["read_mesh", "atom map", "atom_modify map array"]),
    ("no-file", dict(read=read_mesh_line("missing.obj")), GOOD,
     ["read_mesh", "cannot open", "missing.obj"]),
    ("type-range", dict(read=read_mesh_line(kind=3)), GOOD, ["read_mesh", "type", "1 to 2", "'3'"]),
    ("type-label-unknown", dict(read=read_mesh_line(kind="cloth")), GOOD,
     ["read_mesh", "type", "type label", "'cloth'"]),
    ("thickness-zero", dict(read=read_mesh_line(t=0)), GOOD, ["read_mesh", "thickness", "> 0"]),
    ("density-text", dict(read=read_mesh_line(rho="heavy")), GOOD,
     ["read_mesh", "density", "'heavy'"]),
    ("missing-density", dict(read="read_mesh grid.obj type 1 thickness 0.01"), GOOD,
     ["read_mesh", "density", "required"]),
    ("scale-negative", dict(read=read_mesh_line(extra="scale -1")), GOOD,
     ["read_mesh", "scale", "'-1'"]),
    ("rotate-axis-zero", dict(read=read_mesh_line(extra="rotate 30 0 0 0")), GOOD,
     ["read_mesh", "rotate axis", "zero"]),
    ("offset-short", dict(read=read_mesh_line(extra="offset 1 2")), GOOD,
     ["read_mesh", "offset", "3 values"]),
    ("unknown-keyword", dict(read=read_mesh_line(extra="shift 1 2 3")), GOOD,
     ["read_mesh", "unknown keyword", "'shift'"]),
    ("malformed-vertex", {}, "# x\nv 0 0 0\nv 1 0\n", ["grid.obj line 3", "three coordinates"]),
    ("malformed-face", {}, SQUARE + "f 1 2 x\n", ["grid.obj line 5", "'x'"]),
    ("index-range", {}, SQUARE + "f 1 2 3\nf 1 3 5\n", ["grid.obj line 6", "index 5",
                                                        "out of range"]),
    ("zero-area", {}, SQUARE + "v 1 0 0\nf 1 2 3\nf 1 3 4\nf 1 2 5\n",
     ["grid.obj line 8", "zero area"]),
    ("unused-vertex", {}, SQUARE + "v 1 1 1\nf 1 2 3\nf 1 3 4\n",
     ["grid.obj line 5", "vertex 5 is used by no face"]),
    ("non-manifold", {}, SQUARE + "v 0.25 0.25 0.4\nf 1 2 3\nf 1 3 4\nf 3 1 5\n",
     ["grid.obj line 8", "vertices 1 and 3", "more than two triangles", "not a manifold"]),
    ("orientation", {}, SQUARE + "f 1 2 3\nf 1 4 3\n",
     ["grid.obj line 6", "face of line 5", "inconsistent orientation"]),
    ("too-many-triangles", {}, DISK17,
     ["grid.obj line 1", "vertex 1 is in 17 triangles", "16"]),
    ("outside-box", dict(read=read_mesh_line(extra="offset 0 0 1.5")), GOOD,
     ["read_mesh", "vertex 1 of grid.obj", "line 2", "outside the box in z", "offset"]),
    ("outside-box-upper-face", dict(read=read_mesh_line(extra="offset 0 0 1")), GOOD,
     ["read_mesh", "outside the box in z", "upper face excluded"]),
    ("fix-arguments", dict(after="fix NOSB_MESH all nosb/mesh 1"), GOOD,
     ["fix nosb/mesh", "no arguments", "'1'"]),
    ("fix-group", dict(after="group g id 1\nfix M g nosb/mesh"), GOOD,
     ["fix nosb/mesh", "group all", "g"]),
    ("second-fix", dict(after="fix M all nosb/mesh"), GOOD,
     ["fix nosb/mesh", "NOSB_MESH", "exists already"]),
    ("fix-modify", dict(after="fix_modify NOSB_MESH normals maybe"), GOOD,
     ["boolean", "'maybe'"]),
]


def error_deck(read=None, atom_style="peri", atom_map="atom_modify     map array", before="",
               after="", cutoff=0.6):
    read = read if read is not None else read_mesh_line(extra="offset 0 0 0.5")
    box = ["region          box block -1 2 -1 2 -1 1", "create_box      2 box"]
    parts = ["units           si", f"atom_style      {atom_style}", atom_map,
             "boundary        p p f"]
    if before is None:    # read_mesh before the box
        parts += [read] + box
    else:
        parts += box + ([] if atom_style == "peri" else ["mass * 1.0"]) + [read]
    parts += [after, f"comm_modify     cutoff {cutoff}", "fix_modify      NOSB_MESH normals yes",
              "run             0"]
    return "\n".join(p for p in parts if p) + "\n"


@pytest.mark.parametrize("case,args,text,expected", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_an_error_naming_it(tmp_path, case, args, text, expected):
    run = run_deck(error_deck(**args), tmp_path, files={"grid.obj": text}, check=False)
    assert run.returncode > 0 or run.errors, case
    assert run.returncode >= 0, f"{case}: crashed ({run.returncode})"
    assert len(run.errors) >= 1, run.describe()
    line = run.errors[0].lower()
    for part in expected:
        assert part.lower() in line, f"{case}: {part!r} not in {run.errors[0]!r}"


@pytest.mark.mpi
def test_ghost_cutoff_shorter_than_the_edges_is_an_error(tmp_path):
    # the grid's edges reach 0.25 across the sub-domain boundary, farther than the ghost cutoff
    # 0.2: on 2 ranks a vertex's triangle partner on the other rank is not a ghost; every rank
    # stops with the same message
    run = run_deck(error_deck(cutoff=0.2), tmp_path, nprocs=2, files={"grid.obj": GOOD},
                   check=False)
    assert run.returncode > 0
    assert any("neither an owned nor a ghost" in e and "comm_modify cutoff" in e
               and "ghost cutoff 0.2" in e for e in run.errors), run.describe()
    ok = run_deck(error_deck(cutoff=0.3), tmp_path / "ok", nprocs=2, files={"grid.obj": GOOD})
    assert ok.ok


@pytest.mark.mpi
def test_triangles_travel_with_their_atoms(tmp_path):
    # the sheet drifts by 1.5 box units through periodic x on 2 ranks, with atom sorting: its
    # atoms change ranks and memory slots; afterwards the triangles are the same and the
    # normals (computed only after the drift, from ghosts filled at the last neighbor build)
    # are those of the sheet
    drift = "\n".join([
        "atom_modify     sort 7 0.3",
        "velocity        all set 1.0 0.2 0.0",
        "fix             1 all nve",
        "timestep        0.01",
        "write_data      before.data",
        "run             150",
        "fix_modify      NOSB_MESH normals yes",
    ])
    run = run_deck(deck(read_mesh_line(extra="offset 0 0 0.5"), after=drift, normals=False,
                        run="run 0\nwrite_data after.data"),
                   tmp_path, nprocs=2, files={"grid.obj": grid_obj()})
    assert "with 2 MPI tasks" in run.log
    f = frame(tmp_path)
    assert f["step"] == 150
    assert max(abs(v) for v in f["ix"]) >= 1    # the atoms did cross the periodic box
    assert triangles_of(tmp_path / "before.data") == triangles_of(tmp_path / "after.data")
    assert all(normal(f, k) == [0.0, 0.0, 1.0] for k in range(20))
    assert list(f["f_NOSB_MESH[3]"]) == [2, 3, 3, 3, 1, 3, 6, 6, 6, 3, 3, 6, 6, 6, 3, 1, 3, 3,
                                         3, 2]


@pytest.mark.mpi
def test_triclinic_periodic_box(tmp_path):
    # a tilted periodic box: the upper rows of the sheet leave it through y and come back
    # shifted by the tilt xy; the normals still connect the closest images
    frames = []
    for np_ in (1, 2):
        run_deck(deck(read_mesh_line(extra="offset 1.5 1.6 0.5"),
                      box="-1 2 -1 2 -1 1 0.5 0.2 0.1").replace("block", "prism"),
                 tmp_path / f"np{np_}", nprocs=np_, files={"grid.obj": grid_obj()})
        frames.append(frame(tmp_path / f"np{np_}"))
    f = frames[0]
    for k in range(20):
        i, j = k % 5, k // 5
        x, y = 1.5 + i * H, 1.6 + j * H
        if y >= 2.0:    # through the upper y face: back by the box height and the tilt xy
            x, y = x - 0.5, y - 3.0
        assert (f["x"][k], f["y"][k]) == pytest.approx((x, y), abs=1e-14), k
        assert normal(f, k) == pytest.approx([0.0, 0.0, 1.0], abs=1e-15), k
    for col in COLUMNS:
        assert list(frames[0][col]) == list(frames[1][col]), col
