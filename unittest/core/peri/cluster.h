// A small particle cluster for the tests of the energy terms: owned particles and, in periodic
// boxes, ghost images (positions shifted by a box length, reference positions not shifted, as
// LAMMPS keeps them), bond families built from the reference positions, a halo that copies the
// owners' rows to their ghosts, and one evaluation of the bond terms. No LAMMPS.

#ifndef PERISISSM_TEST_CLUSTER_H
#define PERISISSM_TEST_CLUSTER_H

#include "peri/breaking.h"
#include "peri/family.h"
#include "peri/fields.h"
#include "peri/forces.h"
#include "peri/model.h"

#include <cmath>
#include <random>
#include <vector>

namespace PeriSISSMTest {

class Cluster : public PeriSISSM::Halo {
 public:
  // n owned particles on a simple cubic lattice of spacing 1 (nx x ny x nz), jittered by up to
  // jitter and with volumes in [1 - spread, 1 + spread], horizon delta; periodic in x with box
  // length nx when periodic is set.
  Cluster(int nx, int ny, int nz, double delta, bool periodic, unsigned seed, double jitter = 0.12,
          double spread = 0.4) :
      delta_(delta)
  {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> jit(-jitter, jitter), vol(1.0 - spread, 1.0 + spread);
    for (int i = 0; i < nx; i++)
      for (int j = 0; j < ny; j++)
        for (int k = 0; k < nz; k++) {
          x0.insert(x0.end(), {i + 0.5 + jit(rng), j + jit(rng), k + jit(rng)});
          volume.push_back(vol(rng));
        }
    nlocal = (int) volume.size();
    if (periodic) {
      box.periodic[0] = 1;
      box.box[0] = nx;
      box.box[1] = 100.0;
      box.box[2] = 100.0;
      for (int s : {-1, 1})
        for (int i = 0; i < nlocal; i++) {
          owner.push_back(i);
          shift.push_back(s * box.box[0]);
        }
    }
    nall = nlocal + (int) owner.size();
    for (int g = nlocal; g < nall; g++) volume.push_back(volume[owner[g - nlocal]]);
    type.assign(nall, 1);
    smin.assign(nall, 0.0);
    x = positions_of(x0);
    ref = reference_of(x0);
  }

  // an extra owned particle far out with a single partner (a singular shape tensor)
  void add_lonely(double dx)
  {
    // (only before build(); in non-periodic clusters)
    std::vector<double> p = {x0[0] - dx, x0[1], x0[2]};
    x0.insert(x0.begin() + 3 * nlocal, p.begin(), p.end());
    volume.insert(volume.begin() + nlocal, 0.8);
    nlocal++;
    nall++;
    type.assign(nall, 1);
    smin.assign(nall, 0.0);
    x = positions_of(x0);
    ref = reference_of(x0);
  }

  // all ghost rows from positions of the owned rows (owned: 3 * nlocal values)
  std::vector<double> positions_of(const std::vector<double> &own) const
  {
    std::vector<double> out(own.begin(), own.begin() + 3 * nlocal);
    for (size_t g = 0; g < owner.size(); g++)
      out.insert(out.end(),
                 {own[3 * owner[g]] + shift[g], own[3 * owner[g] + 1], own[3 * owner[g] + 2]});
    return out;
  }
  std::vector<double> reference_of(const std::vector<double> &own) const
  {
    std::vector<double> out(own.begin(), own.begin() + 3 * nlocal);
    for (size_t g = 0; g < owner.size(); g++)
      out.insert(out.end(), {own[3 * owner[g]], own[3 * owner[g] + 1], own[3 * owner[g] + 2]});
    return out;
  }

  // families from the reference positions: partners within delta (closest image)
  void build(const PeriSISSM::Model &model)
  {
    npartner.assign(nlocal, 0);
    jl.assign(nlocal, {});
    om.assign(nlocal, {});
    kinv.assign(9 * nlocal, 0.0);
    kregular.assign(nlocal, 0);
    lamref.assign(nlocal, 0.0);
    for (int i = 0; i < nlocal; i++) {
      for (int j = 0; j < nall; j++) {
        if (j == i) continue;
        double d[3];
        for (int k = 0; k < 3; k++) d[k] = x[3 * j + k] - x[3 * i + k];
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (r > delta_) continue;
        jl[i].push_back(j);
        om[i].push_back(model.bond_weight(r, 1, 1, volume[i], volume[j]));
      }
      npartner[i] = (int) jl[i].size();
    }
    rows();
    const PeriSISSM::Families fam = families();
    for (int i = 0; i < nlocal; i++)
      PeriSISSM::update_shape(fam, ref.data(), box, i, model.reference_normal(fam, type[i], i));
  }

  PeriSISSM::Families families()
  {
    PeriSISSM::Families fam;
    fam.npartner = npartner.data();
    fam.jlocal = jrows.data();
    fam.omega = orows.data();
    fam.kinv = krows.data();
    fam.kregular = kregular.data();
    fam.lamref = lamref.data();
    if (!normal.empty()) fam.normal = nrows.data();
    return fam;
  }

