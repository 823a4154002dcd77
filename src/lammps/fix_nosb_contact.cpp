/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   fix nosb/contact: the barrier contact of Incremental Potential Contact between the mesh
   primitives and the volumetric particles of the fix's group, as a force (post_force). The
   barrier, distances and their gradients are the core's (contact/barrier.h,
   contact/distance.h); this file finds the pairs and hands out the forces.

   Pairs. Every point-triangle pair (a vertex and a triangle) and every edge-edge pair of the
   meshes read with read_mesh (fix nosb/mesh) whose primitives are in the group, except those
   that share a vertex: a vertex and the triangles of its own 1-ring, two edges with a common end.
   Adjacency is decided on the mesh alone, not by the peridynamic bond families: a vertex and a
   triangle whose vertices it is bonded to can be far apart on a folded cloth and must still
   repel. (For a flat sheet, dmin + dhat must then stay below the distance of a vertex to the far
   side of its neighbours' triangles, about the triangles' height: the doc says so.)
   The group's atoms that are not mesh vertices are volumetric particles, i.e. points: they form
   point-point pairs with each other and point-triangle pairs with the group's triangles, with
   the same dmin and dhat. Two particles that are or were bond partners (pair peri/nosb's
   families, broken bonds included) are no pair: partners are the particles whose reference
   positions x0 lie within the horizon of their types, as fix nosb/family chose them when it
   built the families (atoms made after that are no one's partners); a broken bond keeps no tag
   in the families, but its reference distance is still there. Without pair peri/nosb no
   particles are partners (a warning says so).

   Candidates. A pair of primitives closer than r = dmin + dhat has vertices closer than
   r + 1.5 L (L the longest edge; two particles are within r): for a point p and a triangle T
   with closest point q, every vertex of T is within L of q, so |p - t_k| < r + L for all k; for
   two edges with closest points qa, qb, an end a_k is within L of qa and the nearer end b_c of
   the other within L/2 of qb. So every pair with an owned vertex o is found from o and a
   neighbor j of o within r + 1.5 L: as (point o, the triangles at j), (point j, the triangles
   at o) and (the edges at o, the edges at j), or (particle o, particle j). The fix builds a
   full occasional neighbor list of cutoff r + 1.5 Lmax + skin at every neighbor list build of
   LAMMPS, with Lmax = the larger of 1.5 x the longest edge at the run's start and that edge +
   2 skin (0 without mesh edges), and
   chooses the candidates again from it, each pair once (sorted by its vertices' IDs and made
   unique), keeping the pairs closer than r + skin at the build: while no atom moves more than
   skin/2 (the fix asks for a build at skin/4, LAMMPS at skin/2 between steps; an error beyond,
   checked at every evaluation: check_motion()) no other pair can come within
   r, and no edge can grow beyond Lmax while its length plus the skin stays below Lmax at each
   build (checked then). The other vertices of a candidate lie within r + skin + 2.5 Lmax of an
   owned atom: the ghost cutoff must cover that (checked at init, like the bending term's).

   Forces. Each rank evaluates all of its candidates (each pair with an owned vertex, once) and
   gives only its owned vertices their shares: no force goes to ghost atoms, so no reverse
   communication; a pair that straddles ranks is evaluated on each of them, with the same
   positions in the same vertex order (by ID), so the shares agree to the last bit. The pairs are
   in the order of their IDs, so that a vertex sums its shares in the same order however the
   atoms are ordered locally or split between ranks.

   Units (atom_style peri: f is a force density, rmass a mass density, vfrac the volume V_i): the
   pair's energy E = kappa b(d - dmin) (times the mollifier for edges) is an energy; vertex k of
   the pair gets the force density -dE/dx_k / V_k (so that fix nve moves it by -dE/dx_k / m_k),
   and an energy density E / (n V_k) (n = 4 vertices, 2 for two particles), as the bending term
   of pair peri/nosb tallies its hinges (pe of peri/nosb is a sum of energy densities:
   doc/pair_peri_nosb.rst). The global scalar
   is that sum of densities (fix_modify energy yes adds it to pe); vector element 4 is the
   energy itself, sum_pairs E; element 6 counts the active point-point pairs.

   Stiffness (kappa auto, doc "Choosing kappa"): IPC's adaptive barrier stiffness, kept as
   kappa_ip in the units of the step's incremental potential (the forces use kappa = kappa_ip / c,
   c the force factor of fix sissm's scheme, from begin_step(), and from set_force_factor() at
   fix sissm's init for the evaluations before the first step). Its
   bounds come from the group's bounding box and mean mass at the first setup (measure_scene(),
   kept in restart files); it is balanced against the rest of the residual at the first iterate
   of every (sub-)step (balance_stiffness(), called by fix sissm, which redoes that evaluation
   when it changed) and doubled at later iterates while the smallest gap is tiny and shrinking
   (adapt_at_iterate(), at the evaluations fix sissm announces with next_iterate(): never at a
   probe of a Jacobian product, whose difference quotient needs the same stiffness as its base).

   Friction (keyword friction mu > 0): the lagged smooth friction of the core
   (contact/friction.h) on every active pair (within dmin + dhat, lambda > 0). Under fix sissm
   (which calls begin_step() at the start of each (sub-)step solve, collision_limit.h) the pairs'
   lagged data and the positions x^n of their vertices (the images used, owned and ghost: no
   neighbor list build inside a step, so the local indices hold) are built there, once per
   (sub-)step, and every evaluation of the step adds the force of D(x - x^n) with the slip
   length eps = epsv h, and add_blocks() its Hessian's diagonal blocks. Otherwise (fix nve, or
   the evaluation after a step that was followed by a neighbor list build, whose local indices
   are gone) the pairs are built at every evaluation from the current positions and
   u = v dt (ghost velocities sent by this fix), eps = epsv dt: Coulomb friction regularised
   below the slip speed epsv. Which recipe: in_step, set by begin_step() and cleared at init().
   D is a potential of the step, not a stored energy: it is in neither the scalar nor pe.
   Element 7 counts the friction pairs, element 8 is the work the friction force of the last
   evaluation does over the step's slip, sum mu lambda f1(|u_T|) |u_T| (the energy it
   dissipates; with u = v dt under fix nve: the dissipated power times dt).
------------------------------------------------------------------------- */

#include "fix_nosb_contact.h"

#include "fix_nosb_family.h"
#include "fix_nosb_mesh.h"
#include "pair_peri_nosb.h"

#include "contact/barrier.h"
#include "contact/ccd.h"
#include "contact/distance.h"
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

