"""dump nosb/mesh (doc/dump_nosb_mesh.rst): a membrane run writes .vtp/.vtu frames with a .pvd
series and .obj frames; an independent reader (Debian's python3-meshio for .vtu and .obj, the
standard library's XML parser for .vtp and .pvd) reads back the positions, triangles and fields
that `dump custom` of the same steps prints; 1 and 2 ranks write identical files; vertices
selected by dump_modify thresh; a file without '*' holds the last frame; write_dump writes the
same frame; every bad input gives an error naming the dump and the value."""
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from lammps_run import read_dump, run_deck
from test_read_mesh import grid_obj as read_mesh_grid
from test_read_mesh import grid_triangles as grid_indices

meshio = pytest.importorskip("meshio", reason="python3-meshio (tools/setup.sh installs it)")

H = 0.25
NX, NY = 5, 4        # the cloth: 5 x 4 vertices, IDs 1..20
SX, SY = 3, 2        # the second mesh: 3 x 2 vertices, IDs 21..26
FIELDS = ["id", "type", "vx", "vy", "vz", "c_s[1]", "c_s[4]", "v_speed"]
STEPS, EVERY, DT = 10, 5, 1e-3


def grid_obj(nx, ny):
    return read_mesh_grid(nx, ny, h=H, header="")


def grid_triangles(nx, ny, first_id):
    """Triangles of grid_obj as atom-ID triples (read_mesh numbers vertices in file order)."""
    return [tuple(first_id + v for v in t) for t in grid_indices(nx, ny)]


def canonical(tri):
    """A triangle with its orientation, rotated to start at its smallest ID."""
    k = tri.index(min(tri))
    return tuple(tri[k:]) + tuple(tri[:k])


CLOTH = {canonical(t) for t in grid_triangles(NX, NY, 1)}
SECOND = {canonical(t) for t in grid_triangles(SX, SY, NX * NY + 1)}


def deck(dumps, group="all"):
    """Two membranes in a box periodic in x and y: the cloth placed across the boundary x = 2
    (read_mesh wraps its vertices beyond it, with image flags 0) and a second mesh above it;
    both drift along x, fall under gravity and are stretched by different vertical velocities of
    their vertices (fix nve). dumps: the dump lines."""
    return "\n".join([
        "units           si",
        "atom_style      peri",
        "atom_modify     map array",
        "boundary        p p f",
        "region          box block -1 2 -1 2 -1 1",
        "create_box      2 box",
        "read_mesh       cloth.obj type 1 thickness 0.01 density 1000 offset 1.6 0.1 0 group cloth",
        "read_mesh       second.obj type 2 thickness 0.01 density 1000 offset 0 0.2 0.5",
        "pair_style      peri/nosb",
        f"pair_coeff      * * linear 1.0e6 5.0e5 {2.0002 * H!r} 0 0 break no membrane yes",
        "neighbor        0.1 bin",
        "variable        shake atom 0.5*sin(7*id)",
        "velocity        all set 3.0 0.5 v_shake",
        "fix             grav all gravity 9.81 vector 0 0 -1",
        "fix             nve all nve",
        "compute         s all nosb/atom",
        "variable        speed atom sqrt(vx*vx+vy*vy+vz*vz)",
        f"timestep        {DT}",
        f"group           sel {group}" if group != "all" else "",
        *dumps,
        f"dump            c all custom {EVERY} dump.atoms id type xu yu zu ix {' '.join(FIELDS[1:])}",
        "dump_modify     c sort id format float %.17g",
        f"run             {STEPS}",
    ]) + "\n"


FILES = {"cloth.obj": grid_obj(NX, NY), "second.obj": grid_obj(SX, SY)}


def run(tmp_path, dumps, nprocs=1, check=True, group="all"):
    return run_deck(deck(dumps, group), tmp_path, nprocs=nprocs, files=FILES, check=check)


def id_triangles(cells, ids):
    return {canonical(tuple(int(ids[v]) for v in c)) for c in cells}


