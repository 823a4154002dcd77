/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact: barrier contact (IPC log barrier with a thickness) between the
   point-triangle and edge-edge pairs of the meshes read by read_mesh and the point-point pairs
   of volumetric particles, with lagged smooth friction (doc/fix_nosb_contact.rst). The pairs,
   their stencils, the stiffness rule, the path limit and the motion tracker are the core's
   (src/core/contact); this fix keeps their storage, communication, restart and output.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(nosb/contact,FixNosbContact);
// clang-format on
#else

#ifndef LMP_FIX_NOSB_CONTACT_H
#define LMP_FIX_NOSB_CONTACT_H

#include "fix.h"

#include "collision_limit.h"

#include "contact/adaptive_stiffness.h"
#include "contact/candidate_distances.h"
#include "contact/candidates.h"
#include "contact/friction_potential.h"
#include "contact/motion_tracker.h"

#include <vector>

namespace LAMMPS_NS {

class FixNosbContact : public Fix, public CollisionLimit {
 public:
  FixNosbContact(class LAMMPS *, int, char **);
  ~FixNosbContact() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void setup(int) override;
  void setup_post_neighbor() override;
  void post_neighbor() override;
  void post_force(int) override;
  double compute_scalar() override;
  double compute_vector(int) override;
  double memory_usage() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // ---- CollisionLimit: the collision-free step of fix sissm (continuous collision detection)
  bool limits_moves() const override { return ccd != 0; }
  void begin_step(double h, double c) override;
  void begin_path() override;
  double limit_move(int groupbit) override;
  bool reach_limited() const override { return reach_bound; }
  void reach_error(const char *integrator) override;
  bool rebuild_wanted() override;
  void add_blocks(double **block) override;
  bool adapts_stiffness() const override { return kappa_auto != 0; }
  void set_force_factor(double c) override { inertia_c = c; }
  void next_iterate() override { iterate_pending = kappa_auto; }
  bool balance_stiffness(double **res, double c, int groupbit) override;

 private:
  double dhat, dmin, kappa;    // kappa: the barrier stiffness the forces use (energy / length^2)
  // kappa auto: IPC's adaptive stiffness, kept in the units of the step's incremental potential
  // (kappa = its value / c, c the scheme's force factor, h^2 for backward Euler)
  int kappa_auto;
  PeriSISSM::AdaptiveStiffness stiffness;
  double inertia_c;       // c of the step being solved (set_force_factor() before the first)
  int iterate_pending;    // the next evaluation is an iterate of fix sissm (next_iterate())
  double mu, epsv;        // friction coefficient (0: none) and slip speed
  PeriSISSM::CandidateRange range;    // the assumed longest edge and the list's cutoff (this run)
  class NeighList *list;
  class MeshView *meshfix;         // nullptr without meshes
  class BondPartners *partners;    // pair peri/nosb's bond partners; nullptr if none
  bigint nparticles;               // volumetric (non-mesh) particles in the group

  std::vector<PeriSISSM::Candidate> candidates;
  int stale;              // the candidates are chosen again at the next force evaluation
  int warned_sissm;       // the not-collision-free warning under fix sissm was given
  int warned_families;    // the no-bond-families warning was given
  PeriSISSM::MotionTracker motion;            // owned positions when the candidates were chosen
  PeriSISSM::CandidateDistances distances;    // at the last force evaluation
  int ccd;          // keyword ccd: fix sissm limits its moves (CollisionLimit)
  double **xref;    // the last admissible positions (owned and ghost; begin_path())
  int nxref;
  int reach_bound;       // the last limit_move() was cut short by the candidates' reach
  double reach_moved;    // then: how far an atom had moved from the list build
  tagint reach_atom;     //   which one

  // friction: the lagged data of the active pairs (each with an owned vertex), built at x^n by
  // begin_step() under fix sissm, or at every evaluation from the current positions otherwise
  std::vector<PeriSISSM::LaggedPair> lagged;
  int in_step;                 // begin_step() was called in this run: the implicit recipe
  double step_h;               // the step of the last begin_step()
  bigint generation;           // candidate builds so far (local indices change with them)
  bigint lagged_generation;    // the generation the lagged data's local indices belong to

  // results of the last force evaluation (this rank)
  double energy_density;    // sum of the owned vertices' shares / their volumes
  double energy_pairs;      // sum of the pair energies (each pair once over all ranks)
  double mindist;           // smallest distance among the candidates
  bigint nactive[3];        // pairs within dmin + dhat by type (each once over all ranks)
  bigint ncandidates;       // candidates (each once over all ranks)
  bigint nfriction;         // lagged friction pairs (each once over all ranks)
  double friction_work;     // sum mu lambda f1(y) y over them (each once)
  int reduced;              // the global sums below are current
  double all_energy_density, all_vector[9];

  void build_candidates();
  void measure_scene();
  void set_kappa_ip(double k);
  void adapt_at_iterate();
  void check_motion();
  double measure_longest_edge(bool owned_partners_only);
  double predicted_comm_cutoff() const;
  void reduce();
  void build_lagged();
  void add_friction();
};

}    // namespace LAMMPS_NS

#endif
#endif