static constexpr int NVECTOR = 9;
// default slip speed below which friction is smoothed: IPC's 1e-3 m/s, in the units' velocity
static constexpr double EPSV_DEFAULT_SI = 1.0e-3;
// Lmax = EDGE_FACTOR x the longest edge at the start of a run (or that edge + 2 skin when the skin
// is large): edges may stretch by 50% less the skin (by a skin) before the candidates could be
// incomplete (an error then)
static constexpr double EDGE_FACTOR = 1.5;

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

/* ----------------------------------------------------------------------
   the local indices of the owned vertices of a pair of nv vertices with the given tags (-1 for
   the others) in own; returns whether this rank counts the pair (it owns the vertex with the
   smallest ID), so that a pair counts once over all ranks
------------------------------------------------------------------------- */

static bool owned_vertices(Atom *atom, const tagint *tag, int nv, int *own)
{
  const int nlocal = atom->nlocal;
  int smallest = 0;
  for (int k = 0; k < nv; k++) {
    const int m = atom->map(tag[k]);
    own[k] = (m >= 0 && m < nlocal) ? m : -1;
    if (tag[k] < tag[smallest]) smallest = k;
  }
  return own[smallest] >= 0;
}

/* ----------------------------------------------------------------------
   a candidate's points (gather), their squared distance (distance2) and the gradient of its
   barrier energy (barrier_gradient)
------------------------------------------------------------------------- */

void FixNosbContact::gather(const Candidate &c, double **x, Vector3d *y)
{
  for (int k = 0; k < c.nv(); k++) y[k] = Vector3d(x[c.v[k]][0], x[c.v[k]][1], x[c.v[k]][2]);
}

double FixNosbContact::distance2(const Candidate &c, const Vector3d *y)
{
  return c.type == PT ? PeriSISSM::point_triangle_distance2(y[0], y[1], y[2], y[3])
      : c.type == EE  ? PeriSISSM::edge_edge_distance2(y[0], y[1], y[2], y[3])
                      : PeriSISSM::point_point_distance2(y[0], y[1]);
}

double FixNosbContact::closing(const Candidate &c, const double *len)
{
  const int na = c.type == EE ? 2 : 1;    // the first primitive's points: p, a0 a1, p
  double la = 0.0, lb = 0.0;
  for (int k = 0; k < c.nv(); k++) {
    double &l = k < na ? la : lb;
    l = std::max(l, len[k]);
  }
  return la + lb;
}

PeriSISSM::Vector12d FixNosbContact::barrier_gradient(const Candidate &c, const Vector3d *y,
                                                      const PeriSISSM::BarrierParameters &prm)
{
  PeriSISSM::Vector12d g = PeriSISSM::Vector12d::Zero();
  if (c.type == PT)
    g = PeriSISSM::point_triangle_barrier_gradient(y[0], y[1], y[2], y[3], prm);
  else if (c.type == EE)
    g = PeriSISSM::edge_edge_barrier_gradient(y[0], y[1], y[2], y[3], c.eps, prm);
  else
    g.head<6>() = PeriSISSM::point_point_barrier_gradient(y[0], y[1], prm);
  return g;
}

/* ---------------------------------------------------------------------- */

