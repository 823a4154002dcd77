/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   pair_style peri/nosb, short-range contact: the candidate pairs from the neighbor list (the
   pairs that can come within contact range before the next neighbor list build; core
   peri/contact_candidates.h), the contact pass of the core (peri/contact.h) with what only
   LAMMPS knows (bonds by atom ID, energy and virial tallies), and, for steps that move the
   atoms many times between neighbor list builds, when the candidates are chosen again (the
   core's motion tracker, contact/motion_tracker.h, as fix nosb/contact uses it).
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"

#include "peri/contact.h"
#include "peri/contact_candidates.h"
#include "peri/model.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>

using namespace LAMMPS_NS;
using PeriSISSM::MotionTracker;

/* ----------------------------------------------------------------------
   is tag jtag an unbroken bond partner of owned atom i
------------------------------------------------------------------------- */

bool PairPeriNosb::bonded(int i, tagint jtag) const
{
  const tagint *p = family->partner[i];
  const int n = family->npartner[i];
  for (int b = 0; b < n; b++)
    if (p[b] == jtag) return true;
  return false;
}

/* ----------------------------------------------------------------------
   short-range contact between particles that are not bonded (never were, or whose bond
   broke), as the built-in PERI styles do for all pairs: a repulsive spring acts when
   r < d = min(0.9 |X_i - X_j|, 1.35 h), h = mean particle size V^(1/3), with stiffness
   kc = 15 * 18 K / (pi delta^4): force density on i kc V_j (d - r)/delta along x_i - x_j,
   energy 1/2 kc (V_i + V_j)/2 (d - r)^2 / delta per pair. Bonded pairs are left to the
   material model, so that an affine deformation gives exactly W(F) also under compression.
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class NosbContactPairs : public PeriSISSM::ContactPairs {
 public:
  explicit NosbContactPairs(PairPeriNosb *pair) : pair_(pair) {}
  bool bonded(int i, int j) const override { return pair_->bonded(i, pair_->atom->tag[j]); }
  void acting(int i, int j) override
  {
    const int *mask = pair_->atom->mask;
    if ((mask[i] ^ mask[j]) & pair_->contact_groupbit) pair_->contact_crossings++;
  }
  void tally(int i, int j, double energy, double fpair, double dx, double dy, double dz) override
  {
    pair_->ev_tally(i, j, pair_->atom->nlocal, pair_->force->newton_pair, energy, 0.0, fpair, dx,
                    dy, dz);
  }

 private:
  PairPeriNosb *pair_;
};
}    // namespace LAMMPS_NS

void PairPeriNosb::compute_contact(int /*eflag*/, int /*vflag*/)
{
  // candidates from the short list made at the last neighbor list build
  // (built here only if that did not happen, e.g. a compute without a run)

  if (!contact_list_current())
    build_contact_list(neighbor->skin);
  else if (follow_explicit)
    follow_motion_explicit();

  // with SISSM blocks: each pair's block into the rows that get its forces, owned and ghost
  // (added to the blocks by add_contact_blocks(), after the bond terms have set them)
  double *rows = nullptr;
  if (block_rows) {
    contact_blocks.assign(6 * (size_t) (atom->nlocal + atom->nghost), 0.0);
    rows = contact_blocks.data();
  }
  const PeriSISSM::Particles p = particles();
  PeriSISSM::ContactCandidates cand;
  cand.inum = shortlist.inum;
  cand.ilist = list->ilist;
  cand.first = shortlist.first.data();
  cand.neigh = shortlist.neigh.data();
  NosbContactPairs pairs(this);
  PeriSISSM::contact_pass(*model_, p, family->box, contact_reach(), cand, force->newton_pair != 0,
                          evflag != 0, pairs, rows);
}

/* ----------------------------------------------------------------------
   the contact blocks of the last compute_contact() added to the SISSM blocks of the owned atoms,
   ghost rows first folded into their owners under newton on (as fix sissm folds the forces);
   all ranks
------------------------------------------------------------------------- */

void PairPeriNosb::add_contact_blocks()
{
  if (force->newton_pair) comm->reverse_comm(this);
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    for (int m = 0; m < 6; m++) block_rows[i][m] += contact_blocks[6 * i + m];
}

