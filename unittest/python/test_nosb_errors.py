"""Bad input to pair_style peri/nosb, fix nosb/family and compute nosb/atom (issue 3): every case
stops with a LAMMPS ERROR line that names what is wrong, and an error exit (returncode > 0),
never a crash (a signal gives a negative returncode) and never a silent run."""
import re

import pytest

from lammps_run import run_deck

COEFF = "linear 1.0e9 0.6e9 0.0030002 0.5 0.25"
LPS_COEFF = "pair_coeff      * * 1.0e9 0.6e9 0.0030002 0.5 0.25"


def deck(atom_style="peri", atom_map="atom_modify     map array", before_box="",
         box="create_box      1 block", properties=None, pair="pair_style      peri/nosb",
         coeff=f"pair_coeff      * * {COEFF}", after="", run="run             0",
         dimension="", boundary="s s s", n=6):
    """A 6^3 block of peri particles with peri/nosb and `run 0`; each argument replaces one
    part of it (the default deck runs without error: see test_the_base_deck_runs)."""
    if properties is None:
        properties = ("set             group all density 1000\n"
                      "set             group all volume 1.0e-9")
    return "\n".join(line for line in [
        "units           si",
        dimension,
        f"boundary        {boundary}",
        f"atom_style      {atom_style}",
        atom_map,
        before_box,
        "lattice         sc 0.001",
        f"region          block block -0.5 {n - 0.5} -0.5 {n - 0.5} -0.5 {n - 0.5}",
        box,
        "create_atoms    1 region block",
        properties,
        pair,
        coeff,
        after,
        run,
    ] if line) + "\n"


def coeff(args):
    return f"pair_coeff      * * {args}"


def test_the_base_deck_runs(tmp_path):
    run = run_deck(deck(), tmp_path)
    assert "bonds/atom" in run.log