def vtp_arrays(path):
    """The arrays of a .vtp file (ASCII): points, connectivity, offsets, point and cell data."""
    piece = ET.parse(path).getroot().find("PolyData/Piece")
    def values(node, kind=float):
        return np.array([kind(w) for w in node.text.split()])
    out = {"npoints": int(piece.get("NumberOfPoints")), "npolys": int(piece.get("NumberOfPolys"))}
    out["points"] = values(piece.find("Points/DataArray")).reshape(-1, 3)
    for a in piece.find("Polys"):
        out[a.get("Name")] = values(a, int)
    out["point"] = {a.get("Name"): values(a, float) for a in piece.find("PointData")}
    out["cell"] = {a.get("Name"): values(a, int) for a in piece.find("CellData")}
    return out


def pvd_frames(path):
    return [(float(d.get("timestep")), d.get("file"))
            for d in ET.parse(path).getroot().find("Collection")]


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    wd = tmp_path_factory.mktemp("serial")
    fields = " ".join(FIELDS)
    run(wd, [f"dump            p all nosb/mesh {EVERY} frames.*.vtp {fields}",
             f"dump            u all nosb/mesh {EVERY} cells.*.vtu {fields}",
             f"dump            o all nosb/mesh {EVERY} shape.*.obj",
             f"dump            last all nosb/mesh {EVERY} last.vtu id vx pvd no",
             f"dump            t all nosb/mesh {EVERY} low.*.vtu id",
             "dump_modify     t thresh id <= 12",
             "write_dump      all nosb/mesh once.obj"])
    return wd


STEPS_WRITTEN = list(range(0, STEPS + 1, EVERY))


@pytest.mark.parametrize("step", STEPS_WRITTEN)
def test_vtu_and_obj_match_dump_custom(serial, step):
    atoms = next(f for f in read_dump(serial / "dump.atoms") if f["step"] == step)
    ids = atoms["id"].astype(int)
    assert list(ids) == list(range(1, NX * NY + SX * SY + 1))
    vtu = meshio.read(serial / f"cells.{step}.vtu")
    # vertices in ID order; positions unwrapped (xu, as dump custom prints them), exactly
    assert list(vtu.point_data["id"]) == list(ids)
    assert vtu.point_data["id"].dtype.kind == "i" and vtu.point_data["type"].dtype.kind == "i"
    # positions: unwrapped (xu, yu, zu as dump custom prints them, exactly), and the vertices
    # read_mesh wrapped into the box (image flags 0) one period (3) further, next to the others
    xu = np.column_stack([atoms["xu"], atoms["yu"], atoms["zu"]])
    shift = np.round((vtu.points - xu) / 3.0)
    moved = np.any(shift != 0, axis=1)
    assert np.array_equal(vtu.points[~moved], xu[~moved])
    assert np.allclose(vtu.points[moved], xu[moved] + 3.0 * shift[moved], rtol=0, atol=1e-14)
    assert set(shift[:, 0]) <= {0.0, 1.0} and not np.any(shift[:, 1:])
    assert np.array_equal(moved, (ids <= NX * NY) & (atoms["xu"] < 0))
    assert np.count_nonzero(moved) == 3 * NY    # the cloth's columns at x 2.1, 2.35, 2.6
    cells = vtu.cells_dict["triangle"]
    edges = np.linalg.norm(vtu.points[cells] - vtu.points[np.roll(cells, 1, axis=1)], axis=2)
    assert edges.max() < 1.5 * H       # no triangle spans the box
    assert id_triangles(cells, ids) == CLOTH | SECOND
    mesh = vtu.cell_data_dict["mesh"]["triangle"]
    assert sorted(mesh) == [1] * len(CLOTH) + [2] * len(SECOND)
    for name in FIELDS[1:]:
        assert np.array_equal(vtu.point_data[name], atoms[name]), name
    if step > 0:    # the meshes are stretched: the fields are not trivial
        assert np.ptp(atoms["vz"]) > 0.5 and np.max(atoms["c_s[4]"]) > 10.0

    obj = meshio.read(serial / f"shape.{step}.obj")
    assert np.array_equal(obj.points, vtu.points)
    assert np.array_equal(obj.cells_dict["triangle"], cells)


