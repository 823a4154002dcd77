/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, the bending term of membranes (pair_coeff ... bend D|auto
   bending plate|hinge).

   The hinge list, the plate triangles' list and their passes are the core's
   (membrane/bending.h, membrane/plate_bending.h); this file gives them the meshes of read_mesh
   as this rank holds them (a hinge's or a stencil's other vertices are ghost atoms), the
   bending moduli and Poisson's ratios. The lists are built again only after a neighbor list
   build or a new run's init: evaluating them is cheap next to finding their vertices.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"
#include "mesh_view.h"

#include "membrane/bending.h"
#include "membrane/plate_bending.h"
#include "peri/bond_stiffness.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"

#include <cmath>

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
  bool plate(int i) const override { return pair_->bend_plate[atom_->type[i]] != 0; }
  double poisson(int i) const override { return pair_->bend_nu[atom_->type[i]]; }

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
               "cutoff), or the run has torn the mesh apart (an unstable time step: compare it "
               "with compute nosb/atom's column 11)",
               missing);
  if (any_plate) {
    if (!plates) plates = std::make_unique<PeriSISSM::PlateBending>();
    const PeriSISSM::PlateProblem p = plates->build(mesh, atom->x0[0], family->box);
    plate_hinges_stale = 1;    // (built when fix sissm's coarse level asks for them)
    using PeriSISSM::StencilStatus;
    const auto &t = p.triangle;
    if (p.status == StencilStatus::missing)
      error->one(FLERR,
                 "Pair peri/nosb bending plate: the curvature stencil of triangle ({} {} {}) near "
                 "atom {} reaches a vertex that is neither owned nor a ghost atom here: the ghost "
                 "cutoff ({}) is shorter than the stencil (comm_modify cutoff), or the run has "
                 "torn the mesh apart (an unstable time step: compare it with compute nosb/atom's "
                 "column 11)",
                 t[0], t[1], t[2], p.vertex, comm->get_comm_cutoff());
    if (p.status == StencilStatus::not_flat)
      error->one(FLERR,
                 "Pair peri/nosb bending plate: the mesh is not flat at rest around triangle "
                 "({} {} {}) near atom {}: the plate energy needs a flat rest shape (use "
                 "'bending hinge' for meshes curved at rest)",
                 t[0], t[1], t[2], p.vertex);
    if (p.status == StencilStatus::degenerate)
      error->one(FLERR,
                 "Pair peri/nosb bending plate: triangle ({} {} {}) near atom {} has no area, or "
                 "its neighbourhood is too narrow to fit a curvature (a strip one triangle wide): "
                 "use 'bending hinge'",
                 t[0], t[1], t[2], p.vertex);
  }
  hinges_stale = 0;
}

/* ----------------------------------------------------------------------
   init: the plate stencils reach two rings of triangles around each triangle, so a rank needs
   the vertices up to kPlateReach of its longest rest edges away as ghosts; the ghost cutoff is
   raised to that (comm_modify cutoff: as the REBO styles do for their bond orders)
------------------------------------------------------------------------- */

static constexpr double kPlateReach = 5.0;

void PairPeriNosb::plate_ghost_cutoff()
{
  double longest = 0.0;
  double **x0 = atom->x0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!meshfix->mesh_of(i) || !bend_plate[atom->type[i]]) continue;
    for (int k = 0; k < meshfix->ntri_of(i); k++) {
      const int j = atom->map(meshfix->corner_of(i, k, 0));
      if (j < 0) continue;
      double d[3] = {x0[j][0] - x0[i][0], x0[j][1] - x0[i][1], x0[j][2] - x0[i][2]};
      domain->minimum_image(d[0], d[1], d[2]);
      longest = std::max(longest, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
  }
  double all = 0.0;
  MPI_Allreduce(&longest, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  const double reach = kPlateReach * all;
  if (reach > comm->cutghostuser) {
    comm->cutghostuser = reach;
    if (comm->me == 0)
      utils::logmesg(lmp,
                     "Pair peri/nosb bending plate: ghost cutoff at least {:.6g} ({} x the "
                     "longest mesh edge {:.6g})\n",
                     reach, kPlateReach, all);
  }
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
  if (any_plate && plates) plates->pass(particles(), block_rows, energy, virial_tallies());
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
  if (any_plate && plates) plates->stable_steps(particles(), atom->rmass, dt);
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
  if (any_plate) {
    // the plate edges' hinges stand in for the plate energy's couplings where those are left
    // out of the matrix (core solvers/block_matrix.h significant_plates); their vertices are
    // in the plate stencils, which build_hinges() checked
    if (plate_hinges_stale) {
      NosbHingeMesh mesh(this);
      PeriSISSM::build_hinges(mesh, atom->x0[0], family->box, plate_hinges, true);
      plate_hinges_stale = 0;
    }
    PeriSISSM::HingeCouplings more;
    PeriSISSM::hinge_couplings(plate_hinges, particles(), gradients, more);
    couplings.vertex.insert(couplings.vertex.end(), more.vertex.begin(), more.vertex.end());
    couplings.row.insert(couplings.row.end(), more.row.begin(), more.row.end());
    couplings.grad.insert(couplings.grad.end(), more.grad.begin(), more.grad.end());
  }
}

/* ----------------------------------------------------------------------
   ImplicitForces: the plate bending stencils for the coarse level's matrix
------------------------------------------------------------------------- */

const PeriSISSM::PlateCouplings &PairPeriNosb::plate_couplings()
{
  static const PeriSISSM::PlateCouplings none{{0}, {}, {}, {}};
  if (!any_plate || !meshfix) return none;
  if (hinges_stale) build_hinges();
  return plates->couplings();
}
