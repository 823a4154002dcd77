/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   pair_style peri/nosb, short-range contact: the core's contact pass (peri/contact.h) with what
   only LAMMPS knows (bonds by atom ID, tallies, the group crossings), over the candidates the
   core's ContactFollower (peri/contact_candidates.h) chooses from the neighbor list and chooses
   again as the atoms move.
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
#include <cmath>
#include <string>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   short-range contact between particles that are not bonded (core peri/contact.h): bonded when
   j's ID is among the unbroken partners of owned atom i
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class NosbContactPairs : public PeriSISSM::ContactPairs {
 public:
  explicit NosbContactPairs(PairPeriNosb *pair) : pair_(pair) {}
  bool bonded(int i, int j) const override
  {
    const tagint *p = pair_->family->partner[i], *end = p + pair_->family->npartner[i];
    return std::find(p, end, pair_->atom->tag[j]) != end;
  }
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

  double margin;
  if (!follower.current(neighbor->lastcall))
    choose_contacts(neighbor->skin);
  else if (follower.explicit_rechoice(atom->x, atom->nlocal + atom->nghost, neighbor->skin, margin))
    choose_contacts(margin);

  // with SISSM blocks: each pair's block into the rows that get its forces, owned and ghost
  // (added to the blocks by add_contact_blocks(), after the bond terms have set them)
  double *rows = nullptr;
  if (block_rows) {
    contact_blocks.assign(6 * (size_t) (atom->nlocal + atom->nghost), 0.0);
    rows = contact_blocks.data();
  }
  NosbContactPairs pairs(this);
  PeriSISSM::contact_pass(*model_, particles(), family->box, follower.reach,
                          follower.candidates(list->ilist), force->newton_pair != 0, evflag != 0,
                          pairs, rows);
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
  return PeriSISSM::pack_reverse_rows(contact_blocks.data(), 6, n, first, buf);
}

void PairPeriNosb::unpack_reverse_comm(int n, int *list, double *buf)
{
  PeriSISSM::add_reverse_rows(contact_blocks.data(), 6, n, list, buf);
}

/* ----------------------------------------------------------------------
   called by fix nosb/family right after every neighbor list build: the hinge list of the bending
   term is stale (atoms migrated or were sorted), the contact candidates are chosen again
------------------------------------------------------------------------- */

void PairPeriNosb::neighbor_rebuilt()
{
  hinges_stale = 1;
  if (!any_contact || !list) return;
  choose_contacts(follower.margin_at_build(atom->x, atom->nlocal + atom->nghost, neighbor->skin));
}

/* ----------------------------------------------------------------------
   pairs of the neighbor list closer than the contact range + margin (core ContactFollower)
------------------------------------------------------------------------- */

void PairPeriNosb::choose_contacts(double margin)
{
  follower.choose(list->inum, list->ilist, list->numneigh, list->firstneigh, NEIGHMASK, atom->x,
                  atom->nlocal + atom->nghost, margin, neighbor->lastcall);
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::track_contact_motion(int flag)
{
  follower.track(flag && any_contact);
}

/* ----------------------------------------------------------------------
   keep the contact candidates complete while an implicit step moves the atoms: chosen again at
   the current positions when an atom moved half the margin from the choice; an iterate farther
   from the neighbor list build than the choice can follow is evaluated with the candidates it
   has and reported as incomplete (-1): the solver does not accept it as converged, and
   contact_end_of_step() refuses a result that is that far. One global max per call.
------------------------------------------------------------------------- */

int PairPeriNosb::contact_follow_motion()
{
  // every rank takes the same branches up to the global max of motion_since()
  if (!follower.tracked() || !list || !follower.current(neighbor->lastcall)) return 0;
  double moved;
  tagint worst;
  const double dc = motion_since(&moved, &worst);
  const int chosen_again = follower.after_motion(dc, moved, neighbor->skin);
  if (chosen_again > 0) choose_contacts(PeriSISSM::MotionTracker::follow_margin(neighbor->skin));
  return chosen_again;
}

/* ----------------------------------------------------------------------
   at the end of an implicit step (all ranks): an error when the step moved an atom farther
   from the last neighbor list build than the candidates can follow; true when it moved one more
   than skin/8, so that the integrator asks for a neighbor list build before the next step
------------------------------------------------------------------------- */

bool PairPeriNosb::contact_end_of_step(const std::string &cause)
{
  if (!follower.tracked() || !list) return false;
  double moved;
  tagint worst;
  motion_since(&moved, &worst);
  if (!follower.reachable(moved, neighbor->skin)) {
    // name the atom that moved farthest (the smallest ID among equals, on any rank count)
    tagint idall;
    MPI_Allreduce(&worst, &idall, 1, MPI_LMP_TAGINT, MPI_MIN, world);
    error->all(FLERR, follower.too_far(update->ntimestep, idall, moved, neighbor->skin, cause));
  }
  return moved > PeriSISSM::MotionTracker::rebuild_distance(neighbor->skin);
}

/* ----------------------------------------------------------------------
   before an implicit (sub-)step (all ranks): whether it should start from a new neighbor list
   (core ContactFollower::build_wanted())
------------------------------------------------------------------------- */

int PairPeriNosb::contact_build_wanted()
{
  if (!follower.tracked() || !list || !follower.current(neighbor->lastcall)) return 0;
  double moved;
  tagint worst;
  motion_since(&moved, &worst);
  return follower.build_wanted(moved, neighbor->skin);
}

/* ----------------------------------------------------------------------
   largest distance of an owned atom from the choice of the candidates (all ranks); also the
   largest distance from the last neighbor list build and (in *worst) the ID of the atom that
   moved farthest from it on this rank if that is the global largest, else MAXTAGINT
------------------------------------------------------------------------- */

double PairPeriNosb::motion_since(double *moved, tagint *worst)
{
  int iworst;
  double local[2], all[2];
  follower.local_moves2(atom->x, atom->nlocal, local, iworst);
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  *moved = sqrt(all[1]);
  *worst = (iworst >= 0 && local[1] == all[1]) ? atom->tag[iworst] : MAXTAGINT;
  return sqrt(all[0]);
}
