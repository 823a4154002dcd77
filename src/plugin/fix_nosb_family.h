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

#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {

class FixNosbFamily : public Fix {
 public:
  FixNosbFamily(class LAMMPS *, int, char **);
  ~FixNosbFamily() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void setup_post_neighbor() override;
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

  // blow-up guard (all ranks): stop with an error naming the step, the worst atom and the
  // likely cause when an owned atom has a non-finite position, velocity or force, or the atoms
  // have moved farther than LAMMPS can follow (beyond one periodic image, or spread beyond
  // what its neighbor bins can index). Called every step in post_integrate, or by an
  // integrator that moves the atoms later in the step (fix sissm) right after it has, telling
  // whether its step converged (1), did not (0), or -1 (explicit integrators).
  void check_motion(int converged = -1);
  // estimate of the stable explicit time step of every owned atom (all ranks; dt[nlocal]):
  //   dt_i = f sqrt(2 rho_i / d_i),  d_i = sum_j omega_ij (s_i + s_j),
  //   s_i = kappa_i (lambda + 2 mu) + C_i / 2,  kappa_i = tr(K_i^-1) / 3
  // (the SISSM block of the linearized material at rest); +infinity without stiffness
  void stable_time_steps(double *dt);
  // smallest stable_time_steps() over all atoms (all ranks)
  double min_stable_time_step();

  // recompute K^-1 and the regular flag of local atom i from its unbroken bonds
  void update_shape(int i);
  // damage of local atom i: 1 - (sum of omega over unbroken bonds) / (over the initial family)
  double damage(int i) const;
  // reference bond xi = X_j - X_i of local atoms i and j (from x0, minimum image)
  void reference_bond(int i, int j, double *xi) const;
  // minimum image of a difference of reference positions, in the box the families were
  // built in (so that a later change of the box does not change the reference bonds)
  inline void reference_image(double &dx, double &dy, double &dz) const
  {
    if (periodic[2]) {
      if (dz > 0.5 * box0[2]) {
        dz -= box0[2];
        dy -= box0[3];
        dx -= box0[4];
      } else if (dz < -0.5 * box0[2]) {
        dz += box0[2];
        dy += box0[3];
        dx += box0[4];
      }
    }
    if (periodic[1]) {
      if (dy > 0.5 * box0[1]) {
        dy -= box0[1];
        dx -= box0[5];
      } else if (dy < -0.5 * box0[1]) {
        dy += box0[1];
        dx += box0[5];
      }
    }
    if (periodic[0]) {
      if (dx > 0.5 * box0[0]) dx -= box0[0];
      else if (dx < -0.5 * box0[0]) dx += box0[0];
    }
  }

  // state (read by pair peri/nosb, compute nosb/atom and integrators)
  // The reference bond is not stored: xi = x0_j - x0_i (x0 = positions when the families
  // were built), with the minimum image convention in periodic boxes (the x0 of a periodic
  // ghost image is not shifted).
  int built;          // 1 once families exist (built at the first run, kept in restarts)
  int maxpartner;     // largest family (bond slots per atom)
  int *npartner;      // bond slots of each atom (broken ones included until migration)
  tagint **partner;   // partner tags, 0 = broken bond
  double **omega;     // per slot: bond weight omega = w beta V_j (pair peri/nosb)
  double **kinv;      // K^-1 (row-major 3x3) of each atom; zeros when K is singular
  int *kregular;      // 1 if K is regular (F defined), 0 otherwise
  double *vinit;      // sum of omega over the initial family (damage reference)
  double *lamref;     // largest eigenvalue of the initial K (reference of the singularity test)
  tagint *owntag;     // the atom's own ID when its family was stored (detects renumbering)
  int **jlocal;       // local index (closest image) of each partner of each owned atom,
                      //   -1 for broken bonds; refreshed after every neighbor list build
  int periodic[3];    // periodicity of the box when the families were built
  double box0[6];     // that box: xprd yprd zprd yz xz xy
  int any_periodic;
  tagint tagmax0;     // largest atom ID when the families were built

 protected:
  class PairPeriNosb *pair;
  class NeighList *list;

  void build_families();
  void refresh_local_indices();
  void resolve_missing(const std::vector<std::pair<int, int>> &);
  void break_reused(const std::vector<tagint> &);
  std::vector<tagint> allgather_tags(const std::vector<tagint> &, int *offset = nullptr);
  std::vector<int> reshape;    // atoms whose K must be recomputed after a refresh
  double *sdiag;               // per atom s_i of stable_time_steps() (owned and ghosts)
  bigint last_check;           // step of the last check_motion()
  int integrator_checks;       // 1: an integrator calls check_motion() (fix sissm)
  double dtstable0;            // min_stable_time_step() at the setup of the run
  std::string likely_cause(int converged);
  void missing_partner(int i, tagint jtag);
  int local_index(tagint) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
