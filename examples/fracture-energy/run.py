#!/usr/bin/env python3
"""Fracture energy G0 that a critical stretch s00 implies, per pair style: the rigid-halves
separation test (README.md), the numerical analogue of the bond-based derivation of
Silling & Askari (2005).

A slab (simple cubic lattice a, horizon delta = m a (+ 0.0002 a for integer m), periodic in x
and y with a width of floor(2 delta/a) + 1 spacings, one layer more per half in z) is cut by
the plane between its two halves; the upper half is moved rigidly along +z and every bond
crossing the plane breaks when its stretch reaches s00 (alpha = 0).  Since the halves are rigid,
the stretch of a crossing bond depends on the displacement u only, so the displacements at
which bonds break are known in advance: the deck in.separation visits exactly those (each
times 1 + 1e-7), and at each one `run 1` gives the state before (setup evaluation) and after
(step evaluation) the bonds break.  Measured per unit area A of the plane:

  work:   G0 = (1/A) sum over the segments between break events of the trapezoid of the force
          on the upper half (sum of f_z V over its particles, f a force density) times du;
  energy: G0 = (1/A) V sum over the events of (pe before - pe after)  (pe sums energy densities).

Both are the energy the separation dissipates; they agree whenever pe is the potential of the
forces (peri/pmb, peri/nosb).  For peri/lps LAMMPS tallies half of the deviatoric energy
(0.5*evdwl passed to ev_tally(i,i,...) with newton off): the work is the meaningful number there.

    /usr/bin/python3 examples/fracture-energy/run.py          # the tables (about 20 s)
    /usr/bin/python3 examples/fracture-energy/run.py --full   # + delta/a = 2.5 ... 6 (~5 min)
    options: --lmp PATH (default: PERI_SISSM_LMP or build/lmp), --keep DIR, --increments N
    (N equal increments up to the last break instead of the break events: shows convergence)
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
DECK = HERE / "in.separation"

A_LATTICE = 0.0005      # lattice constant (m), as examples/impact
K_REF = 14.9e9          # bulk modulus (Pa), as examples/impact
NU_REF = 0.25
S00_REF = 5.0e-4        # critical stretch of examples/impact
EPS_EVENT = 1.0e-7      # each event is visited at (1 + EPS_EVENT) times its break displacement


def shear_from_nu(k, nu):
    return 3.0 * k * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu))


def horizon(m, a=A_LATTICE):
    """Horizon of m lattice spacings: an integer m gets the usual 0.0002 a of margin (so that the
    shell at exactly m a is in the family); any other value is taken as it is."""
    return (m + 0.0002 if float(m).is_integer() else m) * a


# ---------------------------------------------------------------- formulas (continuum)

def g0_pmb_formula(k, delta, s0):
    """Silling & Askari (2005): s0 = sqrt(5 G0 / (9 K delta)) for c = 18 K / (pi delta^4)."""
    return 9.0 / 5.0 * k * delta * s0 ** 2


def g0_lps_formula(k, g, delta, s0):
    """Madenci & Oterkus (2014), 3D state-based:
    s0 = sqrt(G0 / ((3G + (3/4)^4 (K - 5G/3)) delta))."""
    return (3.0 * g + 0.75 ** 4 * (k - 5.0 * g / 3.0)) * delta * s0 ** 2


def g0_pmb_lattice_sum(k, m, s0, a=A_LATTICE):
    """The rigid-halves G0 of peri/pmb on the lattice, summed by hand: every bond crossing the
    plane breaks at the stretch s0 with the energy c beta s0^2 |xi| V^2 / 2 (beta: LAMMPS's
    partial-volume factor); a bond vector with z component xi_z crosses the plane xi_z / a
    times per lattice column (area a^2)."""
    d = horizon(m, a)
    c = 18.0 * k / (math.pi * d ** 4)
    n = int(math.floor(d / a))
    total = 0.0
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            for kz in range(1, n + 1):
                r = math.sqrt(i * i + j * j + kz * kz) * a
                if r > d:
                    continue
                beta = 1.0 if r <= d - a / 2 else (d + a / 2 - r) / a
                total += kz * 0.5 * c * beta * s0 ** 2 * r * a ** 6
    return total / a ** 2


# ---------------------------------------------------------------- break events

def break_displacements(m, s0, a=A_LATTICE):
    """Rigid displacements u (ascending) at which the bonds crossing the mid plane reach the
    stretch s0: a bond (rho, xi_z) with |xi| = sqrt(rho^2 + xi_z^2) <= delta has the stretch
    sqrt(rho^2 + (xi_z + u)^2) / |xi| - 1, which reaches s0 at
    u = sqrt(|xi|^2 (1 + s0)^2 - rho^2) - xi_z.  Values closer than 1e-6 (relative) merge."""
    d2 = (horizon(m, 1.0)) ** 2
    n = int(math.floor(horizon(m, 1.0)))
    us = set()
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            for k in range(1, n + 1):
                r2 = i * i + j * j + k * k
                if r2 > d2:
                    continue
                rho2 = i * i + j * j
                us.add(math.sqrt(r2 * (1.0 + s0) ** 2 - rho2) - k)
    us = sorted(u * a for u in us)
    merged = [us[0]]
    for u in us[1:]:
        if u > merged[-1] * (1.0 + 1.0e-6):
            merged.append(u)
        else:
            merged[-1] = u
    return merged


# ---------------------------------------------------------------- running the deck

def lmp_path(arg=None):
    if arg:
        return Path(arg)
    return Path(os.environ.get("PERI_SISSM_LMP", REPO / "build" / "lmp"))


def thermo_tables(log):
    """Thermo tables (Step, PotEng, c_ftop) of a log, one list of rows per run."""
    tables, rows = [], None
    for line in log.splitlines():
        w = line.split()
        if w[:3] == ["Step", "PotEng", "c_ftop"]:
            rows = []
            continue
        if rows is None:
            continue
        if line.startswith("Loop time of"):
            tables.append(rows)
            rows = None
            continue
        try:
            rows.append([float(x) for x in w])
        except ValueError:
            pass
    return tables


def separate(style, coeff, m=3, s0=S00_REF, a=A_LATTICE, lmp=None, workdir=None,
             increments=None, nhalf=None):
    """Run the separation test; return dict(g0_work, g0_energy (J/m^2), events, residual_pe,
    peak_pe (energy per area after the last event, and its largest value), log (the text)).

    style, coeff: the pair style and what follows `pair_coeff * *` (its s00 must be s0 and its
    alpha 0).  increments: None = visit the break events; N = N equal increments up to 1.001
    times the last break displacement."""
    events = break_displacements(m, s0, a)
    if increments:
        umax = events[-1] * 1.001
        us = list(np.linspace(umax / increments, umax, increments))
    else:
        us = [u * (1.0 + EPS_EVENT) for u in events]
    steps = np.diff([0.0] + us)
    nxy = int(math.floor(2.0 * horizon(m, 1.0))) + 1    # periodic width > 2 horizons
    tmp = None
    if workdir is None:
        tmp = tempfile.TemporaryDirectory(prefix="fracture-energy-")
        workdir = tmp.name
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    tag = re.sub(r"[^A-Za-z0-9]+", "_", f"{style}_{coeff}_m{m}")[:80]
    inc = workdir / f"inc_{tag}.txt"
    inc.write_text("".join(f"{d:.17g}\n" for d in steps))
    log = workdir / f"log_{tag}.lammps"
    cmd = [str(lmp_path(lmp)), "-in", str(DECK), "-log", str(log), "-echo", "none", "-screen",
           "none", "-nocite", "-var", "style", style, "-var", "coeff", coeff, "-var", "a",
           repr(a), "-var", "delta", repr(horizon(m, a)), "-var", "increments", str(inc),
           "-var", "nxy", str(nxy), "-var", "nhalf", str(nhalf or nxy + 1)]
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, timeout=1200,
                          stdin=subprocess.DEVNULL)
    text = log.read_text(errors="replace") if log.exists() else ""
    if proc.returncode != 0 or "ERROR" in text:
        err = [ln for ln in (text + proc.stdout).splitlines() if "ERROR" in ln]
        raise RuntimeError(f"{style} {coeff}: lmp failed: {err or proc.stderr[-2000:]}")
    tables = thermo_tables(text)[2:]  # the first two are the runs 0 at u = 0 (see the deck)
    if len(tables) != len(us):
        raise RuntimeError(f"{style}: expected {len(us)} runs, found {len(tables)}")
    pre = np.array([t[0] for t in tables])    # rows: step pe ftop
    post = np.array([t[-1] for t in tables])
    area = (nxy * a) ** 2
    vol = a ** 3
    # work done on the upper half: -(force on it) du, trapezoid between events (the set of
    # intact bonds is fixed inside a segment, and the force is linear in u to O(s0))
    f_after_prev = np.concatenate([[0.0], post[:-1, 2]])
    work = -np.sum(0.5 * (f_after_prev + pre[:, 2]) * steps) * vol
    released = np.sum(pre[:, 1] - post[:, 1]) * vol
    if tmp is not None:
        tmp.cleanup()
    return dict(g0_work=work / area, g0_energy=released / area, events=len(us),
                residual_pe=post[-1, 1] * vol / area, peak_pe=pre[:, 1].max() * vol / area,
                log=text)


# ---------------------------------------------------------------- the three styles

def coeff_pmb(k, m, s0, a=A_LATTICE):
    d = horizon(m, a)
    return f"{18.0 * k / (math.pi * d ** 4):.17g} {d:.17g} {s0:.17g} 0.0"


def coeff_lps(k, g, m, s0, a=A_LATTICE):
    return f"{k:.17g} {g:.17g} {horizon(m, a):.17g} {s0:.17g} 0.0"


def coeff_nosb(k, g, m, s0, cs=2.0, model="linear", a=A_LATTICE, length=True):
    """peri/nosb's pair_coeff arguments, the deviation form named (length: the default)."""
    form = "length" if length else "vector"
    return (f"{model} {k:.17g} {g:.17g} {horizon(m, a):.17g} {s0:.17g} 0.0 stabilize {cs:.17g} "
            f"deviation {form}")


