/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact: the barrier contact of Incremental Potential Contact between the mesh
   primitives and the volumetric particles of the fix's group, as a force (post_force). The
   core (src/core/contact) has the pairs and the broad phase (candidates.h: which pairs, why the
   list below finds them all, their order), a stencil per kind of pair (stencil.h), the
   distances kept between evaluations (candidate_distances.h), the barrier's and the friction's
   passes (barrier_potential.h: units and shares; friction_potential.h), kappa's rule
   (adaptive_stiffness.h), the path limit (path_limit.h) and the motion tracker
   (motion_tracker.h); this file gathers the atoms, communicates, restarts and reports.

   Pairs: point-triangle and edge-edge pairs of the meshes read with read_mesh (fix nosb/mesh),
   adjacency decided on the mesh alone (a vertex and a triangle whose vertices it is bonded to
   can be far apart on a folded cloth and must still repel); the group's other atoms are
   volumetric particles (points). Two particles that are or were bond partners (bond_partners.h,
   pair peri/nosb's families, broken bonds included) are no pair; without pair peri/nosb no
   particles are partners (a warning says so).

   Candidates: a full occasional neighbor list of cutoff r + 1.5 Lmax + skin (r = dmin + dhat,
   Lmax the larger of 1.5 x the longest edge at the run's start and that edge + 2 skin, 0
   without mesh edges; CandidateRange in candidates.h), built at every neighbor list build of
   LAMMPS, gives the pairs closer than r + skin. They stay complete while no atom moves skin/2
   (motion_tracker.h: an error beyond, checked at every evaluation; a build asked for at skin/4)
   and no edge grows beyond Lmax (checked at each build). The other vertices of a candidate lie
   within r + skin + 2.5 Lmax of an owned atom: the ghost cutoff must cover that (checked at
   init). Each rank evaluates its candidates (each pair with an owned vertex, once) and gives
   only its owned vertices their shares: no reverse communication, and 1 and N ranks agree to
   the last bit.

   Output: the global scalar is the sum of the vertices' energy densities (fix_modify energy yes
   adds it to pe); the vector (compute_vector()) counts the pairs and gives the energy itself,
   the smallest distance, the friction's work and the stiffness.

   Stiffness (kappa auto, doc "Choosing kappa"): AdaptiveStiffness in the units of the step's
   incremental potential, kappa = its value / c with c the force factor of fix sissm's scheme
   (from begin_step(), and from set_force_factor() at fix sissm's init). Its bounds come from
   the group's bounding box and mean mass at the first setup (measure_scene(), kept in restart
   files); balanced at the first iterate of every (sub-)step (balance_stiffness(), called by fix
   sissm, which redoes that evaluation when it changed) and doubled at the evaluations fix sissm
   announces with next_iterate() (never at a probe of a Jacobian product).

   Friction (keyword friction mu > 0): lagged pairs of every active candidate. Under fix sissm
   they are built at x^n in begin_step() (collision_limit.h), once per (sub-)step (no neighbor
   list build inside a step, so the local indices hold), with the slip x - x^n and eps = epsv h,
   and add_blocks() adds their Hessians' diagonal blocks. Otherwise (fix nve, or the evaluation
   after a step followed by a neighbor list build) they are built at every evaluation, with the
   slip v dt (ghost velocities sent by this fix) and eps = epsv dt: Coulomb friction regularised
   below the slip speed epsv. Which recipe: in_step, set by begin_step() and cleared at init().
   The friction potential is not a stored energy: it is in neither the scalar nor pe.
------------------------------------------------------------------------- */

#include "fix_nosb_contact.h"

#include "bond_partners.h"
#include "mesh_view.h"
#include "restart_records.h"

#include "contact/barrier_potential.h"
#include "contact/path_limit.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;
using Eigen::Vector3d;
using PeriSISSM::Candidate;
using PeriSISSM::MotionTracker;

static constexpr int NVECTOR = 9;

/* ---------------------------------------------------------------------- */

static double positive_number(const char *str, const char *what, bool zero_ok, Error *error,
                              LAMMPS *lmp)
{
  const double v = utils::numeric(FLERR, str, false, lmp);
  if (!std::isfinite(v) || v < 0.0 || (!zero_ok && v == 0.0))
    error->all(FLERR, "Illegal fix nosb/contact command: {} must be {} 0, got '{}'", what,
               zero_ok ? ">=" : ">", str);
  return v;
}

