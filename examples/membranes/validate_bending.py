#!/usr/bin/env python3
"""The bending validation table of examples/membranes/README.md ("Bending on any mesh"), every
row from build/lmp runs:

    python3 validate_bending.py [--lmp ../../build/lmp] [--only plate|simply|elastica|cylinder]
        [--bending plate|hinge] [--kinds KIND ...] [--cells A ...]

Five mesh kinds of tools/make_sheet.py: equilateral (--pattern equilateral), right (every
square cut along the same diagonal), alternate (diagonals criss-crossing), jittered (alternate,
--jitter 0.25 --seed 3) and graded (alternate, --grade 2: cells growing by 2 across the sheet).

plate: the 30 cm square plate of in.plate (E = 100 MPa, nu = 0, t = 2 cm, bend auto: D =
E t^3 / 12) clamped by its two top rows of vertices and sagging under its weight q = rho g t,
at 1 cm and 5 mm cells (horizon 3 cells, fix sissm with precond amg, four 0.2 s backward Euler
steps); the free edge's mean sag against q L^4 / (8 D) with L from the middle of the two held
rows to the free edge (L mid) and from the inner held row (L inner).

simply: the same square at nu = 0.3 (D = E t^3 / (12 (1 - nu^2))), its rim held, under its
weight: the centre deflection against Timoshenko's 0.00406 q a^4 / D.

elastica: the clamped plate at 1 cm with E lowered to alpha = q L_mid^3 / D = 5 (the free edge
drops by half the length), against the heavy elastica (tools/elastica.py).

cylinder: the same 1 cm sheets with bend 1 (D = 1 N m) and a membrane of E = 1 Pa, bent
without stretching into a cylinder of curvature kappa = 4 / m about an axis at 0, 30, 45, 60
and 90 degrees to the mesh rows (x), positions set after a run of zero steps has built the
families from the flat sheet; the energy of `run 0` (sum over the atoms of pe/atom times their
volume) against D kappa^2 / 2 times the sheet's area.

Each row prints the measured value over the formula's, and the static runs the relative change
of their answer over the last step. About 7 minutes on one core (2026-11-30), most of it the
5 mm plates.
"""
import argparse
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import make_sheet as ms  # noqa: E402
from dump_to_vtu import read_dump  # noqa: E402
from elastica import heavy_elastica_drop  # noqa: E402

KINDS = {"equilateral": dict(pattern="equilateral"),
         "right": dict(pattern="right"),
         "alternate": dict(pattern="alternate"),
         "jittered": dict(pattern="alternate", jitter=0.25, seed=3),
         "graded": dict(pattern="alternate", grade=2.0)}
SIDE = 0.3
E, T, RHO, G = 1.0e8, 0.02, 1000.0, 9.81
ANGLES = (0, 30, 45, 60, 90)
KAPPA = 4.0
BENDING = ""    # " bending plate|hinge" (--bending), or the pair's default
PRECOND = "amg"    # fix sissm's preconditioner of the plate runs (--precond)
TOLERANCE = None    # fix sissm's tolerance of the plate runs (--tolerance), or tolerance(a)


def tolerance(a):
    """fix sissm's tolerance for a plate of cell size a at 0.2 s steps: above the round-off floor
    that fix sissm reports for the convergence measure (it warns when the tolerance is below it;
    measured 6.7e-7 m at 1 cm and 8.6e-5 m at 5 mm), where a tighter one makes every step fail.
    The sag of the last two steps agrees to 1e-4 or better (printed)."""
    if TOLERANCE is not None:
        return TOLERANCE
    return 1e-5 if a >= 0.01 else 2e-4


def rows_of(vertices):
    """The rows of the sheet as lists of vertex indices, bottom first (make_sheet lists them row
    by row; a row ends where x falls back to the left edge)."""
    rows, start = [], 0
    for k in range(1, len(vertices) + 1):
        if k == len(vertices) or vertices[k][0] < vertices[k - 1][0]:
            rows.append(list(range(start, k)))
            start = k
    return rows


def run_lmp(lmp, deck, workdir):
    (Path(workdir) / "in.deck").write_text(deck)
    out = subprocess.run([str(lmp), "-in", "in.deck", "-log", "log.deck"], cwd=workdir,
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"build/lmp failed in {workdir}:\n{out.stdout[-2000:]}\n{out.stderr}")
    return out.stdout


def ids(indices):
    return " ".join(str(i + 1) for i in indices)


