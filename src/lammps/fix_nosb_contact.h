/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact: IPC barrier contact with lagged friction between mesh primitives and
   volumetric particles (doc/fix_nosb_contact.rst); fix_nosb_contact.cpp says where each part
   lives (the pairs, the potentials and the rules are the core's, src/core/contact).
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
#include "contact/barrier_potential.h"
#include "contact/candidate_distances.h"
#include "contact/candidates.h"
#include "contact/contact_options.h"
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
  bool limits_moves() const override { return opt.ccd; }
  void begin_step(double h, double c) override;
  void begin_path() override;
  double limit_move(int groupbit) override;
  bool reach_limited() const override { return reach_bound; }
  void reach_error(const char *integrator) override;
  bool rebuild_wanted(bool end_of_step) override;
  void keep_blocks() override;
  void add_blocks(double **block) override;
  bool adapts_stiffness() const override { return opt.kappa_auto; }
  void set_force_factor(double c) override { inertia_c = c; }
  void next_iterate() override { iterate_pending = opt.kappa_auto; }
  bool balance_stiffness(double **res, double c, int groupbit) override;

 private:
  PeriSISSM::ContactOptions opt;    // the arguments (kappa: the one given)
  double kappa;                     // the barrier stiffness the forces use (energy / length^2)
  // kappa auto: IPC's adaptive stiffness in incremental-potential units (kappa = its value / c)
  PeriSISSM::AdaptiveStiffness stiffness;
  double inertia_c = 0.0;       // c of the step being solved (set_force_factor() before the first)
  int iterate_pending = 0;      // the next evaluation is an iterate of fix sissm (next_iterate())
  PeriSISSM::ContactRun run;    // what init() found, and the warnings said
  PeriSISSM::CandidateRange range;    // the assumed longest edge and the list's cutoff (this run)
  class NeighList *list = nullptr;
  class MeshView *meshfix = nullptr;         // nullptr without meshes
  class BondPartners *partners = nullptr;    // pair peri/nosb's bond partners; nullptr if none

  std::vector<PeriSISSM::Candidate> candidates;
  int stale = 1;    // the candidates are chosen again at the next force evaluation
  PeriSISSM::MotionTracker motion;            // owned positions when the candidates were chosen
  PeriSISSM::CandidateDistances distances;    // at the last force evaluation
  double **xref = nullptr;    // the last admissible positions (owned and ghost; begin_path())
  int nxref = 0;
  int reach_bound = 0;         // the last limit_move() was cut short by the candidates' reach
  double reach_moved = 0.0;    // then: how far an atom had moved from the list build
  tagint reach_atom = 0;       //   which one

  // friction: the lagged data of the active pairs with an owned vertex (add_friction())
  std::vector<PeriSISSM::LaggedPair> lagged;
  int in_step = 0;                  // begin_step() was called in this run: the implicit recipe
  double step_h = 0.0;              // the step of the last begin_step()
  PeriSISSM::MotionTracker step_start;    // the owned positions at the last begin_step()
  bigint step_start_generation = -1;       // the generation then
  bigint generation = 0;            // candidate builds so far (local indices change with them)
  bigint lagged_generation = -1;    // the generation the lagged data's local indices belong to

  // the pairs within the barrier's range at the last force evaluation (barrier_forces()), and
  // at the evaluation of keep_blocks(), with its positions (owned and ghost), stiffness and
  // whether its friction had blocks (add_blocks())
  std::vector<int> active, kept_active;
  std::vector<double> kept_x;
  std::vector<double *> kept_rows;
  double kept_kappa = 0.0, kept_step_h = 0.0;
  int kept_friction = 0;

  // results of the last force evaluation (this rank; each pair counted once over all ranks)
  PeriSISSM::BarrierTally barrier;
  PeriSISSM::FrictionTally friction;    // none without friction
  int reduced = 0;                      // the global sums below are current
  double all_energy_density = 0.0, all_vector[9] = {};

  void build_candidates();
  void measure_scene();
  void set_kappa_ip(double k);
  void adapt_at_iterate();
  void check_motion();
  double measure_longest_edge(bool owned_partners_only);
  void reduce();
  void build_lagged();
  void add_friction();
};

}    // namespace LAMMPS_NS

#endif
#endif