@pytest.mark.parametrize("step", STEPS_WRITTEN)
def test_vtp_holds_what_vtu_holds(serial, step):
    vtp = vtp_arrays(serial / f"frames.{step}.vtp")
    vtu = meshio.read(serial / f"cells.{step}.vtu")
    assert vtp["npoints"] == len(vtu.points) and vtp["npolys"] == len(CLOTH | SECOND)
    assert np.array_equal(vtp["points"], vtu.points)
    assert np.array_equal(vtp["connectivity"].reshape(-1, 3), vtu.cells_dict["triangle"])
    assert list(vtp["offsets"]) == list(range(3, 3 * vtp["npolys"] + 1, 3))
    assert set(vtp["point"]) == set(FIELDS)
    for name in FIELDS:
        assert np.array_equal(vtp["point"][name], vtu.point_data[name]), name
    assert np.array_equal(vtp["cell"]["mesh"], vtu.cell_data_dict["mesh"]["triangle"])


def test_the_series_lists_every_frame_with_its_time(serial):
    assert pvd_frames(serial / "frames.pvd") == [(s * DT, f"frames.{s}.vtp") for s in STEPS_WRITTEN]
    assert pvd_frames(serial / "cells.pvd") == [(s * DT, f"cells.{s}.vtu") for s in STEPS_WRITTEN]
    assert not (serial / "last.pvd").exists()    # pvd no
    assert pvd_frames(serial / "low.pvd") == [(s * DT, f"low.{s}.vtu") for s in STEPS_WRITTEN]


def test_a_file_without_star_holds_the_last_frame(serial):
    last = meshio.read(serial / "last.vtu")
    final = meshio.read(serial / f"cells.{STEPS}.vtu")
    assert np.array_equal(last.points, final.points)
    assert np.array_equal(last.point_data["vx"], final.point_data["vx"])
    assert list(last.point_data) == ["id", "vx"]


def test_write_dump_writes_the_frame_the_dump_writes(serial):
    once = (serial / "once.obj").read_text().splitlines()
    assert once[0].startswith("# dump WRITE_DUMP nosb/mesh: step 0")
    assert once[1:] == (serial / "shape.0.obj").read_text().splitlines()[1:]


def test_thresh_selects_vertices_and_the_triangles_of_three_selected(serial):
    low = meshio.read(serial / f"low.{STEPS}.vtu")
    want = {t for t in CLOTH if max(t) <= 12}
    ids = low.point_data["id"]
    assert id_triangles(low.cells_dict["triangle"], ids) == want
    assert sorted(ids) == sorted({v for t in want for v in t})


def test_two_ranks_write_the_same_files(serial, tmp_path):
    """Byte for byte: the cloth lies on both ranks (the box is split along x at 0.5 or along y
    at 0.5, and the cloth spans x in [1.6, 2) and [-1, -0.4], y in [0.1, 0.85])."""
    fields = " ".join(FIELDS)
    run(tmp_path, [f"dump            p all nosb/mesh {EVERY} frames.*.vtp {fields}",
                   f"dump            o all nosb/mesh {EVERY} shape.*.obj"], nprocs=2)
    names = ["frames.pvd"] + [f"{stem}.{step}.{suffix}" for step in STEPS_WRITTEN
                              for stem, suffix in (("frames", "vtp"), ("shape", "obj"))]
    for name in names:
        assert (tmp_path / name).read_bytes() == (serial / name).read_bytes(), name


def test_the_group_selects_the_meshes(tmp_path):
    run(tmp_path, ["dump            p sel nosb/mesh 10 cloth.*.vtu id"], group="type 1")
    cloth = meshio.read(tmp_path / "cloth.0.vtu")
    assert id_triangles(cloth.cells_dict["triangle"], cloth.point_data["id"]) == CLOTH


