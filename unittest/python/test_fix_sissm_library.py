"""fix sissm driven through LAMMPS's library interface, where an error inside a run is an
exception the caller can catch and carry on from (issue 9, item 9: flags of the pair left set
when an error is thrown inside a solve).

An error inside fix sissm's solve used to leave pair peri/nosb's "no breaking inside the
implicit step" flag set: every later force evaluation of that LAMMPS instance, also under
fix nve, then kept bonds that should break.
"""
import json
import subprocess
import sys

from lammps_run import library_environment
from sissm_support import BLOCK

SCRIPT = r"""
import json, sys
from lammps import lammps
lmp = lammps(cmdargs=["-log", "log.lammps", "-screen", "none", "-nocite",
                      "-var", "brk", "yes", "-var", "s00", "0.01", "-var", "alpha", "0",
                      "-var", "solver", "krylov", "-var", "dt", "1e-5", "-var", "nsteps", "0"])
lmp.file(sys.argv[1])
lmp.commands_list(["fix keep all store/state 0 x y z", "group one id 5",
                   "velocity one set 1e200 0 0 units box"])
out = {}
try:
    lmp.command("run 1")
    out["error"] = None
except Exception as e:
    out["error"] = str(e).splitlines()[0]
# back to the intact block, stretched along x at 2e4 /s under fix nve: within 2e-6 s its
# bonds reach 4 %, beyond s00 = 1 %
lmp.commands_list(["thermo_style custom step pe ke", "unfix integrate",
                   "variable kx atom f_keep[1]", "variable ky atom f_keep[2]",
                   "variable kz atom f_keep[3]", "set group all x v_kx y v_ky z v_kz",
                   "variable vs atom 2e4*(f_keep[1]-0.0015)",
                   "velocity all set v_vs 0 0 units box",
                   "fix 2 all nve", "timestep 1e-7", "run 20",
                   "compute dmg all reduce max c_nosb[1]", "run 0"])
out["damage"] = lmp.extract_compute("dmg", 0, 0)
print(json.dumps(out))
"""


def test_bonds_break_again_after_an_error_inside_a_solve(tmp_path):
    (tmp_path / "driver.py").write_text(SCRIPT)
    done = subprocess.run([sys.executable, str(tmp_path / "driver.py"), str(BLOCK)],
                          cwd=tmp_path, env=library_environment(), capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    out = json.loads(done.stdout.strip().splitlines()[-1])
    # the error came from inside fix sissm's solve (a velocity of 1e200 m/s overflows)
    assert out["error"] and "Fix sissm" in out["error"] and "non-finite" in out["error"]
    # and the instance breaks bonds again (before the fix: damage 0)
    assert out["damage"] > 0.05
