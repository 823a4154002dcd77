"""The time step check of explicit runs (doc/pair_peri_nosb.rst, "Stable time step"; core
peri/step_check.h): at the setup of every run pair peri/nosb warns once when the time step is
above the stable-step estimate (compute nosb/atom column 11) of a particle that fix nve or
another explicit integrator moves, naming the time step, the smallest estimate and how many
particles lie below the time step; not below the estimate, not under fix sissm or fix move.
A 6 x 6 x 6 block (216 particles, spacing 1 mm, horizon 3 spacings, K = 1 GPa, G = 0.6 K,
rho = 1000 kg/m^3, Cs = 2), at rest, three steps."""
import re

import numpy as np
import pytest

from lammps_run import run_deck

DECK = """variable        factor index 1.05
variable        fix index nve
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
variable        a equal 0.001
neighbor        $(v_a) bin
lattice         sc ${a}
region          box block -0.5 5.5 -0.5 5.5 -0.5 5.5
create_box      1 box
create_atoms    1 box
set             group all density 1000
set             group all volume $(v_a^3)
pair_style      peri/nosb
pair_coeff      * * linear 1.0e9 0.6e9 $(3.0002*v_a) 0.5 0.25 stabilize 2.0 break no
compute         nosb all nosb/atom
compute         dtmin all reduce min c_nosb[11]
thermo_style    custom step pe ke c_dtmin
run             0
write_dump      all custom dump.dt id c_nosb[11] modify format float %.17g
variable        estimate equal c_dtmin
print           "ESTIMATE $(v_estimate:%.17g)"
timestep        $(v_factor*v_estimate)
fix             integrate all ${fix}
run             3
run             2
"""

STEP_RE = re.compile(r"Pair peri/nosb: timestep (\S+) is above the estimated stable explicit "
                     r"time step (\S+) of (\d+) of the (\d+) particles integrated by fix "
                     r"integrate \(nve\)")


def step_warnings(run):
    return [w for w in run.warnings if "peri/nosb: timestep" in w]


def estimates(run, workdir):
    est = float(next(ln.split()[1] for ln in run.stdout.splitlines()
                     if ln.startswith("ESTIMATE")))
    rows = np.loadtxt(workdir / "dump.dt", skiprows=9)
    return est, rows[:, 1]


@pytest.mark.parametrize("nprocs", [1, pytest.param(2, marks=pytest.mark.mpi)])
def test_fix_nve_above_the_estimate_warns_once_per_run(tmp_path, nprocs):
    run = run_deck(DECK, tmp_path, nprocs=nprocs)
    est, dt = estimates(run, tmp_path)
    told = step_warnings(run)
    # once for each of the two runs with fix nve, none for run 0
    assert len(told) == 2, run.warnings
    m = STEP_RE.search(told[0])
    assert m, told[0]
    step, smallest, above, total = float(m[1]), float(m[2]), int(m[3]), int(m[4])
    assert step == pytest.approx(1.05 * est, rel=1e-3)
    assert smallest == pytest.approx(est, rel=1e-3)
    assert total == 216
    # the particles whose estimate (column 11) lies below the time step
    assert above == np.count_nonzero(dt < 1.05 * est)
    assert 0 < above < 216
    assert "Use a timestep below" in told[0] and "fix sissm" in told[0]
    assert told[1] == told[0]


@pytest.mark.parametrize("factor,fix", [
    (0.95, "nve"), (1.05, "sissm"), (1.05, "move linear 0 0 0"),
], ids=["nve-below", "sissm-above", "move-above"])
def test_no_warning_below_the_estimate_nor_for_implicit_or_prescribed_motion(tmp_path, factor,
                                                                               fix):
    run = run_deck(DECK, tmp_path, variables={"factor": factor, "fix": fix})
    assert len(run.thermo) == 3
    assert not step_warnings(run), run.warnings
