/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, the bending term of membranes (pair_coeff ... bend D|auto).

   The hinge list and its pass are the core's (membrane/bending.h); this file gives it the
   meshes of read_mesh as this rank holds them (a hinge's other vertices are ghost atoms) and
   the bending moduli. The list is built again only after a neighbor list build or a new run's
   init: evaluating the hinges is cheap next to finding their vertices and rest shape.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"
#include "mesh_view.h"

#include "membrane/bending.h"
#include "peri/bond_stiffness.h"

#include "atom.h"
#include "domain.h"
#include "error.h"

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   bending modulus of atom i (owned or ghost): the type's D, or with bend auto
   E t^3 / (12 (1 - nu^2)) from its material and its mesh's thickness; 0 without bending
------------------------------------------------------------------------- */

double PairPeriNosb::bending_modulus(int i) const
{
  const int t = atom->type[i];
  const double b = bend[t];
  if (b >= 0.0) return b;
  const double thick = meshfix->thickness_of(i);
  return bend_auto_factor[t] * thick * thick * thick;
}

/* ----------------------------------------------------------------------
   the meshes of this rank for the core's hinge list (membrane/bending.h HingeMesh); an owned
   vertex of a type without bending takes no share even of a hinge whose edge's ends bend
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class NosbHingeMesh : public PeriSISSM::HingeMesh {
 public:
  explicit NosbHingeMesh(const PairPeriNosb *pair) : pair_(pair), atom_(pair->atom) {}
  int nlocal() const override { return atom_->nlocal; }
  std::int64_t id(int i) const override { return atom_->tag[i]; }
  int ntri(int i) const override { return pair_->meshfix->ntri_of(i); }
  void triangle(int i, int k, std::int64_t &a, std::int64_t &b) const override
  {
    a = pair_->meshfix->corner_of(i, k, 0);
    b = pair_->meshfix->corner_of(i, k, 1);
  }
  int image(int i, std::int64_t t) const override
  {
    const int j = atom_->map((tagint) t);
    return j < 0 ? -1 : pair_->domain->closest_image(i, j);
  }
  int sharer(std::int64_t t) const override
  {
    const int j = atom_->map((tagint) t);
    const bool shares = j >= 0 && j < atom_->nlocal && pair_->meshfix->mesh_of(j) &&
        pair_->bend[atom_->type[j]] != 0.0;
    return shares ? j : -1;
  }
  double modulus(int i) const override { return pair_->bending_modulus(i); }

 private:
  const PairPeriNosb *pair_;
  Atom *atom_;
};
}    // namespace LAMMPS_NS

/* ----------------------------------------------------------------------
   the hinge list of this rank (compute_bending(), when stale), with reference positions in the
   box of the families
------------------------------------------------------------------------- */

void PairPeriNosb::build_hinges()
{
  NosbHingeMesh mesh(this);
  const tagint missing = PeriSISSM::build_hinges(mesh, atom->x0[0], family->box, hinges);
  if (missing)
    error->one(FLERR,
               "Pair peri/nosb bend: a vertex of a hinge of atom {} is neither owned nor a ghost "
               "atom here: the ghost cutoff is shorter than two edges of its mesh (comm_modify "
               "cutoff)",
               missing);
  hinges_stale = 0;
}

/* ----------------------------------------------------------------------
   the hinges of this rank's list, each evaluated once (compute(): forces, energy density,
   virial, blocks of its owned vertices)
------------------------------------------------------------------------- */

void PairPeriNosb::compute_bending()
{
  if (hinges_stale) build_hinges();
  PeriSISSM::BendingEnergy energy;
  if (eflag_global) energy.total = &eng_vdwl;
  if (eflag_atom) energy.per_particle = eatom;
  PeriSISSM::bending_pass(hinges, particles(), block_rows, energy, virial_tallies());
}

/* ----------------------------------------------------------------------
   compute nosb/atom and the time step check: the stable time steps dt of the owned atoms (the
   family's elastic estimates) with the bending stiffness of the hinges at the current positions
   (rmass is the density)
------------------------------------------------------------------------- */

void PairPeriNosb::stable_time_steps(double *dt)
{
  family->stable_time_steps(dt);    // all ranks (a forward communication)
  if (!any_bend || !meshfix) return;
  if (hinges_stale) build_hinges();
  PeriSISSM::bending_stable_steps(hinges, particles(), atom->rmass, dt);
}

/* ----------------------------------------------------------------------
   ImplicitForces: the hinges of this rank's list in the current positions, for the coarse
   level's matrix (each hinge once; a vertex's row is where compute_bending() puts its share)
------------------------------------------------------------------------- */

void PairPeriNosb::hinge_couplings(PeriSISSM::HingeCouplings &couplings, bool gradients)
{
  if (!any_bend || !meshfix) {
    couplings = PeriSISSM::HingeCouplings();
    return;
  }
  if (hinges_stale) build_hinges();
  PeriSISSM::hinge_couplings(hinges, particles(), gradients, couplings);
}

/* ----------------------------------------------------------------------
   ImplicitForces: the plate bending stencils for the coarse level's matrix
------------------------------------------------------------------------- */

void PairPeriNosb::plate_couplings(PeriSISSM::PlateCouplings &plates)
{ plates = PeriSISSM::PlateCouplings(); plates.first.assign(1, 0); }
