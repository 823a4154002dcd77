/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   pair_style peri/nosb: the LAMMPS glue of the core's peridynamic model (src/core/peri, terms
   evaluated in the order of peri/forces.h; doc/theory.rst, doc/pair_peri_nosb.rst): coefficients
   and restart (pair_peri_nosb_coeff.cpp, material files in pair_peri_nosb_material.cpp), the
   per-atom state and its halo exchange, contact candidates (pair_peri_nosb_contact.cpp), the
   bending term (pair_peri_nosb_bending.cpp), energy and virial tallies. Forces are the force
   densities f_k = -(1/V_k) dE/dy_k and pe tallies sum_i (W_i + stabilization energy density),
   as the built-in PERI styles tally densities.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"
#include "mesh_view.h"

#include "linalg/fused.h"
#include "materials/moduli.h"
#include "membrane/bending.h"
#include "membrane/plate_bending.h"
#include "peri/bond_stiffness.h"
#include "peri/box_check.h"
#include "peri/breaking.h"
#include "peri/coefficients.h"
#include "peri/contact.h"
#include "peri/family.h"
#include "peri/forces.h"
#include "peri/model.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

PairPeriNosb::PairPeriNosb(LAMMPS *lmp) :
    Pair(lmp), family(nullptr), coeffs(new PeriSISSM::CoefficientTable),
    model_(new PeriSISSM::Model), any_bend(0), any_plate(0), meshfix(nullptr), hinges_stale(1), any_break(0),
    any_contact(0), external_breaking(0), block_rows(nullptr), contact_groupbit(0),
    contact_crossings(0), state_nlocal(-1), nmax(0), gstate(nullptr), hstate(nullptr),
    kstate(nullptr), wdens(nullptr), s0_new(nullptr), cnormal(nullptr), cols(nullptr),
    comm_fields(nullptr), comm_nfields(0)
{
  single_enable = 0;
  no_virial_fdotr_compute = 1;    // forces are densities: f.r is not the virial
  restartinfo = 1;
  // the widest exchange of the halo: F, C, flag with the implicit stiffness
  comm_forward = PeriSISSM::ParticleFields::NG + PeriSISSM::ParticleFields::NK;
  comm_reverse = 6;    // the contact blocks of ghost atoms (add_contact_blocks)
}

/* ---------------------------------------------------------------------- */