FixNosbContact::FixNosbContact(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dhat(-1.0), dmin(0.0), kappa(-1.0), kappa_auto(0), kappa_ip(0.0),
    kappa_ip_min(0.0), kappa_ip_max(0.0), inertia_c(0.0), bbox_diagonal(0.0), mean_mass(0.0),
    iterate_pending(0), prev_min_gap(HUGE_VAL), mu(0.0), epsv(-1.0),
    edge_factor(EDGE_FACTOR),
    longest_edge(0.0), list_cutoff(0.0), list(nullptr), meshfix(nullptr), pair(nullptr),
    nparticles(0), stale(1), warned_sissm(0), warned_families(0), xbuild(nullptr), nxbuild(0),
    ccd(1), xref(nullptr), nxref(0), distance_valid(0), xlast(nullptr), nxlast(0),
    xlast_generation(-1), reach_bound(0), reach_moved(0.0),
    reach_atom(0), in_step(0), step_h(0.0), generation(0),
    lagged_generation(-1), energy_density(0.0), energy_pairs(0.0), mindist(0.0),
    nactive{0, 0, 0}, ncandidates(0), nfriction(0), friction_work(0.0), reduced(0),
    all_energy_density(0.0), all_vector{}
{
  const char *usage = "fix ID group nosb/contact dhat D [dmin d] [kappa k|auto] [friction mu] "
                      "[epsv v] [ccd yes|no]";
  int iarg = 3;
  while (iarg < narg) {
    const std::string key(arg[iarg]);
    if (key != "dhat" && key != "dmin" && key != "kappa" && key != "ccd" && key != "friction" &&
        key != "epsv")
      error->all(FLERR, "Illegal fix nosb/contact command: unknown keyword '{}' ({})", key,
                 usage);
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
  // 1 fs in them: 1 m/s = 1e10 A / 1e15 fs); lj units have no metre: it must be given there
  if (epsv < 0.0) {
    if (mu > 0.0 && strcmp(update->unit_style, "lj") == 0)
      error->all(FLERR,
                 "Illegal fix nosb/contact command: with friction in lj units give the slip speed "
                 "epsv (velocity units; IPC's default is 1e-3 m/s, which lj units cannot convert)");
    epsv = EPSV_DEFAULT_SI * 1.0e10 * force->angstrom / (1.0e15 * force->femtosecond);
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
  memory->destroy(xbuild);
  memory->destroy(xref);
  memory->destroy(xlast);
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
  meshfix = FixNosbMesh::find(lmp);

  // the group's mesh vertices and volumetric (non-mesh) particles
  bigint mine[2] = {0, 0}, all[2];
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) mine[(meshfix && meshfix->mesh[i]) ? 0 : 1]++;
  MPI_Allreduce(mine, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  nparticles = all[1];
  if (all[0] + all[1] == 0)
    error->all(FLERR,
               "Fix nosb/contact {}: group {} holds no atom: the contact acts between the "
               "triangles of meshes read with read_mesh and between volumetric particles",
               id, group->names[igroup]);

  // particles that are or were bond partners are no contact pair: pair peri/nosb's families
  pair = dynamic_cast<PairPeriNosb *>(force->pair_match("peri/nosb", 1));
  if (nparticles && !pair && !warned_families) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "Fix nosb/contact {}: no pair_style peri/nosb, so no bond families: every "
                     "two volumetric particles of group {} closer than dmin + dhat repel",
                     id, group->names[igroup]);
    warned_families = 1;
  }

  const double L = all[0] ? measure_longest_edge(true) : 0.0;
  if (all[0] && !nparticles && !(L > 0.0))
    error->all(FLERR,
               "Fix nosb/contact {}: group {} holds no mesh edge and no volumetric particle", id,
               group->names[igroup]);
  longest_edge = L > 0.0 ? std::max(edge_factor * L, L + 2.0 * neighbor->skin) : 0.0;
  list_cutoff = dmin + dhat + 1.5 * longest_edge;

  const double skin = neighbor->skin;
  const double needed = list_cutoff + skin + longest_edge;
  const double have = predicted_comm_cutoff();
  if (have < needed && longest_edge == 0.0)
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
               id, have, edge_factor, L, needed, needed);

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
  req->set_cutoff(list_cutoff + neighbor->skin);
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
    if (!(atom->mask[i] & groupbit) || !meshfix->mesh[i]) continue;
    for (int k = 0; k < meshfix->ntri[i]; k++)
      for (int e = 0; e < 2; e++) {
        const int m = atom->map(meshfix->tri[i][k][e]);
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
    if (!(bbox_diagonal > 0.0)) measure_scene();
    if (!(inertia_c > 0.0)) inertia_c = update->dt * update->dt;    // (no fix sissm: an error)
    kappa = kappa_ip / inertia_c;
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
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double mass[2] = {0.0, 0.0};
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) {
      lo[d] = std::min(lo[d], x[i][d]);
      hi[d] = std::max(hi[d], x[i][d]);
    }
    mass[0] += atom->rmass[i] * atom->vfrac[i];
    mass[1] += 1.0;
  }
  double alllo[3], allhi[3], allmass[2];
  MPI_Allreduce(lo, alllo, 3, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(hi, allhi, 3, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(mass, allmass, 2, MPI_DOUBLE, MPI_SUM, world);
  double diag2 = 0.0;
  for (int d = 0; d < 3; d++) diag2 += (allhi[d] - alllo[d]) * (allhi[d] - alllo[d]);
  bbox_diagonal = std::sqrt(diag2);
  mean_mass = allmass[0] / allmass[1];
  if (!(bbox_diagonal > 0.0) || !(mean_mass > 0.0))
    error->all(FLERR,
               "Fix nosb/contact {}: kappa auto needs a group of atoms with mass that spans a "
               "box (its diagonal {:.6g}, the mean mass {:.6g})",
               id, bbox_diagonal, mean_mass);
  kappa_ip_min = PeriSISSM::initial_barrier_stiffness(bbox_diagonal, dhat, mean_mass, 0.0, 0.0,
                                                      kappa_ip_max);
  kappa_ip = kappa_ip_min;
}

/* ----------------------------------------------------------------------
   kappa auto: a new stiffness (incremental-potential units); the lagged friction's normal
   forces, proportional to it, follow
------------------------------------------------------------------------- */

void FixNosbContact::set_kappa_ip(double k)
{
  const double ratio = k / kappa_ip;
  kappa_ip = k;
  kappa = kappa_ip / inertia_c;
  for (Lagged &p : lagged) p.pair.lambda *= ratio;
}

/* ----------------------------------------------------------------------
   kappa auto, at an iterate of fix sissm (the distances of the candidates are current):
   IPC's update, the stiffness doubles (up to its upper bound) while the smallest gap is below
   1e-9 of the box's diagonal and still shrinking from the last iterate of the step
------------------------------------------------------------------------- */

void FixNosbContact::adapt_at_iterate()
{
  iterate_pending = 0;
  double gap = HUGE_VAL;
  for (double d : distance) gap = std::min(gap, d - dmin);
  double all;
  MPI_Allreduce(&gap, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  const double k =
      PeriSISSM::update_barrier_stiffness(prev_min_gap, all, kappa_ip_max, kappa_ip, bbox_diagonal);
  prev_min_gap = all;
  if (k != kappa_ip) set_kappa_ip(k);
}

/* ----------------------------------------------------------------------
   kappa auto, after the first evaluation of a fix sissm (sub-)step: IPC's balance, the
   stiffness that minimises |grad E + kappa grad B| (E the step's incremental potential without
   the barrier, B the barrier sum at unit stiffness) over the atoms the step moves, clamped to
   its bounds. -res_i V_i is the gradient of the whole incremental potential (collision_limit.h,
   in units where the inertia's Hessian is the mass), so grad E = -res V - kappa_ip grad B.
   When no pair is active the stiffness is the lower bound (no force depends on it then).
------------------------------------------------------------------------- */

bool FixNosbContact::balance_stiffness(double **res, double force_factor, int igroupbit)
{
  double **x = atom->x;
  const double *vfrac = atom->vfrac;
  const int nlocal = atom->nlocal;
  inertia_c = force_factor;
  const PeriSISSM::BarrierParameters unit{1.0, dhat, dmin};
  const double range = dmin + dhat;
  std::vector<double> grad(3 * (std::size_t) nlocal, 0.0);
  int active = 0;
  for (std::size_t ic = 0; ic < candidates.size(); ic++) {
    const Candidate &c = candidates[ic];
    if (!(distance_valid && distance[ic] < range)) continue;
    Vector3d y[4];
    gather(c, x, y);
    const PeriSISSM::Vector12d g = barrier_gradient(c, y, unit);
    const int *own = c.own;
    for (int k = 0; k < c.nv(); k++) {
      const int i = own[k];
      if (i < 0 || !(atom->mask[i] & igroupbit)) continue;
      active = 1;
      for (int d = 0; d < 3; d++) grad[3 * i + d] += g[3 * k + d];
    }
  }
  // sums over the atoms: res V . grad B, |grad B|^2; lagged friction pairs
  double local[3] = {0.0, 0.0, (double) lagged.size()}, sums[3];
  if (active)
    for (int i = 0; i < nlocal; i++) {
      if (!(atom->mask[i] & igroupbit)) continue;
      for (int d = 0; d < 3; d++) {
        local[0] += res[i][d] * vfrac[i] * grad[3 * i + d];
        local[1] += grad[3 * i + d] * grad[3 * i + d];
      }
    }
  MPI_Allreduce(local, sums, 3, MPI_DOUBLE, MPI_SUM, world);
  double kmax;
  const double k = PeriSISSM::initial_barrier_stiffness(
      bbox_diagonal, dhat, mean_mass, -sums[0] - kappa_ip * sums[1], sums[1], kmax);
  if (k == kappa_ip) return false;
  set_kappa_ip(k);
  // (no active pair and no friction: no force depends on the stiffness, the evaluation stands)
  return sums[1] > 0.0 || sums[2] > 0.0;
}

/* ----------------------------------------------------------------------
   the candidate pairs of this rank (see the file's header), chosen at a neighbor list build
------------------------------------------------------------------------- */

void FixNosbContact::build_candidates()
{
  distance_valid = 0;    // the distances were of the old candidates
  double **x = atom->x;
  double **x0 = atom->x0;
  const tagint *tag = atom->tag;
  const int *type = atom->type;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int *mesh = meshfix ? meshfix->mesh : nullptr;
  const int *ntri = meshfix ? meshfix->ntri : nullptr;
  tagint ***tri = meshfix ? meshfix->tri : nullptr;

  // pair peri/nosb builds its families at the first run's setup, in the setup_post_neighbor of
  // its fix nosb/family, which comes after this fix's (the pair creates that fix at its init):
  // the candidates are then chosen at the setup's force evaluation (post_force)
  FixNosbFamily *fam = pair ? pair->family : nullptr;
  if (nparticles && fam && !fam->built) {
    candidates.clear();
    stale = 1;
    return;
  }

  neighbor->build_one(list);

  // no edge may have grown past what the list's cutoff assumes (see the header)
  const double L = longest_edge > 0.0 ? measure_longest_edge(false) : 0.0;
  if (longest_edge > 0.0 && L + neighbor->skin > longest_edge)
    error->all(FLERR,
               "Fix nosb/contact {}: at step {} a mesh edge is {:.6g} long, more than the "
               "contact candidates of this run allow (the longest edge at the run's start, the "
               "larger of {} x it and it + 2 skin, less the neighbor skin: {:.6g}): start a new "
               "run (which measures the edges again) or use a smaller neighbor skin",
               id, update->ntimestep, L, edge_factor, longest_edge - neighbor->skin);

  // mesh vertices and volumetric particles of the group
  auto member = [&](int k) { return k >= 0 && (mask[k] & groupbit) && mesh && mesh[k]; };
  auto particle = [&](int k) { return (mask[k] & groupbit) && !(mesh && mesh[k]); };
  tagint missing = 0;

  // the triangles and edges at each atom (owned or ghost, vertices at their images closest to
  // it), with bounding spheres (centre, radius) and boxes (lo, hi), found once per atom when
  // first needed
  struct Bounds {
    Vector3d centre, lo, hi;
    double radius;
  };
  struct Tri {
    int v[3];
    Bounds b;
  };
  struct Edge {
    int v[2];
    Bounds b;
  };
  auto bounds = [](const Vector3d *y, int n) {
    Bounds b;
    b.centre = b.lo = b.hi = y[0];
    for (int k = 1; k < n; k++) {
      b.centre += y[k];
      b.lo = b.lo.cwiseMin(y[k]);
      b.hi = b.hi.cwiseMax(y[k]);
    }
    b.centre /= n;
    double r2 = 0.0;
    for (int k = 0; k < n; k++) r2 = std::max(r2, (y[k] - b.centre).squaredNorm());
    b.radius = std::sqrt(r2);
    return b;
  };
  // a bound from the primitives' bounding spheres and boxes: their distance is at least the
  // distance of the centres less the radii, and at least the gap between the boxes
  auto apart = [](const Bounds &a, const Bounds &b, double r) {
    if ((a.centre - b.centre).norm() - a.radius - b.radius >= r) return true;
    for (int d = 0; d < 3; d++)
      if (a.lo[d] - b.hi[d] >= r || b.lo[d] - a.hi[d] >= r) return true;
    return false;
  };
  const int nall = nlocal + atom->nghost;
  std::vector<int> tri_at(nall, -1), edge_at(nall, -1);    // first index, -1: not yet
  std::vector<int> tri_end(nall, 0), edge_end(nall, 0);
  std::vector<Bounds> around(nall);    // the bounds of all the primitives at an atom
  std::vector<Tri> tris;
  std::vector<Edge> edges;
  auto point = [&](int k) { return Vector3d(x[k][0], x[k][1], x[k][2]); };
  auto primitives = [&](int i) {
    if (tri_at[i] >= 0) return;
    tri_at[i] = (int) tris.size();
    edge_at[i] = (int) edges.size();
    for (int k = 0; k < ntri[i]; k++) {
      int w[2];
      for (int e = 0; e < 2; e++) {
        const int m = atom->map(tri[i][k][e]);
        w[e] = m < 0 ? -1 : domain->closest_image(i, m);
      }
      if (w[0] < 0 || w[1] < 0) {
        missing = tag[i];
        continue;
      }
      if (!member(w[0]) || !member(w[1])) continue;
      const Vector3d y[3] = {point(i), point(w[0]), point(w[1])};
      tris.push_back({{i, w[0], w[1]}, bounds(y, 3)});
      for (int e = 0; e < 2; e++) {
        bool seen = false;
        for (int g = edge_at[i]; g < (int) edges.size(); g++)
          seen = seen || tag[edges[g].v[1]] == tag[w[e]];
        if (seen) continue;
        const Vector3d y[2] = {point(i), point(w[e])};
        edges.push_back({{i, w[e]}, bounds(y, 2)});
      }
    }
    tri_end[i] = (int) tris.size();
    edge_end[i] = (int) edges.size();
    // (a sphere about the atom through its farthest edge end, and the box of the triangles)
    Bounds &u = around[i];
    u.centre = u.lo = u.hi = point(i);
    u.radius = 0.0;
    for (int t = tri_at[i]; t < tri_end[i]; t++) {
      u.lo = u.lo.cwiseMin(tris[t].b.lo);
      u.hi = u.hi.cwiseMax(tris[t].b.hi);
    }
    for (int e = edge_at[i]; e < edge_end[i]; e++)
      u.radius = std::max(u.radius, 2.0 * edges[e].b.radius);
  };

  std::vector<Candidate> found;
  // the pairs that can come within dmin + dhat before the next neighbor list build (tested as
  // they are found: a neighbor list with a wide skin finds many times more pairs than it keeps)
  const double reach = dmin + dhat + neighbor->skin;
  auto near = [&](const Candidate &c) {
    Vector3d y[4];
    gather(c, x, y);
    const double D = distance2(c, y);
    return D < reach * reach;
  };
  // a point-triangle pair in canonical order (the triangle's vertices by ID); none if p is one.
  // First the bounds (apart): most pairs the list finds are far
  auto add_pt = [&](int p, const Tri &t) {
    for (int k = 0; k < 3; k++)
      if (tag[t.v[k]] == tag[p]) return;
    const Vector3d y = point(p);
    if (apart(Bounds{y, y, y, 0.0}, t.b, reach)) return;
    int s[3] = {t.v[0], t.v[1], t.v[2]};
    std::sort(s, s + 3, [tag](int a, int b) { return tag[a] < tag[b]; });
    Candidate c{PT, {tag[p], tag[s[0]], tag[s[1]], tag[s[2]]}, {p, s[0], s[1], s[2]}, 0.0};
    if (near(c)) found.push_back(c);
  };
  // an edge-edge pair in canonical order (each edge from its smaller ID, the edges by their
  // first IDs); none if they share a vertex
  auto add_ee = [&](const Edge &a, const Edge &b) {
    for (int k = 0; k < 2; k++)
      for (int l = 0; l < 2; l++)
        if (tag[a.v[k]] == tag[b.v[l]]) return;
    if (apart(a.b, b.b, reach)) return;
    std::array<int, 2> u{a.v[0], a.v[1]}, w{b.v[0], b.v[1]};
    if (tag[u[1]] < tag[u[0]]) std::swap(u[0], u[1]);
    if (tag[w[1]] < tag[w[0]]) std::swap(w[0], w[1]);
    if (tag[w[0]] < tag[u[0]]) std::swap(u, w);
    Candidate c{EE, {tag[u[0]], tag[u[1]], tag[w[0]], tag[w[1]]}, {u[0], u[1], w[0], w[1]}, 0.0};
    if (near(c)) found.push_back(c);
  };

  // were two particles bond partners: their reference distance (x0, minimum image in the box of
  // the families) within the horizon of their types, as fix nosb/family chose the partners (the
  // same test, so broken bonds count too); atoms made after the families are no one's partners
  auto were_bonded = [&](int a, int b) {
    if (!fam || tag[a] > fam->tagmax0 || tag[b] > fam->tagmax0) return false;
    double xi[3];
    PeriSISSM::reference_bond(x0[0], fam->box, a, b, xi);
    const double delta = pair->model().horizon(type[a], type[b]);
    return xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] <= delta * delta;
  };
  // a point-point pair in canonical order (by ID); none if they were bond partners
  auto add_pp = [&](int p, int q) {
    if (tag[q] < tag[p]) std::swap(p, q);
    if (were_bonded(p, q)) return;
    Candidate c{PP, {tag[p], tag[q], 0, 0}, {p, q, -1, -1}, 0.0};
    if (near(c)) found.push_back(c);
  };

  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  // (the list is full and symmetric between owned atoms: what a pair of owned atoms gives is
  // the same from either end, so it is taken from the end with the smaller ID only)
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    if (i >= nlocal || !(member(i) || particle(i))) continue;
    if (member(i)) primitives(i);
    const int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (tag[j] == tag[i] || (j < nlocal && tag[j] < tag[i])) continue;
      if (particle(i) && particle(j)) {
        add_pp(i, j);
        continue;
      }
      if (!member(j) && !particle(j)) continue;
      if (member(j)) primitives(j);
      // (the primitives at i and at j, and the points i and j, lie within their atoms' bounds)
      if (member(i) && member(j) && apart(around[i], around[j], reach)) continue;
      if (member(j))
        for (int t = tri_at[j]; t < tri_end[j]; t++) add_pt(i, tris[t]);
      if (member(i))
        for (int t = tri_at[i]; t < tri_end[i]; t++) add_pt(j, tris[t]);
      if (member(i) && member(j))
        for (int a = edge_at[i]; a < edge_end[i]; a++)
          for (int b = edge_at[j]; b < edge_end[j]; b++) add_ee(edges[a], edges[b]);
    }
  }
  if (missing)
    error->one(FLERR,
               "Fix nosb/contact {}: a vertex of a triangle of atom {} is neither owned nor a "
               "ghost atom here: the ghost cutoff is too short for the mesh (comm_modify cutoff)",
               id, missing);

  // each pair once, in the order of its IDs
  std::sort(found.begin(), found.end(), [](const Candidate &a, const Candidate &b) {
    if (a.type != b.type) return a.type < b.type;
    return std::lexicographical_compare(a.tag, a.tag + 4, b.tag, b.tag + 4);
  });
  const auto same = [](const Candidate &a, const Candidate &b) {
    return a.type == b.type && std::equal(a.tag, a.tag + 4, b.tag);
  };
  found.erase(std::unique(found.begin(), found.end(), same), found.end());

  candidates.clear();
  for (Candidate &c : found) {
    if (c.type == EE) {
      // the rest shape's edge vectors (minimum image: x0 of a periodic ghost is not shifted)
      Vector3d r[2];
      for (int e = 0; e < 2; e++) {
        const int a = c.v[2 * e], b = c.v[2 * e + 1];
        double dx = x0[b][0] - x0[a][0], dy = x0[b][1] - x0[a][1], dz = x0[b][2] - x0[a][2];
        domain->minimum_image(dx, dy, dz);
        r[e] = Vector3d(dx, dy, dz);
      }
      c.eps = PeriSISSM::edge_edge_mollifier_threshold(Vector3d::Zero(), r[0], Vector3d::Zero(),
                                                        r[1]);
    }
    c.counts = owned_vertices(atom, c.tag, c.nv(), c.own);
    candidates.push_back(c);
  }

  // where the owned atoms were (check_motion())
  if (atom->nmax > nxbuild) {
    nxbuild = atom->nmax;
    memory->grow(xbuild, nxbuild, 3, "nosb/contact:xbuild");
  }
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 3; d++) xbuild[i][d] = x[i][d];
  stale = 0;
  generation++;
}

