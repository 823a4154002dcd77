#!/usr/bin/env python3
"""Roofline-style estimate for the bond loops of one explicit peri/nosb force evaluation on this
machine (issue 13), from one invocation (about 10 s).

    /usr/bin/python3 examples/benchmarks/speed/roofline.py [--steps 300] [--lmp build/lmp]

Everything is information: nothing is asserted about wall times. The machine's limits are timed
with the thread's CPU clock, so that time slices lost to other processes on a busy machine do
not count (contention for caches, memory bandwidth and clock frequency still does). Printed:

1. Machine limits, measured here:
   - memory bandwidth: numpy copy of 2 x 256 MiB float64 arrays (8x the 32 MiB L3 of the
     machine this was written on), best of 5, counting read + write bytes (glibc's memcpy
     streams copies this large with non-temporal stores, so there is no write-allocate read to
     add); the same for 2 x 4 MiB (L3-resident) and 2 x 128 KiB (L2-resident), best of 10
     (numpy's call overhead included: lower bounds), for the bytes that do not come from DRAM;
   - scalar double arithmetic: a C++ kernel compiled here (temporary folder) with g++ -O2
     -fno-tree-vectorize (no -march, no -ffast-math: the plugin is built with plain -O3 for
     x86-64, SSE2 and no FMA; -fno-tree-vectorize because GCC 12 SLP-vectorizes at -O2 and
     would pack the scalar chains 2-wide) running independent chains x = a x + b, best of 5
     timings of about 0.1 s per variant; a mul and an add count as one flop each. Variants: 8
     chains, 12 chains (a chain step costs the latency of a mul plus an add, 3 + 3 cycles on AMD
     Zen 4, so 8 chains cannot keep two mul and two add pipes busy and 12 can: the larger of the
     two is the scalar ceiling), and 12 chains of 2-wide packed SSE2 (_mm_mul_pd, _mm_add_pd:
     the ceiling if every operation were packed);
   - L1d/L2/L3 sizes from lscpu.
2. The work per bond slot of the three bond loops (state pass, stabilization pass, force
   pass): the table WORK below, counted from the source (each bond is stored at both ends, so
   a pair is two slots; every pass visits every slot once): flops (mul and add), bytes
   streamed from the family arrays, bytes gathered from the partner's per-particle arrays,
   arithmetic intensity.
3. The achieved rate: examples/impact/in.impact.nosb run serially with --lmp (--steps steps,
   thermo only at the end) in a temporary folder with a copy of impact.geometry; from LAMMPS's
   "Loop time" and "% CPU use" (below 95: other processes took the core; the line says
   "measured under load") and the bond count the plugin prints ("total # of bonds" = slots,
   checked against a numpy count of the lattice that reproduces create_atoms's region test and
   fix nosb/family's |r| <= horizon rule):
   - time per slot = loop time / (steps x slots), for the whole step and for the bond loops
     only (BOND_LOOP_SHARE of the step, from the profile PROFILE measured elsewhere: it needs
     a profiler), each also from the loop's CPU time (loop time x % CPU use);
   - achieved GFlop/s = flops per slot / time per slot; achieved streamed bandwidth = 36 B /
     time per slot;
   - ceilings per slot: arithmetic = flops per slot / scalar GFlop/s (also with the loops'
     mul/add mix on the kernel's half-mul half-add rate, and at the packed rate); memory = 36
     streamed bytes / DRAM bandwidth (also from L3), and a pessimistic one adding 1/4 of the
     288 gathered bytes as misses to DRAM; which one binds and by how much (arithmetic
     intensity against the machine balance GFlop/s / GB/s), and the fraction of the arithmetic
     ceiling achieved.
4. Working sets of the small size and of the 53784-particle one (impact54k.geometry, this
   folder; counted in numpy, not run): per-particle arrays (216 B each) and family arrays
   (12 B per slot and pass) against L2 and L3, and at 54k the time to stream the family arrays
   against the arithmetic ceiling.
"""
from __future__ import annotations

