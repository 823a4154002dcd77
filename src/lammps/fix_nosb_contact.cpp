/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact: the barrier contact of Incremental Potential Contact with lagged smooth
   friction between the mesh primitives and the volumetric particles of the fix's group, as a
   force (post_force); doc/fix_nosb_contact.rst says what it computes and when it stops. Where
   each part lives (src/core/contact): the arguments (contact_options.h), the pairs, the broad
   phase and the ranges of its neighbor list (candidates.h), a stencil per kind of pair
   (stencil.h), the distances kept between evaluations (candidate_distances.h), the barrier's
   and the friction's passes with their units and shares (barrier_potential.h,
   friction_potential.h), kappa's rule (adaptive_stiffness.h), the path limit (path_limit.h),
   the motion tracker (motion_tracker.h); the calls of fix sissm are in
   fix_nosb_contact_sissm.cpp (collision_limit.h). This file gathers the atoms, communicates
   (no reverse communication: only owned vertices get shares), restarts and reports.
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
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;
using Eigen::Vector3d;
using PeriSISSM::Candidate;
using PeriSISSM::MotionTracker;

static constexpr int NVECTOR = 9;

/* ---------------------------------------------------------------------- */

FixNosbContact::FixNosbContact(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  // the arguments (core contact/contact_options.h), numbers and yes/no parsed as LAMMPS does
  try {
    opt = PeriSISSM::parse_contact_options(
        {arg + 3, arg + narg},
        [lmp](const std::string &s) {
          return utils::numeric(FLERR, s, false, lmp);
        },
        [lmp](const std::string &s) {
          return utils::logical(FLERR, s, false, lmp) != 0;
        },
        {strcmp(update->unit_style, "lj") == 0, force->angstrom, force->femtosecond});
  } catch (std::invalid_argument &e) {
    error->all(FLERR, e.what());
  }
  kappa = opt.kappa;

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
  comm_forward = 3;                   // velocities of the ghost atoms (friction without fix sissm)
  restart_global = opt.kappa_auto;    // (write_restart())
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
  // particles that are or were bond partners are no contact pair: pair peri/nosb's families
  partners = dynamic_cast<BondPartners *>(force->pair_match("peri/nosb", 1));

  // the run's checks and warnings (core contact_options.h)
  run.id = id;
  run.group = group->names[igroup];
  run.mesh_vertices = all[0];
  run.particles = all[1];
  run.edge0 = all[0] ? measure_longest_edge(true) : 0.0;
  run.skin = neighbor->skin;
  run.ghost_cutoff = PeriSISSM::run_ghost_cutoff(
      comm->cutghostuser, force->pair ? force->pair->cutsq : nullptr, atom->ntypes, run.skin);
  run.partners = partners != nullptr;
  run.sissm = !modify->get_fix_by_style("^sissm$").empty();
  for (const PeriSISSM::ContactRunMessage &m : PeriSISSM::check_contact_run(opt, run)) {
    if (m.error) error->all(FLERR, m.text);
    if (comm->me == 0) error->warning(FLERR, m.text);
  }
  range = PeriSISSM::CandidateRange(opt.dmin, opt.dhat, run.edge0, run.skin);
  // (fix sissm's init, before or after this one, sets inertia_c for the run: set_force_factor())
  iterate_pending = 0;

  // an occasional list, built by this fix at every neighbor list build (build_candidates):
  // LAMMPS 4Feb2025 would make fix nosb/family's occasional list (no custom cutoff) a trimmed
  // copy of a perpetual list with a custom cutoff longer than the pair's, trimmed to a zero
  // cutoff (NPairTrim with cutoff_custom 0): empty families, no bonds. Occasional lists are not
  // copied from. The skin is added here (LAMMPS adds it to perpetual lists only).
  auto req = neighbor->add_request(this, NeighConst::REQ_FULL | NeighConst::REQ_OCCASIONAL);
  req->set_cutoff(range.list_cutoff + run.skin);
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
  if (opt.kappa_auto) {
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
  if (!all.error().empty()) error->all(FLERR, "Fix nosb/contact {}: {}", id, all.error());
  stiffness.set_scene(all.diagonal(), all.mean_mass(), opt.dhat);
}

/* ----------------------------------------------------------------------
   the candidate pairs of this rank (core candidates.h), chosen at a neighbor list build
------------------------------------------------------------------------- */

void FixNosbContact::build_candidates()
{
  distances.invalidate();    // the distances were of the old candidates
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;

  // pair peri/nosb builds its families at the first run's setup, in the setup_post_neighbor of
  // its fix nosb/family, which comes after this fix's (the pair creates that fix at its init):
  // the candidates are then chosen at the setup's force evaluation (post_force)
  if (run.particles && partners && !partners->partners_known()) {
    candidates.clear();
    stale = 1;
    return;
  }

  neighbor->build_one(list);

  // no edge may have grown past what the list's cutoff assumes (CandidateRange)
  if (range.longest_edge > 0.0) {
    const std::string grown = range.edge_error(measure_longest_edge(false), neighbor->skin);
    if (!grown.empty())
      error->all(FLERR, "Fix nosb/contact {}: at step {} {}", id, update->ntimestep, grown);
  }

  // the atoms as the core's broad phase sees them: IDs, roles, the triangles at each vertex
  std::vector<std::int64_t> tags(atom->tag, atom->tag + nall);
  const std::vector<PeriSISSM::ContactRole> role =
      PeriSISSM::contact_roles(nall, atom->mask, groupbit, meshfix ? meshfix->mesh_ids() : nullptr);
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
  const PeriSISSM::NeighborView view{list->inum, list->ilist, list->numneigh, list->firstneigh,
                                     NEIGHMASK};
  const double reach = opt.dmin + opt.dhat + neighbor->skin;
  const std::int64_t missing = PeriSISSM::find_candidates(atoms, view, reach, candidates);
  if (missing)
    error->one(FLERR, "Fix nosb/contact {}: {}", id, PeriSISSM::missing_vertex_error(missing));

  // where the owned atoms were (check_motion())
  motion.record(atom->x, nlocal);
  stale = 0;
  generation++;
}

/* ----------------------------------------------------------------------
   the motion since the candidates were chosen (motion_tracker.h): an error beyond skin/2
   (neigh_modify check no with a long every, or an implicit step that moves the atoms that far
   inside one step); beyond skin/4, a neighbor list build at the next step (collective)
------------------------------------------------------------------------- */

void FixNosbContact::check_motion()
{
  const double limit = MotionTracker::error_distance(neighbor->skin);
  int i;
  const double most = motion.largest_move2(atom->x, atom->nlocal, atom->mask, groupbit, i);
  if (most > limit * limit)
    error->one(FLERR, "Fix nosb/contact {}: {}", id,
               MotionTracker::moved_error(atom->tag[i], std::sqrt(most), neighbor->lastcall));
  // LAMMPS checks the motion only once per step; fix sissm's iterates move the atoms inside the
  // step (its post_integrate, before that check): beyond a quarter of the skin, the next step
  // builds a new list (decided on all ranks alike). A pending request is not moved: fix sissm
  // evaluates the forces of step n + 1 before LAMMPS decides on that step's list build. Under
  // fix sissm with ccd yes the end of each step decides instead (rebuild_wanted()).
  if (in_step) return;
  double all;
  MPI_Allreduce(&most, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  const double request = MotionTracker::request_distance(neighbor->skin);
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

  reduced = 0;

  // the candidates' distances at these positions (exact, or lower bounds where that suffices:
  // candidate_distances.h): the gaps limit_move() starts from when fix sissm evaluates at the
  // positions it has just marked admissible (begin_path() clears the mark)
  const double nearest = opt.dmin + opt.dhat + neighbor->skin;
  // (near pairs within a sixteenth of the skin beyond the range: on the cloth on a ball, 3
  // layers, a quarter took 0.85 of the time, a half 0.81 more; an eighth and a thirty-second
  // as much as a sixteenth in the counts of pairs looked at)
  distances.evaluate(candidates, atom->x, atom->nlocal + atom->nghost, generation,
                     opt.dmin + opt.dhat, nearest, neighbor->skin / 16.0);
  if (iterate_pending) adapt_at_iterate();
  const PeriSISSM::BarrierParameters prm{kappa, opt.dhat, opt.dmin};
  barrier =
      PeriSISSM::barrier_forces(candidates, distances, atom->x, atom->vfrac, prm, nearest, atom->f,
                                &active);
  if (barrier.too_close >= 0)
    error->one(FLERR, "Fix nosb/contact {}: at step {} {}", id, update->ntimestep,
               PeriSISSM::too_close_error(candidates[barrier.too_close],
                                          distances[barrier.too_close], opt.dmin));
  if (opt.mu > 0.0) add_friction();
}

/* ----------------------------------------------------------------------
   the lagged friction data of every active candidate pair at the current positions
------------------------------------------------------------------------- */

void FixNosbContact::build_lagged()
{
  PeriSISSM::build_lagged_pairs(candidates, atom->x, {kappa, opt.dhat, opt.dmin}, lagged);
  lagged_generation = generation;
}

/* ----------------------------------------------------------------------
   the friction force densities of the owned vertices of every lagged pair: under fix sissm
   the pairs lagged at x^n in begin_step(), with the slip x - x^n and eps = epsv h; otherwise
   (fix nve, or the evaluation after a step followed by a neighbor list build) lagged here, with
   the slip v dt (ghost velocities sent by this fix) and eps = epsv dt
------------------------------------------------------------------------- */

void FixNosbContact::add_friction()
{
  const bool implicit = in_step && lagged_generation == generation;
  if (!implicit) {
    comm->forward_comm(this);
    build_lagged();
  }
  const double dt = update->dt;
  const PeriSISSM::FrictionParameters prm{opt.mu, opt.epsv * (implicit ? step_h : dt)};
  friction = PeriSISSM::friction_forces(lagged, atom->x, implicit ? nullptr : atom->v, dt, prm,
                                        atom->vfrac, atom->f);
}

/* ----------------------------------------------------------------------
   velocities of the ghost atoms (the explicit friction recipe)
------------------------------------------------------------------------- */

int FixNosbContact::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                      int * /*pbc*/)
{
  double **v = atom->v;
  int m = 0;
  for (int i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) buf[m++] = v[list[i]][d];
  return m;
}

void FixNosbContact::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v;
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int d = 0; d < 3; d++) v[i][d] = buf[m++];
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
  if (!opt.kappa_auto || list[0] != 3.0) return;
  stiffness.set_scene(list[2], list[3], opt.dhat);
  stiffness.restore(list[1]);
}

