// The elastic (correspondence) term (see elastic.h).

#include "peri/elastic.h"

#include "linalg/double4.h"
#include "linalg/fused.h"
#include "membrane/membrane.h"
#include "peri/bond_rows.h"
#include "peri/columns.h"
#include "peri/instances.h"
#include "peri/model.h"
#include "peri/particle.h"
#include "peri/stabilization.h"

#include <algorithm>
#include <vector>

namespace PeriSISSM {

namespace {

  // The breaking check of the bond ij (BreakingRule::check) from eta = (e0, e1, e2) and xi =
  // (x0, x1, x2); true if it breaks
  template <int MODE, int UNIFORM, bool FUSED>
  [[gnu::always_inline]] inline bool bond_breaks(const BreakingRule &rule, const Particles &p,
                                                 int itype, int j, double smini, double e0,
                                                 double e1, double e2, double x0, double x1,
                                                 double x2, double &acc, double &den)
  {
    const double r2 = madd<FUSED>(e2, e2, madd<FUSED>(e1, e1, e0 * e0));
    const double q2 = madd<FUSED>(x2, x2, madd<FUSED>(x1, x1, x0 * x0));
    const int jtype = UNIFORM ? 1 : p.type[j];
    return rule.check<MODE, UNIFORM>(r2, q2, itype, jtype, std::max(smini, p.smin[j]), acc, den);
  }