  // the halo: owners' rows to their ghosts
  using PeriSISSM::Halo::forward;
  void forward(const PeriSISSM::HaloField *fields, int n) override
  {
    for (int q = 0; q < n; q++) {
      double *rows = fields[q].rows;
      const int width = fields[q].width;
      for (size_t g = 0; g < owner.size(); g++)
        for (int k = 0; k < width; k++) rows[(nlocal + g) * width + k] = rows[owner[g] * width + k];
    }
  }

  // the particles as the passes see them (current positions x), force densities into f
  PeriSISSM::Particles particles(double *f)
  {
    PeriSISSM::Particles p;
    p.nlocal = nlocal;
    p.nall = nall;
    p.x = x.data();
    p.x0 = ref.data();
    p.volume = volume.data();
    p.type = type.data();
    p.smin = smin.data();
    p.f = f;
    return p;
  }

  struct Result {
    double energy = 0.0;           // sum_i V_i w_i
    std::vector<double> f;         // force densities of the owned rows
    std::vector<double> k;         // implicit stiffness rows (all rows)
    std::vector<double> g;         // F, C, regular (all rows)
    std::vector<double> h;         // H (all rows)
    std::vector<double> blocks;    // SISSM diagonal blocks of the owned rows (6 each)
    double virial[6] = {0, 0, 0, 0, 0, 0};
  };

  // one evaluation of the bond terms at owned positions y (3 * nlocal)
  Result evaluate(const PeriSISSM::Model &model, const std::vector<double> &y)
  {
    x = positions_of(y);
    Result out;
    std::vector<double> f(3 * nall, 0.0), g(nall * PeriSISSM::ParticleFields::NG, 0.0),
        h(9 * nall, 0.0), kk(nall * PeriSISSM::ParticleFields::NK, 0.0), w(nall, 0.0),
        sn(nall, 0.0), nrm(3 * nall, 0.0),
        cols(columns ? PeriSISSM::ParticleFields::NCOLS * nall : 0, 0.0);
    const PeriSISSM::Particles p = particles(f.data());
    PeriSISSM::ParticleFields fields;
    fields.g = g.data();
    fields.h = h.data();
    fields.k = kk.data();
    fields.w = w.data();
    fields.smin_new = sn.data();
    fields.normal = nrm.data();
    fields.cols = columns ? cols.data() : nullptr;
    fields.energy = energy;
    PeriSISSM::Virial vir;
    if (virial) vir.global = out.virial;
    std::vector<int> broke;
    out.blocks.assign(6 * nlocal, 0.0);
    std::vector<double *> brows(nlocal);
    for (int i = 0; i < nlocal; i++) brows[i] = out.blocks.data() + 6 * i;
    PeriSISSM::evaluate_bond_terms(model, p, families(), box, PeriSISSM::BreakingRule::NOBREAK,
                                   brows.data(), fields, *this, vir, broke);
    for (int i = 0; i < nlocal; i++) out.energy += volume[i] * w[i];
    out.f.assign(f.begin(), f.begin() + 3 * nlocal);
    out.k = kk;
    out.g = g;
    out.h = h;
    return out;
  }

  // what evaluate() asks for: the fused passes' columns scratch (ParticleFields::cols), the
  // energy (else Result::energy lacks the stabilization's), the virial
  bool columns = true, energy = true, virial = true;

  int nlocal = 0, nall = 0;
  std::vector<double> x, x0, ref, volume, smin, shift;
  std::vector<int> type, owner;
  PeriSISSM::ReferenceBox box;
  std::vector<int> npartner, kregular;
  std::vector<std::vector<int>> jl;
  std::vector<std::vector<double>> om;
  std::vector<double> kinv, lamref;
  std::vector<double> normal;    // reference normals of membrane particles (3 per owned
                                 // particle; empty: none), set before build()
  std::vector<int *> jrows;
  std::vector<double *> orows, krows, nrows;

 private:
  void rows()
  {
    jrows.resize(nlocal);
    orows.resize(nlocal);
    krows.resize(nlocal);
    for (int i = 0; i < nlocal; i++) {
      jrows[i] = jl[i].data();
      orows[i] = om[i].data();
      krows[i] = kinv.data() + 9 * i;
    }
    nrows.clear();
    for (int i = 0; i < nlocal && !normal.empty(); i++) nrows.push_back(normal.data() + 3 * i);
  }
  double delta_;
};

// bonds of every type pair 1..ntypes never break (s00 and alpha 0)
inline void never_breaks(PeriSISSM::Model &m, int ntypes)
{
  m.breaking().configure(
      ntypes,
      [](int, int) {
        return false;
      },
      [](int, int) {
        return 0.0;
      },
      [](int, int) {
        return 0.0;
      });
}

}    // namespace PeriSISSMTest

#endif    // PERISISSM_TEST_CLUSTER_H