/* ----------------------------------------------------------------------
   the candidates are complete while no atom has moved skin/2 since they were chosen: an error
   beyond (neigh_modify check no with a long every, or an implicit step that moves the atoms
   farther than a quarter of the skin inside one step); beyond skin/4, a neighbor list build at
   the next step (collective: every force evaluation calls it on all ranks)
------------------------------------------------------------------------- */

double FixNosbContact::moved_since_build(int &farthest) const
{
  double **x = atom->x;
  double most = 0.0;
  farthest = -1;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    double r2 = 0.0;
    for (int d = 0; d < 3; d++) r2 += (x[i][d] - xbuild[i][d]) * (x[i][d] - xbuild[i][d]);
    if (r2 > most) {
      most = r2;
      farthest = i;
    }
  }
  return most;
}

void FixNosbContact::check_motion()
{
  const double limit = 0.25 * neighbor->skin * neighbor->skin;
  int i;
  const double most = moved_since_build(i);
  if (most > limit)
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
  if (all > 0.25 * limit && next_reneighbor < update->ntimestep)
    next_reneighbor = update->ntimestep + 1;
}


/* ----------------------------------------------------------------------
   the 3x3 diagonal blocks of a pair's Hessian H (nv vertices) divided by the volume of each
   owned vertex (own: local indices, -1 for the others), added to block (xx yy zz xy xz yz)
------------------------------------------------------------------------- */

