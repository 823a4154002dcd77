import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).parent))
from lammps_run import LMP  # noqa: E402


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: physics check taking more than ~20 s")
    config.addinivalue_line("markers", "mpi: runs LAMMPS on more than one rank")


@pytest.fixture(scope="session", autouse=True)
def lmp_built():
    if not LMP.exists():
        pytest.exit(f"{LMP} is missing: run tools/setup.sh first", returncode=2)
