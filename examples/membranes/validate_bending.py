#!/usr/bin/env python3
"""The bending validation table of examples/membranes/README.md ("Bending on any mesh"), every
row from build/lmp runs:

    python3 validate_bending.py [--lmp ../../build/lmp] [--only plate|cylinder]

Five mesh kinds of tools/make_sheet.py: equilateral (--pattern equilateral), right (every
square cut along the same diagonal), alternate (diagonals criss-crossing), jittered (alternate,
--jitter 0.25 --seed 3) and graded (alternate, --grade 2: cells growing by 2 across the sheet).

plate: the 30 cm square plate of in.plate (E = 100 MPa, nu = 0, t = 2 cm, bend auto: D =
E t^3 / 12) clamped by its two top rows of vertices and sagging under its weight q = rho g t,
at 1 cm and 5 mm cells (horizon 3 cells, fix sissm with precond amg, four 0.2 s backward Euler
steps); the free edge's mean sag against q L^4 / (8 D) with L from the middle of the two held
rows to the free edge (L mid) and from the inner held row (L inner).

cylinder: the same 1 cm sheets with bend 1 (D = 1 N m) and a membrane of E = 1 Pa, bent
without stretching into a cylinder of curvature kappa = 4 / m about an axis at 0, 30, 45, 60
and 90 degrees to the mesh rows (x), positions set after a run of zero steps has built the
families from the flat sheet; the energy of `run 0` (sum over the atoms of pe/atom times their
volume) against D kappa^2 / 2 times the sheet's area.

Each row prints the measured value over the formula's. A few minutes on one core.
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
TOLERANCE = 1e-7    # fix sissm's tolerance of the plate runs (--tolerance)


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


def plate(lmp, kind, a, workdir):
    """Sag of the clamped plate over q L^4 / (8 D), L from the middle of the two held rows and
    from the inner held row."""
    vertices, faces = ms.rectangle(SIDE, SIDE, a, **KINDS[kind])
    ms.write_obj(Path(workdir) / "sheet.obj", vertices, faces)
    rows = rows_of(vertices)
    held = rows[-1] + rows[-2]
    mean_y = [sum(vertices[i][1] for i in r) / len(r) for r in rows]
    L_mid, L_inner = 0.5 * (mean_y[-1] + mean_y[-2]) - mean_y[0], mean_y[-2] - mean_y[0]
    q, D = RHO * G * T, E * T ** 3 / 12.0
    deck = f"""units si
boundary f f f
atom_style peri
atom_modify map array
region box block -0.2 0.2 -0.2 0.2 -0.3 0.1
create_box 1 box
read_mesh sheet.obj type 1 thickness {T} density {RHO}
pair_style peri/nosb
pair_coeff * * linear {E / 3} {E / 2} {3.0006 * a} 0 0 break no membrane yes bend auto{BENDING}
neighbor {a} bin
group held id {ids(held)}
group free subtract all held
group tip id {ids(rows[0])}
compute tipz tip reduce ave z
fix grav all gravity {G} vector 0 0 -1
timestep 0.2
fix integrate free sissm solver krylov precond {PRECOND} iterations 10000 tolerance {TOLERANCE}
thermo_style custom step pe c_tipz f_integrate[1]
thermo_modify format float %.10g
run 4
print "TIPZ $(c_tipz:%.12g)"
"""
    out = run_lmp(lmp, deck, workdir)
    tipz = float(re.search(r"^TIPZ (\S+)", out, re.M).group(1))
    return [-tipz / (q * L ** 4 / (8.0 * D)) for L in (L_mid, L_inner)]


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
    ap.add_argument("--only", choices=("plate", "cylinder"))
    ap.add_argument("--bending", choices=("plate", "hinge"),
                    help="the bending energy (pair_coeff bending); default: the pair's")
    ap.add_argument("--kinds", nargs="+", choices=list(KINDS), default=list(KINDS))
    ap.add_argument("--cells", nargs="+", type=float, default=[0.01, 0.005],
                    help="plate cell sizes (m)")
    ap.add_argument("--precond", choices=("amg", "block"), default="amg")
    ap.add_argument("--tolerance", type=float, default=1e-7,
                    help="fix sissm tolerance of the plate runs (m)")
    args = ap.parse_args()
    global BENDING, PRECOND, TOLERANCE
    TOLERANCE = args.tolerance
    BENDING = f" bending {args.bending}" if args.bending else ""
    PRECOND = args.precond
    with tempfile.TemporaryDirectory() as tmp:
        if args.only != "cylinder":
            print("plate sag / (q L^4 / 8D)   " + "  ".join(f"{k:>11s}" for k in args.kinds))
            for a in args.cells:
                vals = [plate(args.lmp, kind, a, tmp) for kind in args.kinds]
                for col, what in enumerate(("L mid  ", "L inner")):
                    print(f"  {a * 1000:4.0f} mm cells, {what}   " +
                          "  ".join(f"{v[col]:11.4f}" for v in vals), flush=True)
        if args.only != "plate":
            print("cylinder E / (D k^2 A / 2) " + "  ".join(f"{k:>11s}" for k in args.kinds))
            for angle in ANGLES:
                vals = [cylinder(args.lmp, kind, angle, tmp) for kind in args.kinds]
                print(f"  axis at {angle:2d} deg            " +
                      "  ".join(f"{v:11.4f}" for v in vals), flush=True)


if __name__ == "__main__":
    main()