/* ---------------------------------------------------------------------- */

FixNosbContact::FixNosbContact(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dhat(-1.0), dmin(0.0), kappa(-1.0), kappa_auto(0), inertia_c(0.0),
    iterate_pending(0), mu(0.0), epsv(-1.0), list(nullptr), meshfix(nullptr), partners(nullptr),
    nparticles(0), stale(1), warned_sissm(0), warned_families(0), ccd(1), xref(nullptr), nxref(0),
    reach_bound(0), reach_moved(0.0), reach_atom(0), in_step(0), step_h(0.0), generation(0),
    lagged_generation(-1), energy_density(0.0), energy_pairs(0.0), mindist(0.0), nactive{0, 0, 0},
    ncandidates(0), nfriction(0), friction_work(0.0), reduced(0),
    all_energy_density(0.0), all_vector{}
{
  const char *usage = "fix ID group nosb/contact dhat D [dmin d] [kappa k|auto] [friction mu] "
                      "[epsv v] [ccd yes|no]";
  int iarg = 3;
  while (iarg < narg) {
    const std::string key(arg[iarg]);
    if (key != "dhat" && key != "dmin" && key != "kappa" && key != "ccd" && key != "friction" &&
        key != "epsv")
      error->all(FLERR, "Illegal fix nosb/contact command: unknown keyword '{}' ({})", key, usage);
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "fix nosb/contact " + key, error);
    const char *val = arg[iarg + 1];
    if (key == "dhat")
      dhat = positive_number(val, "dhat", false, error, lmp);
    else if (key == "dmin")
      dmin = positive_number(val, "dmin", true, error, lmp);
    else if (key == "ccd")
      ccd = utils::logical(FLERR, val, false, lmp);
    else if (key == "friction")
      mu = positive_number(val, "friction mu", true, error, lmp);
    else if (key == "epsv")
      epsv = positive_number(val, "epsv", false, error, lmp);
    else if (strcmp(val, "auto") == 0) {
      kappa_auto = 1;
      kappa = -1.0;
    } else {
      kappa_auto = 0;
      kappa = positive_number(val, "kappa", false, error, lmp);
    }
    iarg += 2;
  }
  if (dhat < 0.0)
    error->all(FLERR, "Illegal fix nosb/contact command: keyword dhat is required ({})", usage);
  // epsv: IPC's 1e-3 m/s in the deck's units (force->angstrom and force->femtosecond are 1 A and
  // 1 fs in them); lj units have no metre: it must be given there
  if (epsv < 0.0) {
    if (mu > 0.0 && strcmp(update->unit_style, "lj") == 0)
      error->all(FLERR,
                 "Illegal fix nosb/contact command: with friction in lj units give the slip speed "
                 "epsv (velocity units; IPC's default is 1e-3 m/s, which lj units cannot convert)");
    epsv = PeriSISSM::default_slip_speed(force->angstrom, force->femtosecond);
  }
  if (kappa < 0.0 && !kappa_auto)
    error->all(FLERR,
               "Illegal fix nosb/contact command: keyword kappa is required (a number, or auto "
               "under fix sissm) ({})",
               usage);

  scalar_flag = 1;
  vector_flag = 1;
  size_vector = NVECTOR;
  global_freq = 1;
  extscalar = 1;
  extvector = 0;
  energy_global_flag = 1;
  thermo_energy = 0;
  force_reneighbor = 1;
  next_reneighbor = -1;
  comm_forward = 3;    // velocities of the ghost atoms (friction without fix sissm)
  // kappa auto: the adapted stiffness and the scales it comes from are kept in restart files
  restart_global = kappa_auto;
}

/* ---------------------------------------------------------------------- */

FixNosbContact::~FixNosbContact()
{
  memory->destroy(xref);
}

/* ---------------------------------------------------------------------- */

int FixNosbContact::setmask()
{
  return POST_FORCE | POST_NEIGHBOR;
}

/* ----------------------------------------------------------------------
   the mesh (if any), the group (mesh vertices and volumetric particles), the bond families,
   the longest edge, the ghost cutoff, the neighbor list
------------------------------------------------------------------------- */