def sheet_head(a, modulus, nu, extra="", zlo=-0.3, zhi=0.1):
    """The deck's lines up to the neighbor list: sheet.obj as a membrane of a linear material
    with modulus and nu, horizon 3 cells, bend auto (and the --bending keyword)."""
    K, Gs = modulus / (3 * (1 - 2 * nu)), modulus / (2 * (1 + nu))
    return f"""units si
boundary f f f
atom_style peri
atom_modify map array
region box block -0.2 0.2 -0.2 0.2 {zlo} {zhi}
create_box 1 box
read_mesh sheet.obj type 1 thickness {T} density {RHO}
pair_style peri/nosb
pair_coeff * * linear {K} {Gs} {3.0006 * a} 0 0 break no membrane yes bend auto{BENDING}{extra}
neighbor {a} bin
"""


def plate(lmp, kind, a, workdir, alpha=None, width=SIDE, nu=0.0):
    """Sag of the clamped plate over q L^4 / (8 D), L from the middle of the two held rows and
    from the inner held row; with alpha, E is lowered to D = q L_mid^3 / alpha and the drop is
    compared with the heavy elastica of q L^3 / D for each L (large deflection: alpha = 5 drops
    the free edge by half the length; six backward Euler steps of 1 s). With width and nu (a
    narrow strip): the sag over the beam's q L^4 / (8 E t^3 / 12) instead, and the curvature
    across the strip over that along it at mid-length (-nu where the strip curls freely)."""
    vertices, faces = ms.rectangle(width, SIDE, a, **KINDS[kind])
    ms.write_obj(Path(workdir) / "sheet.obj", vertices, faces)
    rows = rows_of(vertices)
    held = rows[-1] + rows[-2]
    mean_y = [sum(vertices[i][1] for i in r) / len(r) for r in rows]
    L_mid, L_inner = 0.5 * (mean_y[-1] + mean_y[-2]) - mean_y[0], mean_y[-2] - mean_y[0]
    q, D = RHO * G * T, E * T ** 3 / 12.0
    if width != SIDE:
        D = E * T ** 3 / 12.0    # the beam's
    modulus, dt, steps, contact = E, 0.2, 4, ""
    if alpha is not None:
        # (contact no: the 1 s steps move the free edge farther than short-range contact follows)
        D = q * L_mid ** 3 / alpha
        modulus, dt, steps, contact = 12.0 * D / T ** 3, 1.0, 6, " contact no"
    deck = sheet_head(a, modulus, nu, contact) + f"""group held id {ids(held)}
group free subtract all held
group tip id {ids(rows[0])}
compute tipz tip reduce ave z
fix grav all gravity {G} vector 0 0 -1
timestep {dt}
fix integrate free sissm solver krylov precond {PRECOND} iterations 20000 tolerance {tolerance(a)}
thermo_style custom step pe c_tipz f_integrate[1]
thermo_modify format float %.10g
run {steps - 1}
variable before equal $(c_tipz:%.12g)
run 1
print "TIPZ $(c_tipz:%.12g) ${{before}}"
write_dump all custom final.txt id x y z modify format float %.15g
"""
    out = run_lmp(lmp, deck, workdir)
    tipz, before = (float(v) for v in re.search(r"^TIPZ (\S+) (\S+)", out, re.M).groups())
    if width != SIDE:
        return [-tipz / (q * L ** 4 / (8.0 * D)) for L in (L_mid, L_inner)] + \
            [tipz / before - 1.0, curvature_ratio(Path(workdir) / "final.txt",
                                                   0.5 * (mean_y[0] + mean_y[-2]), 2.0 * a)]
    if alpha is not None:
        return [-tipz / (heavy_elastica_drop(q * L ** 3 / D) * L) for L in (L_mid, L_inner)] + \
            [tipz / before - 1.0]
    return [-tipz / (q * L ** 4 / (8.0 * D)) for L in (L_mid, L_inner)] + [tipz / before - 1.0]


def quadratic_fit(dump, x0, y0, near):
    """Coefficients of 1, x, y, x^2, x y, y^2 (x, y from (x0, y0)) of the quadratic fitted to the
    z of the vertices of a write_dump custom file (x y z columns) for which near(x, y) holds."""
    import numpy as np
    _, columns, rows = read_dump(dump)[-1]
    pts = np.array([[float(r[columns.index(c)]) for c in ("x", "y", "z")] for r in rows])
    x, y = pts[:, 0] - x0, pts[:, 1] - y0
    keep = near(x, y)
    x, y = x[keep], y[keep]
    A = np.column_stack([np.ones_like(x), x, y, x * x, x * y, y * y])
    return np.linalg.lstsq(A, pts[keep, 2], rcond=None)[0]