@pytest.mark.parametrize("dump, group, message", [
    ("dump p all nosb/mesh 5 f.*.vtp foo", "all",
     "Invalid attribute foo in dump nosb/mesh command"),
    ("dump p all nosb/mesh 5 f.*.vtp c_nothing", "all",
     "Could not find dump nosb/mesh compute ID: nothing"),
    ("dump p all nosb/mesh 5 f.*.vtp element", "all",
     "Illegal dump nosb/mesh command: field element is text; fields are numbers"),
    ("dump p all nosb/mesh 5 f.*.vtk id", "all",
     "Illegal dump nosb/mesh command: file name f.*.vtk ends in none of .vtp, .vtu, .obj"),
    ("dump p all nosb/mesh 5 f%.*.vtp id", "all",
     "Illegal dump nosb/mesh command: file name f%.*.vtp has a %: rank 0 writes each frame"),
    ("dump p all nosb/mesh 5 f.*.obj vx", "all",
     "Illegal dump nosb/mesh command: field vx: OBJ files hold no fields (write a .vtp or "
     ".vtu file for them)"),
    ("dump p all nosb/mesh 5 f.*.vtp id pvd maybe", "all",
     "Illegal dump nosb/mesh command: pvd maybe: yes, no, or a file name ending in .pvd"),
    ("dump p all nosb/mesh 5 f.*.vtp id pvd yes colour red", "all",
     "Illegal dump nosb/mesh command: unknown keyword colour"),
    ("dump p all nosb/mesh 5 f.*.vtp id pvd", "all",
     "Illegal dump nosb/mesh command: keyword pvd needs a value"),
    ("dump p all nosb/mesh 5 f.*.obj pvd f.pvd", "all",
     "Illegal dump nosb/mesh command: pvd f.pvd: a series lists VTK files, not OBJ"),
    ("dump p sel nosb/mesh 5 f.*.vtp id", "id 1 2 21",
     "Dump nosb/mesh p: group sel holds no mesh triangle (a triangle of read_mesh is written "
     "when its three vertices are in the group)"),
    ("dump p all nosb/mesh 5 nofolder/f.*.vtp id", "all",
     "Dump nosb/mesh p: cannot open file nofolder/f.0.vtp: No such file or directory"),
    ("dump p all nosb/mesh 5 f.*.vtp id\ndump_modify p sort id", "all",
     "Dump nosb/mesh p: dump_modify sort does not apply (each frame is a file of its own, "
     "ordered by atom ID)"),
])
def test_bad_input_gives_an_error_naming_it(tmp_path, dump, group, message):
    r = run(tmp_path, [dump], check=False, group=group)
    assert not r.ok
    assert any(message in e for e in r.errors), r.errors or r.describe()


def test_an_unwritable_file_is_an_error_on_two_ranks(tmp_path):
    r = run(tmp_path, ["dump p all nosb/mesh 5 nofolder/f.*.vtp id"], nprocs=2, check=False)
    assert any("cannot open file nofolder/f.0.vtp: No such file or directory" in e
               for e in r.errors), r.describe()


def test_a_deck_without_mesh_is_an_error(tmp_path):
    text = "\n".join([
        "units           si",
        "atom_style      peri",
        "atom_modify     map array",
        "region          box block 0 1 0 1 0 1",
        "create_box      1 box",
        "create_atoms    1 single 0.5 0.5 0.5",
        "set             atom 1 mass 1.0",
        "dump            p all nosb/mesh 1 f.*.vtp id",
        "run             0",
    ]) + "\n"
    r = run_deck(text, tmp_path, check=False)
    assert any("Dump nosb/mesh p: the deck has no mesh (read_mesh, or fix nosb/mesh for a data "
               "file's triangles)" in e for e in r.errors), r.describe()
