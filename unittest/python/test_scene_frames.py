"""The scene decks write what their pictures.sh renders only when asked: with -var frames N
(cloth scenes: dump nosb/mesh frames of the meshes) or -var dump N (impact: dump custom with
damage), a few steps each, and nothing of it without the variable (the reference logs' runs)."""
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

from lammps_run import REPO, read_dump, run_deck

EXAMPLES = REPO / "examples"
sys.path.insert(0, str(REPO / "tools"))
import render_mesh  # noqa: E402


def scene(tmp_path, folder):
    """A copy of the example folder (its meshes and include files) to run in."""
    work = tmp_path / folder
    shutil.copytree(EXAMPLES / folder, work, ignore=shutil.ignore_patterns(
        "*.png", "*.gif", "*.svg", "log.*", "dump.*", "frames"))
    return work


# folder, deck, variables, the frame written, vertices, meshes, its point arrays
CLOTHS = [
    ("tablecloth", "in.tablecloth", {"steps": 2, "every": 2, "dump": 0, "frames": 2},
     "frames/ci.2.vtp", 1134, [1], ["id", "vx", "vy", "vz"]),
    ("cloth-on-ball", "in.cloth-on-ball", {"steps": 2, "every": 2, "layers": 2, "frames": 2},
     "frames/layers2.2.vtp", 252 + 2 * 441, [1, 2, 3], ["id", "vx", "vy", "vz"]),
    ("twisting-cloth", "in.twisting-cloth", {"steps": 2, "every": 2, "frames": 2},
     "frames/twist.2.vtp", 150, [1], ["id", "vx", "vy", "vz", "v_across"]),
    ("hanging-cloth", "in.hanging", {"steps": 1, "every": 1, "frames": 1},
     "frames/hanging.1.vtp", 3038, [1], ["id", "vx", "vy", "vz"]),
]


@pytest.mark.parametrize("folder, deck, variables, frame, vertices, meshes, fields", CLOTHS,
                         ids=[c[0] for c in CLOTHS])
def test_cloth_scene_writes_frames_when_asked(tmp_path, folder, deck, variables, frame,
                                              vertices, meshes, fields):
    work = scene(tmp_path, folder)
    run_deck(work / deck, work, variables=variables)
    f = render_mesh.read_mesh(work / frame)
    assert f.points.shape == (vertices, 3)
    assert sorted(set(f.meshes)) == meshes
    assert list(f.fields) == fields
    assert f.step == variables["steps"]
    assert (work / frame).parent.joinpath(Path(frame).name.split(".")[0] + ".pvd").exists()
    if "v_across" in f.fields:
        # where each vertex started across the strip: the mesh file's y of the vertex
        start = render_mesh.read_obj(work / "strip.obj").points[:, 1]
        assert np.array_equal(f.fields["v_across"][np.argsort(f.fields["id"])], start)


@pytest.mark.parametrize("folder, deck", [("twisting-cloth", "in.twisting-cloth"),
                                          ("cloth-on-ball", "in.cloth-on-ball")])
def test_without_the_variable_no_frames(tmp_path, folder, deck):
    work = scene(tmp_path, folder)
    run_deck(work / deck, work, variables={"steps": 1, "every": 1})
    assert not (work / "frames").exists()


@pytest.mark.parametrize("deck, columns", [
    ("in.impact.nosb", ["id", "x", "y", "z", "v_damage", "c_nosb[4]"]),
    ("in.impact.lps", ["id", "x", "y", "z", "v_damage"]),
])
def test_impact_dumps_damage_when_asked(tmp_path, deck, columns):
    work = scene(tmp_path, "impact")
    run = run_deck(work / deck, work, variables={"nsteps": 10, "thermo_every": 10, "dump": 10})
    name = "dump." + deck[3:]
    frames = read_dump(work / name)
    assert [f["step"] for f in frames] == [0, 10]
    assert [c for c in frames[-1] if c not in ("step", "natoms", "box")] == columns
    assert frames[-1]["natoms"] == 3487
    # the damage column is the thermo's c_dmax at that step
    assert frames[-1]["v_damage"].max() == pytest.approx(run.thermo[-1]["c_dmax"][-1],
                                                         rel=1e-5, abs=1e-12)
