// Zero-energy-mode stabilization (see stabilization.h).

#include "peri/stabilization.h"

#include "linalg/double4.h"
#include "linalg/fused.h"
#include "linalg/small_matrix.h"
#include "membrane/membrane.h"
#include "peri/bond_rows.h"
#include "peri/columns.h"
#include "peri/instances.h"
#include "peri/model.h"

#include <cmath>

namespace PeriSISSM {

// Cs 18K/(pi delta^5) * kappa_i / kappa_0 with kappa = tr(K^-1)/3 and kappa_0 = 15/(4 pi delta^5):
// the delta^5 and pi cancel, 18 * 4 / 15 / 3 = 8/5.
double stabilization_modulus(double Cs, double K, const double Kinv[9])
{
  return 1.6 * Cs * K * (Kinv[0] + Kinv[4] + Kinv[8]);
}

namespace {

  // For each bond
  //   z = eta - Fbar xi,  Fbar = a_i F_i + a_j F_j  (a = 1/2 each; 1 and 0 when one end has a
  //   singular K and no F),
  // direct force density Cbar omega z on i, energy density 1/4 Cbar omega |z|^2 on i, and
  // Q_i = -sum_j a_i Cbar omega z (x) xi, so that H_i = A_i + Q_i K_i^-1.
  // The loop over the bonds of each particle forms z and the direct force, and stores u = 2 a_i
  // Cbar omega z with xi; the 3x3 sum Q of u (x) xi follows from those rows (bond_rows.h). The
  // energy is summed only when asked for (EFLAG), which keeps the loop at three accumulators.
  // the image of a membrane particle's reference tangent plane under F: a_k = F t_k for the
  // tangent frame (t1, t2) of its reference normal n0, and c = a1 x a2 (the current normal times
  // the area stretch)
  struct PlaneImage {
    double t1[3], t2[3], a1[3], a2[3], c[3];
    PlaneImage(const double *F, const double *n0)
    {
      tangent_frame(n0, t1, t2);
      for (int k = 0; k < 3; k++) {
        a1[k] = F[3 * k] * t1[0] + F[3 * k + 1] * t1[1] + F[3 * k + 2] * t1[2];
        a2[k] = F[3 * k] * t2[0] + F[3 * k + 1] * t2[1] + F[3 * k + 2] * t2[2];
      }
      cross3(a1, a2, c);
    }
  };

  // current unit normal of every membrane particle with an F (owned and ghost rows):
  // n = F t1 x F t2 / |F t1 x F t2|; zero for the others and where the image of the plane has
  // collapsed
  void current_normals(const Model &model, const Particles &p, const Families &fam,
                       ParticleFields &fields)
  {
    constexpr int NG = ParticleFields::NG;
    for (int r = 0; r < p.nall; r++) {
      double *n = fields.normal + 3 * r;
      n[0] = n[1] = n[2] = 0.0;
      const double *g = fields.g + NG * r;
      if (!model.membrane(p.type[r]) || !(g[ParticleFields::G_REG] > 0.0)) continue;
      const PlaneImage im(g, fam.normal[r]);
      const double *c = im.c, *a1 = im.a1, *a2 = im.a2;
      const double l = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      const double scale = std::sqrt(a1[0] * a1[0] + a1[1] * a1[1] + a1[2] * a1[2]) *
          std::sqrt(a2[0] * a2[0] + a2[1] * a2[1] + a2[2] * a2[2]);
      if (!(l > 1.0e-14 * scale)) continue;
      for (int k = 0; k < 3; k++) n[k] = c[k] / l;
    }
  }

  // G = (a2 x w) (x) t1 + (w x a1) (x) t2 (stabilization.h): the derivative of the particle's
  // stabilization energy density through its normal, as a stress-like 3x3 (row-major) added to Q
  inline void normal_term(const double *F, const double *n0, const double *nrm, const double gn[3],
                          double G[9])
  {
    const PlaneImage im(F, n0);
    const double *c = im.c;
    const double l = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double along = gn[0] * nrm[0] + gn[1] * nrm[1] + gn[2] * nrm[2];
    double w[3], u[3], v[3];
    for (int k = 0; k < 3; k++) w[k] = (gn[k] - along * nrm[k]) / l;
    cross3(im.a2, w, u);
    cross3(w, im.a1, v);
    for (int r = 0; r < 3; r++)
      for (int c2 = 0; c2 < 3; c2++) G[3 * r + c2] = u[r] * im.t1[c2] + v[r] * im.t2[c2];
  }