int PairPeriNosb::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < 6; k++) buf[m++] = contact_blocks[6 * i + k];
  return m;
}

void PairPeriNosb::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 6; k++) contact_blocks[6 * list[i] + k] += buf[m++];
}

/* ----------------------------------------------------------------------
   whether the contact candidates were chosen from the current neighbor list (the same answer on
   every rank: all build their lists at the same step)
------------------------------------------------------------------------- */

bool PairPeriNosb::contact_list_current() const
{
  return shortlist.chosen() && contact_lastcall == neighbor->lastcall;
}

/* ----------------------------------------------------------------------
   called by fix nosb/family right after every neighbor list build: the hinge list of the
   bending term is stale (atoms migrated or were sorted), the contact candidates are chosen again
------------------------------------------------------------------------- */

void PairPeriNosb::neighbor_rebuilt()
{
  hinges_stale = 1;
  if (!any_contact || !list) return;
  const double skin = neighbor->skin;
  follow_explicit =
      !track_motion && MotionTracker::followable(contact_reach(), contact_horizon(), skin);
  if (track_motion || follow_explicit) at_build.record(atom->x, atom->nlocal + atom->nghost);
  // followed (fix sissm's iterates, or explicit runs): the narrow margin, chosen again as the
  // atoms move; otherwise the whole skin, which covers all motion until the next build
  build_contact_list(track_motion || follow_explicit ? MotionTracker::follow_margin(skin) : skin);
}

/* ----------------------------------------------------------------------
   explicit runs: the candidates, chosen with the margin m = skin/4 instead of the skin, stay
   complete while no atom has moved m/2 from where they were chosen; beyond, they are chosen
   again with the margin MotionTracker::reachable_margin() allows (LAMMPS keeps max|x - x_n|
   below skin/2 by its own rebuilds, and follow_explicit is set only where
   MotionTracker::followable()). Owned and ghost atoms alike (every candidate pair has both on
   this rank; ghost indices do not change between neighbor list builds), so each rank decides
   alone. About six times fewer candidates than with the whole skin as margin on a lattice with
   horizon 3a and skin 2a.
------------------------------------------------------------------------- */

void PairPeriNosb::follow_motion_explicit()
{
  const int nall = atom->nlocal + atom->nghost;
  if (!at_choice.moved_at_least2(atom->x, nall, 0.25 * contact_margin * contact_margin)) return;
  int farthest;
  const double moved = at_build.largest_move2(atom->x, nall, nullptr, 0, farthest);
  build_contact_list(MotionTracker::reachable_margin(contact_reach(), sqrt(moved),
                                                     contact_horizon(), neighbor->skin));
}

/* ----------------------------------------------------------------------
   largest distance at which two particles touch: 1.35 x the largest particle size
------------------------------------------------------------------------- */