import argparse
import datetime
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "solver"))
from bench_common import LOOP, REPO, build_info, print_build  # noqa: E402
from lammps_run import LMP, parse_thermo  # noqa: E402

IMPACT = REPO / "examples" / "impact"
DECK = IMPACT / "in.impact.nosb"
GEOMETRY = {"small": IMPACT / "impact.geometry", "54k": HERE / "impact54k.geometry"}
CPU = re.compile(r"([0-9.]+)% CPU use with")
BONDS = re.compile(r"total # of bonds = (\d+)")
SINGULAR = re.compile(r"atoms with a singular shape tensor = (\d+)")

# ---------------------------------------------------------------------------------------------
# Work per bond slot, counted from the source (line numbers of commit 1a299d1) for the variant
# an explicit impact run takes on its regular steps: breaking mode BREAK with the uniform rule
# (one s00 and alpha), no periodic image, no energy or virial (EFLAG = EVFLAG = 0: thermo asks
# for the energy only on its own steps), both ends regular (K invertible), bond unbroken.
# +, -, * count one flop each; compares, max() and the index arithmetic do not. A broken slot
# (jlocal < 0) costs only its index load and a branch in each pass.
#
# State pass, src/core/peri/elastic.cpp state_pass():
#   53-55  eta = x_j - x_i                                    3 sub
#   57     xi = x0_j - x0_i                                   3 sub
#   60     r2 = |eta|^2                                       3 mul 2 add
#   61     q2 = |xi|^2                                        3 mul 2 add
#   63 -> breaking.h check<BREAK, 1>:
#     66   lim = 1 + s00 - alpha smax                         1 mul 2 add (1 + s00 is the same
#          for every bond but is a member read through a reference: counted as written)
#     67   r2 > lim lim q2                                    2 mul
#     69   r2 den < acc q2                                    2 mul
#   71-73  u = omega eta (scratch row; 74-76 store xi)        3 mul
#   83-91  M += u (x) xi, second loop over the scratch row    9 mul 9 add
#   = 23 mul + 21 add = 44 flops.
#   Bytes: streamed jlocal 4 + omega 8 (50, 69); gathered x_j 24 (52), x0_j 24 (56),
#   smin_j 8 (63: s0[j]) = 56; scratch row 48 B written (70-76) and read back (81-82), in L1.
# Stabilization pass, src/core/peri/stabilization.cpp pass(), branch regi && regj:
#   68     eta = x_j - x_i                                    3 sub
#   69     xi = x0_j - x0_i                                   3 sub
#   74-76  F_i + F_j                                          9 add
#          (F_i + F_j) xi                                     9 mul 6 add
#          0.5 ( ... )                                        3 mul
#          z = eta - ...                                      3 sub
#   88     cw = 0.5 (C_i + C_j) omega                         2 mul 1 add
#   89     t = cw z                                           3 mul
#   90-92  force sum                                          3 add
#   95-97  u = qa t (scratch row; 98-100 store xi)            3 mul
#   116-124 Q += u (x) xi, second loop over the scratch row   9 mul 9 add
#   = 29 mul + 37 add = 66 flops.
#   Bytes: streamed jlocal 4 + omega 8 (62, 88); gathered g_j = F (9), C, regular flag:
#   NG = 11 doubles = 88 (64-65, 74-76, 88; fields.h), x_j 24 (66), x0_j 24 (67) = 136;
#   scratch row 48 B written and read back, in L1.
# Force pass, src/core/peri/elastic.cpp force_pass():
#   188    xi = x0_j - x0_i                                   3 sub
#   190-192 H_i + H_j                                         9 add
#          (H_i + H_j) xi                                     9 mul 6 add
#          omega ( ... )                                      3 mul
#   193-195 force sum                                         3 add
#   = 12 mul + 21 add = 33 flops.
#   Bytes: streamed jlocal 4 + omega 8 (183, 186); gathered h_j 72 (185), x0_j 24 (187) = 96
#   (x_j only with the virial, 197).
# Per slot: 64 mul + 79 add = 143 flops; 36 B streamed from the family arrays (12 per pass);
# 288 B gathered from per-particle arrays (hits in L1/L2 mostly: neighbouring particles share
# partners). Per particle, the arrays the bond loops gather from: x 24 + x0 24 + g 88 + h 72 +
# smin 8 = 216 B.
WORK = [
    # pass, term, mul, add
    ("state", "eta, xi", 0, 6),
    ("state", "|eta|^2, |xi|^2", 6, 4),
    ("state", "breaking rule", 5, 2),
    ("state", "omega eta", 3, 0),
    ("state", "M += u (x) xi", 9, 9),
    ("stabilization", "eta, xi", 0, 6),
    ("stabilization", "F_i + F_j", 0, 9),
    ("stabilization", "(F_i + F_j) xi, x 0.5, z", 12, 9),
    ("stabilization", "cw = 0.5 (C_i + C_j) omega", 2, 1),
    ("stabilization", "t = cw z, force sum", 3, 3),
    ("stabilization", "u = qa t", 3, 0),
    ("stabilization", "Q += u (x) xi", 9, 9),
    ("force", "xi", 0, 3),
    ("force", "H_i + H_j", 0, 9),
    ("force", "(H_i + H_j) xi, x omega", 12, 6),
    ("force", "force sum", 0, 3),
]
PASSES = ("state", "stabilization", "force")
# bytes per slot and pass: streamed from the family arrays (jlocal int + omega double), gathered
# from per-particle arrays of the partner
STREAMED = {"state": 12, "stabilization": 12, "force": 12}
GATHERED = {"state": 56, "stabilization": 136, "force": 96}
PER_PARTICLE = {"x": 24, "x0": 24, "g (F, C, flag)": 88, "h (H)": 72, "smin": 8}
FAMILY_BYTES = 12            # jlocal 4 + omega 8 per slot, read once per pass
MISS_FRACTION = 0.25         # pessimistic memory ceiling: this share of the gathered bytes missed