  // The bonds of particle i in the state pass: the breaking check (a bond that breaks gets
  // partner index -1), and M = sum omega eta (x) xi over the unbroken bonds (row-major), from
  // rows of omega eta and xi (bond_rows.h). Returns 1 if a bond broke.
  template <int MODE, int UNIFORM, int PBC, bool FUSED>
  [[gnu::always_inline]] inline int state_bonds(const BreakingRule &rule, const Particles &p,
                                                const Families &fam, const ReferenceBox &box, int i,
                                                double smini, double &acc, double &den,
                                                BondRows &rows, double M[9])
  {
    const double *xf = p.x;
    const double *rf = p.x0;
    const int itype = p.type[i];
    const double xi0 = xf[3 * i], xi1 = xf[3 * i + 1], xi2 = xf[3 * i + 2];
    const double ri0 = rf[3 * i], ri1 = rf[3 * i + 1], ri2 = rf[3 * i + 2];
    const int n = fam.npartner[i];
    int *jl = fam.jlocal[i];
    const double *om = fam.omega[i];
    int broke = 0;
    rows.clear();
    for (int b = 0; b < n; b++) {
      const int j = jl[b];
      if (j < 0) continue;
      const double *xj = xf + 3 * j;
      const double e0 = xj[0] - xi0;
      const double e1 = xj[1] - xi1;
      const double e2 = xj[2] - xi2;
      const double *rj = rf + 3 * j;
      double x0 = rj[0] - ri0, x1 = rj[1] - ri1, x2 = rj[2] - ri2;
      if (PBC) box.image(x0, x1, x2);
      if (MODE != BreakingRule::NOBREAK &&
          bond_breaks<MODE, UNIFORM, FUSED>(rule, p, itype, j, smini, e0, e1, e2, x0, x1, x2, acc,
                                            den)) {
        jl[b] = -1;
        broke = 1;
        continue;
      }
      const double w = om[b];
      rows.push(w * e0, w * e1, w * e2, x0, x1, x2);
    }
    rows.outer_sum<FUSED>(M);
    return broke;
  }

#ifdef PERISISSM_CPU_DISPATCH
  // state_bonds of the fused version, 4-wide (linalg/double4.h): eta in lanes 0-2, each
  // component of xi in every lane of its own register, M by columns summed bond by bond; the
  // same operations in the same order as state_bonds<..., FUSED = true>, so the same bits.
  //
  // The uniform breaking check (one rule for all pairs: the common case) goes
  // four bonds at a time, one per lane (four consecutive slots without a broken bond; other
  // bonds one at a time): |eta|^2, |xi|^2, the limit and both comparisons of BreakingRule::check
  // are its scalar operations lane by lane, |xi|^2 from the terms of M. Bonds break rarely, and
  // whether one breaks depends on itself alone (s_min of its ends from the last evaluation), so
  // the four add their terms of M first; the smallest stretch is updated lane after lane only
  // where one of the four is smaller than the kept one against the state before them (none
  // can be otherwise). If a bond of the family breaks, M and the smallest stretch are made
  // again one bond at a time from the start. Either way: the same bits, the same broken bonds
  // as the scalar code.
  template <int MODE, int UNIFORM, int PBC>
  PERISISSM_FUSED_TARGET int state_bonds_fused(const BreakingRule &rule, const Particles &p,
                                               const Families &fam, const ReferenceBox &box, int i,
                                               double smini, double &acc, double &den, double M[9])
  {
    const double *xf = p.x;
    const double *rf = p.x0;
    const int itype = p.type[i];
    const double *xi = xf + 3 * i, *ri = rf + 3 * i;
    const Double4 xiv = load3(xi);
    const Double4 ri0 = splat(ri[0]), ri1 = splat(ri[1]), ri2 = splat(ri[2]);
    const int n = fam.npartner[i];
    int *jl = fam.jlocal[i];
    const double *om = fam.omega[i];
    int broke = 0;
    Double4 m0 = splat(0.0), m1 = m0, m2 = m0;

    // the term omega eta (x) xi of bond b (eta in e, xi by components)
    auto add_term = [&](int b, Double4 e, Double4 x0, Double4 x1, Double4 x2)
                        PERISISSM_FUSED_TARGET PERISISSM_INLINE {
                          const Double4 we = bcast(om + b) * e;
                          m0 = fma4(we, x0, m0);
                          m1 = fma4(we, x1, m1);
                          m2 = fma4(we, x2, m2);
                        };
    // bond b to partner j: the check (one bond), and its term of M if it holds
    auto one_bond = [&](int b, int j) PERISISSM_FUSED_TARGET PERISISSM_INLINE {
      const double *xj = xf + 3 * j;
      Double4 x0, x1, x2;
      bond_xi<PBC>(rf + 3 * j, ri0, ri1, ri2, box, x0, x1, x2);
      if (MODE != BreakingRule::NOBREAK &&
          bond_breaks<MODE, UNIFORM, true>(rule, p, itype, j, smini, xj[0] - xi[0], xj[1] - xi[1],
                                           xj[2] - xi[2], lane0(x0), lane0(x1), lane0(x2), acc,
                                           den)) {
        jl[b] = -1;
        broke = 1;
        return;
      }
      add_term(b, load3(xj) - xiv, x0, x1, x2);
    };

    int b = 0;
    if constexpr (MODE != BreakingRule::NOBREAK && UNIFORM) {
      const Double4 one_s00 = splat(1.0 + rule.uniform_s00()), alpha = splat(rule.uniform_alpha());
      const Double4 smin_i = splat(smini);
      const double acc0 = acc, den0 = den;
      bool breaks = false;
      while (b + 4 <= n && !breaks) {
        const int j0 = jl[b], j1 = jl[b + 1], j2 = jl[b + 2], j3 = jl[b + 3];
        if ((j0 | j1 | j2 | j3) < 0) {
          if (j0 >= 0) one_bond(b, j0);
          b++;
          continue;
        }
        // the four terms of M, in order
        const Double4 e0 = load3(xf + 3 * j0) - xiv, e1 = load3(xf + 3 * j1) - xiv;
        const Double4 e2 = load3(xf + 3 * j2) - xiv, e3 = load3(xf + 3 * j3) - xiv;
        // (and |xi|^2 of each in every lane)
        auto term = [&](int bb, int j, Double4 e) PERISISSM_FUSED_TARGET PERISISSM_INLINE {
          Double4 x0, x1, x2;
          bond_xi<PBC>(rf + 3 * j, ri0, ri1, ri2, box, x0, x1, x2);
          add_term(bb, e, x0, x1, x2);
          return fma4(x2, x2, fma4(x1, x1, x0 * x0));
        };
        const Double4 q20 = term(b, j0, e0), q21 = term(b + 1, j1, e1);
        const Double4 q22 = term(b + 2, j2, e2), q23 = term(b + 3, j3, e3);
        const Double4 q2 = lanes(q20, q21, q22, q23);
        // the four checks, one per lane
        Double4 c0, c1, c2;
        columns3(e0, e1, e2, e3, c0, c1, c2);
        const Double4 r2 = fma4(c2, c2, fma4(c1, c1, c0 * c0));
        if (MODE == BreakingRule::BREAK) {
          const Double4 lim = one_s00 - alpha * max4(smin_i, load_at(p.smin, j0, j1, j2, j3));
          breaks |= any4(or4(less4(lim, splat(0.0)), greater4(r2, lim * lim * q2)));
        }
        if (any4(less4(r2 * splat(den), splat(acc) * q2))) {
          double r2l[4], q2l[4];
          store4(r2l, r2);
          store4(q2l, q2);
          for (int l = 0; l < 4; l++) BreakingRule::keep_smaller(r2l[l], q2l[l], acc, den);
        }
        b += 4;
      }
      if (breaks) {
        // a bond of the family breaks: M and the smallest stretch again, one bond at a time
        m0 = m1 = m2 = splat(0.0);
        acc = acc0;
        den = den0;
        b = 0;
      }
    }
    for (; b < n; b++)
      if (jl[b] >= 0) one_bond(b, jl[b]);

    double c[12];
    store4(c, m0);
    store4(c + 4, m1);
    store4(c + 8, m2);
    for (int r = 0; r < 3; r++)
      for (int k = 0; k < 3; k++) M[3 * r + k] = c[4 * k + r];
    return broke;
  }
#endif