def curvature_ratio(dump, y_mid, reach):
    """kappa_xx / kappa_yy of a quadratic w(x, y) fitted to the vertices within reach of y_mid in
    y (all across the strip)."""
    c = quadratic_fit(dump, 0.0, y_mid, lambda x, y: abs(y) < reach)
    return c[3] / c[5]


def simply_supported(lmp, kind, a, workdir, nu=0.3):
    """Centre deflection of the simply supported square plate under a uniform load over
    Timoshenko's 0.00406 q a^4 / D (nu = 0.3; Timoshenko and Woinowsky-Krieger, Theory of Plates
    and Shells, 1959). The rim's vertices are held (w = 0 and no in-plane motion: at a
    deflection of 0.4% of the thickness the membrane force this brings is of second order), the
    bending moment at the rim is free (the energy's natural boundary condition). The deflection
    at the centre: a quadratic in x and y fitted to the vertices within two cells of it."""
    import numpy as np
    vertices, faces = ms.rectangle(SIDE, SIDE, a, **KINDS[kind])
    ms.write_obj(Path(workdir) / "sheet.obj", vertices, faces)
    xs = [v[0] for v in vertices]
    ys = [v[1] for v in vertices]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    eps = 1e-9
    rim = [i for i, v in enumerate(vertices)
           if min(v[0] - x0, x1 - v[0], v[1] - y0, y1 - v[1]) < eps]
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    side = 0.5 * ((x1 - x0) + (y1 - y0))
    q, D = RHO * G * T, E * T ** 3 / (12.0 * (1.0 - nu * nu))
    deck = sheet_head(a, E, nu, zlo=-0.1) + f"""group held id {ids(rim)}
group free subtract all held
fix grav all gravity {G} vector 0 0 -1
timestep 0.2
fix integrate free sissm solver krylov precond {PRECOND} iterations 10000 tolerance {tolerance(a)}
thermo_style custom step pe f_integrate[1]
run 3
write_dump all custom before.txt id x y z modify format float %.15g
run 1
write_dump all custom after.txt id x y z modify format float %.15g
"""
    run_lmp(lmp, deck, workdir)

    def centre(name):
        return quadratic_fit(Path(workdir) / name, cx, cy,
                             lambda x, y: np.hypot(x, y) < 2.0 * a)[0]
    w, before = centre("after.txt"), centre("before.txt")
    return [-w / (0.00406 * q * side ** 4 / D), w / before - 1.0]


