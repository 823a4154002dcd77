/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact: barrier contact (IPC log barrier with a thickness) between the
   point-triangle and edge-edge pairs of the meshes read by read_mesh and the point-point pairs
   of volumetric particles, with lagged smooth friction (doc/fix_nosb_contact.rst).
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

#include "contact/barrier.h"
#include "contact/friction.h"

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
  // a candidate pair: a point and a triangle (PT: v = p, t0, t1, t2), two edges (EE:
  // v = a0, a1, b0, b1) or two volumetric particles (PP: v = p, q; v[2], v[3] are -1 and
  // tag[2], tag[3] 0), local indices of the images used, tags in canonical order
  enum { PT = 0, EE = 1, PP = 2 };
  struct Candidate {
    int type;
    tagint tag[4];
    int v[4];
    double eps;    // EE: the mollifier threshold from the rest shape
    int own[4] = {-1, -1, -1, -1};    // local indices of its owned vertices (-1: others; build)
    bool counts = false;   // this rank counts it (it owns the vertex with the smallest ID)
    // the number of vertices used (v[0] .. v[nv() - 1])
    int nv() const { return type == PP ? 2 : 4; }
  };

  double dhat, dmin, kappa;    // kappa: the barrier stiffness the forces use (energy / length^2)
  // kappa auto (IPC's adaptive barrier stiffness, the file's header): the stiffness kept in the
  // units of the step's incremental potential, kappa_ip = c kappa (c the scheme's force factor,
  // h^2 for backward Euler), with its bounds, and the scene's scales they come from
  int kappa_auto;
  double kappa_ip, kappa_ip_min, kappa_ip_max;
  double inertia_c;            // c of the step being solved (set_force_factor() before the first)
  double bbox_diagonal;        // of the group at the first run's setup (0: not yet measured)
  double mean_mass;            // of the group's atoms, then
  int iterate_pending;         // the next evaluation is an iterate of fix sissm (next_iterate())
  double prev_min_gap;         // the smallest gap at the last iterate of this step
  double mu, epsv;             // friction coefficient (0: none) and slip speed
  double edge_factor;          // assumed longest edge = edge_factor x the longest at init
  double longest_edge;         // that assumption (this run)
  double list_cutoff;          // dmin + dhat + 1.5 longest_edge (neighbor skin added by LAMMPS)
  class NeighList *list;
  class FixNosbMesh *meshfix;    // nullptr without meshes
  class PairPeriNosb *pair;      // its bond families exclude particle pairs; nullptr if none
  bigint nparticles;             // volumetric (non-mesh) particles in the group

  std::vector<Candidate> candidates;
  int stale;                   // the candidates are chosen again at the next force evaluation
  int warned_sissm;            // the not-collision-free warning under fix sissm was given
  int warned_families;         // the no-bond-families warning was given
  double **xbuild;             // owned positions when they were chosen
  int nxbuild;
  int ccd;                     // keyword ccd: fix sissm limits its moves (CollisionLimit)
  double **xref;               // the last admissible positions (owned and ghost; begin_path())
  // the candidates' distances at the last force evaluation: exact, or (for a pair that is
  // neither active nor the nearest) a lower bound, the last one less how far its points moved
  std::vector<double> distance;
  std::vector<char> distance_exact;    // 1: distance[ic] is the distance, 0: a lower bound
  int distance_valid;          // 1: the positions are still those (cleared by begin_path())
  double **xlast;              // the positions (owned and ghost) of the last force evaluation
  int nxlast;
  bigint xlast_generation;     // the candidate build they belong to (-1: none)
  int nxref;
  int reach_bound;             // the last limit_move() was cut short by the candidates' reach
  double reach_moved;          // then: how far an atom had moved from the list build
  tagint reach_atom;           //   which one

  // friction: the lagged data of the active pairs (each with an owned vertex), built at x^n by
  // begin_step() under fix sissm, or at every evaluation from the current positions otherwise
  struct Lagged {
    int type;
    tagint tag[4];
    int v[4];                    // local indices of the images used at the build
    double xn[12];               // their positions then
    PeriSISSM::FrictionPair pair;
  };
  std::vector<Lagged> lagged;
  int in_step;                 // begin_step() was called in this run: the implicit recipe
  double step_h;               // the step of the last begin_step()
  bigint generation;           // candidate builds so far (local indices change with them)
  bigint lagged_generation;    // the generation the lagged data's local indices belong to

  // results of the last force evaluation (this rank)
  double energy_density;       // sum of the owned vertices' shares / their volumes
  double energy_pairs;         // sum of the pair energies (each pair once over all ranks)
  double mindist;              // smallest distance among the candidates
  bigint nactive[3];           // pairs within dmin + dhat by type (each once over all ranks)
  bigint ncandidates;          // candidates (each once over all ranks)
  bigint nfriction;            // lagged friction pairs (each once over all ranks)
  double friction_work;        // sum mu lambda f1(y) y over them (each once)
  int reduced;                 // the global sums below are current
  double all_energy_density, all_vector[9];

  void build_candidates();
  void measure_scene();
  void set_kappa_ip(double k);
  void adapt_at_iterate();
  void check_motion();
  // the largest squared distance of an owned atom of the group from where it was at the last
  // candidate build (this rank), and that atom's local index (-1: none)
  double moved_since_build(int &farthest) const;
  // the positions in x of candidate c's points into y[0 .. c.nv() - 1]; their squared distance
  static void gather(const Candidate &c, double **x, Eigen::Vector3d *y);
  static double distance2(const Candidate &c, const Eigen::Vector3d *y);
  // how much a move of its points by len[k] (k < nv()) can shrink the pair's distance: the
  // largest move of a point of each primitive, summed
  static double closing(const Candidate &c, const double *len);
  // the gradient of the pair's barrier energy (12 values; zeros past the pair's vertices)
  static PeriSISSM::Vector12d barrier_gradient(const Candidate &c, const Eigen::Vector3d *y,
                                               const PeriSISSM::BarrierParameters &prm);
  double measure_longest_edge(bool owned_partners_only);
  double predicted_comm_cutoff() const;
  void reduce();
  void build_lagged();
  bool lagged_vertices(const Lagged &p, int *idx);
  void add_friction();
};

}    // namespace LAMMPS_NS

#endif
#endif