  // FUSED: the version with fused multiply-adds (linalg/fused.h); inlined into the function
  // that selects it, so that it is compiled for that function's target (peri/instances.h)
  template <int MODE, int UNIFORM, int PBC, int MEMBRANE, bool FUSED>
  [[gnu::always_inline]] inline void
  state_pass(const Model &model, const Particles &p, const Families &fam, const ReferenceBox &box,
             bool blocks, ParticleFields &fields, std::vector<int> &broke_list)
  {
    constexpr int NG = ParticleFields::NG, NK = ParticleFields::NK;
    const BreakingRule &rule = model.breaking();
    const double *rf = p.x0;
    const int *type = p.type;
    double *s0 = p.smin;
    const int nlocal = p.nlocal;
    constexpr double ACC0 = BreakingRule::initial<UNIFORM>();
    BondRows rows(fam, nlocal);
    // the stresses of regular particles G at a time (their SVDs side by side; 4 in the lanes of
    // the fused version's registers, fast_svd.h): M of those waiting, and of the current one
    constexpr int G = FUSED ? 4 : 2;
    double mrow[G][9];
    CorrespondenceState wait[G];
    int nwait = 0;

    for (int i = 0; i < nlocal; i++) {
      const int itype = type[i];
      double acc = ACC0, den = 0.0;
      int broke = 0;
      const double smini = (MODE != BreakingRule::NOBREAK) ? s0[i] : 0.0;

      // the breaking check, and M = sum omega eta (x) xi over the unbroken bonds (M of a
      // regular particle goes to the free row of mrow)
      double *M = mrow[nwait];
      // (the 4-wide loop with the other 4-wide passes: where fields.cols is given)
#ifdef PERISISSM_CPU_DISPATCH
      if (FUSED && fields.cols)
        broke = state_bonds_fused<MODE, UNIFORM, PBC>(rule, p, fam, box, i, smini, acc, den, M);
      else
#endif
        broke =
            state_bonds<MODE, UNIFORM, PBC, FUSED>(rule, p, fam, box, i, smini, acc, den, rows, M);

      if (MODE != BreakingRule::NOBREAK) {
        fields.smin_new[i] = BreakingRule::smin_from<UNIFORM>(acc, den, smini);
        if (broke) {
          update_shape(fam, rf, box, i, MEMBRANE ? model.reference_normal(fam, itype, i) : nullptr);
          broke_list.push_back(i);
        }
      }

      double *g = fields.g + NG * i;
      double *h = fields.h + 9 * i;
      if (MEMBRANE && fam.kregular[i] && model.membrane(itype)) {
        // a membrane particle: its own state (membrane/membrane.h)
        g[ParticleFields::G_C] = model.stabilization_modulus(itype, fam.kinv[i]);
        double *k = blocks ? fields.k + NK * i : nullptr;
        if (k) {
          k[ParticleFields::K_C] = g[ParticleFields::G_C];
          k[ParticleFields::K_ONE] = 1.0;
        }
        g[ParticleFields::G_REG] = 1.0;
        fields.w[i] = membrane_state(model.material(itype), M, fam.kinv[i], fam.normal[i], g, h, k);
      } else if (fam.kregular[i]) {
        // this one waits for the next, or goes with those waiting
        g[ParticleFields::G_C] = model.stabilization_modulus(itype, fam.kinv[i]);
        double *k = blocks ? fields.k + NK * i : nullptr;
        if (k) {
          k[ParticleFields::K_C] = g[ParticleFields::G_C];
          k[ParticleFields::K_ONE] = 1.0;
        }
        g[ParticleFields::G_REG] = 1.0;
        const CorrespondenceState state{
            &model.material(itype), M, fam.kinv[i], g, h, k, fields.w + i};
        wait[nwait++] = state;
        if (nwait == G) {
          if constexpr (G == 4)
            correspondence_states(wait);
          else
            correspondence_states(wait[0], wait[1]);
          nwait = 0;
        }
      } else {
        // singular K: F is undefined, the particle carries no force state of its own (H = 0,
        // C = 0, W = 0) and F is reported as the identity
        for (int k = 0; k < 9; k++) g[k] = (k % 4 == 0) ? 1.0 : 0.0;
        for (int k = 0; k < 9; k++) h[k] = 0.0;
        if (blocks) {
          for (int k = 0; k < NK; k++) fields.k[NK * i + k] = 0.0;
          fields.k[NK * i + ParticleFields::K_ONE] = 1.0;
        }
        g[ParticleFields::G_C] = 0.0;
        g[ParticleFields::G_REG] = 0.0;
        fields.w[i] = 0.0;
      }
    }

    for (int q = 0; q + 1 < nwait; q += 2) correspondence_states(wait[q], wait[q + 1]);
    if (nwait % 2) {
      const CorrespondenceState &last = wait[nwait - 1];
      *last.W = correspondence_state(*last.material, last.M, last.Kinv, last.F, last.A, last.H);
    }

    if (MODE != BreakingRule::NOBREAK)
      for (int i = 0; i < nlocal; i++) s0[i] = fields.smin_new[i];
  }