PairPeriNosb::~PairPeriNosb()
{
  if (modify->get_fix_by_id("NOSB_FAMILY")) modify->delete_fix("NOSB_FAMILY");

  memory->destroy(gstate);
  memory->destroy(hstate);
  memory->destroy(kstate);
  memory->destroy(cols);
  memory->destroy(wdens);
  memory->destroy(s0_new);
  memory->destroy(cnormal);

  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n, n, "pair:cutsq");
  coeffs->resize(atom->ntypes);
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::init_style()
{
  if (!atom->peri_flag || !atom->vfrac_flag || !atom->x0)
    error->all(FLERR, "Pair style peri/nosb requires atom_style peri");
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "Pair style peri/nosb requires an atom map, see atom_modify map array");
  if (!atom->tag_enable) error->all(FLERR, "Pair style peri/nosb requires atom IDs");
  if (domain->dimension != 3) error->all(FLERR, "Pair style peri/nosb requires a 3d simulation");

  // as a sub-style of hybrid, hybrid/overlay or hybrid/scaled, types mapped to other styles
  // would get bond families with unset coefficients, and fix sissm would not see the other
  // styles' forces in its implicit residual: not supported

  if (force->pair != this)
    error->all(FLERR,
               "Pair style peri/nosb cannot be a sub-style of pair_style {}: use pair_style "
               "peri/nosb alone (several materials: pair_coeff per type pair; other "
               "interactions: fixes such as wall or indent)",
               force->pair_style);

  configure_model();    // coefficients of all type pairs (pair_peri_nosb_coeff.cpp)
  check_membranes();
  hinges_stale = 1;    // bending moduli, types or meshes may have changed since the last run
  if (any_plate && meshfix) plate_ghost_cutoff();

  // every bond partner must have one image within reach (core peri/box_check.h)

  const bool tri = domain->triclinic;
  const PeriSISSM::ReferenceBox now{{0, 0, 0},
                                    {domain->xprd, domain->yprd, domain->zprd,
                                     tri ? domain->yz : 0.0, tri ? domain->xz : 0.0,
                                     tri ? domain->xy : 0.0}};
  const int periodicity[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  const std::string narrow =
      PeriSISSM::periodic_box_problem(now, periodicity, coeffs->largest_horizon());
  if (!narrow.empty()) error->all(FLERR, narrow);

  // contact reaches 1.35 x the largest particle size; the neighbor list, the smallest horizon of
  // the type pairs with contact

  double hone = 0.0, hmax;
  for (int i = 0; i < atom->nlocal; i++) hone = std::max(hone, cbrt(atom->vfrac[i]));
  MPI_Allreduce(&hone, &hmax, 1, MPI_DOUBLE, MPI_MAX, world);
  follower.reach = 1.35 * hmax;
  follower.horizon = coeffs->smallest_contact_horizon();

  // the bond-family fix, created once (or recreated from a restart file)

  family = dynamic_cast<FixNosbFamily *>(modify->get_fix_by_id("NOSB_FAMILY"));
  if (!family)
    family = dynamic_cast<FixNosbFamily *>(modify->add_fix("NOSB_FAMILY all nosb/family"));
  family->attach(model_.get(), [this]() {
    neighbor_rebuilt();
  });

  // a half neighbor list only for short-range contact (an implicit integrator asks again
  // for the motion tracking in its own init, which follows this one)

  if (any_contact) neighbor->add_request(this);
  track_contact_motion(0);

  // minimization: the line searches evaluate trial positions far from the path (up to
  // min_modify dmax), and bonds breaking there would change the energy being minimized

  if (update->whichflag == 2 && any_break && comm->me == 0)
    utils::logmesg(lmp,
                   "Pair peri/nosb: bonds do not break during a minimization; they are checked "
                   "again from the first step of the next run\n");

  // which version of the bond passes runs (linalg/fused.h): the same on every rank, the fused
  // one only where every rank can run it (results of the two differ in round-off); logged, so
  // that a user comparing runs of two machines finds it here

  int fused_here = PeriSISSM::fused_passes_available() ? 1 : 0, fused_all = 0;
  MPI_Allreduce(&fused_here, &fused_all, 1, MPI_INT, MPI_MIN, world);
  PeriSISSM::set_fused_passes(fused_all != 0);
  if (!passes_reported && comm->me == 0)
    utils::logmesg(lmp, "Pair peri/nosb: bond passes {}\n", PeriSISSM::fused_passes_description());
  passes_reported = 1;
}

/* ----------------------------------------------------------------------
   membrane types: their atoms must be vertices of a mesh read with read_mesh (the membrane
   correspondence needs the mesh's normals and thickness)
------------------------------------------------------------------------- */

void PairPeriNosb::check_membranes()
{
  // (asked for in every deck: after read_restart, restore() defines the mesh fix of the file
  // again before LAMMPS discards its data)
  meshfix = MeshView::restore(lmp);
  const int n = atom->ntypes;
  bend.resize(n + 1, 0.0);
  bend_auto_factor = coeffs->bending_factors(bend);
  any_bend = std::any_of(bend.begin() + 1, bend.end(), [](double b) {
    return b != 0.0;
  });
  bend_plate.assign(n + 1, 0);
  bend_nu.assign(n + 1, 0.0);
  any_plate = 0;
  for (int t = 1; t <= n; t++) {
    if (bend[t] == 0.0) continue;
    bend_plate[t] = coeffs->at(t, t).plate ? 1 : 0;
    bend_nu[t] = PeriSISSM::poisson_ratio(coeffs->at(t, t).moduli);
    any_plate = any_plate || bend_plate[t];
  }
  if (!model_->any_membrane()) return;
  tagint bad = 0;
  int badtype = 0;
  for (int i = 0; i < atom->nlocal && !bad; i++) {
    if (!model_->membrane(atom->type[i])) continue;
    if (!meshfix || meshfix->mesh_of(i) == 0) {
      bad = atom->tag[i];
      badtype = atom->type[i];
    }
  }
  tagint anybad = 0;
  MPI_Allreduce(&bad, &anybad, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if (anybad) {
    if (bad == anybad)
      error->one(FLERR,
                 "Pair peri/nosb: atom {} is of type {}, a membrane type (pair_coeff ... "
                 "membrane yes), but not a vertex of a mesh read with read_mesh: membrane "
                 "particles are made by read_mesh",
                 bad, badtype);
    MPI_Barrier(world);
    error->all(FLERR, "Pair peri/nosb: an atom of a membrane type is not a mesh vertex");
  }
}

/* ---------------------------------------------------------------------- */

template <class Test> bool PairPeriNosb::any_type_in_group(int groupbit, Test of_type)
{
  int mine = 0, any = 0;
  for (int i = 0; i < atom->nlocal && !mine; i++)
    if ((atom->mask[i] & groupbit) && of_type(atom->type[i])) mine = 1;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, world);
  return any == 1;
}