void FixNosbContact::init()
{
  if (!atom->peri_flag || !atom->vfrac)
    error->all(FLERR, "Fix nosb/contact requires atom_style peri (per-atom volume vfrac)");
  meshfix = MeshView::find(lmp);

  // the group's mesh vertices and volumetric (non-mesh) particles
  bigint mine[2] = {0, 0}, all[2];
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mine[(meshfix && meshfix->mesh_of(i)) ? 0 : 1]++;
  MPI_Allreduce(mine, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  nparticles = all[1];
  if (all[0] + all[1] == 0)
    error->all(FLERR,
               "Fix nosb/contact {}: group {} holds no atom: the contact acts between the "
               "triangles of meshes read with read_mesh and between volumetric particles",
               id, group->names[igroup]);

  // particles that are or were bond partners are no contact pair: pair peri/nosb's families
  partners = dynamic_cast<BondPartners *>(force->pair_match("peri/nosb", 1));
  if (nparticles && !partners && !warned_families) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "Fix nosb/contact {}: no pair_style peri/nosb, so no bond families: every "
                     "two volumetric particles of group {} closer than dmin + dhat repel",
                     id, group->names[igroup]);
    warned_families = 1;
  }

  const double L = all[0] ? measure_longest_edge(true) : 0.0;
  if (all[0] && !nparticles && !(L > 0.0))
    error->all(FLERR, "Fix nosb/contact {}: group {} holds no mesh edge and no volumetric particle",
               id, group->names[igroup]);
  const double skin = neighbor->skin;
  range = PeriSISSM::CandidateRange(dmin, dhat, L, skin);
  const double needed = range.ghost_cutoff(skin);
  const double have = predicted_comm_cutoff();
  if (have < needed && range.longest_edge == 0.0)
    error->all(FLERR,
               "Fix nosb/contact {}: the ghost cutoff {:.6g} is shorter than a contact pair "
               "needs: dmin + dhat + skin = {:.6g} (the other particle of a pair with an owned "
               "one must be a ghost atom); set comm_modify cutoff {:.6g} or more",
               id, have, needed, needed);
  if (have < needed)
    error->all(FLERR,
               "Fix nosb/contact {}: the ghost cutoff {:.6g} is shorter than a contact pair "
               "needs: dmin + dhat + skin + 2.5 x max({} x the longest edge ({:.6g}), that edge + "
               "2 skin) = {:.6g} (the other vertices of a pair with an owned vertex must be ghost "
               "atoms); set comm_modify cutoff {:.6g} or more",
               id, have, PeriSISSM::CandidateRange::kEdgeFactor, L, needed, needed);

  // ccd no: fix sissm's steps are not collision-free; say so once (doc/fix_nosb_contact.rst)
  if (!ccd && !warned_sissm && !modify->get_fix_by_style("^sissm$").empty()) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "Fix nosb/contact {}: ccd no: under fix sissm the barrier is part of the "
                     "implicit step, but the step is not collision-free: a pair can pass through "
                     "the barrier within one step unless the step moves vertices by less than "
                     "dhat",
                     id);
    warned_sissm = 1;
  }

  // kappa auto: the stiffness is set against the implicit step's inertia (the file's header)
  if (kappa_auto && modify->get_fix_by_style("^sissm$").empty())
    error->all(FLERR,
               "Fix nosb/contact {}: kappa auto needs fix sissm (the barrier's stiffness is "
               "set against the inertia of its implicit step, as in IPC); under an explicit "
               "integrator give kappa as a number (doc/fix_nosb_contact.rst, 'Choosing kappa')",
               id);
  // (fix sissm's init, before or after this one, sets inertia_c for the run: set_force_factor())
  iterate_pending = 0;

  // an occasional list, built by this fix at every neighbor list build (build_candidates):
  // LAMMPS 4Feb2025 would make fix nosb/family's occasional list (no custom cutoff) a trimmed
  // copy of a perpetual list with a custom cutoff longer than the pair's, trimmed to a zero
  // cutoff (NPairTrim with cutoff_custom 0): empty families, no bonds. Occasional lists are not
  // copied from. The skin is added here (LAMMPS adds it to perpetual lists only).
  auto req = neighbor->add_request(this, NeighConst::REQ_FULL | NeighConst::REQ_OCCASIONAL);
  req->set_cutoff(range.list_cutoff + skin);
  stale = 1;
  // the explicit friction recipe until fix sissm starts a step (begin_step())
  in_step = 0;
  lagged.clear();
}