  // The SISSM block of particle i (elastic.h) from a[] = sum_j omega_ij k_j over its unbroken
  // bonds, in family order (a[K_ONE] is the family's weight sum, k_j[K_ONE] being 1).
  inline void finish_block(const ParticleFields &fields, int i, const double *a, double *out)
  {
    constexpr int NK = ParticleFields::NK, K_C = ParticleFields::K_C;
    const double *ki = fields.k + NK * i;
    const double wsum = a[ParticleFields::K_ONE];
    const double cdiag = 0.5 * (wsum * ki[K_C] + a[K_C]);
    for (int k = 0; k < 6; k++) out[k] = wsum * ki[k] + a[k] + (k < 3 ? cdiag : 0.0);
    // a membrane's stabilization acts in its tangent plane only (stabilization.h): its share of
    // the block is cdiag (I - n n^T) with the particle's current normal
    if (fields.normal) {
      const double *n = fields.normal + 3 * i;
      if (has_normal(n)) {
        out[0] -= cdiag * n[0] * n[0];
        out[1] -= cdiag * n[1] * n[1];
        out[2] -= cdiag * n[2] * n[2];
        out[3] -= cdiag * n[0] * n[1];
        out[4] -= cdiag * n[0] * n[2];
        out[5] -= cdiag * n[1] * n[2];
      }
    }
  }