bool PairPeriNosb::has_unbent_membranes(int groupbit)
{
  // (collective: every rank takes part in the reduction)
  const bool membranes = model_ && model_->any_membrane();
  return any_type_in_group(groupbit,
                           [&](int t) { return membranes && coeffs->unbent_membrane(t, bend); });
}

bool PairPeriNosb::only_membranes(int groupbit)
{
  return !any_type_in_group(groupbit, [&](int t) { return !coeffs->at(t, t).membrane; });
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::grow_peratom()
{
  if (atom->nmax > nmax) {
    using PeriSISSM::ParticleFields;
    nmax = atom->nmax;
    memory->grow(kstate, nmax * ParticleFields::NK, "pair:kstate");
    memory->grow(gstate, nmax * ParticleFields::NG, "pair:gstate");
    memory->grow(hstate, nmax * 9, "pair:hstate");
    memory->grow(cols, nmax * ParticleFields::NCOLS, "pair:cols");
    memory->grow(wdens, nmax, "pair:wdens");
    memory->grow(s0_new, nmax, "pair:s0_new");
    memory->destroy(cnormal);
  }
  if (model_->any_membrane() && !cnormal && nmax > 0)
    memory->create(cnormal, 3 * nmax, "pair:cnormal");
}

/* ----------------------------------------------------------------------
   the atoms as the core sees them
------------------------------------------------------------------------- */

PeriSISSM::Particles PairPeriNosb::particles() const
{
  PeriSISSM::Particles p;
  p.nlocal = atom->nlocal;
  p.nall = atom->nlocal + atom->nghost;
  p.x = atom->x[0];
  p.x0 = atom->x0[0];
  p.volume = atom->vfrac;
  p.type = atom->type;
  p.smin = atom->s0;
  p.f = atom->f[0];
  return p;
}

/* ----------------------------------------------------------------------
   the core's halo callback: a forward communication of one per-atom field
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class NosbHalo : public PeriSISSM::Halo {
 public:
  explicit NosbHalo(PairPeriNosb *pair) : pair_(pair) {}
  void forward(const PeriSISSM::HaloField *fields, int n) override
  {
    pair_->comm_fields = fields;
    pair_->comm_nfields = n;
    pair_->comm->forward_comm(pair_);
  }

 private:
  PairPeriNosb *pair_;
};
}    // namespace LAMMPS_NS

/* ---------------------------------------------------------------------- */

void PairPeriNosb::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow_peratom();
  if (!family->built) return;

  if (any_contact) compute_contact(eflag, vflag);

  // Bonds break in every force evaluation of a run, but not in the setup evaluation at the
  // start of a run (it only refreshes s_min): a run split into several (or by a restart) then
  // breaks exactly the bonds the unsplit run breaks. Nothing breaks, and s_min is left alone,
  // during a minimization (see init_style).

  using PeriSISSM::BreakingRule;
  const int nobreak = !any_break || external_breaking || update->whichflag == 2;
  const int mode = nobreak ? BreakingRule::NOBREAK
      : update->setupflag  ? BreakingRule::S0ONLY
                           : BreakingRule::BREAK;
  const PeriSISSM::Particles p = particles();
  PeriSISSM::ParticleFields fields;
  fields.g = gstate;
  fields.h = hstate;
  fields.k = kstate;
  fields.w = wdens;
  fields.energy = eflag_either;
  fields.smin_new = s0_new;
  fields.normal = cnormal;
  fields.cols = cols;
  const PeriSISSM::Virial vir = virial_tallies();
  NosbHalo halo(this);
  broke.clear();
  PeriSISSM::evaluate_bond_terms(*model_, p, family->view(), family->box, mode, block_rows, fields,
                                 halo, vir, broke);
  family->forget_broken(broke);
  if (any_contact && block_rows) add_contact_blocks();
  if (any_bend && meshfix) compute_bending();

  if (eflag_either)
    PeriSISSM::tally_energy_densities(atom->nlocal, wdens, eflag_global ? &eng_vdwl : nullptr,
                                      eflag_atom ? eatom : nullptr);
  state_nlocal = atom->nlocal;
}