# Share of a step spent in each part, from a profile of the impact deck (in.impact.nosb)
# measured by the engineer working on issue 13, reported 2026-11-26 for the build of commit
# 1a299d1. Not measured by this script (it needs a profiler; none is assumed here). The three
# bond loops are 32 + 23 + 15 = 70 % of a step; the rest is the SVD/stress work (6 %), the
# contact pass (5 %) and fix nve, neighbor lists, thermo and the per-particle work.
PROFILE = {"stabilization pass": 0.32, "state pass": 0.23, "force pass": 0.15, "SVD": 0.06,
           "contact": 0.05}
PROFILE_SOURCE = "profile reported 2026-11-26, build of commit 1a299d1"
BOND_LOOP_SHARE = PROFILE["stabilization pass"] + PROFILE["state pass"] + PROFILE["force pass"]

# ---------------------------------------------------------------------------------------------
KERNEL = r"""
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <emmintrin.h>

// N independent chains x = a x + b: one mul and one add per chain and iteration
template <int N> static double scalar(long n, double a, double b)
{
  double x[N];
  for (int k = 0; k < N; k++) x[k] = 0.5 + 0.01 * k;
  for (long i = 0; i < n; i++) {
#pragma GCC unroll 16
    for (int k = 0; k < N; k++) x[k] = a * x[k] + b;
  }
  double s = 0.0;
  for (int k = 0; k < N; k++) s += x[k];
  return s;
}

// the same, 2-wide packed (SSE2)
template <int N> static double packed(long n, double a, double b)
{
  __m128d x[N];
  const __m128d va = _mm_set1_pd(a), vb = _mm_set1_pd(b);
  for (int k = 0; k < N; k++) x[k] = _mm_set_pd(0.5 + 0.01 * k, 0.25 + 0.01 * k);
  for (long i = 0; i < n; i++) {
#pragma GCC unroll 16
    for (int k = 0; k < N; k++) x[k] = _mm_add_pd(_mm_mul_pd(va, x[k]), vb);
  }
  double s = 0.0, t[2];
  for (int k = 0; k < N; k++) {
    _mm_storeu_pd(t, x[k]);
    s += t[0] + t[1];
  }
  return s;
}

// CPU time of this thread: time slices lost to other processes do not count
static double cpu_seconds()
{
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

// best GFlop/s of 5 timings of about `seconds` each
template <class F> static void run(const char *name, int flops_per_iter, F f, double a, double b,
                                   double seconds)
{
  long n = 1 << 16;
  double best = 0.0, sink = 0.0;
  for (int r = 0; r < 5;) {
    const double t0 = cpu_seconds();
    sink += f(n, a, b);
    const double dt = cpu_seconds() - t0;
    if (dt < 0.5 * seconds) {
      n = static_cast<long>(n * std::min(16.0, 1.2 * seconds / std::max(dt, 1e-6)));
      continue;
    }
    best = std::max(best, flops_per_iter * static_cast<double>(n) / dt);
    r++;
  }
  std::printf("%s %.6g %.17g\n", name, best * 1e-9, sink);
}

int main(int argc, char **argv)
{
  // a, b and the duration from the command line: nothing to fold at compile time
  const double a = std::atof(argv[1]), b = std::atof(argv[2]), seconds = std::atof(argv[3]);
  run("scalar8", 2 * 8, scalar<8>, a, b, seconds);
  run("scalar12", 2 * 12, scalar<12>, a, b, seconds);
  run("packed12", 2 * 2 * 12, packed<12>, a, b, seconds);
  return 0;
}
"""
KERNEL_FLAGS = ["-O2", "-fno-tree-vectorize"]


