"""Particles for viewers (README.md, "Looking at results"): a `dump custom` of compute nosb/atom
columns converted by tools/dump_to_vtu.py into .vtu point clouds (and a .pvd series) that an
independent reader (Debian's python3-meshio) reads back with the dump's positions and columns,
and tools/render_particles.py's slice picture of the same dump: the particles of the slice, the
column's range there, a PNG of the size asked for."""
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from lammps_run import REPO, read_dump, run_deck

PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable
TOOLS = REPO / "tools"
A = 0.001    # lattice spacing (m)

# a 6 x 6 x 6 mm block of peri/nosb (7 x 7 x 7 = 343 particles) whose part at x >= 3 mm is
# moved 0.3 mm along x after the families are built: the bonds across the cut stretch past s0
# and break, so damage is 0 far from the cut and positive next to it
DECK = f"""
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
lattice         sc {A}
region          b block 0 6 0 6 0 6
create_box      1 b
create_atoms    1 region b
set             group all volume {A**3}
set             group all density 2000
pair_style      peri/nosb
pair_coeff      * * linear 14.9e9 8.94e9 {3.0002 * A} 0.0005 0.25
compute         s all nosb/atom
fix             1 all nve
timestep        1.0e-8
run             0 post no
region          right block 2.9 INF INF INF INF INF
group           right region right
displace_atoms  right move 0.0003 0 0 units box
dump            d all custom 1 dump.atoms id type x y z c_s[*]
dump_modify     d sort id format float %.17g
run             2 post no
"""


@pytest.fixture(scope="module")
def block(tmp_path_factory):
    wd = tmp_path_factory.mktemp("block")
    run_deck(DECK, wd)
    return wd


def tool(name, *args, cwd):
    return subprocess.run([PYTHON, str(TOOLS / name), *map(str, args)], cwd=cwd,
                          capture_output=True, text=True)


def test_dump_to_vtu_holds_the_dump(block, tmp_path):
    meshio = pytest.importorskip("meshio")    # tools/setup.sh installs python3-meshio
    done = tool("dump_to_vtu.py", block / "dump.atoms", "-o", tmp_path / "vtk" / "atoms",
                cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "3 frames" in done.stdout
    dump = read_dump(block / "dump.atoms")
    series = ET.parse(tmp_path / "vtk" / "atoms.pvd").getroot()
    entries = [(d.get("timestep"), d.get("file")) for d in series.iter("DataSet")]
    assert entries == [(str(f["step"]), f"atoms.{f['step']}.vtu") for f in dump]
    for frame in dump:
        mesh = meshio.read(tmp_path / "vtk" / f"atoms.{frame['step']}.vtu")
        assert mesh.points.shape == (343, 3)
        assert np.array_equal(mesh.points, np.column_stack([frame["x"], frame["y"],
                                                            frame["z"]]))
        assert [c.type for c in mesh.cells] == ["vertex"]
        assert np.array_equal(mesh.cells[0].data.ravel(), np.arange(343))
        data = mesh.point_data
        assert set(data) == {"id", "type"} | {f"c_s[{k}]" for k in range(1, 12)}
        assert data["id"].dtype.kind == "i" and np.array_equal(data["id"], frame["id"])
        for k in range(1, 12):
            assert np.array_equal(data[f"c_s[{k}]"], frame[f"c_s[{k}]"]), k
    last = dump[-1]
    assert last["c_s[1]"].max() > 0.1 and last["c_s[1]"].min() == 0.0    # damage at the cut


def test_dump_to_vtu_names_bad_input(tmp_path):
    (tmp_path / "noxyz").write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\n"
                                    "ITEM: BOX BOUNDS ss ss ss\n0 1\n0 1\n0 1\n"
                                    "ITEM: ATOMS id vx\n1 0.5\n")
    (tmp_path / "text").write_text("hello\n")
    done = tool("dump_to_vtu.py", "noxyz", cwd=tmp_path)
    assert done.returncode == 1 and "no x y z (or xu yu zu) columns (columns: id vx)" in \
        done.stderr
    done = tool("dump_to_vtu.py", "text", cwd=tmp_path)
    assert done.returncode == 1 and "text: not a LAMMPS dump file" in done.stderr