/* ---------------------------------------------------------------------- */

bool PairPeriNosb::state_current() const
{
  return gstate && state_nlocal == atom->nlocal;
}

/* ----------------------------------------------------------------------
   ImplicitForces: the bond-projected stiffness (the evaluation with blocks sent H+ to the ghosts)
------------------------------------------------------------------------- */

void PairPeriNosb::bond_springs(PeriSISSM::BondSprings &springs, bool values)
{
  PeriSISSM::ParticleFields fields;
  fields.k = kstate;
  fields.normal = cnormal;    // (null without membranes)
  PeriSISSM::bond_springs(family->view(), particles(), fields, values, springs);
}

/* ----------------------------------------------------------------------
   ImplicitForces: a step and its evaluations
------------------------------------------------------------------------- */

void PairPeriNosb::begin_implicit_step(int groupbit)
{
  external_breaking = 1;
  contact_groupbit = groupbit;
  contact_crossings = 0;
}

void PairPeriNosb::end_implicit_step()
{
  external_breaking = 0;
  contact_groupbit = 0;
}

void PairPeriNosb::evaluate(double **block)
{
  block_rows = block;
  compute(0, 0);
  block_rows = nullptr;
}

// only short-range contact writes forces on ghost atoms (bond forces are summed by the owner of
// each bond's end); the same answer on every rank, as the reverse communication it decides on
// needs
bool PairPeriNosb::ghost_forces() const
{
  return any_contact && force->newton_pair;
}

/* ----------------------------------------------------------------------
   ImplicitForces: no unbroken bond joins an owned atom of the group with one outside it, and no
   short-range contact acted between them in the evaluations of this step (all ranks)
------------------------------------------------------------------------- */

bool PairPeriNosb::group_coupled(int groupbit)
{
  // group all: every atom is in it, no bond leaves it (and no pass over the bonds is needed)
  const bool every_atom = groupbit == group->bitmask[0];
  int coupled = contact_crossings > 0 ||
      (!every_atom &&
       PeriSISSM::bonds_leave_group(family->view(), atom->nlocal, atom->mask, groupbit));
  int any;
  MPI_Allreduce(&coupled, &any, 1, MPI_INT, MPI_MAX, world);
  return any != 0;
}

void PairPeriNosb::check_motion(int converged)
{
  family->check_motion(converged);
}

/* ---------------------------------------------------------------------- */

int PairPeriNosb::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  return PeriSISSM::pack_halo_rows(comm_fields, comm_nfields, n, list, buf);
}

void PairPeriNosb::unpack_forward_comm(int n, int first, double *buf)
{
  PeriSISSM::unpack_halo_rows(comm_fields, comm_nfields, n, first, buf);
}

/* ---------------------------------------------------------------------- */

double PairPeriNosb::memory_usage()
{
  using PeriSISSM::ParticleFields;
  double bytes = (double) nmax *
      (ParticleFields::NG + ParticleFields::NK + 9 + 2 + ParticleFields::NCOLS) * sizeof(double);
  bytes += follower.bytes() + (double) contact_blocks.capacity() * sizeof(double);
  bytes += (double) hinges.capacity() * sizeof(PeriSISSM::Hinge);
  const double n = atom->ntypes + 1;
  bytes += n * n * (sizeof(PeriSISSM::PairCoefficients) + sizeof(double) + sizeof(int));
  return bytes;
}
