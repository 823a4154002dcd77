/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm, the forces of the other fixes that act in post_force: which are
   re-evaluated at every iterate and which are lagged (solvers/external_forces.h), and the
   lagged force of a step.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "collision_limit.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "modify.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ----------------------------------------------------------------------
   the roles of the other fixes and the mode of the step (solvers/external_forces.h), from what
   LAMMPS tells about each fix, and what is logged when it changes
------------------------------------------------------------------------- */

void FixSissm::choose_external()
{
  const auto &fixes = modify->get_fix_list();
  std::vector<PeriSISSM::ExternalFix> about;
  for (Fix *f : fixes) {
    auto *limit = dynamic_cast<CollisionLimit *>(f);
    PeriSISSM::ExternalFix what;
    what.id = f->id;
    what.style = f->style;
    what.post_force = (modify->get_fix_mask(f) & POST_FORCE) != 0;
    what.integrator = f->time_integrate != 0;
    what.dynamic_group = strcmp(f->style, "GROUP") == 0;
    what.reservoir = f->ecouple_flag != 0;
    // a contact of fix sissm's steps (collision_limit.h) keeps its stiffness in restart files
    // but changes it only where fix sissm tells it to: it is no state of a step
    what.keeps_state = f->restart_global != 0 && !limit;
    what.potential = f->energy_global_flag != 0 || f->virial_global_flag != 0;
    what.adapts_stiffness = limit && limit->adapts_stiffness();
    what.limits_moves = limit && limit->limits_moves();
    about.push_back(what);
  }
  const PeriSISSM::ExternalChoice choice =
      PeriSISSM::choose_external(about, opt.lagged, opt.implicit_external, id);
  if (!choice.problem.empty()) error->all(FLERR, choice.problem);
  external_mode = choice.mode;
  if (choice.note != external_note && comm->me == 0 && !choice.note.empty())
    utils::logmesg(lmp, choice.note);
  external_note = choice.note;
  if (!choice.refusal.empty()) error->all(FLERR, choice.refusal);

  // the contacts among the fixes of every iterate: their lagged friction is built at the start
  // of each (sub-)step
  implicit_fixes.clear();
  limiters.clear();
  contacts.clear();
  adapting.clear();
  for (int k : choice.implicit) {
    implicit_fixes.push_back(fixes[k]);
    auto *limit = dynamic_cast<CollisionLimit *>(fixes[k]);
    if (!limit || external_mode == PeriSISSM::ExternalMode::lagged) continue;
    contacts.push_back(limit);
    if (limit->adapts_stiffness()) adapting.push_back(limit);
    if (limit->limits_moves()) limiters.push_back(limit);
  }
}

/* ----------------------------------------------------------------------
   external lagged: pair peri/nosb has just computed its force density (and nothing else has
   been added yet, other pair-like contributions do not exist with atom_style peri): keep it,
   for owned and ghost atoms, so that fext = f - fint can be formed at the start of the next
   step
------------------------------------------------------------------------- */

void FixSissm::capture_internal_force()
{
  if (external_mode != PeriSISSM::ExternalMode::lagged &&
      external_mode != PeriSISSM::ExternalMode::mixed)
    return;
  grow();
  double **f = atom->f;
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++)
    for (int k = 0; k < 3; k++) fint[i][k] = f[i][k];
}

void FixSissm::setup_pre_reverse(int, int)
{
  capture_internal_force();
}

void FixSissm::pre_reverse(int, int)
{
  capture_internal_force();
}

/* ---------------------------------------------------------------------- */

int FixSissm::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < 3; k++) buf[m++] = fint[i][k];
  return m;
}

void FixSissm::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++)
    for (int c = 0; c < 3; c++) fint[list[k]][c] += buf[m++];
}

/* ----------------------------------------------------------------------
   at the start of a step (positions y^n, velocities v^n), the force of the lagged fixes: what
   the evaluation that ended the previous step added beyond the pair force (f - fint); external
   mixed: minus what the re-evaluated fixes give at y^n and v^n (all of them add forces
   independent of the force so far, solvers/external_forces.h)
------------------------------------------------------------------------- */

void FixSissm::lagged_external_force()
{
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) flagged[i][k] = (mask[i] & groupbit) ? f[i][k] - fint[i][k] : 0.0;
  if (external_mode != PeriSISSM::ExternalMode::mixed) return;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  for (Fix *fix : implicit_fixes) fix->post_force(0);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit)
      for (int k = 0; k < 3; k++) flagged[i][k] -= f[i][k];
}
