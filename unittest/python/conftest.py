import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))
from lammps_run import LMP  # noqa: E402


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: physics check taking more than ~20 s")
    config.addinivalue_line("markers", "mpi: runs LAMMPS on more than one rank")
    config.addinivalue_line("markers", "full: runs only in the full tier (bash tools/test.sh "
                            "--full): benchmark drivers end to end, builds of their own")


def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist (--dist loadgroup, as tools/test.sh runs it) the tests that use a
    fixture of module scope go to one process, so that the fixture's runs are made once."""
    for item in items:
        defs = getattr(item, "_fixtureinfo", None)
        if defs is None:
            continue
        if any(d.scope == "module" for fd in defs.name2fixturedefs.values() for d in fd):
            item.add_marker(pytest.mark.xdist_group(name=item.module.__name__))


@pytest.fixture(scope="session", autouse=True)
def lmp_built():
    if not LMP.exists():
        pytest.exit(f"{LMP} is missing: run tools/setup.sh first", returncode=2)