double PairPeriNosb::contact_reach() const
{
  return 1.35 * hmax;
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::track_contact_motion(int flag)
{
  track_motion = flag && any_contact;
  follow_explicit = 0;    // decided again at the next neighbor list build
  if (!track_motion) {
    at_build.clear();
    at_choice.clear();
  }
}

/* ----------------------------------------------------------------------
   keep the contact candidates complete while an implicit step moves the atoms (see the
   header). Candidates chosen at positions x_c with a margin m (all pairs of the neighbor list
   within reach + m) cover every pair within contact reach while no atom has moved m/2 from
   x_c. Beyond that they are chosen again, at the current positions, with the margin skin/4;
   the neighbor list holds the pairs within horizon + skin of its build (positions x_n), so the
   new choice is complete only while MotionTracker::reachable() (contact_reachable()). An
   iterate farther away is evaluated with the candidates it has and reported as incomplete
   (-1): the solver does not accept it as converged, and the step's end (contact_end_of_step())
   refuses a result that is that far. One global max per call.
------------------------------------------------------------------------- */

int PairPeriNosb::contact_follow_motion()
{
  // every rank takes the same branches up to the global max of motion_since()
  if (!track_motion || !list || !contact_list_current()) return 0;
  double moved;
  tagint worst;
  const double dc = motion_since(at_choice, &moved, &worst);
  if (!contact_reachable(moved)) return -1;
  if (dc < 0.5 * contact_margin) return 0;
  build_contact_list(MotionTracker::follow_margin(neighbor->skin));
  return 1;
}

/* ----------------------------------------------------------------------
   whether contact candidates chosen from the neighbor list with the margin skin/4 are complete
   after atoms moved by up to `moved` from the neighbor list build (false if not finite)
------------------------------------------------------------------------- */

bool PairPeriNosb::contact_reachable(double moved) const
{
  const double skin = neighbor->skin;
  return MotionTracker::reachable(contact_reach(), MotionTracker::follow_margin(skin), moved,
                                  contact_horizon(), skin);
}

/* ----------------------------------------------------------------------
   the smallest horizon among the type pairs with contact (it bounds the neighbor list's reach)
------------------------------------------------------------------------- */

double PairPeriNosb::contact_horizon() const
{
  double hz = DBL_MAX;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (contactflag[i][j]) hz = std::min(hz, cut[i][j]);
  return hz;
}

/* ----------------------------------------------------------------------
   at the end of an implicit step (all ranks): an error when the step moved an atom farther
   from the last neighbor list build than the contact candidates can follow (its contact
   forces could not be complete); true when it moved one more than skin/8, so that the
   integrator asks for a neighbor list build before the next step. A step therefore starts
   with max|x - x_n| <= skin/8 and may move atoms by (horizon - reach)/2 + skin/4.
------------------------------------------------------------------------- */

bool PairPeriNosb::contact_end_of_step(const std::string &cause)
{
  if (!track_motion || !list) return false;
  double moved;
  tagint worst;
  motion_since(at_build, &moved, &worst);
  const double skin = neighbor->skin;
  if (!contact_reachable(moved)) {
    // name the atom that moved farthest (the smallest ID among equals, on any rank count)
    tagint idall;
    MPI_Allreduce(&worst, &idall, 1, MPI_LMP_TAGINT, MPI_MIN, world);
    const double hz = contact_horizon();
    error->all(FLERR,
               "Pair peri/nosb: the implicit step {} moved atom {} by {:.4g} from where it was "
               "at the last neighbor list build, farther than short-range contact can follow "
               "inside one step with neighbor skin {:.4g} (a step may move atoms by (horizon - "
               "1.35 x particle size) / 2 + skin / 4 = {:.4g}){}; use a smaller time step, a "
               "neighbor skin of at least {:.4g}, or turn contact off for these types "
               "(pair_coeff ... contact no)",
               update->ntimestep, idall, moved, skin, 0.5 * (hz - contact_reach()) + 0.25 * skin,
               cause.empty() ? "" : "; " + cause, 2.0 * (2.0 * moved + contact_reach() - hz));
  }
  return moved > MotionTracker::rebuild_distance(skin);
}

/* ----------------------------------------------------------------------
   largest distance of an owned atom from its position in `since` (all ranks); also the largest
   distance from the last neighbor list build and (in *worst) the ID of the atom that moved
   farthest from it on this rank if that is the global largest, else MAXTAGINT
------------------------------------------------------------------------- */

double PairPeriNosb::motion_since(const MotionTracker &since, double *moved, tagint *worst)
{
  const int nlocal = atom->nlocal;
  int ifar, iworst;
  double local[2], all[2];
  local[0] = since.largest_move2(atom->x, nlocal, nullptr, 0, ifar);
  local[1] = at_build.largest_move2(atom->x, nlocal, nullptr, 0, iworst);
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  *moved = sqrt(all[1]);
  *worst = (iworst >= 0 && local[1] == all[1]) ? atom->tag[iworst] : MAXTAGINT;
  return sqrt(all[0]);
}

/* ----------------------------------------------------------------------
   pairs of the neighbor list closer than the contact range + margin (the skin at a neighbor
   list build): the pair neighbor list reaches horizon + skin, but only these pairs can come
   within the contact range before the next neighbor list build (each atom moves less than
   skin/2 from where it was at the build)
------------------------------------------------------------------------- */

void PairPeriNosb::build_contact_list(double margin)
{
  contact_margin = margin;
  shortlist.choose(list->inum, list->ilist, list->numneigh, list->firstneigh, NEIGHMASK, atom->x,
                   contact_reach() + margin);
  contact_lastcall = neighbor->lastcall;
  if (track_motion || follow_explicit) at_choice.record(atom->x, atom->nlocal + atom->nghost);
}