static void add_diagonal_blocks(const PeriSISSM::Matrix12d &H, int nv, const int *own,
                                const double *vfrac, double **block)
{
  for (int k = 0; k < nv; k++) {
    const int i = own[k];
    if (i < 0) continue;
    const double w = 1.0 / vfrac[i];
    const int o = 3 * k;
    block[i][0] += w * H(o, o);
    block[i][1] += w * H(o + 1, o + 1);
    block[i][2] += w * H(o + 2, o + 2);
    block[i][3] += w * H(o, o + 1);
    block[i][4] += w * H(o, o + 2);
    block[i][5] += w * H(o + 1, o + 2);
  }
}

/* ----------------------------------------------------------------------
   the barrier force densities of the owned vertices of every candidate pair
------------------------------------------------------------------------- */

void FixNosbContact::post_force(int /*vflag*/)
{
  if (stale) build_candidates();
  else check_motion();
  if (stale)
    error->all(FLERR,
               "Fix nosb/contact {}: the bond families of pair peri/nosb were not built at the "
               "run's setup",
               id);

  double **x = atom->x;
  double **f = atom->f;
  const double *vfrac = atom->vfrac;
  const int nlocal = atom->nlocal;
  const double range = dmin + dhat;

  energy_density = energy_pairs = 0.0;
  nactive[0] = nactive[1] = nactive[2] = 0;
  ncandidates = 0;
  mindist = dmin + dhat + neighbor->skin;
  reduced = 0;

  // the candidates' distances at these positions: the gaps limit_move() starts from when fix
  // sissm evaluates at the positions it has just marked admissible (begin_path() clears the mark).
  // Since the last evaluation (of the same candidates) a pair's distance shrank at most by how
  // far a point of each primitive moved: when that lower bound is beyond the barrier's range and
  // not below the smallest distance found so far, the pair neither acts nor is the nearest, and
  // the bound stands in for the distance (limit_move() takes it as a smaller gap: conservative)
  const int nall = nlocal + atom->nghost;
  const bool bounded = xlast_generation == generation && (int) distance.size() ==
      (int) candidates.size();
  std::vector<double> moved;
  if (bounded) {
    moved.resize(nall);
    for (int i = 0; i < nall; i++) {
      const double dx = x[i][0] - xlast[i][0], dy = x[i][1] - xlast[i][1],
                   dz = x[i][2] - xlast[i][2];
      moved[i] = std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  }
  distance.resize(candidates.size());
  distance_exact.assign(candidates.size(), 1);
  distance_valid = 0;
  double nearest = mindist;
  for (std::size_t ic = 0; ic < candidates.size(); ic++) {
    const Candidate &c = candidates[ic];
    if (bounded) {
      double len[4];
      for (int k = 0; k < c.nv(); k++) len[k] = moved[c.v[k]];
      const double bound = distance[ic] - closing(c, len);
      if (bound >= range && bound >= nearest) {
        distance[ic] = bound;
        distance_exact[ic] = 0;
        continue;
      }
    }
    Vector3d y[4];
    gather(c, x, y);
    distance[ic] = std::sqrt(distance2(c, y));
    nearest = std::min(nearest, distance[ic]);
  }
  distance_valid = 1;
  if (nall > nxlast) {
    nxlast = atom->nmax;
    memory->grow(xlast, nxlast, 3, "nosb/contact:xlast");
  }
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) xlast[i][d] = x[i][d];
  xlast_generation = generation;
  if (iterate_pending) adapt_at_iterate();
  const PeriSISSM::BarrierParameters prm{kappa, dhat, dmin};

  for (std::size_t ic = 0; ic < candidates.size(); ic++) {
    const Candidate &c = candidates[ic];
    const int nv = c.nv();
    // the owned vertices of the pair, and whether this rank counts it (its smallest ID)
    const int *own = c.own;
    const bool counts = c.counts;
    if (counts) ncandidates++;
    const double d = distance[ic];
    mindist = std::min(mindist, d);
    if (!(d < range)) continue;
    Vector3d y[4];
    gather(c, x, y);
    if (!(d > dmin)) {
      static const char *const kind[3] = {"point-triangle", "edge-edge", "point-point"};
      std::string atoms = std::to_string(c.tag[0]);
      for (int k = 1; k < nv; k++) atoms += " " + std::to_string(c.tag[k]);
      error->one(FLERR,
                 "Fix nosb/contact {}: at step {} the {} pair of atoms {} is {:.6g} apart, not "
                 "more than dmin = {:.6g}: the barrier is infinite there (the primitives came "
                 "through the barrier: use a larger kappa, a smaller time step or a larger dhat)",
                 id, update->ntimestep, kind[c.type], atoms, d, dmin);
    }

    const double E = c.type == PT
        ? PeriSISSM::point_triangle_barrier_energy(y[0], y[1], y[2], y[3], prm)
        : c.type == EE ? PeriSISSM::edge_edge_barrier_energy(y[0], y[1], y[2], y[3], c.eps, prm)
                       : PeriSISSM::point_point_barrier_energy(y[0], y[1], prm);
    const PeriSISSM::Vector12d g = barrier_gradient(c, y, prm);
    if (counts) {
      nactive[c.type]++;
      energy_pairs += E;
    }
    // each vertex's share of the energy: E / nv (1 / nv exact: 0.25 or 0.5)
    const double share = 1.0 / nv;
    for (int k = 0; k < nv; k++) {
      const int i = own[k];
      if (i < 0) continue;
      const double vi = vfrac[i];
      for (int dim = 0; dim < 3; dim++) f[i][dim] -= g[3 * k + dim] / vi;
      energy_density += share * E / vi;
    }
  }
  if (mu > 0.0) add_friction();
}

