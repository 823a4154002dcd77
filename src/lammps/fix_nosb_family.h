/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/family: bond families of pair_style peri/nosb (created by the pair style as
   "NOSB_FAMILY all nosb/family"; users do not define it).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(nosb/family,FixNosbFamily);
// clang-format on
#else

#ifndef LMP_FIX_NOSB_FAMILY_H
#define LMP_FIX_NOSB_FAMILY_H

#include "fix.h"

#include "peri/family.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace PeriSISSM {
class Model;
template <class Id> struct FamilyArrays;
}    // namespace PeriSISSM

namespace LAMMPS_NS {

class FixNosbFamily : public Fix {
 public:
  FixNosbFamily(class LAMMPS *, int, char **);
  ~FixNosbFamily() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void setup_post_neighbor() override;
  void setup(int) override;
  void post_neighbor() override;
  void min_post_neighbor() override;
  void post_integrate() override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;

  // blow-up guard (all ranks; doc/pair_peri_nosb.rst "Blow-ups end in an error"): every step
  // in post_integrate, or by an integrator that moves the atoms later in the step (fix sissm)
  // right after it has, telling whether its step converged (1) or not (0; -1: explicit
  // integrators, the default); after such a call the check of post_integrate is left to that
  // integrator until the next init
  void check_motion(int converged = -1);
  // estimate of the stable explicit time step of every owned atom (all ranks; dt[nlocal];
  // core peri/stable_step.h); +infinity without stiffness
  void stable_time_steps(double *dt);
  // smallest stable_time_steps() over all atoms (all ranks)
  double min_stable_time_step();

  // the rule object of the families (horizons, bond weights, materials for the time step
  // estimate) and what to call right after every neighbor list build (the pair style, at
  // every init)
  void attach(const PeriSISSM::Model *model, std::function<void()> neighbor_rebuilt);
  // the families as the core sees them
  PeriSISSM::Families view();
  // bonds that the core broke in an evaluation (partner index -1) lose their partner tag too
  void forget_broken(const std::vector<int> &atoms);
  // damage of local atom i: 1 - (sum of omega over unbroken bonds) / (over the initial family)
  double damage(int i) const;

  // state (read by pair peri/nosb, compute nosb/atom and integrators)
  // The reference bond xi = x0_j - x0_i is not stored (x0: positions when the families were
  // built; minimum image in box, core peri/family.h ReferenceBox).
  int built;           // 1 once families exist (built at the first run, kept in restarts)
  int maxpartner;      // largest family (bond slots per atom)
  int *npartner;       // bond slots of each atom (broken ones included until migration)
  tagint **partner;    // partner tags, 0 = broken bond
  double **omega;      // per slot: bond weight omega = w beta V_j (pair peri/nosb)
  double **kinv;       // K^-1 (row-major 3x3) of each atom; zeros when K is singular
  int *kregular;       // 1 if K is regular (F defined), 0 otherwise
  double *vinit;       // sum of omega over the initial family (damage reference)
  double *lamref;      // largest eigenvalue of the initial K (reference of the singularity test)
  tagint *owntag;      // the atom's own ID when its family was stored (detects renumbering)
  int **jlocal;        // local index (closest image) of each partner of each owned atom,
                       //   -1 for broken bonds; refreshed after every neighbor list build
  PeriSISSM::ReferenceBox box;    // the box the families were built in (reference bonds)
  tagint tagmax0;                 // largest atom ID when the families were built

 protected:
  const PeriSISSM::Model *model;
  std::function<void()> neighbor_rebuilt;
  class NeighList *list;

  void build_families();
  void resize_bond_slots();
  void refresh_local_indices();
  void resolve_missing(const std::vector<std::pair<int, int>> &);
  void break_reused(const std::vector<tagint> &);
  std::vector<tagint> allgather_tags(const std::vector<tagint> &, int *offset = nullptr);
  std::vector<int> reshape;    // atoms whose K must be recomputed after a refresh
  double *sdiag;               // per atom s_i of stable_time_steps() (owned and ghosts)
  int integrator_checks;       // 1: an integrator has called check_motion(0 or 1) in this run
  double dtstable0;            // min_stable_time_step() at the setup of the run
  int local_index(tagint) const;
  PeriSISSM::FamilyArrays<tagint> rows() const;    // the per-atom arrays (core peri/)
};

}    // namespace LAMMPS_NS

#endif
#endif
