/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   pair_style peri/nosb: non-ordinary state-based (correspondence) peridynamics with
   isotropic hyperelastic models, zero-energy-mode stabilization, bond breaking and
   short-range contact.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(peri/nosb,PairPeriNosb);
// clang-format on
#else

#ifndef LMP_PAIR_PERI_NOSB_H
#define LMP_PAIR_PERI_NOSB_H

#include "pair.h"

#include <string>

namespace PeriSISSM {
class Material;
}

namespace LAMMPS_NS {

class PairPeriNosb : public Pair {
 public:
  // per-atom doubles in gstate[i]: F (row-major 3x3), C, regular flag (1.0 or 0.0)
  enum { GSTATE_C = 9, GSTATE_REG = 10, NGSTATE = 11 };

  PairPeriNosb(class LAMMPS *);
  ~PairPeriNosb() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

  // ---- interface for fix nosb/family, compute nosb/atom and integrators ----

  // weight omega = w * beta * V_j of a bond of reference length r between types itype, jtype
  // (influence function w = 1, beta the partial-volume factor)
  double bond_weight(double r, int itype, int jtype, double vi, double vj) const;
  // horizon of a bond between types itype and jtype
  double horizon(int itype, int jtype) const { return cut[itype][jtype]; }
  // material of particles of type itype (valid after init)
  const PeriSISSM::Material &material(int itype) const { return *materials[itype]; }
  // stabilization modulus C_i of local atom i (0 if its shape tensor is singular)
  double particle_stabilization(int i) const;
  // called by fix nosb/family right after every neighbor list build
  void neighbor_rebuilt();
  // true when compute() has filled the per-atom state of the current owned atoms
  bool state_current() const;

  // SISSM support (fix sissm): with stiffness_flag set, compute() also stores each particle's
  // implicit stiffness H = kappa U diag(c) U^T and C in kstate; implicit_blocks() then sums
  // for every owned atom  sum_j omega_ij (H_i + H_j + (C_i + C_j)/2 I)  (xx yy zz xy xz yz)
  void implicit_blocks(double **block);

  // Implicit steps (fix sissm) move atoms many times between neighbor list builds. With
  // track_contact_motion(1), contact_follow_motion() (call it after every move, with ghost
  // positions current) keeps the short-range contact candidates complete: it re-selects them
  // from the neighbor list when an atom has moved more than half their margin since they were
  // selected (returns 1; 0: nothing to do), and returns -1 when the atoms have moved farther
  // than the neighbor list covers (then the candidates are incomplete for this iterate).
  // contact_end_of_step() stops with an error when the step's result is that far, and returns
  // true when the next step should start from a new neighbor list.
  void track_contact_motion(int flag);
  int contact_follow_motion();
  // (cause: what the integrator knows about the step, for the error message; may be empty)
  bool contact_end_of_step(const std::string &cause);
  // contact pairs that coupled an atom of contact_groupbit with one outside it, counted over
  // this rank's evaluations since the counter was last reset (0: not counted)
  int contact_groupbit;
  bigint contact_crossings;

  class FixNosbFamily *family;
  int external_breaking;    // 1: compute() does not break bonds (inside an implicit step)
  int stiffness_flag;       // 1: compute() fills kstate (an integrator needs implicit blocks)
  double **kstate;          // per atom: H (xx yy zz xy xz yz) and C, see implicit_blocks()
  // per-atom results of the last compute() (owned atoms; ghosts as communicated):
  double **gstate;          // F, C, regular flag (see above)
  double **hstate;          // H = (P + Q) K^-1 (row-major 3x3), 0 if K is singular
  double *wdens;            // W(F) + stabilization energy density (what pe tallies per atom)

 protected:
  // per type pair (as given for i <= j; mixed and mirrored in init_style)
  int **model;              // index into PeriSISSM::material_names()
  double **bulk, **shear, **cut, **s00, **alpha, **cs;
  int **breakflag, **contactflag;
  double **kcontact;        // short-range contact stiffness 15 * 18 K / (pi delta^4)
  double **g0;              // G0 keyword (critical energy release rate), 0 = s00 given
  double **g0_s00;          // s00 that G0 gave at the last init (to log it once)
  // per type
  PeriSISSM::Material **materials;
  // summary flags
  int any_break, any_stab, any_contact;
  int uniform_break;        // all type pairs breakable with the same s00 and alpha
  double hmax;              // largest particle size V^(1/3) (contact range)
  int *contact_first, *contact_neigh;    // short list of contact candidates
  int contact_maxfirst, contact_maxneigh, contact_inum;
  double contact_margin;    // the candidates hold the pairs within contact_reach() + this
  int track_motion;         // keep the positions below (fix sissm)
  int nmotion;              // their allocated length
  double **xneigh;          // positions of owned atoms at the last neighbor list build
  double **xcontact;        // positions of owned atoms when the contact candidates were chosen
  double contact_reach() const;    // largest contact range, 1.35 hmax
  void grow_motion();
  double motion_since(double **ref, double *moved, tagint *worst);
  bool contact_reachable(double moved) const;
  double contact_horizon() const;
  int state_nlocal;         // nlocal when compute() last filled the per-atom state
  enum { RESTART_VERSION = 2 };

  int nmax;
  enum { COMM_STATE, COMM_H, COMM_K };
  enum { NKSTATE = 7 };
  int commflag;
  double *s0_new;

  void allocate();
  void s00_from_fracture_energy();
  void grow_peratom();
  void compute_contact(int, int);
  void build_contact_list(double margin);
  enum { NOBREAK = 0, S0ONLY, BREAK };
  template <int MODE, int UNIFORM, int PBC> void compute_state();
  template <int MODE, int UNIFORM>
  bool check_bond(double, double, int, int, double, double &, double &) const;
  template <int UNIFORM> double smin_from(double, double, double) const;
  template <int EVFLAG, int PBC> void compute_stabilization();
  template <int EVFLAG, int PBC> void compute_forces();
  bool bonded(int i, tagint jtag) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