def kappa(res, m, s0, a=A_LATTICE):
    """G0 / (delta s0^2): a modulus (Pa)."""
    return res["g0_work"] / (horizon(m, a) * s0 ** 2)


# the relation of pair_coeff peri/nosb ... G0 (doc/pair_peri_nosb.rst, "Fracture energy"):
#   G0 = delta s00^2 (C_M (K + 4G/3) + C_L Cs K)            (deviation length, the default)
#   G0 = delta s00^2 (C_M (K + 4G/3) + C_S Cs K delta/h)    (deviation vector)
C_M = 0.58376
C_S = 1.19321
C_L = 1.00391
FIT_S0 = 1.0e-6         # the relation is the small-strain limit; fitted at this s00


def nosb_modulus(k, g, cs, delta, h, length=True):
    stab = C_L * cs * k if length else C_S * cs * k * delta / h
    return C_M * (k + 4.0 * g / 3.0) + stab


def g0_nosb_relation(k, g, cs, delta, s0, h, length=True):
    return delta * s0 ** 2 * nosb_modulus(k, g, cs, delta, h, length)


def s00_nosb_relation(g0, k, g, cs, delta, h, length=True):
    return math.sqrt(g0 / (delta * nosb_modulus(k, g, cs, delta, h, length)))


FIT_CASES = [(0.25, 0.0), (0.0, 0.0), (0.4, 0.0), (0.25, 2.0), (0.25, 1.0)]   # (nu, Cs)


