// Storage of the per-atom family arrays for the tests of peri/family_records.h and
// peri/family_ids.h: nrows rows of kMaxBonds bond slots, as fix nosb/family allocates them.
#ifndef PERISISSM_TEST_FAMILY_STORAGE_H
#define PERISISSM_TEST_FAMILY_STORAGE_H

#include "peri/family_records.h"

#include <vector>

namespace PeriSISSM {

constexpr int kMaxBonds = 8;

template <class Id> struct FamilyStorage {
  explicit FamilyStorage(int nrows) :
      npartner(nrows, 0), kregular(nrows, 0), vinit(nrows, 0.0), lamref(nrows, 0.0),
      owntag(nrows, 0), partner_data(nrows * kMaxBonds, 0), omega_data(nrows * kMaxBonds, 0.0),
      jlocal_data(nrows * kMaxBonds, -7), kinv_data(nrows * 9, 0.0), partner(nrows), omega(nrows),
      jlocal(nrows), kinv(nrows)
  {
    for (int i = 0; i < nrows; i++) {
      partner[i] = &partner_data[i * kMaxBonds];
      omega[i] = &omega_data[i * kMaxBonds];
      jlocal[i] = &jlocal_data[i * kMaxBonds];
      kinv[i] = &kinv_data[i * 9];
    }
  }
  FamilyArrays<Id> arrays()
  {
    return {npartner.data(), partner.data(), omega.data(),  jlocal.data(), kinv.data(),
            kregular.data(), vinit.data(),   lamref.data(), owntag.data()};
  }
  // row i: the given partner IDs (0 = broken), omega 0.1 (b + 1), jlocal 10 b, per-atom data
  // from own
  void fill(int i, Id own, const std::vector<Id> &ids)
  {
    npartner[i] = (int) ids.size();
    for (int b = 0; b < npartner[i]; b++) {
      partner[i][b] = ids[b];
      omega[i][b] = 0.1 * (b + 1);
      jlocal[i][b] = 10 * b;
    }
    for (int k = 0; k < 9; k++) kinv[i][k] = 0.5 + k;
    kregular[i] = 1;
    vinit[i] = 2.5;
    lamref[i] = 3.25;
    owntag[i] = own;
  }
  std::vector<int> npartner, kregular;
  std::vector<double> vinit, lamref;
  std::vector<Id> owntag, partner_data;
  std::vector<double> omega_data;
  std::vector<int> jlocal_data;
  std::vector<double> kinv_data;
  std::vector<Id *> partner;
  std::vector<double *> omega;
  std::vector<int *> jlocal;
  std::vector<double *> kinv;
};

}    // namespace PeriSISSM

#endif
