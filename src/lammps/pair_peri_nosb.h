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

#include "bond_partners.h"
#include "implicit_forces.h"

#include "peri/contact_candidates.h"
#include "peri/fields.h"

#include <memory>
#include <string>
#include <vector>

namespace PeriSISSM {
class Model;
class CoefficientTable;
struct MaterialEntry;
struct Hinge;
class PlateBending;
}    // namespace PeriSISSM

namespace LAMMPS_NS {

class PairPeriNosb : public Pair, public ImplicitForces, public BondPartners {
 public:
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
  int pack_reverse_comm(int, int, double *) override;    // contact blocks of ghost atoms
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  // ---- for compute nosb/atom ----

  // the model (materials, horizons, breaking rule; valid after init)
  const PeriSISSM::Model &model() const { return *model_; }
  // true when compute() has filled the per-atom state of the current owned atoms
  bool state_current() const;
  // F (row-major 3x3) of owned atom i at the last compute() (the identity if its K is singular)
  const double *deformation_gradient(int i) const
  {
    return gstate + PeriSISSM::ParticleFields::NG * i;
  }
  // W(F) + stabilization energy density of owned atom i (what pe tallies per atom)
  double energy_density(int i) const { return wdens[i]; }
  class FixNosbFamily *family;
  // dt (owned atoms; all ranks) of compute nosb/atom's stable-step column: the family's elastic
  // estimates combined with the bending hinges' (core membrane/bending.h bending_stable_steps)
  void stable_time_steps(double *dt);

  // ---- ImplicitForces (fix sissm) ----

  void begin_implicit_step(int groupbit) override;
  void end_implicit_step() override;
  void evaluate(double **block) override;
  bool ghost_forces() const override;
  void bond_springs(PeriSISSM::BondSprings &springs, bool values) override;
  void hinge_couplings(PeriSISSM::HingeCouplings &couplings, bool gradients) override;
  const PeriSISSM::PlateCouplings &plate_couplings() override;
  void track_contact_motion(int flag) override;
  int contact_follow_motion() override;
  bool contact_end_of_step(const std::string &cause) override;
  int contact_build_wanted() override;
  bool group_coupled(int groupbit) override;
  void check_motion(int converged) override;
  bool has_unbent_membranes(int groupbit) override;
  bool only_membranes(int groupbit) override;

  // ---- BondPartners (fix nosb/contact; pair_peri_nosb_partners.cpp) ----

  bool partners_known() const override;
  bool were_partners(int a, int b) const override;

 protected:
  // the coefficients of pair_coeff per type pair (mixed and mirrored in init_style)
  std::unique_ptr<PeriSISSM::CoefficientTable> coeffs;
  std::unique_ptr<PeriSISSM::Model> model_;    // the core's view of coeffs (init_style)
  // per type: density and name of the material file entry of pair_coeff I I (0: numbers given)
  std::vector<double> material_density;
  std::vector<std::string> material_name;
  // per type: bending modulus of pair_coeff I I ... bend (0 = none, -1 = auto), and for auto
  // coeffs->bending_factors() (set at init; D = that times the thickness cubed)
  std::vector<double> bend, bend_auto_factor;
  // per type: bending plate (1) or hinge (0) of pair_coeff I I, and Poisson's ratio of its
  // material (set at init)
  std::vector<int> bend_plate;
  std::vector<double> bend_nu;
  int any_bend, any_plate;
  class MeshView *meshfix;    // the meshes (read_mesh), null if none
  // the hinges of the bending term with an owned vertex here, each once per rank (straddling
  // ones on every rank; core membrane/bending.h)
  std::vector<PeriSISSM::Hinge> hinges;
  int hinges_stale;    // local indices may have changed: build the list again
  // the triangles of the plate bending term whose stencil holds an owned vertex (core
  // membrane/plate_bending.h; kept for the run: its stencils depend on the rest shape only)
  std::unique_ptr<PeriSISSM::PlateBending> plates;
  // the plate edges' hinges: in the coarse level's matrix only (stand-ins for the plate energy)
  std::vector<PeriSISSM::Hinge> plate_hinges;
  int plate_hinges_stale = 1;    // built again at the next hinge_couplings()
  // summary flags
  int any_break, any_contact;
  int passes_reported = 0;    // the bond passes' version was written to the log
  int external_breaking;      // 1: compute() does not break bonds (inside an implicit step)
  double **block_rows;        // not null: compute() also sums the SISSM blocks into these rows
  int contact_groupbit;       // contact pairs crossing this group's boundary are counted
  bigint contact_crossings;
  PeriSISSM::ContactFollower follower;    // the contact candidates (peri/contact_candidates.h)
  void choose_contacts(double margin);
  double motion_since(double *moved, tagint *worst);
  std::vector<double> contact_blocks;    // SISSM blocks of the contact pairs, 6 per owned and
                                         //   ghost atom (compute_contact with blocks)
  void add_contact_blocks();
  // true on all ranks when some owned atom of groupbit has a type t with of_type(t)
  template <class Test> bool any_type_in_group(int groupbit, Test of_type);
  int state_nlocal;    // nlocal when compute() last filled the per-atom state

  // per-atom results of the last compute() (owned atoms; ghosts as communicated), rows of
  // PeriSISSM::ParticleFields
  int nmax;
  double *gstate;    // F, C, regular flag
  double *hstate;    // H = (P + Q) K^-1
  double *kstate;    // implicit stiffness and C (fix sissm)
  double *wdens;     // energy density
  double *s0_new;
  double *cnormal;           // current normals of membrane particles (decks with membranes only)
  double *cols;              // scratch of the fused passes: F, then H, by columns
  std::vector<int> broke;    // atoms that lost bonds in the last compute()
  const PeriSISSM::HaloField *comm_fields;    // the fields forward_comm sends
  int comm_nfields;

  void allocate();
  PeriSISSM::MaterialEntry read_material(const std::string &file, const std::string &name);
  void check_material_density();
  void s00_from_fracture_energy();
  void configure_model();
  void check_membranes();
  PeriSISSM::Particles particles() const;
  // where the virial of this evaluation goes (ev_init's flags)
  PeriSISSM::Virial virial_tallies()
  {
    return {vflag_global ? virial : nullptr, vflag_atom ? vatom : nullptr};
  }
  void grow_peratom();
  void compute_contact(int, int);
  void compute_bending();
  void build_hinges();
  void plate_ghost_cutoff();
  double bending_modulus(int i) const;
  void neighbor_rebuilt();
  friend class NosbHalo;
  friend class NosbContactPairs;
  friend class NosbHingeMesh;
};

}    // namespace LAMMPS_NS

#endif
#endif