def arithmetic_rates(tmp: Path) -> dict:
    """GFlop/s of the kernel's variants {scalar8, scalar12, packed12}."""
    src, exe = tmp / "flops.cpp", tmp / "flops"
    src.write_text(KERNEL)
    subprocess.run(["g++", *KERNEL_FLAGS, str(src), "-o", str(exe)], check=True)
    out = subprocess.run([str(exe), "0.999999", "1e-6", "0.1"], check=True, capture_output=True,
                         text=True).stdout
    return {w[0]: float(w[1]) for w in (ln.split() for ln in out.splitlines())}


def copy_bandwidth(nbytes: int, copies: int, reps: int = 5) -> float:
    """GB/s of np.copyto between two float64 arrays of nbytes each (read + write bytes), best of
    reps timings (thread CPU time) of `copies` copies."""
    src = np.ones(nbytes // 8)
    dst = np.empty_like(src)
    np.copyto(dst, src)                    # touch the pages
    best = float("inf")
    for _ in range(reps):
        t0 = time.thread_time()
        for _ in range(copies):
            np.copyto(dst, src)
        best = min(best, (time.thread_time() - t0) / copies)
    return 2 * src.nbytes / best / 1e9


def cache_sizes() -> dict:
    """{level: (bytes per instance, lscpu's text)} for L1d, L2, L3 (None if unknown)."""
    out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    unit = {"B": 1, "K": 2**10, "KB": 2**10, "KIB": 2**10, "M": 2**20, "MB": 2**20,
            "MIB": 2**20, "G": 2**30, "GB": 2**30, "GIB": 2**30}
    sizes = {}
    for level in ("L1d", "L2", "L3"):
        m = re.search(rf"^{level} cache:\s*(.+)$", out, re.M)
        if not m:
            sizes[level] = (None, "?")
            continue
        text = m.group(1).strip()
        s = re.match(r"([0-9.]+)\s*([KMG]i?B?|B)?", text, re.I)
        total = float(s.group(1)) * unit.get((s.group(2) or "B").upper(), 1) if s else None
        inst = re.search(r"\((\d+) instances?\)", text)
        sizes[level] = (total / int(inst.group(1)) if total and inst else total, text)
    return sizes


# ---------------------------------------------------------------------------------------------
def lattice_families(path: Path) -> dict:
    """The particles and bond slots of an impact geometry file, counted in numpy: simple cubic
    lattice points (i a, j a, k a) inside the y-axis cylinder region as LAMMPS's create_atoms
    tests them (sqrt(dx^2 + dz^2) <= radius, lo <= y <= hi; the shrink-wrapped box is the
    region's extent, widened), and per particle the partners at |r| <= horizon (fix nosb/family
    build_families(): nothing beyond the horizon is kept; the partial-volume factor only
    weights the bonds between horizon - a/2 and the horizon)."""
    text = path.read_text()
    a = float(re.search(r"^variable\s+a\s+equal\s+(\S+)", text, re.M).group(1))
    factor = float(re.search(r"^variable\s+horizon\s+equal\s+(\S+)\*v_a", text, re.M).group(1))
    assert re.search(r"^lattice\s+sc\s+\$\{a\}", text, re.M), f"{path}: not lattice sc ${{a}}"
    c1, c2, radius, lo, hi = (float(v) for v in re.search(
        r"^region\s+\S+\s+cylinder\s+y\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", text,
        re.M).groups())
    horizon = factor * a
    pad = int(np.ceil(factor))
    ix = np.arange(int(np.floor((c1 - radius) / a)) - 1, int(np.ceil((c1 + radius) / a)) + 2)
    iy = np.arange(int(np.floor(lo / a)) - 1, int(np.ceil(hi / a)) + 2)
    iz = np.arange(int(np.floor((c2 - radius) / a)) - 1, int(np.ceil((c2 + radius) / a)) + 2)
    x, y, z = np.meshgrid(ix * a, iy * a, iz * a, indexing="ij")
    inside = (np.sqrt((x - c1) ** 2 + (z - c2) ** 2) <= radius) & (y >= lo) & (y <= hi)
    grid = np.pad(inside, pad)
    r = np.arange(-pad, pad + 1)
    offsets = [(p, q, s) for p in r for q in r for s in r
               if 0 < (p * a) ** 2 + (q * a) ** 2 + (s * a) ** 2 <= horizon ** 2]
    count = np.zeros(grid.shape, dtype=np.int32)
    n0, n1, n2 = grid.shape
    core = grid[pad:n0 - pad, pad:n1 - pad, pad:n2 - pad]
    for p, q, s in offsets:
        count[pad:n0 - pad, pad:n1 - pad, pad:n2 - pad] += (
            core & grid[pad + p:n0 - pad + p, pad + q:n1 - pad + q, pad + s:n2 - pad + s])
    partners = count[grid]
    return dict(particles=int(inside.sum()), bulk=len(offsets), slots=int(partners.sum()),
                mean=float(partners.mean()), min=int(partners.min()), max=int(partners.max()),
                horizon_over_a=factor)


def run_impact(lmp: Path, steps: int, workdir: Path) -> dict:
    """Run in.impact.nosb serially for `steps` steps; what its log says."""
    shutil.copy(GEOMETRY["small"], workdir / "impact.geometry")
    log = workdir / "log.lammps"
    cmd = [str(lmp), "-in", str(DECK), "-log", str(log), "-echo", "log", "-nocite",
           "-var", "nsteps", str(steps), "-var", "thermo_every", str(steps)]
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True,
                          stdin=subprocess.DEVNULL)
    text = log.read_text(errors="replace") if log.exists() else ""
    if proc.returncode != 0 or not LOOP.search(text):
        tail = (proc.stdout + proc.stderr).splitlines()[-10:]
        sys.exit("LAMMPS run failed: " + " | ".join(tail))
    seconds, procs, nsteps, atoms = LOOP.findall(text)[-1]
    thermo = parse_thermo(text)[-1]
    cpu = CPU.findall(text)
    return dict(seconds=float(seconds), steps=int(nsteps), atoms=int(atoms),
                slots=int(BONDS.findall(text)[-1]), singular=int(SINGULAR.findall(text)[-1]),
                cpu=float(cpu[-1]) if cpu else float("nan"),
                damage=float(thermo["c_dsum"][-1]) / int(atoms))


