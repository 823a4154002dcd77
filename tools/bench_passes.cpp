// Development benchmark: the time of each bond pass of peri/nosb on an n x n x n simple cubic
// lattice (horizon 3.0002 spacings, linear model, stabilization, uniform breaking that breaks
// nothing), without LAMMPS. The passes run in turn, round after round, in one process, so that
// a busy machine slows them alike; per pass the minimum and the median over the rounds.
// Compares variants of one pass (state with and without the breaking check, force with and
// without the SISSM blocks) and sums the passes of an explicit step and of a fix sissm
// iteration (no halo, contact or solver: the bond loops only); times the state pass's signed
// SVD alone, one, two and four matrices at a time. Built and run by
// tools/bench_passes.sh; nothing is asserted.

#include "peri/cluster.h"

#include "linalg/fast_svd.h"
#include "linalg/fused.h"
#include "materials/material.h"
#include "peri/elastic.h"
#include "peri/stabilization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <vector>

using namespace PeriSISSM;

namespace {
// 64-byte aligned storage, as LAMMPS allocates its per-atom arrays (LAMMPS_MEMALIGN = 64): a row
// of eight doubles is then one cache line
template <class T> struct Aligned64 {
  using value_type = T;
  Aligned64() = default;
  template <class U> Aligned64(const Aligned64<U> &) {}
  T *allocate(size_t n)
  {
    return static_cast<T *>(::operator new(n * sizeof(T), std::align_val_t(64)));
  }
  void deallocate(T *p, size_t) { ::operator delete(p, std::align_val_t(64)); }
  template <class U> bool operator==(const Aligned64<U> &) const { return true; }
  template <class U> bool operator!=(const Aligned64<U> &) const { return false; }
};
typedef std::vector<double, Aligned64<double>> Doubles;

double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}    // namespace

