"""LAMMPS from Python (README "Looking at results"): examples/python/drive_deck.py runs with a
plain python3 after tools/setup.sh (no PYTHONPATH, no plugin path in the environment), drives
the README's first deck through LAMMPS's own module with the plugin loaded, and writes its
picture; the numbers it reads through numpy are those a dump custom of build/lmp prints."""
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lammps_run import REPO, read_dump, run_deck

PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable
SCRIPT = REPO / "examples" / "python" / "drive_deck.py"


def test_the_python_example_reads_what_dump_custom_prints(tmp_path):
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "LAMMPS_PLUGIN_PATH", "LAMMPS_POTENTIALS")}
    done = subprocess.run([PYTHON, str(SCRIPT), "-o", "beam.png"], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-3000:]
    m = re.search(r"^(\d+) particles; tip deflection (\S+) um; largest von Mises stress (\S+) Pa",
                  done.stdout, re.M)
    assert m, done.stdout
    png = (tmp_path / "beam.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10000

    deck = (REPO / "examples" / "first-deck" / "in.first").read_text().replace(
        "run             20",
        "compute         s all nosb/atom\n"
        "dump            d all custom 20 dump.beam id z c_s[4]\n"
        "dump_modify     d sort id format float %.17g\n"
        "run             20")
    assert "dump.beam" in deck
    run_deck(deck, tmp_path / "lmp")
    first, last = read_dump(tmp_path / "lmp" / "dump.beam")
    uz = (last["z"] - first["z"]) * 1e6
    assert int(m.group(1)) == last["natoms"] == 775
    assert float(m.group(2)) == pytest.approx(uz.min(), rel=1e-5)
    assert float(m.group(3)) == pytest.approx(np.max(last["c_s[4]"]), rel=1e-5)
    assert uz.min() < -0.05    # the beam did bend (by about 0.1 um)
