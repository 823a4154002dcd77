"""tools/render_mesh.py: reads the .vtp, .vtu and .obj frames of dump nosb/mesh alike, shades
each triangle by Lambert's law with the light in the camera's frame, leaves no seams between
triangles (a flat sheet seen from above is one uniform colour, no background between its
triangles), colours by a field, and names what is wrong with bad input."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lammps_run import REPO, run_deck
from test_read_mesh import grid_obj

sys.path.insert(0, str(REPO / "tools"))
import render_mesh  # noqa: E402

PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable
TOOL = REPO / "tools" / "render_mesh.py"
N = 9    # vertices per side of the test sheet


def sheet_obj(n=N, h=0.1):
    return grid_obj(n, n, h=h, header="")


@pytest.fixture(scope="module")
def frames(tmp_path_factory):
    """A sheet written by dump nosb/mesh at step 0 as .vtp, .vtu and .obj (field: z + id)."""
    wd = tmp_path_factory.mktemp("frames")
    deck = "\n".join([
        "units si", "atom_style peri", "atom_modify map array", "boundary f f f",
        "region box block -0.5 1.5 -0.5 1.5 -0.5 0.5", "create_box 1 box",
        "read_mesh sheet.obj type 1 thickness 0.01 density 1000",
        "variable f atom z+id",
        "dump p all nosb/mesh 1 s.*.vtp id v_f", "dump u all nosb/mesh 1 s.*.vtu id v_f",
        "dump o all nosb/mesh 1 s.*.obj", "run 0"]) + "\n"
    run_deck(deck, wd, files={"sheet.obj": sheet_obj()})
    return wd


def test_the_three_formats_read_alike(frames):
    p, tp, fp = render_mesh.read_mesh(frames / "s.0.vtp")
    u, tu, fu = render_mesh.read_mesh(frames / "s.0.vtu")
    o, to, fo = render_mesh.read_mesh(frames / "s.0.obj")
    assert p.shape == (N * N, 3) and tp.shape == (2 * (N - 1) ** 2, 3)
    assert np.array_equal(p, u) and np.array_equal(p, o)
    assert np.array_equal(tp, tu) and np.array_equal(tp, to)
    assert list(fp) == ["id", "v_f"] and np.array_equal(fp["v_f"], fu["v_f"]) and fo == {}
    assert np.array_equal(fp["v_f"], fp["id"])    # z = 0


def test_lambert_shading_and_the_camera_frame():
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    tris = np.array([[0, 1, 2], [0, 2, 1], [0, 1, 3]])    # +z, -z, facing -y
    shade = render_mesh.lambert(pts, tris, np.array([0, 0, 1.0]), 0.25)
    assert shade == pytest.approx([1.0, 1.0, 0.25])       # both sides lit; edge-on: ambient
    right, up, toward = render_mesh.camera_frame(90.0, -90.0)
    assert toward == pytest.approx([0, 0, 1], abs=1e-15)    # from above
    m = np.array([right, up, toward])
    assert m @ m.T == pytest.approx(np.eye(3), abs=1e-15)
    assert np.linalg.det(m) == pytest.approx(1.0)           # right-handed


def pixels(path):
    import matplotlib.image
    return matplotlib.image.imread(str(path))[..., :3]


def test_a_flat_sheet_from_above_is_one_colour_without_seams(frames, tmp_path):
    out = tmp_path / "top.png"
    assert render_mesh.main([str(frames / "s.0.obj"), "-o", str(out), "--elev", "90",
                             "--azim", "-90", "--zoom", "1.4", "--dpi", "100"]) == 0
    img = pixels(out)
    h, w = img.shape[:2]
    inside = img[int(0.4 * h):int(0.6 * h), int(0.4 * w):int(0.6 * w)].reshape(-1, 3)
    assert np.all(inside.max(axis=1) < 0.95), "background shows through the sheet"
    assert np.ptp(inside, axis=0).max() < 0.02
    # the light straight from the viewer: full colour; from the side: darker
    side = tmp_path / "side.png"
    render_mesh.main([str(frames / "s.0.obj"), "-o", str(side), "--elev", "90", "--azim", "-90",
                      "--zoom", "1.4", "--dpi", "100", "--light", "1", "0", "0.2"])
    dim = pixels(side)[int(0.5 * h), int(0.5 * w)]
    assert dim.sum() < 0.6 * inside[0].sum()


def test_field_colours(frames, tmp_path):
    out = tmp_path / "field.png"
    done = subprocess.run([PYTHON, str(TOOL), str(frames / "s.0.vtp"), "-o", str(out),
                           "--field", "v_f", "--elev", "90", "--azim", "-90"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert f"{out} ({2 * (N - 1) ** 2} triangles)" in done.stdout
    img = pixels(out)
    h, w = img.shape[:2]
    # the field grows along y (id = j N + i + 1): the sheet's two halves differ in colour
    lower, upper = img[int(0.6 * h), int(0.4 * w)], img[int(0.35 * h), int(0.4 * w)]
    assert np.abs(lower - upper).max() > 0.2


@pytest.mark.parametrize("args, message", [
    (["s.0.obj", "--field", "v_f"], "no field v_f in the file (fields: none)"),
    (["s.0.vtp", "--field", "c_x"], "no field c_x in the file (fields: id, v_f)"),
    (["missing.vtp"], "No such file or directory"),
    (["sheet.obj.txt"], "sheet.obj.txt: not a .vtp, .vtu or .obj file"),
])
def test_bad_input_is_named(frames, args, message):
    done = subprocess.run([PYTHON, str(TOOL), *args, "-o", "x.png"], cwd=frames,
                          capture_output=True, text=True)
    assert done.returncode == 1 and message in done.stderr, done.stderr