/* ---------------------------------------------------------------------- */

void FixNosbContact::init_list(int /*id*/, NeighList *ptr)
{
  list = ptr;
}

/* ----------------------------------------------------------------------
   the ghost cutoff the coming run will have (Comm::get_comm_cutoff() after Neighbor::init,
   which comes after this fix's init): the larger of comm_modify cutoff and the pair's
   cutoff + skin
------------------------------------------------------------------------- */

double FixNosbContact::predicted_comm_cutoff() const
{
  double cut = comm->cutghostuser;
  if (force->pair && force->pair->cutsq) {
    const int n = atom->ntypes;
    for (int i = 1; i <= n; i++)
      for (int j = 1; j <= n; j++)
        if (force->pair->cutsq[i][j] > 0.0)
          cut = std::max(cut, std::sqrt(force->pair->cutsq[i][j]) + neighbor->skin);
  }
  return cut;
}

/* ----------------------------------------------------------------------
   the longest edge of the group's triangles (all ranks). owned_partners_only: at init, when
   the ghost atoms may not exist yet, only the edges whose ends are both owned on some rank
   count (an edge between ranks is then missed: the 50% margin covers a mesh of even edges);
   otherwise every edge at an owned vertex (ghosts current: after a neighbor list build)
------------------------------------------------------------------------- */

double FixNosbContact::measure_longest_edge(bool owned_partners_only)
{
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  double L2 = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit) || !meshfix->mesh_of(i)) continue;
    for (int k = 0; k < meshfix->ntri_of(i); k++)
      for (int e = 0; e < 2; e++) {
        const int m = atom->map(meshfix->corner_of(i, k, e));
        if (m < 0 || (owned_partners_only && m >= nlocal)) continue;
        if (!(atom->mask[m] & groupbit)) continue;
        const int j = domain->closest_image(i, m);
        double r2 = 0.0;
        for (int d = 0; d < 3; d++) r2 += (x[j][d] - x[i][d]) * (x[j][d] - x[i][d]);
        L2 = std::max(L2, r2);
      }
  }
  double all;
  MPI_Allreduce(&L2, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return std::sqrt(all);
}

/* ---------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   right after every neighbor list build (ghost positions current): the candidates are chosen
   at the positions the list was built from, so that its skin covers them (under fix sissm the
   step's first force evaluation may already be elsewhere)
------------------------------------------------------------------------- */

void FixNosbContact::setup_post_neighbor()
{
  build_candidates();
}

void FixNosbContact::post_neighbor()
{
  build_candidates();
}

/* ---------------------------------------------------------------------- */

void FixNosbContact::setup(int vflag)
{
  if (kappa_auto) {
    if (!stiffness.measured()) measure_scene();
    if (!(inertia_c > 0.0)) inertia_c = update->dt * update->dt;    // (no fix sissm: an error)
    kappa = stiffness.value() / inertia_c;
  }
  post_force(vflag);
}

/* ----------------------------------------------------------------------
   kappa auto, at the first setup (not after a restart, which brings them): the diagonal of the
   group's bounding box and its atoms' mean mass, the bounds of the stiffness they give, and
   the stiffness to start from (the lower bound)
------------------------------------------------------------------------- */