def fit_nosb(m, lmp, workdir, s0=FIT_S0, a=A_LATTICE, length=True):
    """G0 / (delta s0^2) = cK K + cG G + cS Cs K for peri/nosb linear with the deviation form
    `length` or vector: least squares on the FIT_CASES; returns the coefficients and the
    largest relative residual."""
    rows, rhs = [], []
    for nu, cs in FIT_CASES:
        g = shear_from_nu(K_REF, nu)
        res = separate("peri/nosb", coeff_nosb(K_REF, g, m, s0, cs, a=a, length=length), m, s0,
                       a, lmp, workdir)
        rows.append([1.0, g / K_REF, cs])
        rhs.append(kappa(res, m, s0, a) / K_REF)
    coef, *_ = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)
    resid = np.array(rows) @ coef - np.array(rhs)
    return coef, float(np.max(np.abs(resid / np.array(rhs))))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp")
    ap.add_argument("--keep", help="keep the logs in this directory")
    ap.add_argument("--full", action="store_true",
                    help="also the lattice resolutions delta/a = 2.5 ... 6 (about 5 minutes)")
    ap.add_argument("--increments", type=int, default=0,
                    help="also run the m = 3 styles with N equal increments (convergence)")
    args = ap.parse_args()
    workdir = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="fracture-energy-"))
    lmp = args.lmp
    k, g, s0 = K_REF, shear_from_nu(K_REF, NU_REF), S00_REF
    d3 = horizon(3)

    print(f"Rigid-halves separation: simple cubic lattice a = {A_LATTICE} m, horizon "
          f"3.0002 a, alpha = 0, K = {k:g} Pa, nu = {NU_REF} (G = {g:g} Pa), s00 = {s0:g}\n")
    print("| style | G0 measured, work (J/m^2) | energy | formula | measured/formula | "
          "G0/(K delta s00^2) |")
    print("|---|---|---|---|---|---|")
    rows = [
        ("peri/pmb", coeff_pmb(k, 3, s0), g0_pmb_formula(k, d3, s0), "9/5 K delta s0^2"),
        ("peri/lps", coeff_lps(k, g, 3, s0), g0_lps_formula(k, g, d3, s0), "Madenci-Oterkus"),
        ("peri/nosb linear Cs=2", coeff_nosb(k, g, 3, s0, 2.0),
         g0_nosb_relation(k, g, 2.0, d3, s0, A_LATTICE), "G0 keyword relation"),
        ("peri/nosb linear Cs=0", coeff_nosb(k, g, 3, s0, 0.0),
         g0_nosb_relation(k, g, 0.0, d3, s0, A_LATTICE), "G0 keyword relation"),
        ("peri/nosb linear Cs=2 deviation vector", coeff_nosb(k, g, 3, s0, 2.0, length=False),
         g0_nosb_relation(k, g, 2.0, d3, s0, A_LATTICE, False), "G0 keyword relation"),
    ]
    measured = {}
    for name, coeff, formula, fname in rows:
        style = name.split()[0]
        res = separate(style, coeff, 3, s0, lmp=lmp, workdir=workdir)
        measured[name] = res["g0_work"]
        print(f"| {name} | {res['g0_work']:.4f} | {res['g0_energy']:.4f} | {formula:.4f} "
              f"({fname}) | {res['g0_work'] / formula:.4f} | {kappa(res, 3, s0) / k:.4f} |",
              flush=True)
        if args.increments:
            r2 = separate(style, coeff, 3, s0, lmp=lmp, workdir=workdir,
                          increments=args.increments)
            print(f"| {name}, {args.increments} equal increments | {r2['g0_work']:.4f} | "
                  f"{r2['g0_energy']:.4f} | | | |", flush=True)

    print(f"\nperi/pmb, the same sum done by hand over the lattice bonds: "
          f"{g0_pmb_lattice_sum(k, 3, s0):.4f} J/m^2 (the procedure is exact; the 13% below the "
          "formula are the lattice and its partial volumes).")
    lrows, lrhs = [], []
    for nu in (0.25, 0.0, 0.4):
        gl = shear_from_nu(k, nu)
        res = separate("peri/lps", coeff_lps(k, gl, 3, s0), 3, s0, lmp=lmp, workdir=workdir)
        lrows.append([1.0, gl / k])
        lrhs.append(kappa(res, 3, s0) / k)
    lc, *_ = np.linalg.lstsq(np.array(lrows), np.array(lrhs), rcond=None)
    lres = np.max(np.abs(np.array(lrows) @ lc / np.array(lrhs) - 1.0))
    print(f"peri/lps, fit on nu = 0.25, 0, 0.4: G0 = delta s00^2 ({lc[0]:.4f} K + {lc[1]:.4f} G) "
          f"(largest residual {lres:.1e}); Madenci-Oterkus: delta s00^2 "
          f"({0.75 ** 4:.4f} K + {3.0 - 5.0 / 3.0 * 0.75 ** 4:.4f} G).")

    lps, nosb = measured["peri/lps"], measured["peri/nosb linear Cs=2"]
    print(f"\nAt equal s00, peri/nosb (Cs = 2) dissipates {nosb / lps:.2f} times the energy of "
          f"peri/lps; the same G0 as peri/lps needs s00 = {s0 * math.sqrt(lps / nosb):.4g} "
          f"(= s00_nosb_relation: "
          f"{s00_nosb_relation(lps, k, g, 2.0, d3, A_LATTICE):.4g}).")

    print("\nperi/nosb linear, fit G0 = delta s00^2 (cK K + cG G + cS Cs K) on (nu, Cs) = "
          f"{FIT_CASES}, at s00 = {FIT_S0:g} (small-strain limit):\n")
    print("| deviation | delta/a | cK | cG | cG/cK | cS | cS/(delta/a) | "
          "largest relative residual |")
    print("|---|---|---|---|---|---|---|---|")
    ms = [3, 2.5, 2.8, 3.015, 3.5, 4, 4.5, 5, 6] if args.full else [3]
    for length in (True, False):
        for m in ms:
            coef, resid = fit_nosb(m, lmp, workdir, length=length)
            dh = horizon(m, 1.0)
            print(f"| {'length' if length else 'vector'} | {dh:.4f} | {coef[0]:.5f} | "
                  f"{coef[1]:.5f} | {coef[1] / coef[0]:.5f} | {coef[2]:.5f} | "
                  f"{coef[2] / dh:.5f} | {resid:.1e} |", flush=True)

    print("\nChecks: peri/nosb G0 measured against the G0 keyword relation "
          f"(C_M = {C_M}, C_L = {C_L}, C_S = {C_S}, h = a):\n")
    print("| case | deviation | G0 measured (J/m^2) | relation | measured/relation |")
    print("|---|---|---|---|---|")
    checks = [
        ("linear nu=0.1 Cs=0.5", "linear", K_REF, shear_from_nu(K_REF, 0.1), 0.5, s0, 3, A_LATTICE),
        ("linear nu=-0.3 Cs=3", "linear", K_REF, shear_from_nu(K_REF, -0.3), 3.0, s0, 3,
         A_LATTICE),
        ("linear K=1 GPa nu=0.33 Cs=2, a=2 mm", "linear", 1e9, shear_from_nu(1e9, 0.33), 2.0, s0,
         3, 0.002),
        ("stvk (nu=0.25, Cs=2)", "stvk", K_REF, g, 2.0, s0, 3, A_LATTICE),
        ("neohookean (nu=0.25, Cs=2)", "neohookean", K_REF, g, 2.0, s0, 3, A_LATTICE),
        ("linear s00=5e-3 (nu=0.25, Cs=2)", "linear", K_REF, g, 2.0, 5e-3, 3, A_LATTICE),
        ("neohookean s00=5e-3 (nu=0.25, Cs=2)", "neohookean", K_REF, g, 2.0, 5e-3, 3, A_LATTICE),
        ("neohookean s00=5e-2 (nu=0.25, Cs=2)", "neohookean", K_REF, g, 2.0, 5e-2, 3, A_LATTICE),
    ]
    if args.full:
        checks += [(f"linear delta = {m} a (nu=0.25, Cs=2)", "linear", K_REF, g, 2.0, s0, m,
                    A_LATTICE) for m in [2.5, 2.8, 3.015, 3.5, 4, 4.5, 5, 6]]
    for length in (True, False):
        for name, model, kk, gg, cs, ss, m, aa in checks:
            res = separate("peri/nosb", coeff_nosb(kk, gg, m, ss, cs, model, aa, length), m, ss,
                           aa, lmp, workdir)
            rel = g0_nosb_relation(kk, gg, cs, horizon(m, aa), ss, aa, length)
            print(f"| {name} | {'length' if length else 'vector'} | {res['g0_work']:.5g} | "
                  f"{rel:.5g} | {res['g0_work'] / rel:.4f} |", flush=True)

    if not args.keep:
        import shutil
        shutil.rmtree(workdir, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