def mb(nbytes: float) -> str:
    return f"{nbytes / 2**20:.2f} MiB"


def main():
    ap = argparse.ArgumentParser(description=" ".join(__doc__.split("\n\n")[0].split()))
    ap.add_argument("--steps", type=int, default=300, help="steps of the impact run (300)")
    ap.add_argument("--lmp", type=Path, default=LMP)
    args = ap.parse_args()
    start = build_info()
    print("Roofline estimate for the bond loops of one explicit peri/nosb force evaluation")
    print(f"date {datetime.datetime.now():%Y-%m-%d %H:%M}, load average "
          + " ".join(f"{v:.2f}" for v in os.getloadavg())
          + f" on {os.cpu_count()} CPUs")

    # 1. machine limits
    caches = cache_sizes()
    bw_dram = copy_bandwidth(256 * 2**20, 1)
    bw_l3 = copy_bandwidth(4 * 2**20, 40, reps=10)
    bw_l2 = copy_bandwidth(128 * 2**10, 1000, reps=10)
    with tempfile.TemporaryDirectory(prefix="roofline-") as tmp:
        rates = arithmetic_rates(Path(tmp))
    scalar = max(rates["scalar8"], rates["scalar12"])
    print("\n== 1. machine limits (measured here) ==")
    for level in ("L1d", "L2", "L3"):
        size, text = caches[level]
        print(f"{level} cache (lscpu): {text}" + (f" -> {mb(size)} per instance" if size else ""))
    print(f"memory bandwidth, numpy copy 2 x 256 MiB, read + write, best of 5: {bw_dram:.1f} GB/s")
    print(f"L3-resident copy 2 x 4 MiB: {bw_l3:.1f} GB/s; L2-resident copy 2 x 128 KiB: "
          f"{bw_l2:.1f} GB/s (best of 10; numpy call overhead included)")
    print(f"scalar double mul+add (g++ {' '.join(KERNEL_FLAGS)}, SSE2, no FMA), best of 5: "
          f"8 chains {rates['scalar8']:.2f} GFlop/s, 12 chains {rates['scalar12']:.2f} GFlop/s "
          f"-> scalar ceiling {scalar:.2f} GFlop/s")
    print(f"2-wide packed SSE2 mul+add, 12 chains: {rates['packed12']:.2f} GFlop/s")
    print(f"machine balance (scalar GFlop/s / DRAM GB/s): {scalar / bw_dram:.2f} flop/B")

    # 2. per-slot work
    mul = sum(w[2] for w in WORK)
    add = sum(w[3] for w in WORK)
    flops = mul + add
    streamed = sum(STREAMED.values())
    gathered = sum(GATHERED.values())
    print("\n== 2. work per bond slot (counted from the source; a pair is two slots) ==")
    print(f"{'pass':<15}{'mul':>5}{'add':>5}{'flops':>7}{'streamed B':>12}{'gathered B':>12}")
    for p in PASSES:
        m = sum(w[2] for w in WORK if w[0] == p)
        s = sum(w[3] for w in WORK if w[0] == p)
        print(f"{p:<15}{m:>5}{s:>5}{m + s:>7}{STREAMED[p]:>12}{GATHERED[p]:>12}")
    print(f"{'total':<15}{mul:>5}{add:>5}{flops:>7}{streamed:>12}{gathered:>12}")
    per_particle = sum(PER_PARTICLE.values())
    print("per-particle arrays gathered: " + " + ".join(
        f"{k} {v}" for k, v in PER_PARTICLE.items()) + f" = {per_particle} B")
    print(f"arithmetic intensity: {flops / streamed:.2f} flop/B of streamed bytes; "
          f"{flops / (streamed + MISS_FRACTION * gathered):.2f} flop/B counting also "
          f"{MISS_FRACTION:g} of the gathered bytes")

    # 3. achieved rate
    small = lattice_families(GEOMETRY["small"])
    with tempfile.TemporaryDirectory(prefix="roofline-") as tmp:
        run = run_impact(args.lmp, args.steps, Path(tmp))
    print(f"\n== 3. achieved: examples/impact/in.impact.nosb, 1 rank, {run['steps']} steps ==")
    print_build(start)
    print(f"atoms {run['atoms']} (numpy lattice count {small['particles']}); bond slots "
          f"{run['slots']} (LAMMPS 'total # of bonds'; numpy {small['slots']}"
          + (", agree" if run["slots"] == small["slots"] else ", DIFFER") + ")")
    print(f"slots per particle: mean {run['slots'] / run['atoms']:.2f}, min {small['min']}, max "
          f"{small['max']}, bulk {small['bulk']} (lattice points 0 < |r| <= "
          f"{small['horizon_over_a']:g} a); singular shape tensors: {run['singular']}")
    print(f"mean damage at the end: {run['damage']:.4f} (about the fraction of slots broken; "
          "damage weights them by omega; a broken slot costs only its index load)")
    # ns per slot: loop time / (steps x slots), and the same from the loop's CPU time
    cpu_time = run["seconds"] * min(1.0, run["cpu"] / 100)
    t_step = run["seconds"] / (run["steps"] * run["slots"]) * 1e9
    t_bond = BOND_LOOP_SHARE * t_step
    t_step_cpu = cpu_time / (run["steps"] * run["slots"]) * 1e9
    t_bond_cpu = BOND_LOOP_SHARE * t_step_cpu
    rows = {"whole step (loop time)": t_step, "bond loops only (loop time)": t_bond,
            "whole step (CPU time)": t_step_cpu, "bond loops only (CPU time)": t_bond_cpu}
    cpu_note = "" if run["cpu"] >= 95 else "  <- below 95 %: measured under load"
    print(f"loop time {run['seconds']:.3f} s, % CPU use {run['cpu']:.1f}{cpu_note}")
    print(f"us per particle-step: {run['seconds'] / (run['steps'] * run['atoms']) * 1e6:.3f} "
          f"(loop time), {cpu_time / (run['steps'] * run['atoms']) * 1e6:.3f} (CPU time = loop "
          "time x % CPU use)")
    print(f"bond-loop share of a step: {BOND_LOOP_SHARE:.2f} ("
          + ", ".join(f"{k} {v:.2f}" for k, v in PROFILE.items()) + f"; {PROFILE_SOURCE})")
    print(f"{'per bond slot':<34}{'ns/slot':>9}{'GFlop/s':>9}{'streamed GB/s':>15}")
    for name, t in rows.items():
        print(f"{name:<34}{t:>9.2f}{flops / t:>9.2f}{streamed / t:>15.2f}")

    t_arith = flops / scalar
    t_mix = 2 * max(mul, add) / scalar
    t_packed = flops / rates["packed12"]
    t_mem = streamed / bw_dram
    t_pess = (streamed + MISS_FRACTION * gathered) / bw_dram
    t_l3 = streamed / bw_l3
    print("\nceilings per slot (the loop cannot run faster than):")
    print(f"  arithmetic, scalar: {flops} flops / {scalar:.2f} GFlop/s = {t_arith:.2f} ns")
    print(f"  arithmetic, scalar with the loops' mix ({add} add vs {mul} mul: the kernel's rate "
          f"is half adds, half muls, on separate pipes): 2 x {max(mul, add)} / {scalar:.2f} = "
          f"{t_mix:.2f} ns")
    print(f"  arithmetic, all 2-wide packed: {flops} / {rates['packed12']:.2f} = {t_packed:.2f} ns")
    print(f"  memory, streamed {streamed} B from DRAM: {t_mem:.2f} ns; from L3: {t_l3:.2f} ns")
    print(f"  memory, pessimistic: {streamed} + {MISS_FRACTION:g} x {gathered} gathered B from "
          f"DRAM = {t_pess:.2f} ns")
    bind = ("arithmetic" if t_arith >= t_pess else
            "arithmetic for the streamed bytes, memory in the pessimistic count"
            if t_arith >= t_mem else "memory")
    print(f"binding limit: {bind}: arithmetic ceiling / memory ceiling = {t_arith / t_mem:.1f}x "
          f"(streamed), {t_arith / t_pess:.1f}x (pessimistic); arithmetic intensity "
          f"{flops / streamed:.2f} (pessimistic "
          f"{flops / (streamed + MISS_FRACTION * gathered):.2f}) flop/B vs machine balance "
          f"{scalar / bw_dram:.2f} flop/B")
    for what, tb, ts in (("loop time", t_bond, t_step), ("CPU time", t_bond_cpu, t_step_cpu)):
        print(f"achieved ({what}), bond loops: {tb:.2f} ns per slot = {t_arith / tb:.0%} of the "
              f"scalar arithmetic ceiling ({t_mix / tb:.0%} with the mix, {t_packed / tb:.0%} of "
              f"the packed one); whole step: {t_arith / ts:.0%} of the scalar ceiling")

    # 4. working sets
    large = lattice_families(GEOMETRY["54k"])
    l2, l3 = caches["L2"][0], caches["L3"][0]
    print("\n== 4. working sets (numpy counts of the geometry files; not run) ==")
    for name, g in (("small", small), ("54k", large)):
        ws = per_particle * g["particles"]
        fam = FAMILY_BYTES * g["slots"]

        def where(nbytes):
            if l2 and nbytes <= l2:
                return "fits in L2"
            if l3 and nbytes <= l3:
                return "fits in L3, not L2"
            return "exceeds L3"
        print(f"{name}: {g['particles']} particles, {g['slots']} slots ({g['mean']:.1f} per "
              f"particle); per-particle arrays {per_particle} B x {g['particles']} = {mb(ws)} "
              f"({where(ws)}); family arrays {FAMILY_BYTES} B x {g['slots']} = {mb(fam)} per pass "
              f"({where(fam)}); together {mb(ws + fam)} ({where(ws + fam)})")
    fam54 = FAMILY_BYTES * large["slots"]
    source, bw = ("DRAM", bw_dram) if not l3 or fam54 > l3 else ("L3", bw_l3)
    print(f"54k: the family arrays ({mb(fam54)}) come from {source} in each of the 3 passes: at "
          f"{bw:.1f} GB/s {3 * fam54 / bw / 1e6:.2f} ms per step, against "
          f"{t_arith * large['slots'] / 1e6:.2f} ms of scalar arithmetic at the ceiling "
          f"({t_arith * large['slots'] / (3 * fam54 / bw):.1f}x): still arithmetic-bound"
          if t_arith * large["slots"] > 3 * fam54 / bw else
          f"54k: the family arrays ({mb(fam54)}) come from {source} in each of the 3 passes: at "
          f"{bw:.1f} GB/s {3 * fam54 / bw / 1e6:.2f} ms per step, more than the "
          f"{t_arith * large['slots'] / 1e6:.2f} ms of scalar arithmetic at the ceiling: "
          "memory-bound")

if __name__ == "__main__":
    main()