void FixNosbContact::measure_scene()
{
  PeriSISSM::SceneExtent mine, all;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mine.add(atom->x[i], atom->rmass[i] * atom->vfrac[i]);
  MPI_Allreduce(mine.lo, all.lo, 3, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(mine.hi, all.hi, 3, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(mine.mass, all.mass, 2, MPI_DOUBLE, MPI_SUM, world);
  const double diagonal = all.diagonal(), mean_mass = all.mean_mass();
  if (!(diagonal > 0.0) || !(mean_mass > 0.0))
    error->all(FLERR,
               "Fix nosb/contact {}: kappa auto needs a group of atoms with mass that spans a "
               "box (its diagonal {:.6g}, the mean mass {:.6g})",
               id, diagonal, mean_mass);
  stiffness.set_scene(diagonal, mean_mass, dhat);
}

/* ----------------------------------------------------------------------
   the candidate pairs of this rank (see the file's header), chosen at a neighbor list build
------------------------------------------------------------------------- */

void FixNosbContact::build_candidates()
{
  distances.invalidate();    // the distances were of the old candidates
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;

  // pair peri/nosb builds its families at the first run's setup, in the setup_post_neighbor of
  // its fix nosb/family, which comes after this fix's (the pair creates that fix at its init):
  // the candidates are then chosen at the setup's force evaluation (post_force)
  if (nparticles && partners && !partners->partners_known()) {
    candidates.clear();
    stale = 1;
    return;
  }

  neighbor->build_one(list);

  // no edge may have grown past what the list's cutoff assumes (the file's header)
  const double L = range.longest_edge > 0.0 ? measure_longest_edge(false) : 0.0;
  if (range.longest_edge > 0.0 && !range.covers(L, neighbor->skin))
    error->all(FLERR,
               "Fix nosb/contact {}: at step {} a mesh edge is {:.6g} long, more than the "
               "contact candidates of this run allow (the longest edge at the run's start, the "
               "larger of {} x it and it + 2 skin, less the neighbor skin: {:.6g}): start a new "
               "run (which measures the edges again) or use a smaller neighbor skin",
               id, update->ntimestep, L, PeriSISSM::CandidateRange::kEdgeFactor,
               range.longest_edge - neighbor->skin);

  // the atoms as the core's broad phase sees them: IDs, roles, the triangles at each vertex
  std::vector<std::int64_t> tags(tag, tag + nall);
  std::vector<PeriSISSM::ContactRole> role(nall, PeriSISSM::ContactRole::kNone);
  const int *mesh = meshfix ? meshfix->mesh_ids() : nullptr;
  for (int i = 0; i < nall; i++)
    if (mask[i] & groupbit)
      role[i] = (mesh && mesh[i]) ? PeriSISSM::ContactRole::kMeshVertex
                                  : PeriSISSM::ContactRole::kParticle;
  PeriSISSM::ContactAtoms atoms;
  atoms.nlocal = nlocal;
  atoms.nall = nall;
  atoms.x = atom->x;
  atoms.tag = tags.data();
  atoms.role = role.data();
  atoms.triangles = [this](int i, std::vector<std::array<int, 2>> &others) {
    for (int k = 0; k < meshfix->ntri_of(i); k++) {
      std::array<int, 2> w;
      for (int e = 0; e < 2; e++) {
        const int m = atom->map(meshfix->corner_of(i, k, e));
        w[e] = m < 0 ? -1 : domain->closest_image(i, m);
      }
      others.push_back(w);
    }
  };
  if (partners)
    atoms.were_partners = [this](int a, int b) {
      return partners->were_partners(a, b);
    };
  // (minimum image: x0 of a periodic ghost is not shifted)
  atoms.rest_vector = [this](int a, int b) {
    double dx = atom->x0[b][0] - atom->x0[a][0], dy = atom->x0[b][1] - atom->x0[a][1],
           dz = atom->x0[b][2] - atom->x0[a][2];
    domain->minimum_image(dx, dy, dz);
    return Vector3d(dx, dy, dz);
  };
  atoms.owned = [this](std::int64_t t) {
    const int m = atom->map((tagint) t);
    return (m >= 0 && m < atom->nlocal) ? m : -1;
  };
  PeriSISSM::NeighborView view;
  view.inum = list->inum;
  view.ilist = list->ilist;
  view.numneigh = list->numneigh;
  view.firstneigh = list->firstneigh;
  view.neighmask = NEIGHMASK;
  const double reach = dmin + dhat + neighbor->skin;
  const std::int64_t missing = PeriSISSM::find_candidates(atoms, view, reach, candidates);
  if (missing)
    error->one(FLERR,
               "Fix nosb/contact {}: a vertex of a triangle of atom {} is neither owned nor a "
               "ghost atom here: the ghost cutoff is too short for the mesh (comm_modify cutoff)",
               id, (tagint) missing);

  // where the owned atoms were (check_motion())
  motion.record(atom->x, nlocal);
  stale = 0;
  generation++;
}

/* ----------------------------------------------------------------------
   the candidates are complete while no atom has moved skin/2 since they were chosen: an error
   beyond (neigh_modify check no with a long every, or an implicit step that moves the atoms
   farther than a quarter of the skin inside one step); beyond skin/4, a neighbor list build at
   the next step (collective: every force evaluation calls it on all ranks)
------------------------------------------------------------------------- */

void FixNosbContact::check_motion()
{
  const double skin = neighbor->skin;
  const double limit = MotionTracker::error_distance(skin);
  int i;
  const double most = motion.largest_move2(atom->x, atom->nlocal, atom->mask, groupbit, i);
  if (most > limit * limit)
    error->one(FLERR,
               "Fix nosb/contact {}: atom {} moved {:.6g} since the last neighbor list build at "
               "step {}, more than half the neighbor skin: contact pairs may be missing; let "
               "LAMMPS rebuild the lists when needed (neigh_modify every 1 delay 0 check yes), "
               "use a larger skin or a smaller time step",
               id, atom->tag[i], std::sqrt(most), neighbor->lastcall);
  // LAMMPS checks the motion only once per step; fix sissm's iterates move the atoms inside the
  // step (its post_integrate, before that check): beyond a quarter of the skin, the next step
  // builds a new list (decided on all ranks alike). A pending request is not moved: fix sissm
  // evaluates the forces of step n + 1 before LAMMPS decides on that step's list build.
  double all;
  MPI_Allreduce(&most, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  const double request = MotionTracker::request_distance(skin);
  if (all > request * request && next_reneighbor < update->ntimestep)
    next_reneighbor = update->ntimestep + 1;
}

/* ----------------------------------------------------------------------
   the barrier force densities of the owned vertices of every candidate pair
------------------------------------------------------------------------- */

void FixNosbContact::post_force(int /*vflag*/)
{
  if (stale)
    build_candidates();
  else
    check_motion();
  if (stale)
    error->all(FLERR,
               "Fix nosb/contact {}: the bond families of pair peri/nosb were not built at the "
               "run's setup",
               id);

  double **x = atom->x;
  const double *vfrac = atom->vfrac;
  const double range = dmin + dhat;

  mindist = dmin + dhat + neighbor->skin;
  reduced = 0;

  // the candidates' distances at these positions (exact, or lower bounds where that suffices:
  // candidate_distances.h): the gaps limit_move() starts from when fix sissm evaluates at the
  // positions it has just marked admissible (begin_path() clears the mark)
  distances.evaluate(candidates, x, atom->nlocal + atom->nghost, generation, range, mindist);
  if (iterate_pending) adapt_at_iterate();
  const PeriSISSM::BarrierParameters prm{kappa, dhat, dmin};

  const PeriSISSM::BarrierTally t =
      PeriSISSM::barrier_forces(candidates, distances, x, vfrac, prm, mindist, atom->f);
  if (t.too_close >= 0) {
    const Candidate &c = candidates[t.too_close];
    std::string atoms = std::to_string(c.tag[0]);
    for (int k = 1; k < c.nv(); k++) atoms += " " + std::to_string(c.tag[k]);
    error->one(FLERR,
               "Fix nosb/contact {}: at step {} the {} pair of atoms {} is {:.6g} apart, not "
               "more than dmin = {:.6g}: the barrier is infinite there (the primitives came "
               "through the barrier: use a larger kappa, a smaller time step or a larger dhat)",
               id, update->ntimestep, c.stencil().name(), atoms, distances[t.too_close], dmin);
  }
  energy_density = t.energy_density;
  energy_pairs = t.energy_pairs;
  for (int k = 0; k < 3; k++) nactive[k] = t.nactive[k];
  ncandidates = t.ncandidates;
  mindist = t.mindist;
  if (mu > 0.0) add_friction();
}

/* ----------------------------------------------------------------------
   the lagged friction data of every active candidate pair at the current positions (x^n under
   fix sissm), with those positions
------------------------------------------------------------------------- */

void FixNosbContact::build_lagged()
{
  PeriSISSM::build_lagged_pairs(candidates, atom->x, {kappa, dhat, dmin}, lagged);
  lagged_generation = generation;
}

/* ----------------------------------------------------------------------
   the friction force densities of the owned vertices of every lagged pair (the file's header:
   the implicit recipe inside a step of fix sissm, the explicit one otherwise)
------------------------------------------------------------------------- */

void FixNosbContact::add_friction()
{
  const bool implicit = in_step && lagged_generation == generation;
  if (!implicit) {
    comm->forward_comm(this);
    build_lagged();
  }
  const double dt = update->dt;
  const PeriSISSM::FrictionParameters prm{mu, epsv * (implicit ? step_h : dt)};
  const PeriSISSM::FrictionTally t = PeriSISSM::friction_forces(
      lagged, atom->x, implicit ? nullptr : atom->v, dt, prm, atom->vfrac, atom->f);
  nfriction = t.npairs;
  friction_work = t.work;
}

/* ----------------------------------------------------------------------
   velocities of the ghost atoms (the explicit friction recipe)
------------------------------------------------------------------------- */

int FixNosbContact::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                      int * /*pbc*/)
{
  double **v = atom->v;
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    buf[m++] = v[j][0];
    buf[m++] = v[j][1];
    buf[m++] = v[j][2];
  }
  return m;
}

void FixNosbContact::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v;
  int m = 0;
  for (int i = first; i < first + n; i++) {
    v[i][0] = buf[m++];
    v[i][1] = buf[m++];
    v[i][2] = buf[m++];
  }
}