def cylinder(lmp, kind, angle, workdir, a=0.01):
    """Energy of the sheet bent into a cylinder over D kappa^2 / 2 times its area."""
    vertices, faces = ms.rectangle(SIDE, SIDE, a, **KINDS[kind])
    ms.write_obj(Path(workdir) / "sheet.obj", vertices, faces)
    area = ms.mesh_stats(vertices, faces)["area"]
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    R = 1.0 / KAPPA
    # u across the axis (axis along (c, s)): arc length u becomes R sin(u/R) in the plane and
    # R (1 - cos(u/R)) out of it (from the stored flat positions: set changes x before y and z)
    deck = f"""units si
boundary f f f
atom_style peri
atom_modify map array
region box block -0.4 0.4 -0.4 0.4 -0.2 0.4
create_box 1 box
read_mesh sheet.obj type 1 thickness 0.001 density 1000
pair_style peri/nosb
pair_coeff * * linear {1 / 3} {1 / 2} {3.0006 * a} 0 0 break no membrane yes bend 1.0{BENDING}
neighbor {a} bin
run 0 post no
fix ref all store/state 0 x y
variable u atom -f_ref[1]*{s}+f_ref[2]*{c}
variable v atom f_ref[1]*{c}+f_ref[2]*{s}
variable nx atom v_v*{c}-{R}*sin(v_u/{R})*{s}
variable ny atom v_v*{s}+{R}*sin(v_u/{R})*{c}
variable nz atom {R}*(1-cos(v_u/{R}))
set group all x v_nx y v_ny z v_nz
compute pea all pe/atom
compute vol all property/atom vfrac
variable ev atom c_pea*c_vol
compute etot all reduce sum v_ev
thermo_style custom step pe c_etot
run 0 post no
print "ENERGY $(c_etot:%.12g)"
"""
    out = run_lmp(lmp, deck, workdir)
    energy = float(re.search(r"^ENERGY (\S+)", out, re.M).group(1))
    return energy / (0.5 * KAPPA ** 2 * area)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=str(HERE.parents[1] / "build" / "lmp"))
    ap.add_argument("--only", choices=("plate", "simply", "elastica", "strip", "cylinder"))
    ap.add_argument("--bending", choices=("plate", "hinge"),
                    help="the bending energy (pair_coeff bending); default: the pair's")
    ap.add_argument("--kinds", nargs="+", choices=list(KINDS), default=list(KINDS))
    ap.add_argument("--cells", nargs="+", type=float, default=[0.01, 0.005],
                    help="plate cell sizes (m)")
    ap.add_argument("--precond", choices=("amg", "block"), default="amg")
    ap.add_argument("--tolerance", type=float,
                    help="fix sissm tolerance of the plate runs (m); default: 1e-5 at 1 cm "
                    "cells, 2e-4 at 5 mm")
    args = ap.parse_args()
    global BENDING, PRECOND, TOLERANCE
    TOLERANCE = args.tolerance
    BENDING = f" bending {args.bending}" if args.bending else ""
    PRECOND = args.precond
    with tempfile.TemporaryDirectory() as tmp:
        if args.only in (None, "plate"):
            print("plate sag / (q L^4 / 8D)   " + "  ".join(f"{k:>11s}" for k in args.kinds))
            for a in args.cells:
                vals = [plate(args.lmp, kind, a, tmp) for kind in args.kinds]
                for col, what in enumerate(("L mid  ", "L inner")):
                    print(f"  {a * 1000:4.0f} mm cells, {what}   " +
                          "  ".join(f"{v[col]:11.4f}" for v in vals), flush=True)
                print(f"  (last step's change)      " +
                      "  ".join(f"{v[2]:11.1e}" for v in vals), flush=True)
        if args.only in (None, "simply"):
            print("simply supported w / (0.00406 q a^4 / D), nu = 0.3   " +
                  "  ".join(f"{k:>11s}" for k in args.kinds))
            for a in args.cells:
                vals = [simply_supported(args.lmp, kind, a, tmp) for kind in args.kinds]
                print(f"  {a * 1000:4.0f} mm cells                                  " +
                      "  ".join(f"{v[0]:11.4f}" for v in vals), flush=True)
                print(f"  (last step's change)                          " +
                      "  ".join(f"{v[1]:11.1e}" for v in vals), flush=True)
        if args.only in (None, "elastica"):
            print("heavy elastica, alpha = 5  " + "  ".join(f"{k:>11s}" for k in args.kinds))
            vals = [plate(args.lmp, kind, 0.01, tmp, alpha=5.0) for kind in args.kinds]
            for col, what in enumerate(("L mid  ", "L inner")):
                print(f"    10 mm cells, {what}   " + "  ".join(f"{v[col]:11.4f}" for v in vals),
                      flush=True)
            print(f"  (last step's change)      " + "  ".join(f"{v[2]:11.1e}" for v in vals),
                  flush=True)
        if args.only in (None, "strip"):
            print("strip 6 cm x 30 cm, sag / (q L^4 / (8 E t^3 / 12)) and kappa_across / "
                  "kappa_along " + "  ".join(f"{k:>11s}" for k in args.kinds))
            for nu in (0.0, 0.3):
                vals = [plate(args.lmp, kind, 0.01, tmp, width=0.06, nu=nu)
                        for kind in args.kinds]
                for col, what in ((1, "sag, L inner"), (3, "curvatures  ")):
                    print(f"  nu = {nu:.1f}, {what}      " +
                          "  ".join(f"{v[col]:11.4f}" for v in vals), flush=True)
        if args.only in (None, "cylinder"):
            print("cylinder E / (D k^2 A / 2) " + "  ".join(f"{k:>11s}" for k in args.kinds))
            for angle in ANGLES:
                vals = [cylinder(args.lmp, kind, angle, tmp) for kind in args.kinds]
                print(f"  axis at {angle:2d} deg            " +
                      "  ".join(f"{v:11.4f}" for v in vals), flush=True)


if __name__ == "__main__":
    main()
