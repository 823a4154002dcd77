// Per-bond rows of one particle, kept between two loops over its bonds: the first loop stores
// a 3-vector a and the reference bond xi of each bond it keeps, the second sums a (x) xi. Both
// the moment M = sum omega eta (x) xi (elastic.cpp) and the stabilization's Q (stabilization.cpp)
// are such sums; splitting them off the loop that forms a keeps the nine accumulators of the sum
// in registers (in one loop with the rest they spilled to the stack on x86-64).

#ifndef PERISISSM_PERI_BOND_ROWS_H
#define PERISISSM_PERI_BOND_ROWS_H

#include "linalg/fused.h"
#include "peri/family.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace PeriSISSM {

class BondRows {
 public:
  // room for the largest family of the owned particles 0 .. nlocal-1
  BondRows(const Families &fam, int nlocal)
  {
    int nmax = 0;
    for (int i = 0; i < nlocal; i++) nmax = std::max(nmax, fam.npartner[i]);
    rows_.resize(6 * static_cast<size_t>(nmax));
  }

  // start the rows of the next particle
  void clear() { n_ = 0; }

  // one row: a and xi
  void push(double a0, double a1, double a2, double x0, double x1, double x2)
  {
    double *u = rows_.data() + 6 * n_++;
    u[0] = a0;
    u[1] = a1;
    u[2] = a2;
    u[3] = x0;
    u[4] = x1;
    u[5] = x2;
  }

  // S = sum over the rows of a (x) xi (row-major 3x3), each entry summed in row order
  // (FUSED: each term added with one rounding, linalg/fused.h)
  template <bool FUSED = false> [[gnu::always_inline]] void outer_sum(double S[9]) const
  {
    double s00 = 0.0, s01 = 0.0, s02 = 0.0, s10 = 0.0, s11 = 0.0, s12 = 0.0, s20 = 0.0, s21 = 0.0,
           s22 = 0.0;
    for (int k = 0; k < n_; k++) {
      const double *u = rows_.data() + 6 * k;
      const double a0 = u[0], a1 = u[1], a2 = u[2], x0 = u[3], x1 = u[4], x2 = u[5];
      s00 = madd<FUSED>(a0, x0, s00);
      s01 = madd<FUSED>(a0, x1, s01);
      s02 = madd<FUSED>(a0, x2, s02);
      s10 = madd<FUSED>(a1, x0, s10);
      s11 = madd<FUSED>(a1, x1, s11);
      s12 = madd<FUSED>(a1, x2, s12);
      s20 = madd<FUSED>(a2, x0, s20);
      s21 = madd<FUSED>(a2, x1, s21);
      s22 = madd<FUSED>(a2, x2, s22);
    }
    S[0] = s00;
    S[1] = s01;
    S[2] = s02;
    S[3] = s10;
    S[4] = s11;
    S[5] = s12;
    S[6] = s20;
    S[7] = s21;
    S[8] = s22;
  }

 private:
  std::vector<double> rows_;
  int n_ = 0;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_BOND_ROWS_H