def test_slice_picture_of_the_damage(block, tmp_path):
    """The slice z = 3 mm (one lattice plane of 49 particles): the tool counts them, gives the
    damage range of exactly those particles, and writes an 800 x 450 picture in which the
    damage shows (the colours of the broken and the intact particles differ)."""
    import matplotlib.image

    out = tmp_path / "damage.png"
    done = tool("render_particles.py", block / "dump.atoms", block / "dump.atoms",
                "--column", "c_s[1]", "--slice", "z", "--at", 3 * A, "--labels", "one", "two",
                "--cmap", "viridis", "-o", out, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    last = read_dump(block / "dump.atoms")[-1]
    plane = np.abs(last["z"] - 3 * A) <= A / 2
    damage = last["c_s[1]"][plane]
    assert plane.sum() == 49 and damage.max() > damage.min()
    line = (f"step 2, 49 particles in the slice, c_s[1] from {damage.min():g} to "
            f"{damage.max():g}")
    assert done.stdout.count(line) == 2, done.stdout
    img = matplotlib.image.imread(str(out))[..., :3]
    assert img.shape[:2] == (450, 800)
    colours = np.unique((img.reshape(-1, 3) * 255).round().astype(int), axis=0)
    assert len(colours) > 10    # background, axes, colour bar and the squares' colours
    # in the left picture (the colour bar is on the right) the colour map's two ends appear:
    # the intact particles' colour and the most damaged one's
    import matplotlib.pyplot as plt
    cmap = plt.get_cmap("viridis")
    left = img[:, :int(0.4 * img.shape[1])].reshape(-1, 3)
    for end in (0.0, 1.0):
        target = np.array(cmap(end)[:3])
        assert np.abs(left - target).max(axis=1).min() < 0.02, end


@pytest.mark.parametrize("args, message", [
    (["--column", "c_x"], "no column c_x (columns: id type x y z c_s[1]"),
    (["--column", "c_s[1]", "--at", "0.5"], "no particle within"),
    (["--column", "c_s[1]", "--labels", "a", "b"], "--labels needs one label per dump file"),
])
def test_render_particles_names_bad_input(block, tmp_path, args, message):
    done = tool("render_particles.py", block / "dump.atoms", *args, "-o", tmp_path / "x.png",
                cwd=tmp_path)
    assert done.returncode == 1 and message in done.stderr, done.stderr


def test_frames_by_step_in_rows(block, tmp_path):
    """--steps picks each file's frame by its timestep, --rows stacks the pictures; a step the
    dump does not hold is an error."""
    import matplotlib.image

    out = tmp_path / "steps.png"
    done = tool("render_particles.py", block / "dump.atoms", block / "dump.atoms",
                block / "dump.atoms", "--column", "c_s[1]", "--at", 3 * A, "--steps", 0, 1, 2,
                "--rows", 2, "--size", 6, 6, "-o", out, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    for step in (0, 1, 2):
        assert done.stdout.count(f"step {step}, 49 particles in the slice") == 1, done.stdout
    assert matplotlib.image.imread(str(out)).shape[:2] == (600, 600)
    done = tool("render_particles.py", block / "dump.atoms", "--column", "c_s[1]", "--steps", 7,
                "-o", out, cwd=tmp_path)
    assert done.returncode == 1 and "no frame at step 7" in done.stderr, done.stderr
    done = tool("render_particles.py", block / "dump.atoms", "--column", "c_s[1]", "--steps", 0,
                1, "-o", out, cwd=tmp_path)
    assert done.returncode == 1 and "--steps needs one step per dump file" in done.stderr