  // the SISSM block of particle i, plain arithmetic
  inline void implicit_block(const Families &fam, const ParticleFields &fields, int i, double *out)
  {
    constexpr int NK = ParticleFields::NK;
    const int n = fam.npartner[i];
    const int *jl = fam.jlocal[i];
    const double *om = fam.omega[i];
    double a[NK] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (int b = 0; b < n; b++) {
      const int j = jl[b];
      if (j < 0) continue;
      const double *kj = fields.k + NK * j;
      const double w = om[b];
      for (int k = 0; k < NK; k++) a[k] = madd<false>(w, kj[k], a[k]);
    }
    finish_block(fields, i, a, out);
  }

#ifdef PERISISSM_CPU_DISPATCH
  // lo, hi += w k_j (the eight doubles of a row of k)
  PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void
  add_k_row(const double *kf, int j, double w, Double4 &lo, Double4 &hi)
  {
    constexpr int NK = ParticleFields::NK;
    lo = fma4(w, kf + NK * j, lo);
    hi = fma4(w, kf + NK * j + 4, hi);
  }

  // The SISSM blocks of the P particles i0 .. i0+P-1 with fused multiply-adds: the same sums in
  // the same order as implicit_block, each row of k (eight doubles) in two 4-wide multiply-adds.
  // A particle's sum is a chain of dependent multiply-adds (one per bond), so a single family
  // waits on their latency; the families of P particles go side by side, bond b of each in
  // turn, and the chains overlap.
  template <int P>
  PERISISSM_FUSED_TARGET inline void
  implicit_blocks_fused(const Families &fam, const ParticleFields &fields, int i0, double **block)
  {
    constexpr int NK = ParticleFields::NK;
    static_assert(NK == 8, "a row of k is two 4-wide vectors");
    const double *kf = fields.k;
    const int *jl[P];
    const double *om[P];
    int n[P];
    Double4 lo[P], hi[P];
    int nmin = fam.npartner[i0];
    for (int q = 0; q < P; q++) {
      jl[q] = fam.jlocal[i0 + q];
      om[q] = fam.omega[i0 + q];
      n[q] = fam.npartner[i0 + q];
      nmin = std::min(nmin, n[q]);
      lo[q] = hi[q] = Double4{0.0, 0.0, 0.0, 0.0};
    }
    for (int b = 0; b < nmin; b++)
#pragma GCC unroll 4
      for (int q = 0; q < P; q++)
        if (jl[q][b] >= 0) add_k_row(kf, jl[q][b], om[q][b], lo[q], hi[q]);
    for (int q = 0; q < P; q++) {
      for (int b = nmin; b < n[q]; b++)
        if (jl[q][b] >= 0) add_k_row(kf, jl[q][b], om[q][b], lo[q], hi[q]);
      double a[NK];
      __builtin_memcpy(a, &lo[q], sizeof lo[q]);
      __builtin_memcpy(a + 4, &hi[q], sizeof hi[q]);
      finish_block(fields, i0 + q, a, block[i0 + q]);
    }
  }
#endif

#ifdef PERISISSM_CPU_DISPATCH
  // The fused force pass, 4-wide (linalg/double4.h): the same operations in the same order as
  // force_pass<..., FUSED = true> below, so the same bits. H of each particle comes by columns
  // from fields.cols (peri/columns.h, filled here), each component of xi is in every lane of its
  // own register; the force is a 3-vector in lanes 0-2.
  template <int EVFLAG, int PBC, int BLOCKS>
  PERISISSM_FUSED_TARGET void
  force_pass_columns(const Particles &p, const Families &fam, const ReferenceBox &box,
                     const ParticleFields &fields, const Virial &virial, double **block)
  {
    constexpr int NC = ParticleFields::NCOLS;
    const double *xf = p.x;
    const double *rf = p.x0;
    const double *cols = fields.cols;
    const int nlocal = p.nlocal;
    fill_columns(fields.h, 9, p.nall, fields.cols);

    for (int i = 0; i < nlocal; i++) {
      const double *ci = cols + NC * i;
      const Double4 hi0 = load4(ci), hi1 = load4(ci + 4), hi2 = load4(ci + 8);
      const double *ri = rf + 3 * i;
      const Double4 ri0 = splat(ri[0]), ri1 = splat(ri[1]), ri2 = splat(ri[2]);
      const int n = fam.npartner[i];
      const int *jl = fam.jlocal[i];
      const double *om = fam.omega[i];
      Double4 fsum = splat(0.0);
      BondVirial vir;

      for (int b = 0; b < n; b++) {
        const int j = jl[b];
        if (j < 0) continue;
        const double *cj = cols + NC * j;
        Double4 x0, x1, x2;
        bond_xi<PBC>(rf + 3 * j, ri0, ri1, ri2, box, x0, x1, x2);
        // w (H_i + H_j) xi
        const Double4 t = bcast(om + b) *
            mat_vec(hi0 + load4(cj), hi1 + load4(cj + 4), hi2 + load4(cj + 8), x0, x1, x2);
        fsum += t;
        if (EVFLAG) {
          double tv[4], ev[4];
          store4(tv, t);
          store4(ev, load3(xf + 3 * j) - load3(xf + 3 * i));
          vir.add(ev[0], ev[1], ev[2], tv[0], tv[1], tv[2]);
        }
      }

      double fs[4];
      store4(fs, fsum);
      p.f[3 * i] += fs[0];
      p.f[3 * i + 1] += fs[1];
      p.f[3 * i + 2] += fs[2];
      if (EVFLAG) vir.tally(virial, i, -0.5 * p.volume[i]);
      // (while the last four families are in the cache)
      if constexpr (BLOCKS)
        if ((i & 3) == 3) implicit_blocks_fused<4>(fam, fields, i - 3, block);
    }
    if constexpr (BLOCKS)
      for (int i = nlocal & ~3; i < nlocal; i++) implicit_blocks_fused<1>(fam, fields, i, block);
  }
#endif