# (case id, deck keyword arguments, strings the ERROR line must contain (case-insensitive))
BAD_INPUT = [
    # data model
    ("atom-style-atomic",
     dict(atom_style="atomic", properties="mass            1 1.0"),
     ["peri/nosb", "atom_style peri"]),
    ("no-atom-map", dict(atom_map=""), ["peri/nosb", "atom map"]),
    # pair_style / pair_coeff syntax
    ("pair-style-argument", dict(pair="pair_style      peri/nosb 0.003"),
     ["pair_style peri/nosb", "0.003"]),
    ("unknown-model", dict(coeff=coeff("hookean 1.0e9 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff", "hookean", "linear", "stvk", "neohookean"]),
    ("too-few-arguments", dict(coeff=coeff("linear 1.0e9 0.6e9 0.0030002 0.5")),
     ["pair_coeff peri/nosb", "7 arguments"]),
    ("no-model-name", dict(coeff=coeff("1.0e9 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb"]),
    ("type-out-of-range", dict(coeff=f"pair_coeff      1 2 {COEFF}"), ["2"]),
    ("K-zero", dict(coeff=coeff("linear 0 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "bulk modulus K", "0"]),
    ("K-negative", dict(coeff=coeff("linear -1.0e9 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "bulk modulus K", "-1.0e9"]),
    ("K-not-a-number", dict(coeff=coeff("linear stiff 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "bulk modulus K", "stiff"]),
    ("K-nan", dict(coeff=coeff("linear nan 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "bulk modulus K", "nan"]),
    ("K-inf", dict(coeff=coeff("linear inf 0.6e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "bulk modulus K", "inf"]),
    ("G-zero", dict(coeff=coeff("stvk 1.0e9 0 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "shear modulus G", "0"]),
    ("G-negative", dict(coeff=coeff("stvk 1.0e9 -5e8 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "shear modulus G", "-5e8"]),
    ("G-not-a-number", dict(coeff=coeff("stvk 1.0e9 0.6e9x 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "shear modulus G", "0.6e9x"]),
    ("horizon-zero", dict(coeff=coeff("neohookean 1.0e9 0.6e9 0 0.5 0.25")),
     ["pair_coeff peri/nosb", "horizon", "0"]),
    ("horizon-negative", dict(coeff=coeff("neohookean 1.0e9 0.6e9 -0.003 0.5 0.25")),
     ["pair_coeff peri/nosb", "horizon", "-0.003"]),
    ("horizon-not-a-number", dict(coeff=coeff("neohookean 1.0e9 0.6e9 3a 0.5 0.25")),
     ["pair_coeff peri/nosb", "horizon", "3a"]),
    # K > 0 and G > 0 always give -1 < nu < 1/2 in exact arithmetic; the only reachable
    # impossible ratio is nu = -1 in floating point (3K - 2G rounds to -2G)
    ("poisson-ratio-minus-one", dict(coeff=coeff("linear 1e-300 1.0e9 0.0030002 0.5 0.25")),
     ["pair_coeff peri/nosb", "poisson", "(-1, 0.5)"]),
    ("s00-zero-with-breaking", dict(coeff=coeff("linear 1.0e9 0.6e9 0.0030002 0 0.25")),
     ["pair_coeff peri/nosb", "s00", "break no"]),
    ("s00-not-a-number", dict(coeff=coeff("linear 1.0e9 0.6e9 0.0030002 half 0.25")),
     ["pair_coeff peri/nosb", "s00", "half"]),
    ("alpha-negative", dict(coeff=coeff("linear 1.0e9 0.6e9 0.0030002 0.5 -0.25")),
     ["pair_coeff peri/nosb", "alpha", "-0.25"]),
    ("unknown-keyword", dict(coeff=coeff(f"{COEFF} damping 0.3")),
     ["pair_coeff peri/nosb", "damping", "stabilize"]),
    ("stabilize-negative", dict(coeff=coeff(f"{COEFF} stabilize -0.1")),
     ["pair_coeff peri/nosb", "stabilize", "-0.1"]),
    ("stabilize-not-a-number", dict(coeff=coeff(f"{COEFF} stabilize yes")),
     ["pair_coeff peri/nosb", "stabilize", "yes"]),
    ("stabilize-missing-value", dict(coeff=coeff(f"{COEFF} stabilize")),
     ["pair_coeff peri/nosb", "stabilize", "missing"]),
    ("break-not-boolean", dict(coeff=coeff(f"{COEFF} break maybe")), ["maybe"]),
    ("contact-missing-value", dict(coeff=coeff(f"{COEFF} contact")),
     ["pair_coeff peri/nosb", "contact", "missing"]),
    ("pair-coeff-before-box",
     dict(before_box=f"pair_style      peri/nosb\npair_coeff      * * {COEFF}"),
     ["pair_coeff", "box"]),
    ("no-pair-coeff", dict(coeff=""), ["pair coeffs"]),
    # the package's other styles without the pair style
    ("compute-without-pair-style",
     dict(pair="pair_style      peri/lps", coeff=LPS_COEFF,
          after="compute         c all nosb/atom"),
     ["compute nosb/atom", "peri/nosb"]),
    ("compute-extra-argument", dict(after="compute         c all nosb/atom 3"),
     ["compute nosb/atom"]),
    ("family-fix-without-pair-style",
     dict(pair="pair_style      peri/lps", coeff=LPS_COEFF,
          after="fix             f all nosb/family"),
     ["nosb/family", "peri/nosb"]),
    ("family-fix-argument", dict(after="fix             f all nosb/family 3"),
     ["fix nosb/family"]),
    # geometry the families cannot be built from
    ("periodic-box-shorter-than-two-horizons", dict(boundary="p p p", n=5),
     ["peri/nosb", "periodic", "horizon"]),
    # bond families are stored by atom ID: IDs that change after the families were built
    # (delete_atoms renumbers by default, reset_atoms id) make every bond point at another
    # atom; the run must stop instead of computing with the wrong partners (measured before
    # the fix: pe of an undeformed block 1.7e11 and 3.7e11 with no error)
    ("atom-ids-compressed-by-delete-atoms",
     dict(after="run             0\n"
                "region          cut block INF 0.0025 INF INF INF INF units box\n"
                "delete_atoms    region cut"),
     ["peri/nosb", "atom IDs", "compress no"]),
    ("atom-ids-reset", dict(after="run             0\nreset_atoms     id sort yes"),
     ["peri/nosb", "atom IDs", "reset_atoms"]),
    ("two-atoms-at-one-position",
     dict(after="create_atoms    1 single 0.0 0.0 0.0 units box"),
     ["peri/nosb", "same position"]),
]


TWO_D = """
units           si
dimension       2
boundary        s s p
atom_style      peri
atom_modify     map array
lattice         sq 0.001
region          block block -0.5 5.5 -0.5 5.5 -0.5 0.5
create_box      1 block
create_atoms    1 region block
set             group all density 1000
set             group all volume 1.0e-9
pair_style      peri/nosb
pair_coeff      * * linear 1.0e9 0.6e9 0.0030002 0.5 0.25
run             0
"""


def test_two_dimensions_is_an_error(tmp_path):
    run = run_deck(TWO_D, tmp_path, check=False)
    assert run.returncode > 0, run.describe()
    line = error_line(run)
    assert "peri/nosb" in line and "3d" in line, line


def error_line(run) -> str:
    assert run.errors, run.describe()
    return run.errors[0]


@pytest.mark.parametrize("case,changes,expected", BAD_INPUT, ids=[c[0] for c in BAD_INPUT])
def test_bad_input_is_an_error(tmp_path, case, changes, expected):
    run = run_deck(deck(**changes), tmp_path, check=False)
    assert run.returncode > 0, run.describe()  # an error exit, not a signal, not success
    line = error_line(run)
    for word in expected:
        assert word.lower() in line.lower(), (word, line)
    assert "Segmentation" not in run.stdout + run.stderr
    assert not re.search(r"Signal: |signal \d+", run.stdout + run.stderr), run.stderr


@pytest.mark.parametrize("keywords", ["break no", "contact no", "stabilize 0",
                                      "stabilize 0.5 break yes contact yes"])
def test_valid_keywords_are_accepted(tmp_path, keywords):
    # the positive counterpart of the keyword errors above (and s00 = 0 is fine when bonds
    # cannot break, as the s00 error message suggests)
    s00 = "0" if keywords == "break no" else "0.5"
    run_deck(deck(coeff=coeff(f"linear 1.0e9 0.6e9 0.0030002 {s00} 0.25 {keywords}")), tmp_path)


LOST_PARTNER = """
units           si
boundary        s s s
atom_style      peri
atom_modify     map array
lattice         sc 0.001
region          block block -0.5 7.5 -0.5 3.5 -0.5 3.5
create_box      1 block
create_atoms    1 region block
set             group all density 1000
set             group all volume 1.0e-9
neighbor        0.001 bin
pair_style      peri/nosb
pair_coeff      * * linear 1.0e9 0.6e9 0.0030002 0.5 0.25 break no
run             0
region          far block 0.0036 INF INF INF INF INF units box
group           far region far
displace_atoms  far move 0.02 0.0 0.0 units box
run             0
"""


@pytest.mark.mpi
def test_partner_lost_from_the_ghosts_is_an_error(tmp_path):
    # Unbreakable bonds pulled 20 spacings long on 2 ranks: the partners are beyond the ghost
    # cutoff (horizon + skin = 4 spacings). The family fix must say which partner of which
    # atom is missing and what to change, not read a wrong atom or crash.
    run = run_deck(LOST_PARTNER, tmp_path, nprocs=2, check=False)
    assert "with 2 MPI tasks" in run.log or "2 by 1 by 1" in run.log + run.stdout
    assert run.returncode > 0, run.describe()
    line = next(ln for ln in (run.stdout + run.log).splitlines() if "ERROR" in ln)
    for word in ("peri/nosb", "partner", "ghost", "comm_modify cutoff"):
        assert word in line, (word, line)
    assert re.search(r"atom \d+ of atom \d+", line), line