/* ----------------------------------------------------------------------
   the lagged friction data of every active candidate pair at the current positions (x^n under
   fix sissm), with those positions
------------------------------------------------------------------------- */

void FixNosbContact::build_lagged()
{
  double **x = atom->x;
  const PeriSISSM::BarrierParameters prm{kappa, dhat, dmin};
  const double range = dmin + dhat;
  lagged.clear();
  for (const Candidate &c : candidates) {
    const int nv = c.nv();
    Vector3d y[4];
    gather(c, x, y);
    const double D = distance2(c, y);
    // (a pair at or within dmin is an error of the force evaluation)
    if (!(D < range * range) || !(D > dmin * dmin)) continue;
    Lagged l;
    l.type = c.type;
    for (int k = 0; k < 4; k++) {
      l.tag[k] = c.tag[k];
      l.v[k] = c.v[k];
      for (int d = 0; d < 3; d++) l.xn[3 * k + d] = k < nv ? y[k][d] : 0.0;
    }
    l.pair = c.type == PT
        ? PeriSISSM::point_triangle_friction_pair(y[0], y[1], y[2], y[3], prm)
        : c.type == EE ? PeriSISSM::edge_edge_friction_pair(y[0], y[1], y[2], y[3], c.eps, prm)
                       : PeriSISSM::point_point_friction_pair(y[0], y[1], prm);
    if (l.pair.lambda > 0.0) lagged.push_back(l);
  }
  lagged_generation = generation;
}

