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
    p, tp, fp, mp, timep, stepp = render_mesh.read_mesh(frames / "s.0.vtp")
    u, tu, fu, mu, timeu, _ = render_mesh.read_mesh(frames / "s.0.vtu")
    o, to, fo, mo, timeo, _ = render_mesh.read_mesh(frames / "s.0.obj")
    assert p.shape == (N * N, 3) and tp.shape == (2 * (N - 1) ** 2, 3)
    assert np.array_equal(p, u) and np.array_equal(p, o)
    assert np.array_equal(tp, tu) and np.array_equal(tp, to)
    assert list(fp) == ["id", "v_f"] and np.array_equal(fp["v_f"], fu["v_f"]) and fo == {}
    assert np.array_equal(fp["v_f"], fp["id"])    # z = 0
    # one mesh (the dump's cell array, the OBJ's object mesh_1); the VTK files give the time
    assert np.all(mp == 1) and np.all(mu == 1) and np.all(mo == 1)
    assert timep == timeu == 0.0 and timeo is None and stepp == 0


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


def test_a_picture_has_the_size_asked_for(frames, tmp_path):
    out = tmp_path / "small.png"
    assert render_mesh.main([str(frames / "s.0.vtp"), "-o", str(out), "--size", "4", "3",
                             "--dpi", "50"]) == 0
    assert pixels(out).shape[:2] == (150, 200)
    assert pixels(out).reshape(-1, 3).std(axis=0).max() > 0.05    # not a blank picture


def centre_colour(path):
    img = pixels(path)
    h, w = img.shape[:2]
    return img[int(0.45 * h):int(0.55 * h), int(0.45 * w):int(0.55 * w)].reshape(-1, 3).mean(0)


def test_front_and_back_colours(frames, tmp_path):
    """The sheet's triangles face +z (counterclockwise from above): from above the front colour
    shows, from below the back colour, each times the same shading (light from the viewer)."""
    common = ["--color", "#ff0000", "--back-color", "#0000ff", "--azim", "-90", "--zoom", "1.4",
              "--light", "0", "0", "1", "--ambient", "0.5", "--dpi", "50"]
    render_mesh.main([str(frames / "s.0.vtp"), "-o", str(tmp_path / "up.png"), "--elev", "90",
                      *common])
    render_mesh.main([str(frames / "s.0.vtp"), "-o", str(tmp_path / "down.png"), "--elev",
                      "-90", *common])
    assert centre_colour(tmp_path / "up.png") == pytest.approx([1, 0, 0], abs=0.02)
    assert centre_colour(tmp_path / "down.png") == pytest.approx([0, 0, 1], abs=0.02)