  // H_i -= Q_i K_i^-1 / 2 from q (sum_j 2 a_i Cbar omega z (x) xi, row-major)
  inline void add_q_term(const double q[9], const double *k, double *h)
  {
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        h[3 * r + c] -= 0.5 * (q[3 * r] * k[c] + q[3 * r + 1] * k[3 + c] + q[3 * r + 2] * k[6 + c]);
  }

  // H_i += G_i K_i^-1 from the normal term G (normal_term, row-major)
  inline void add_normal_term(const double G[9], const double *k, double *h)
  {
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        h[3 * r + c] += G[3 * r] * k[c] + G[3 * r + 1] * k[3 + c] + G[3 * r + 2] * k[6 + c];
  }

  // The length form of bond ij (stabilization.h): with g = Fbar xi = e - z and
  // |e|^2 - |g|^2 = z . (e + g) = diff (summed (p0 + p1) + p2 over the components p_k = z_k
  // (e_k + g_k); no cancellation), d = diff / (2 |xi|) and s = cw d / |xi| = length_scale(cw,
  // diff, q2) with q2 = |xi|^2; the direct force density on i is t = s e, the term of Q_i
  // u = qa s g (in place of qa cw z), and cw d^2 = s diff / 2 the energy sum's term. Both passes
  // form p with the same operations (the 4-wide one on the lanes of e, z and g).
  inline double length_scale(double cw, double diff, double q2)
  {
    return 0.5 * cw * diff / q2;
  }

#ifdef PERISISSM_CPU_DISPATCH
  // The fused pass, 4-wide (linalg/double4.h): the same operations
  // in the same order as pass<..., FUSED = true> below, so the same bits. F of each particle
  // comes by columns from fields.cols (peri/columns.h; lane 3 of column 0 holds C, of column 1
  // the regular flag); z, the direct force and the columns of Q are 3-vectors in lanes 0-2 (lane
  // 3 carries finite values nobody reads), each component of xi is in every lane of its own
  // register, and Q is summed bond by bond in family order as BondRows::outer_sum sums it.
  // LENGTH: the length form for every bond not between membranes (length_form() on the lanes).
  template <int EFLAG, int EVFLAG, int PBC, int MEMBRANE, int LENGTH>
  PERISISSM_FUSED_TARGET void pass_columns(const Particles &p, const Families &fam,
                                           const ReferenceBox &box, ParticleFields &fields,
                                           const Virial &virial)
  {
    constexpr int NC = ParticleFields::NCOLS;
    const double *xf = p.x;
    const double *rf = p.x0;
    const double *cols = fields.cols;
    const int nlocal = p.nlocal;
    fill_columns(fields.g, ParticleFields::NG, p.nall, fields.cols);
    const Double4 half = splat(0.5);

    for (int i = 0; i < nlocal; i++) {
      const double *ci = cols + NC * i;
      const Double4 fi0 = load4(ci), fi1 = load4(ci + 4), fi2 = load4(ci + 8);
      const Double4 cmod = bcast(ci + 3);
      const int regi = ci[7] > 0.0;
      const double *ri = rf + 3 * i;
      const Double4 xi = load3(xf + 3 * i);
      const Double4 ri0 = splat(ri[0]), ri1 = splat(ri[1]), ri2 = splat(ri[2]);
      const int n = fam.npartner[i];
      const int *jl = fam.jlocal[i];
      const double *om = fam.omega[i];
      Double4 fsum = splat(0.0), q0 = fsum, q1 = fsum, q2 = fsum;
      double ws = 0.0;
      BondVirial vir;
      const double *ni = MEMBRANE ? fields.normal + 3 * i : nullptr;
      const bool hasni = MEMBRANE && has_normal(ni);
      const Double4 niv = MEMBRANE ? load3(fields.normal + 3 * i) : splat(0.0);
      Double4 gn = splat(0.0);    // membranes: dE/dn_i per unit volume

      for (int b = 0; b < n; b++) {
        const int j = jl[b];
        if (j < 0) continue;
        const double *cj = cols + NC * j;
        const int regj = cj[7] > 0.0;
        Double4 x0, x1, x2;
        bond_xi<PBC>(rf + 3 * j, ri0, ri1, ri2, box, x0, x1, x2);
        const Double4 e = load3(xf + 3 * j) - xi;
        Double4 z;
        if (regi && regj)
          z = e -
              half * mat_vec(fi0 + load4(cj), fi1 + load4(cj + 4), fi2 + load4(cj + 8), x0, x1, x2);
        else if (regi)
          z = e - mat_vec(fi0, fi1, fi2, x0, x1, x2);
        else if (regj)
          z = e - mat_vec(load4(cj), load4(cj + 4), load4(cj + 8), x0, x1, x2);
        else
          continue;
        const Double4 cw = half * (cmod + bcast(cj + 3)) * bcast(om + b);
        if constexpr (LENGTH > 0) {
          // (only in decks without membranes: every bond has the length form)
          const Double4 g = e - z;
          double pv[4];
          store4(pv, z * (e + g));
          const double diff = (pv[0] + pv[1]) + pv[2];
          const double xx = lane0(fma4(x2, x2, fma4(x1, x1, x0 * x0)));
          const double s = length_scale(lane0(cw), diff, xx);
          const double qa = (regi && regj) ? 1.0 : (regi ? 2.0 : 0.0);
          const Double4 t = splat(s) * e, u = splat(qa * s) * g;
          fsum += t;
          q0 = fma4(u, x0, q0);
          q1 = fma4(u, x1, q1);
          q2 = fma4(u, x2, q2);
          if (EFLAG) ws += 0.5 * s * diff;
          if (EVFLAG) {
            double tv[4], ev[4];
            store4(tv, t);
            store4(ev, e);
            vir.add(ev[0], ev[1], ev[2], tv[0], tv[1], tv[2]);
          }
          continue;
        }
        Double4 t = cw * z;
        if (MEMBRANE) {
          // the part of z in the tangent planes of the two ends (an end without a normal takes
          // the other's), as pass<> below does it
          const double *nj = fields.normal + 3 * j;
          const bool hasnj = has_normal(nj);
          if (hasni || hasnj) {
            const Double4 njv = load3(nj);
            const Double4 na = hasni ? niv : njv, nb = hasnj ? njv : niv;
            double pa[4], pb[4];
            store4(pa, na * z);
            store4(pb, nb * z);
            const double da = pa[0] + pa[1] + pa[2], db = pb[0] + pb[1] + pb[2];
            if (hasni) {
              const double sg = -0.5 * lane0(cw) * (hasnj ? da : 2.0 * da);
              gn += splat(sg) * z;
            }
            t = cw * (z - half * (splat(da) * na + splat(db) * nb));
          }
        }
        fsum += t;
        // the bond's weight in Q_i, times 2 (qa: 1, or 2 and 0 where one end has no F)
        const Double4 u = (regi && regj) ? t : (regi ? splat(2.0) * t : splat(0.0) * t);
        q0 = fma4(u, x0, q0);
        q1 = fma4(u, x1, q1);
        q2 = fma4(u, x2, q2);
        if (EFLAG || EVFLAG) {
          double tz[4], tv[4], ev[4];
          store4(tz, t * z);
          store4(tv, t);
          store4(ev, e);
          if (EFLAG) ws += tz[0] + tz[1] + tz[2];
          if (EVFLAG) vir.add(ev[0], ev[1], ev[2], tv[0], tv[1], tv[2]);
        }
      }

      double fs[4];
      store4(fs, fsum);
      p.f[3 * i] += fs[0];
      p.f[3 * i + 1] += fs[1];
      p.f[3 * i + 2] += fs[2];
      if (EFLAG) fields.w[i] += 0.25 * ws;
      if (EVFLAG) vir.tally(virial, i, -0.5 * p.volume[i]);
      if (!regi) continue;
      double c[12];
      store4(c, q0);
      store4(c + 4, q1);
      store4(c + 8, q2);
      const double q[9] = {c[0], c[4], c[8], c[1], c[5], c[9], c[2], c[6], c[10]};
      const double *k = fam.kinv[i];
      double *h = fields.h + 9 * i;
      add_q_term(q, k, h);
      if (MEMBRANE && hasni) {
        double gv[4], G[9];
        store4(gv, gn);
        normal_term(fields.g + ParticleFields::NG * i, fam.normal[i], ni, gv, G);
        add_normal_term(G, k, h);
      }
    }
  }
#endif