/* ----------------------------------------------------------------------
   fix sissm starts a (sub-)step of length h at the current positions x^n (ghosts current): the
   friction of its iterates is lagged here
------------------------------------------------------------------------- */

void FixNosbContact::begin_step(double h, double c)
{
  in_step = 1;
  step_h = h;
  if (kappa_auto) {
    inertia_c = c;
    kappa = kappa_ip / inertia_c;
    prev_min_gap = HUGE_VAL;
  }
  if (mu == 0.0) return;
  if (stale) build_candidates();
  build_lagged();
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
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  const double *vfrac = atom->vfrac;
  const double dt = update->dt;
  const PeriSISSM::FrictionParameters prm{mu, epsv * (implicit ? step_h : dt)};
  nfriction = 0;
  friction_work = 0.0;
  for (const Lagged &p : lagged) {
    const int nv = p.pair.count;
    PeriSISSM::Vector12d u = PeriSISSM::Vector12d::Zero();
    for (int k = 0; k < nv; k++)
      for (int d = 0; d < 3; d++)
        u[3 * k + d] = implicit ? x[p.v[k]][d] - p.xn[3 * k + d] : v[p.v[k]][d] * dt;
    int own[4];
    if (owned_vertices(atom, p.tag, nv, own)) {
      const double y = PeriSISSM::tangential_displacement(p.pair, u).norm();
      nfriction++;
      friction_work += mu * p.pair.lambda * PeriSISSM::friction_f1(y, prm.slip_length) * y;
    }
    const PeriSISSM::Vector12d g = PeriSISSM::friction_gradient(p.pair, u, prm);
    for (int k = 0; k < nv; k++) {
      const int i = own[k];
      if (i < 0) continue;
      for (int d = 0; d < 3; d++) f[i][d] -= g[3 * k + d] / vfrac[i];
    }
  }
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
  if (comm->me != 0) return;
  const double list[4] = {3.0, kappa_ip, bbox_diagonal, mean_mass};
  const int size = 4 * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), 4, fp);
}

void FixNosbContact::restart(char *buf)
{
  const auto *list = (const double *) buf;
  if (!kappa_auto || list[0] != 3.0) return;
  bbox_diagonal = list[2];
  mean_mass = list[3];
  kappa_ip_min =
      PeriSISSM::initial_barrier_stiffness(bbox_diagonal, dhat, mean_mass, 0.0, 0.0, kappa_ip_max);
  kappa_ip = std::min(kappa_ip_max, std::max(kappa_ip_min, list[1]));
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

/* ----------------------------------------------------------------------
   CollisionLimit (collision_limit.h): fix sissm's path of admissible positions.

   The reference is the positions of the last admissible state, owned and ghost (the indices
   of the ghosts do not change inside a step: no neighbor list build). A move from it to the
   current positions is checked pair by pair with additive CCD (core contact/ccd.h: the
   fraction returned keeps the pair's gap above 0.1 of its gap at the reference, so it never
   reaches dmin on the straight move), over the candidates: a pair that is not a candidate was
   farther than dmin + dhat + skin apart at the list build and cannot come within dmin + dhat
   while no atom has moved skin/2 from there (the file's header), so the move is also limited
   to that reach. The fraction is the minimum over all pairs and ranks; the owned atoms of the
   integrator's group go back to it.
------------------------------------------------------------------------- */

void FixNosbContact::begin_path()
{
  const int nall = atom->nlocal + atom->nghost;
  if (nall > nxref) {
    nxref = atom->nmax;
    memory->grow(xref, nxref, 3, "nosb/contact:xref");
  }
  double **x = atom->x;
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) xref[i][d] = x[i][d];
  distance_valid = 0;
}