def test_mesh_colours_follow_the_dump_mesh_ids(tmp_path):
    """Two meshes side by side (read_mesh twice): mesh 1 takes the first --mesh-colors colour,
    mesh 2 the second, in the .vtp (cell array mesh) and the .obj (objects mesh_1, mesh_2)."""
    deck = "\n".join([
        "units si", "atom_style peri", "atom_modify map array", "boundary f f f",
        "region box block -1 3 -1 2 -1 1", "create_box 1 box",
        "read_mesh sheet.obj type 1 thickness 0.01 density 1000",
        "read_mesh sheet.obj type 1 thickness 0.01 density 1000 offset 1.0 0 0",
        "write_dump all nosb/mesh two.vtp id", "write_dump all nosb/mesh two.obj"]) + "\n"
    run_deck(deck, tmp_path, files={"sheet.obj": sheet_obj(5, 0.2)})
    for name in ("two.vtp", "two.obj"):
        frame = render_mesh.read_mesh(tmp_path / name)
        assert sorted(set(frame.meshes)) == [1, 2]
        out = tmp_path / (name + ".png")
        assert render_mesh.main([str(tmp_path / name), "-o", str(out), "--elev", "90",
                                 "--azim", "-90", "--mesh-colors", "#ff0000", "#0000ff",
                                 "--light", "0", "0", "1", "--ambient", "0.5"]) == 0
        img = pixels(out)
        h, w = img.shape[:2]
        left, right = img[h // 2, int(0.3 * w)], img[h // 2, int(0.7 * w)]
        assert left == pytest.approx([1, 0, 0], abs=0.02)      # mesh 1 at x 0 ... 0.8
        assert right == pytest.approx([0, 0, 1], abs=0.02)     # mesh 2 at x 1 ... 1.8


def test_a_box_is_drawn_under_the_mesh(frames, tmp_path):
    """A box larger than the sheet, below it: from above the sheet covers the box's middle
    (no speckles of the box through it) and the box shows around the sheet."""
    out = tmp_path / "table.png"
    assert render_mesh.main([str(frames / "s.0.vtp"), "-o", str(out), "--elev", "90",
                             "--azim", "-90", "--color", "#ff0000", "--box", "-0.4", "1.2",
                             "-0.4", "1.2", "-0.5", "-0.01", "--box-color", "#0000ff",
                             "--light", "0", "0", "1", "--ambient", "0.5",
                             "--limits", "-0.4", "1.2", "-0.4", "1.2", "-0.5", "0"]) == 0
    img = pixels(out)
    h, w = img.shape[:2]
    sheet = img[int(0.4 * h):int(0.6 * h), int(0.4 * w):int(0.6 * w)].reshape(-1, 3)
    assert np.all(np.abs(sheet - [1, 0, 0]).max(axis=1) < 0.02)
    box = img[h // 2, int(0.5 * w) - int(0.3 * h)]    # left of the sheet, on the box
    assert box == pytest.approx([0, 0, 1], abs=0.02)
    # the box alone: its 12 triangles, their normals outwards
    points, triangles = render_mesh.box_mesh([0, 0, 0], [1, 2, 3])
    n = render_mesh.normals(points, triangles)
    outwards = points[triangles].mean(axis=1) - [0.5, 1.0, 1.5]
    assert len(triangles) == 12 and np.all(np.sum(n * outwards, axis=1) > 0)


def test_an_animation_of_a_series(tmp_path):
    """A sheet falling for 4 steps, a frame every 2 steps (.pvd series of 3 frames): the GIF
    has the 3 frames at the size asked for, in one view (the sheet moves down in it), and the
    title's {time} and {step} are the frames'."""
    deck = "\n".join([
        "units si", "atom_style peri", "atom_modify map array", "boundary f f f",
        "region box block -0.5 1.5 -0.5 1.5 -2 0.5", "create_box 1 box",
        "read_mesh sheet.obj type 1 thickness 0.01 density 1000",
        "velocity all set 0 0 -100", "fix 1 all nve", "timestep 0.001",
        "dump p all nosb/mesh 2 s.*.vtp", "run 4"]) + "\n"
    run_deck(deck, tmp_path, files={"sheet.obj": sheet_obj()})
    series = render_mesh.series_files(tmp_path / "s.pvd")
    assert [p.name for p in series] == ["s.0.vtp", "s.2.vtp", "s.4.vtp"]
    frames = [render_mesh.read_mesh(p) for p in series]
    assert [f.time for f in frames] == pytest.approx([0.0, 0.002, 0.004])
    assert [f.step for f in frames] == [0, 2, 4]
    out = tmp_path / "fall.gif"
    done = subprocess.run([PYTHON, str(TOOL), str(tmp_path / "s.pvd"), "-o", str(out),
                           "--size", "3", "2", "--dpi", "50", "--elev", "10", "--azim", "-90",
                           "--title", "t = {time:.3f} s, step {step}"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert f"{out} (3 frames)" in done.stdout
    from PIL import Image
    gif = Image.open(out)
    assert gif.n_frames == 3 and gif.size == (150, 100)
    rows = []
    for k in range(3):
        gif.seek(k)
        img = np.asarray(gif.convert("RGB"), float) / 255
        dark = np.nonzero(img.max(axis=2) < 0.9)[0]
        rows.append(dark[dark > 20].mean())    # below the title: the sheet, nearly edge-on
    assert rows[0] < rows[1] < rows[2]
