"""The layout the architecture promises (README "Layout"): the core in src/core uses neither
LAMMPS nor MPI and builds and passes its tests alone; nothing in the repository points at design
notes outside it."""
import pathlib
import re
import shutil
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def test_core_includes_no_lammps_or_mpi():
    """Every #include of src/core is the core's own, Eigen, the standard library or the
    compiler's x86 intrinsics (immintrin.h, in the fused passes' linalg/double4.h only)."""
    bad = []
    for path in sorted((REPO / "src" / "core").rglob("*")):
        if path.suffix not in (".h", ".cpp"):
            continue
        for n, line in enumerate(path.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s*[<"]([^>"]+)[>"]', line)
            if not m:
                continue
            inc = m.group(1)
            own = (REPO / "src" / "core" / inc).exists()
            intrinsics = inc == "immintrin.h" and path.name == "double4.h"
            if not (own or intrinsics or inc.startswith("Eigen/")
                    or re.fullmatch(r"[a-z_]+", inc)):
                bad.append(f"{path.relative_to(REPO)}:{n}: {inc}")
    assert not bad, "includes outside the core, Eigen and the standard library:\n" + "\n".join(bad)
    text = "\n".join(p.read_text() for p in (REPO / "src" / "core").rglob("*") if p.is_file())
    assert "lammps" not in text and "MPI_" not in text


def project_files(top):
    """The files of the checkout under top (a folder or a file) that git tracks or would track:
    not what it ignores (the frames and dumps that the examples' picture scripts write). Every
    file under top where git is not at hand."""
    listed = subprocess.run(["git", "-C", str(REPO), "ls-files", "-co", "--exclude-standard", "-z",
                             "--", top], capture_output=True, text=True) \
        if shutil.which("git") and (REPO / ".git").exists() else None
    if listed is not None and listed.returncode == 0:
        return sorted(REPO / name for name in listed.stdout.split("\0") if name)
    root = REPO / top
    return [root] if root.is_file() else sorted(root.rglob("*"))


def test_no_pointers_outside_the_repository():
    """Docs and comments cite papers or files of the repository, never the design notes the
    project started from."""
    pattern = re.compile(r"math\.md|interface\.md|style\.md|notes\.md|\.\./shared|the talk",
                         re.IGNORECASE)
    hits = []
    for top in ("src", "doc", "examples", "unittest", "tools", "README.md", "CMakeLists.txt"):
        for path in project_files(top):
            if not path.is_file() or path.suffix in (".png", ".csv") or path.name.startswith("log."):
                continue
            if path == pathlib.Path(__file__):
                continue
            for n, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                if pattern.search(line):
                    hits.append(f"{path.relative_to(REPO)}:{n}: {line.strip()}")
    assert not hits, "\n".join(hits)


@pytest.mark.full
@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not installed")
def test_core_builds_and_passes_alone(tmp_path):
    """Configure the project without LAMMPS: only the core and its unit tests are built, and
    they pass (a second build of the core: full tier)."""
    build = tmp_path / "core"
    # (without the fused version, as -DPERISISSM_CPU_DISPATCH=OFF and compilers or processors
    # other than GCC/Clang on x86-64 build it; the plugin's own build has it)
    subprocess.run(["cmake", "-S", str(REPO), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                    "-DPERISISSM_CPU_DISPATCH=OFF"], check=True, capture_output=True, text=True)
    out = subprocess.run(["cmake", "--build", str(build), "-j", "2"], capture_output=True,
                         text=True)
    assert out.returncode == 0, out.stdout[-3000:] + out.stderr[-3000:]
    assert not list(build.rglob("perisissmplugin.so")), "the plugin was built without LAMMPS"
    run = subprocess.run([str(build / "unittest" / "core" / "test_core"), "--gtest_brief=1"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout[-3000:]
    assert re.search(r"\[  PASSED  \] \d+ tests", run.stdout), run.stdout[-2000:]


GLUE = REPO / "src" / "lammps"


def glue_includes():
    """{file name: the project's own headers it includes} for src/lammps."""
    own = {p.name for p in GLUE.glob("*.h")}
    out = {}
    for path in sorted(GLUE.glob("*.[ch]*")):
        incs = re.findall(r'^\s*#\s*include\s*"([^"]+)"', path.read_text(), re.MULTILINE)
        out[path.name] = {i for i in incs if i in own}
    return out


def test_no_source_file_above_800_lines():
    """Each file holds one concept: none of src/ is longer than 800 lines."""
    long = []
    for path in sorted((REPO / "src").rglob("*")):
        if path.suffix in (".h", ".cpp"):
            n = len(path.read_text().splitlines())
            if n > 800:
                long.append(f"{path.relative_to(REPO)}: {n} lines")
    assert not long, "\n".join(long)


def test_style_headers_form_no_include_cycle():
    """Following the #include lines among src/lammps's headers never comes back to where it
    started."""
    incs = glue_includes()
    headers = {k: v for k, v in incs.items() if k.endswith(".h")}

    def reach(start):
        seen, todo = set(), list(headers.get(start, ()))
        while todo:
            h = todo.pop()
            if h not in seen:
                seen.add(h)
                todo.extend(headers.get(h, ()))
        return seen

    cycles = [h for h in headers if h in reach(h)]
    assert not cycles, cycles


def test_contact_fix_sees_the_pair_through_an_interface_only():
    """fix nosb/contact reaches pair peri/nosb's bond partners through bond_partners.h, never
    through the pair's or the family fix's class."""
    incs = glue_includes()
    for name in ("fix_nosb_contact.h", "fix_nosb_contact.cpp", "fix_nosb_contact_sissm.cpp"):
        assert not incs[name] & {"pair_peri_nosb.h", "fix_nosb_family.h"}, name
        assert "PairPeriNosb" not in (GLUE / name).read_text(), name


def test_meshes_are_read_through_an_interface_only():
    """Styles read the meshes of read_mesh through mesh_view.h; fix_nosb_mesh.h is included only
    by the fix's own files, read_mesh (which fills it) and the plugin entry."""
    allowed = {"fix_nosb_mesh.cpp", "fix_nosb_mesh_data.cpp", "read_mesh.cpp", "perisissmplugin.cpp"}
    incs = glue_includes()
    users = {name for name, own in incs.items() if "fix_nosb_mesh.h" in own}
    assert users <= allowed, sorted(users - allowed)
    readers = {n for n in GLUE.glob("*.[ch]*") if "FixNosbMesh" in n.read_text()}
    assert {n.name for n in readers} <= allowed | {"fix_nosb_mesh.h"}, sorted(n.name for n in readers)