  // FUSED: the version with fused multiply-adds (linalg/fused.h, peri/instances.h); LENGTH: 0 the
  // vector form, 1 the length form where model.length_bond() says so, 2 the length form for every
  // bond not between membranes
  template <int EFLAG, int EVFLAG, int PBC, int MEMBRANE, int LENGTH, bool FUSED>
  [[gnu::always_inline]] inline void pass(const Model &model, const Particles &p,
                                          const Families &fam, const ReferenceBox &box,
                                          ParticleFields &fields, const Virial &virial)
  {
    constexpr int NG = ParticleFields::NG;
    const double *xf = p.x;
    const double *rf = p.x0;
    double *f = p.f;
    const double *vfrac = p.volume;
    const int nlocal = p.nlocal;
    const double *gf = fields.g;
    BondRows rows(fam, nlocal);

    for (int i = 0; i < nlocal; i++) {
      const double *gi = gf + NG * i;
      const double *Fi = gi;
      const double ci = gi[ParticleFields::G_C];
      const int regi = gi[ParticleFields::G_REG] > 0.0;
      const double xi0 = xf[3 * i], xi1 = xf[3 * i + 1], xi2 = xf[3 * i + 2];
      const double ri0 = rf[3 * i], ri1 = rf[3 * i + 1], ri2 = rf[3 * i + 2];
      const int n = fam.npartner[i];
      const int *jl = fam.jlocal[i];
      const double *om = fam.omega[i];
      double fx = 0.0, fy = 0.0, fz = 0.0, ws = 0.0;
      BondVirial vir;
      rows.clear();
      const double *ni = MEMBRANE ? fields.normal + 3 * i : nullptr;
      const bool hasni = MEMBRANE && has_normal(ni);
      double gn[3] = {0.0, 0.0, 0.0};    // membranes: dE/dn_i per unit volume

      for (int b = 0; b < n; b++) {
        const int j = jl[b];
        if (j < 0) continue;
        const double *gj = gf + NG * j;
        const int regj = gj[ParticleFields::G_REG] > 0.0;
        const double *xj = xf + 3 * j;
        const double *rj = rf + 3 * j;
        const double e0 = xj[0] - xi0, e1 = xj[1] - xi1, e2 = xj[2] - xi2;
        double x0 = rj[0] - ri0, x1 = rj[1] - ri1, x2 = rj[2] - ri2;
        if (PBC) box.image(x0, x1, x2);
        double z0, z1, z2, qa;    // qa = 2 a_i (weight of this bond in Q_i, times 2)
        if (regi && regj) {
          // Fbar = (F_i + F_j) / 2
          z0 = e0 -
              0.5 *
                  madd<FUSED>(Fi[2] + gj[2], x2,
                              madd<FUSED>(Fi[1] + gj[1], x1, (Fi[0] + gj[0]) * x0));
          z1 = e1 -
              0.5 *
                  madd<FUSED>(Fi[5] + gj[5], x2,
                              madd<FUSED>(Fi[4] + gj[4], x1, (Fi[3] + gj[3]) * x0));
          z2 = e2 -
              0.5 *
                  madd<FUSED>(Fi[8] + gj[8], x2,
                              madd<FUSED>(Fi[7] + gj[7], x1, (Fi[6] + gj[6]) * x0));
          qa = 1.0;
        } else if (regi || regj) {
          // one end without F: Fbar is the other end's F
          const double *Fo = regi ? Fi : gj;
          z0 = e0 - madd<FUSED>(Fo[2], x2, madd<FUSED>(Fo[1], x1, Fo[0] * x0));
          z1 = e1 - madd<FUSED>(Fo[5], x2, madd<FUSED>(Fo[4], x1, Fo[3] * x0));
          z2 = e2 - madd<FUSED>(Fo[8], x2, madd<FUSED>(Fo[7], x1, Fo[6] * x0));
          qa = regi ? 2.0 : 0.0;
        } else {
          continue;
        }
        const double cw = 0.5 * (ci + gj[ParticleFields::G_C]) * om[b];
        if (MEMBRANE) {
          // the part of z in the tangent planes of the two ends (an end without a normal takes
          // the other's)
          const double *nj = fields.normal + 3 * j;
          const bool hasnj = has_normal(nj);
          if (hasni || hasnj) {
            const double *na = hasni ? ni : nj, *nb = hasnj ? nj : ni;
            const double da = na[0] * z0 + na[1] * z1 + na[2] * z2;
            const double db = nb[0] * z0 + nb[1] * z1 + nb[2] * z2;
            if (hasni) {
              const double s = -0.5 * cw * (hasnj ? da : 2.0 * da);
              gn[0] += s * z0;
              gn[1] += s * z1;
              gn[2] += s * z2;
            }
            const double p0 = z0 - 0.5 * (da * na[0] + db * nb[0]);
            const double p1 = z1 - 0.5 * (da * na[1] + db * nb[1]);
            const double p2 = z2 - 0.5 * (da * na[2] + db * nb[2]);
            const double t0 = cw * p0, t1 = cw * p1, t2 = cw * p2;
            fx += t0;
            fy += t1;
            fz += t2;
            if (EFLAG) ws += t0 * z0 + t1 * z1 + t2 * z2;
            rows.push(qa * t0, qa * t1, qa * t2, x0, x1, x2);
            if (EVFLAG) vir.add(e0, e1, e2, t0, t1, t2);
            continue;
          }
        }
        if (LENGTH == 2 || (LENGTH == 1 && model.length_bond(p.type[i], p.type[j]))) {
          const double q2 = madd<FUSED>(x2, x2, madd<FUSED>(x1, x1, x0 * x0));
          const double g0 = e0 - z0, g1 = e1 - z1, g2 = e2 - z2;
          const double diff = (z0 * (e0 + g0) + z1 * (e1 + g1)) + z2 * (e2 + g2);
          const double s = length_scale(cw, diff, q2);
          const double t0 = s * e0, t1 = s * e1, t2 = s * e2;
          const double sq = qa * s;
          fx += t0;
          fy += t1;
          fz += t2;
          if (EFLAG) ws += 0.5 * s * diff;
          rows.push(sq * g0, sq * g1, sq * g2, x0, x1, x2);
          if (EVFLAG) vir.add(e0, e1, e2, t0, t1, t2);
          continue;
        }
        const double t0 = cw * z0, t1 = cw * z1, t2 = cw * z2;
        fx += t0;
        fy += t1;
        fz += t2;
        if (EFLAG) ws += t0 * z0 + t1 * z1 + t2 * z2;
        rows.push(qa * t0, qa * t1, qa * t2, x0, x1, x2);
        if (EVFLAG) vir.add(e0, e1, e2, t0, t1, t2);
      }

      f[3 * i] += fx;
      f[3 * i + 1] += fy;
      f[3 * i + 2] += fz;
      if (EFLAG) fields.w[i] += 0.25 * ws;
      if (EVFLAG) vir.tally(virial, i, -0.5 * vfrac[i]);
      if (!regi) continue;

      double q[9];
      rows.outer_sum<FUSED>(q);
      // H_i = A_i + Q_i K_i^-1 with Q_i = -(sum above)/2 (the sum carries 2 a_i)
      const double *k = fam.kinv[i];
      double *h = fields.h + 9 * i;
      add_q_term(q, k, h);
      if (MEMBRANE && hasni) {
        double G[9];
        normal_term(Fi, fam.normal[i], ni, gn, G);
        add_normal_term(G, k, h);
      }
    }
  }

}    // namespace

void stabilization_pass(const Model &model, const Particles &p, const Families &fam,
                        const ReferenceBox &box, ParticleFields &fields, const Virial &virial,
                        bool energy)
{
  // membranes only in decks that have them (the volume decks' loop is unchanged)
  const bool membranes = fam.normal && fields.normal && model.any_membrane();
  if (membranes) current_normals(model, p, fam, fields);
  // the length form only in decks that use it (the 4-wide pass has the vector form alone)
  const int length = model.all_length_deviation() ? 2 : (model.any_length_deviation() ? 1 : 0);
  with_version([&](auto fused) PERISISSM_INLINE {
    with_flags(energy, membranes, [&](auto eflag, auto membrane) PERISISSM_INLINE {
      with_flags(virial.any(), box.any(), [&](auto ev, auto pbc) PERISISSM_INLINE {
        constexpr int EF = decltype(eflag)::value, EV = decltype(ev)::value;
        constexpr int PBC = decltype(pbc)::value, MB = decltype(membrane)::value;
        constexpr bool FU = decltype(fused)::value;
        // (a deck with some types of each form goes through the scalar pass, asking per bond)
        if (length == 1) {
          pass<EF, EV, PBC, MB, 1, FU>(model, p, fam, box, fields, virial);
          return;
        }
#ifdef PERISISSM_CPU_DISPATCH
        if constexpr (FU)
          if (fields.cols) {
            if (length == 2)
              pass_columns<EF, EV, PBC, 0, 1>(p, fam, box, fields, virial);
            else
              pass_columns<EF, EV, PBC, MB, 0>(p, fam, box, fields, virial);
            return;
          }
#endif
        if (length == 2) {
          pass<EF, EV, PBC, 0, 2, FU>(model, p, fam, box, fields, virial);
          return;
        }
        pass<EF, EV, PBC, MB, 0, FU>(model, p, fam, box, fields, virial);
      });
    });
  });
}

}    // namespace PeriSISSM