/* ----------------------------------------------------------------------
   kappa auto: the adapted stiffness (incremental-potential units) and the scene's scales its
   bounds come from travel in restart files (restart_global is set only then)
------------------------------------------------------------------------- */

void FixNosbContact::write_restart(FILE *fp)
{
  const double list[4] = {3.0, stiffness.value(), stiffness.bbox_diagonal(), stiffness.mean_mass()};
  write_global_record(fp, comm->me, list, 4);
}

void FixNosbContact::restart(char *buf)
{
  const auto *list = (const double *) buf;
  if (!kappa_auto || list[0] != 3.0) return;
  stiffness.set_scene(list[2], list[3], dhat);
  stiffness.restore(list[1]);
}

/* ----------------------------------------------------------------------
   global sums of the last evaluation (collective; once per evaluation)
------------------------------------------------------------------------- */

void FixNosbContact::reduce()
{
  if (reduced) return;
  double local[3] = {energy_density, energy_pairs, friction_work}, sums[3];
  bigint counts[5] = {nactive[0], nactive[1], ncandidates, nactive[2], nfriction}, countsall[5];
  MPI_Allreduce(local, sums, 3, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(counts, countsall, 5, MPI_LMP_BIGINT, MPI_SUM, world);
  double mind;
  MPI_Allreduce(&mindist, &mind, 1, MPI_DOUBLE, MPI_MIN, world);
  all_energy_density = sums[0];
  all_vector[0] = countsall[0];
  all_vector[1] = countsall[1];
  all_vector[2] = mind;
  all_vector[3] = sums[1];
  all_vector[4] = countsall[2];
  all_vector[5] = countsall[3];
  all_vector[6] = countsall[4];
  all_vector[7] = sums[2];
  all_vector[8] = kappa;
  reduced = 1;
}

double FixNosbContact::compute_scalar()
{
  reduce();
  return all_energy_density;
}

/* ----------------------------------------------------------------------
   1 active point-triangle pairs, 2 active edge-edge pairs (closer than dmin + dhat),
   3 smallest distance among the candidates (dmin + dhat + skin when there is none),
   4 barrier energy sum_pairs E, 5 candidate pairs, 6 active point-point pairs,
   7 friction pairs, 8 the work of their friction force over the step's slip (dissipated),
   9 the barrier stiffness kappa of the evaluation (kappa auto: the adapted one)
------------------------------------------------------------------------- */

double FixNosbContact::compute_vector(int n)
{
  reduce();
  return all_vector[n];
}

/* ---------------------------------------------------------------------- */

double FixNosbContact::memory_usage()
{
  return (double) candidates.capacity() * sizeof(Candidate) +
      (double) lagged.capacity() * sizeof(PeriSISSM::LaggedPair) +
      3.0 * (motion.size() + nxref) * sizeof(double);
}