double FixNosbContact::limit_move(int groupbit)
{
  if (stale) build_candidates();
  double **x = atom->x;
  const int nlocal = atom->nlocal;

  // pairs: the largest fraction that no candidate pair contradicts
  double t_pairs = 1.0;
  PeriSISSM::CcdOptions opt;
  opt.dmin = dmin;
  for (std::size_t ic = 0; ic < candidates.size(); ic++) {
    const Candidate &c = candidates[ic];
    Vector3d y[4], dy[4];
    bool moved = false;
    for (int k = 0; k < c.nv(); k++) {
      const double *a = xref[c.v[k]], *b = x[c.v[k]];
      y[k] = Vector3d(a[0], a[1], a[2]);
      dy[k] = Vector3d(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
      moved = moved || dy[k].squaredNorm() > 0.0;
    }
    if (!moved) continue;
    if (distance_valid) {
      // the gap at the reference is known (the last evaluation was there, or a lower bound of
      // it): a pair whose points move less than 0.9 of it over [0, t_pairs] keeps 0.1 of it, as
      // ACCD would certify
      // (a lower bound that does not suffice is replaced by the distance: the same pairs are
      // skipped as with the distances, and the move is the same)
      double len[4];
      for (int k = 0; k < c.nv(); k++) len[k] = dy[k].norm();
      const double most = closing(c, len) * t_pairs;
      if (most <= (1.0 - opt.s) * (distance[ic] - dmin)) continue;
      if (!distance_exact[ic]) {
        distance[ic] = std::sqrt(distance2(c, y));
        distance_exact[ic] = 1;
        if (most <= (1.0 - opt.s) * (distance[ic] - dmin)) continue;
      }
    }
    // (a query that reaches ACCD's sub-step cap returns the last safe time: still conservative)
    opt.t_max = t_pairs;
    const double t = c.type == PT
        ? PeriSISSM::point_triangle_ccd(y[0], y[1], y[2], y[3], dy[0], dy[1], dy[2], dy[3], opt)
        : c.type == EE
        ? PeriSISSM::edge_edge_ccd(y[0], y[1], y[2], y[3], dy[0], dy[1], dy[2], dy[3], opt)
        : PeriSISSM::point_point_ccd(y[0], y[1], dy[0], dy[1], opt);
    t_pairs = std::min(t_pairs, t);
  }

  // reach: no atom of the group farther than skin/2 from the list build (exactly: the largest
  // t with |xref + t (x - xref) - xbuild| <= skin/2; the segment is inside the ball when both
  // ends are)
  const double R = 0.5 * neighbor->skin * (1.0 - 1.0e-9);    // inside check_motion()'s bound
  double t_reach = 1.0, far = 0.0;
  tagint who = MAXTAGINT;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & this->groupbit)) continue;
    double a2 = 0.0, ad = 0.0, d2 = 0.0, e2 = 0.0;
    for (int k = 0; k < 3; k++) {
      const double a = xref[i][k] - xbuild[i][k], d = x[i][k] - xref[i][k];
      a2 += a * a;
      ad += a * d;
      d2 += d * d;
      e2 += (a + d) * (a + d);
    }
    if (e2 <= R * R) continue;
    // |a + t d|^2 = R^2 for the root in [0, 1] (a2 <= R^2: the reference is admissible)
    const double disc = std::max(0.0, ad * ad - d2 * (a2 - R * R));
    const double t = std::max(0.0, (-ad + std::sqrt(disc)) / d2) * (1.0 - 1.0e-12);
    if (t < t_reach || (t == t_reach && atom->tag[i] < who)) {
      t_reach = t;
      who = atom->tag[i];
      far = std::sqrt(a2);
    }
  }

  double mine[2] = {t_pairs, t_reach}, all[2];
  MPI_Allreduce(mine, all, 2, MPI_DOUBLE, MPI_MIN, world);
  const double t = std::min(all[0], all[1]);
  reach_bound = all[1] < 1.0 && all[1] <= all[0];
  if (reach_bound) {
    // the atom that set the reach limit (smallest ID among the ranks that found it)
    const tagint mine_who = (t_reach == all[1]) ? who : MAXTAGINT;
    MPI_Allreduce(&mine_who, &reach_atom, 1, MPI_LMP_TAGINT, MPI_MIN, world);
    const double mine_far = (mine_who == reach_atom) ? far : 0.0;
    MPI_Allreduce(&mine_far, &reach_moved, 1, MPI_DOUBLE, MPI_MAX, world);
  }
  if (t < 1.0)
    for (int i = 0; i < nlocal; i++)
      if (atom->mask[i] & groupbit)
        for (int k = 0; k < 3; k++) x[i][k] = xref[i][k] + t * (x[i][k] - xref[i][k]);
  return t;
}

/* ----------------------------------------------------------------------
   an implicit step that ended where the contact candidates' reach cut it short
------------------------------------------------------------------------- */

void FixNosbContact::reach_error(const char *integrator)
{
  error->all(FLERR,
             "Fix nosb/contact {}: {} step {} needs atom {} to move farther than half the "
             "neighbor skin ({:.6g}) from where it was at the last neighbor list build (it was "
             "{:.6g} from there at the start of the move): the contact candidates cannot follow "
             "a step that far; use a larger neighbor skin (a step may move the atoms by 3/8 of "
             "it at least: the lists are built again after a step that moved an atom skin/8) or "
             "a smaller time step",
             id, integrator, update->ntimestep, reach_atom, 0.5 * neighbor->skin, reach_moved);
}

/* ----------------------------------------------------------------------
   at the end of an implicit step: a new neighbor list before the next step once an atom has
   moved skin/8 from the last build, so that every step may move the atoms by 3/8 of the skin
   at least (fix sissm builds it right after its step, before the forces of that step)
------------------------------------------------------------------------- */

bool FixNosbContact::rebuild_wanted()
{
  int farthest;
  const double most = moved_since_build(farthest);
  double all;
  MPI_Allreduce(&most, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  const double trigger = 0.125 * neighbor->skin;
  return all > trigger * trigger;
}

/* ----------------------------------------------------------------------
   the barrier's diagonal stiffness blocks of the owned vertices at the current positions:
   the 3x3 diagonal blocks of each active pair's Hessian projected to positive semi-definite,
   divided by the vertex's volume (the force is a density), added to block (xx yy zz xy xz yz)
------------------------------------------------------------------------- */

void FixNosbContact::add_blocks(double **block)
{
  double **x = atom->x;
  const double *vfrac = atom->vfrac;
  const PeriSISSM::BarrierParameters prm{kappa, dhat, dmin};
  const double range = dmin + dhat;
  for (std::size_t ic = 0; ic < candidates.size(); ic++) {
    const Candidate &c = candidates[ic];
    // the distance of the last force evaluation (these positions: fix sissm calls this right
    // after post_force)
    if (!(distance_valid && distance[ic] < range)) continue;
    Vector3d y[4];
    gather(c, x, y);
    PeriSISSM::Matrix12d H;
    if (c.type == PT)
      H = PeriSISSM::point_triangle_barrier_hessian(y[0], y[1], y[2], y[3], prm, true);
    else if (c.type == EE)
      H = PeriSISSM::edge_edge_barrier_hessian(y[0], y[1], y[2], y[3], c.eps, prm, true);
    else
      H.topLeftCorner<6, 6>() = PeriSISSM::point_point_barrier_hessian(y[0], y[1], prm, true);
    add_diagonal_blocks(H, c.nv(), c.own, vfrac, block);
  }

  // the friction's (positive semi-definite) blocks at the current slip of the step
  if (!(mu > 0.0) || !in_step || lagged_generation != generation) return;
  const PeriSISSM::FrictionParameters fprm{mu, epsv * step_h};
  for (const Lagged &p : lagged) {
    const int nv = p.pair.count;
    PeriSISSM::Vector12d u = PeriSISSM::Vector12d::Zero();
    for (int k = 0; k < nv; k++)
      for (int d = 0; d < 3; d++) u[3 * k + d] = x[p.v[k]][d] - p.xn[3 * k + d];
    int own[4];
    owned_vertices(atom, p.tag, nv, own);
    add_diagonal_blocks(PeriSISSM::friction_hessian(p.pair, u, fprm), nv, own, vfrac, block);
  }
}

/* ---------------------------------------------------------------------- */

double FixNosbContact::memory_usage()
{
  return (double) candidates.capacity() * sizeof(Candidate) +
      (double) lagged.capacity() * sizeof(Lagged) + 3.0 * (nxbuild + nxref) * sizeof(double);
}