int main(int argc, char **argv)
{
  const int n = argc > 1 ? std::atoi(argv[1]) : 38;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 15;
  if (n < 4 || rounds < 1) {
    std::fprintf(stderr, "usage: bench_passes [n >= 4, default 38] [rounds >= 1, default 15]\n");
    return 2;
  }
  Model m;
  m.set_ntypes(1);
  const auto lame = lame_from_bulk_shear(1.0, 0.6);
  m.set_type(1, make_material("linear", lame.mu, lame.lambda), 1.0, 1.0);
  m.set_pair(1, 1, 3.0002, false, 0.0);
  m.breaking().configure(
      1,
      [](int, int) {
        return true;
      },
      [](int, int) {
        return 0.5;
      },
      [](int, int) {
        return 0.25;
      });
  PeriSISSMTest::Cluster c(n, n, n, 3.0002, false, 5u, 0.0, 0.0);
  c.build(m);
  // a small stretch and a ripple, far from breaking
  for (int i = 0; i < c.nlocal; i++)
    for (int k = 0; k < 3; k++)
      c.x[3 * i + k] = c.x0[3 * i + k] * (1.0 + 0.001 * k) + 1.0e-3 * ((7 * i + k) % 5);

  const int nall = c.nall;
  Doubles f(3 * nall), g(nall * ParticleFields::NG), h(9 * nall), k(nall * ParticleFields::NK),
      w(nall), smin_new(nall), blocks(6 * nall);
  std::vector<double *> rows(nall);
  for (int i = 0; i < nall; i++) rows[i] = blocks.data() + 6 * i;
  const Particles p = c.particles(f.data());
  ParticleFields fields;
  fields.g = g.data();
  fields.h = h.data();
  fields.k = k.data();
  fields.w = w.data();
  fields.smin_new = smin_new.data();
  Doubles cols(ParticleFields::NCOLS * static_cast<size_t>(nall));
  fields.cols = std::getenv("BENCH_PASSES_SCALAR") ? nullptr : cols.data();
  Virial virial;
  std::vector<int> broke;
  const Families fam = c.families();

  enum {
    STATE_BREAK,
    STATE_BREAK_SCALAR,
    STATE,
    STATE_K,
    STAB,
    STAB_SCALAR,
    FORCE,
    FORCE_SCALAR,
    FORCE_BLOCKS,
    SVD1,
    SVD2,
    SVD4,
    NPASS
  };
  const char *names[NPASS] = {"state, breaking check",
                              "state, check, scalar",
                              "state, no check",
                              "state, no check, k rows",
                              "stabilization",
                              "stabilization, scalar",
                              "force",
                              "force, scalar",
                              "force and blocks",
                              "svd, one at a time",
                              "svd, two side by side",
                              "svd, four (lanes)"};
  // the scalar code of the fused version: without the columns scratch
  ParticleFields scalar = fields;
  scalar.cols = nullptr;
  // the state pass's signed SVD alone, as many matrices as particles (a multiple of 4): F of a
  // body that turns, rotations of small strains (the lattice's own F are nearly diagonal,
  // which the Jacobi sweeps finish at once), one at a time, two and four side by side
  std::vector<Eigen::Matrix3d> turned(c.nlocal - c.nlocal % 4);
  std::vector<SignedSVD> svd(turned.size());
  {
    std::mt19937_64 rng(3u);
    std::normal_distribution<double> normal;
    for (Eigen::Matrix3d &F : turned) {
      Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
      Eigen::Matrix3d e;
      for (int k = 0; k < 9; k++) e(k) = 1.0e-4 * normal(rng);
      F = q.normalized().toRotationMatrix() * (Eigen::Matrix3d::Identity() + e);
    }
  }
  const size_t nsvd = turned.size();
  std::vector<std::vector<double>> t(NPASS);
  auto timed = [&](int q, auto &&pass) {
    const double t0 = now();
    pass();
    t[q].push_back(now() - t0);
  };
  for (int r = 0; r < rounds; r++) {
    timed(STATE_BREAK, [&] {
      elastic_state_pass(m, p, fam, c.box, BreakingRule::BREAK, false, fields, broke);
    });
    timed(STATE_BREAK_SCALAR, [&] {
      elastic_state_pass(m, p, fam, c.box, BreakingRule::BREAK, false, scalar, broke);
    });
    timed(STATE, [&] {
      elastic_state_pass(m, p, fam, c.box, BreakingRule::NOBREAK, false, fields, broke);
    });
    timed(STATE_K, [&] {
      elastic_state_pass(m, p, fam, c.box, BreakingRule::NOBREAK, true, fields, broke);
    });
    timed(STAB, [&] {
      stabilization_pass(m, p, fam, c.box, fields, virial, false);
    });
    timed(STAB_SCALAR, [&] {
      stabilization_pass(m, p, fam, c.box, scalar, virial, false);
    });
    timed(FORCE, [&] {
      elastic_force_pass(p, fam, c.box, fields, virial, nullptr);
    });
    timed(FORCE_SCALAR, [&] {
      elastic_force_pass(p, fam, c.box, scalar, virial, nullptr);
    });
    timed(FORCE_BLOCKS, [&] {
      elastic_force_pass(p, fam, c.box, fields, virial, rows.data());
    });
    timed(SVD1, [&] {
      for (size_t i = 0; i < nsvd; i++) svd[i] = fast_signed_svd(turned[i]);
    });
    timed(SVD2, [&] {
      for (size_t i = 0; i < nsvd; i += 2)
        fast_signed_svd(turned[i], turned[i + 1], svd[i], svd[i + 1]);
    });
    timed(SVD4, [&] {
      for (size_t i = 0; i < nsvd; i += 4) fast_signed_svd(&turned[i], &svd[i]);
    });
  }
  if (!broke.empty()) std::fprintf(stderr, "warning: %zu families lost bonds\n", broke.size());

  double lo[NPASS], mid[NPASS];
  std::printf("%d particles, %d rounds, %s passes; ms per pass: min, median\n", c.nlocal, rounds,
              fused_passes() ? "fused" : "plain");
  for (int q = 0; q < NPASS; q++) {
    std::sort(t[q].begin(), t[q].end());
    lo[q] = 1e3 * t[q].front();
    mid[q] = 1e3 * t[q][t[q].size() / 2];
    std::printf("  %-26s %9.2f %9.2f\n", names[q], lo[q], mid[q]);
  }
  const double step = lo[STATE_BREAK] + lo[STAB] + lo[FORCE];
  const double iter = lo[STATE_K] + lo[STAB] + lo[FORCE_BLOCKS];
  std::printf("explicit step (state with check + stabilization + force): %.2f ms\n", step);
  std::printf("sissm iteration (state with k rows + stabilization + force and blocks): %.2f ms"
              " = %.3f x the step\n",
              iter, iter / step);
  std::printf("breaking check: %.3f x the state pass without it; blocks: %.3f x the force pass\n",
              lo[STATE_BREAK] / lo[STATE], lo[FORCE_BLOCKS] / lo[FORCE]);
  std::printf("signed SVD of %zu turned F (rotated small strains): ns per matrix alone %.0f,"
              " two side by side %.0f, four %.0f (%.3f x two)\n",
              nsvd, 1e6 * lo[SVD1] / nsvd, 1e6 * lo[SVD2] / nsvd, 1e6 * lo[SVD4] / nsvd,
              lo[SVD4] / lo[SVD2]);
  const double step_scalar = lo[STATE_BREAK_SCALAR] + lo[STAB_SCALAR] + lo[FORCE_SCALAR];
  std::printf("4-wide against scalar (fields.cols given or not): state with check %.3f x,"
              " stabilization %.3f x, force %.3f x; explicit step %.3f x (%.2f ms scalar)\n",
              lo[STATE_BREAK] / lo[STATE_BREAK_SCALAR], lo[STAB] / lo[STAB_SCALAR],
              lo[FORCE] / lo[FORCE_SCALAR], step / step_scalar, step_scalar);
  // the bits of the results (force densities summed over the rounds, H, the blocks, F): the
  // same n, rounds and version of the passes give the same fingerprint
  unsigned long long hash = 1469598103934665603ull;
  for (const Doubles *v : {&f, &h, &blocks, &g})
    for (const double a : *v) {
      unsigned long long bits;
      std::memcpy(&bits, &a, sizeof bits);
      hash = (hash ^ bits) * 1099511628211ull;
    }
  std::printf("fingerprint of the results: %016llx\n", hash);
  return 0;
}
