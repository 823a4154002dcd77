/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   compute nosb/atom: per-atom damage, strain energy density, J, von Mises and Cauchy stress
   of pair_style peri/nosb, and the estimate of the particle's stable explicit time step.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(nosb/atom,ComputeNosbAtom);
// clang-format on
#else

#ifndef LMP_COMPUTE_NOSB_ATOM_H
#define LMP_COMPUTE_NOSB_ATOM_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeNosbAtom : public Compute {
 public:
  ComputeNosbAtom(class LAMMPS *, int, char **);
  ~ComputeNosbAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  int nmax;
  double **values;
  double *dtstable;
  class PairPeriNosb *pair;
};

}    // namespace LAMMPS_NS

#endif
#endif