  template <int EVFLAG, int PBC, int BLOCKS, bool FUSED>
  [[gnu::always_inline]] inline void
  force_pass(const Particles &p, const Families &fam, const ReferenceBox &box,
             const ParticleFields &fields, const Virial &virial, double **block)
  {
    const double *xf = p.x;
    const double *rf = p.x0;
    double *f = p.f;
    const double *vfrac = p.volume;
    const int nlocal = p.nlocal;
    const double *hf = fields.h;

    for (int i = 0; i < nlocal; i++) {
      const double *hi = hf + 9 * i;
      const double xi0 = xf[3 * i], xi1 = xf[3 * i + 1], xi2 = xf[3 * i + 2];
      const double ri0 = rf[3 * i], ri1 = rf[3 * i + 1], ri2 = rf[3 * i + 2];
      const int n = fam.npartner[i];
      const int *jl = fam.jlocal[i];
      const double *om = fam.omega[i];
      double fx = 0.0, fy = 0.0, fz = 0.0;
      BondVirial vir;

      for (int b = 0; b < n; b++) {
        const int j = jl[b];
        if (j < 0) continue;
        const double *hj = hf + 9 * j;
        const double w = om[b];
        const double *rj = rf + 3 * j;
        double x0 = rj[0] - ri0, x1 = rj[1] - ri1, x2 = rj[2] - ri2;
        if (PBC) box.image(x0, x1, x2);
        // w (H_i + H_j) xi
        const double t0 = w *
            madd<FUSED>(hi[2] + hj[2], x2, madd<FUSED>(hi[1] + hj[1], x1, (hi[0] + hj[0]) * x0));
        const double t1 = w *
            madd<FUSED>(hi[5] + hj[5], x2, madd<FUSED>(hi[4] + hj[4], x1, (hi[3] + hj[3]) * x0));
        const double t2 = w *
            madd<FUSED>(hi[8] + hj[8], x2, madd<FUSED>(hi[7] + hj[7], x1, (hi[6] + hj[6]) * x0));
        fx += t0;
        fy += t1;
        fz += t2;
        if (EVFLAG) {
          const double *xj = xf + 3 * j;
          vir.add(xj[0] - xi0, xj[1] - xi1, xj[2] - xi2, t0, t1, t2);
        }
      }

      f[3 * i] += fx;
      f[3 * i + 1] += fy;
      f[3 * i + 2] += fz;
      if (EVFLAG) vir.tally(virial, i, -0.5 * vfrac[i]);
      if constexpr (BLOCKS && !FUSED) implicit_block(fam, fields, i, block[i]);
#ifdef PERISISSM_CPU_DISPATCH
      // (while the last four families are in the cache; only the dispatch builds the fused
      // version)
      if constexpr (BLOCKS && FUSED)
        if ((i & 3) == 3) implicit_blocks_fused<4>(fam, fields, i - 3, block);
#endif
    }
#ifdef PERISISSM_CPU_DISPATCH
    if constexpr (BLOCKS && FUSED)
      for (int i = nlocal & ~3; i < nlocal; i++) implicit_blocks_fused<1>(fam, fields, i, block);
#endif
  }

}    // namespace

void elastic_state_pass(const Model &model, const Particles &p, const Families &fam,
                        const ReferenceBox &box, int mode, bool blocks, ParticleFields &fields,
                        std::vector<int> &broke)
{
  using R = BreakingRule;
  const bool uniform = model.breaking().uniform();
  // membrane particles only in decks that have them (the volume decks' loop is unchanged)
  const bool membranes = fam.normal && model.any_membrane();
  with_version([&](auto fused) PERISISSM_INLINE {
    with_flags(box.any(), membranes, [&](auto pbc, auto membrane) PERISISSM_INLINE {
      constexpr bool F = decltype(fused)::value;
      constexpr int PBC = decltype(pbc)::value, MB = decltype(membrane)::value;
      if (mode == R::NOBREAK)
        state_pass<R::NOBREAK, 0, PBC, MB, F>(model, p, fam, box, blocks, fields, broke);
      else if (mode == R::S0ONLY)
        uniform ? state_pass<R::S0ONLY, 1, PBC, MB, F>(model, p, fam, box, blocks, fields, broke)
                : state_pass<R::S0ONLY, 0, PBC, MB, F>(model, p, fam, box, blocks, fields, broke);
      else
        uniform ? state_pass<R::BREAK, 1, PBC, MB, F>(model, p, fam, box, blocks, fields, broke)
                : state_pass<R::BREAK, 0, PBC, MB, F>(model, p, fam, box, blocks, fields, broke);
    });
  });
}

void elastic_force_pass(const Particles &p, const Families &fam, const ReferenceBox &box,
                        const ParticleFields &fields, const Virial &virial, double **block)
{
  with_version([&](auto fused) PERISISSM_INLINE {
    with_flag(block != nullptr, [&](auto blocks) PERISISSM_INLINE {
      with_flags(virial.any(), box.any(), [&](auto ev, auto pbc) PERISISSM_INLINE {
#ifdef PERISISSM_CPU_DISPATCH
        if constexpr (decltype(fused)::value)
          if (fields.cols) {
            force_pass_columns<decltype(ev)::value, decltype(pbc)::value, decltype(blocks)::value>(
                p, fam, box, fields, virial, block);
            return;
          }
#endif
        force_pass<decltype(ev)::value, decltype(pbc)::value, decltype(blocks)::value,
                   decltype(fused)::value>(p, fam, box, fields, virial, block);
      });
    });
  });
}

}    // namespace PeriSISSM