/* ----------------------------------------------------------------------
   global sums of the last evaluation (collective; once per evaluation)
------------------------------------------------------------------------- */

void FixNosbContact::reduce()
{
  if (reduced) return;
  const PeriSISSM::BarrierTally &b = barrier;
  bigint counts[5] = {b.nactive[0], b.nactive[1], b.ncandidates, b.nactive[2], friction.npairs};
  double local[3] = {b.energy_density, b.energy_pairs, friction.work}, sums[3], mind;
  bigint c[5];
  MPI_Allreduce(local, sums, 3, MPI_DOUBLE, MPI_SUM, world);
  MPI_Allreduce(counts, c, 5, MPI_LMP_BIGINT, MPI_SUM, world);
  MPI_Allreduce(&b.mindist, &mind, 1, MPI_DOUBLE, MPI_MIN, world);
  all_energy_density = sums[0];
  const double entries[NVECTOR] = {(double) c[0], (double) c[1], mind,    sums[1], (double) c[2],
                                   (double) c[3], (double) c[4], sums[2], kappa};
  std::copy(entries, entries + NVECTOR, all_vector);
  reduced = 1;
}

double FixNosbContact::compute_scalar()
{
  reduce();
  return all_energy_density;
}

/* ----------------------------------------------------------------------
   the nine entries of doc/fix_nosb_contact.rst (Output) in reduce()'s order (the smallest
   distance is dmin + dhat + skin when there is no candidate)
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
      3.0 * (motion.size() + nxref) * sizeof(double) + distances.memory_bytes() +
      (double) (kept_x.capacity() + 3 * step_start.size()) * sizeof(double) +
      (double) kept_rows.capacity() * sizeof(double *) +
      (double) (active.capacity() + kept_active.capacity()) * sizeof(int);
}
