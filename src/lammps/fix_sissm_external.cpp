/* ----------------------------------------------------------------------
   PERI-SISSM: fix sissm, the forces of the other fixes (those that add forces after the pair
   style, in post_force): which are re-evaluated at every iterate and which are lagged (the
   rule of src/core/solvers/external_forces.h applied to what LAMMPS tells about each fix, and
   the keywords external and lagged), and the lagged force of a step.
------------------------------------------------------------------------- */

#include "fix_sissm.h"

#include "collision_limit.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "modify.h"

#include <algorithm>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ----------------------------------------------------------------------
   the roles of the fixes that act in post_force, in the order Modify::post_force calls them
   (the dynamic-group fixes, style GROUP, first), the mode of the step, and what is logged
   when it changes. Contact that limits the moves (collision-free steps) or adapts its
   stiffness must be part of every iterate.
------------------------------------------------------------------------- */

void FixSissm::choose_external()
{
  for (const std::string &name : opt.lagged) {
    Fix *f = modify->get_fix_by_id(name);
    if (!f) error->all(FLERR, "Fix sissm {} lagged: no fix with ID {}", id, name);
    if (!(modify->get_fix_mask(f) & POST_FORCE))
      error->all(FLERR, "Fix sissm {} lagged: fix {} ({}) adds no force after the pair style", id,
                 name, f->style);
  }
  implicit_fixes.clear();
  std::vector<PeriSISSM::ExternalRole> roles;
  std::string lagged_names, rewriting_names;
  const auto &fixes = modify->get_fix_list();
  for (int pass = 0; pass < 2; pass++) {
    for (Fix *f : fixes) {
      if (f == this || !(modify->get_fix_mask(f) & POST_FORCE)) continue;
      const bool dynamic_group = strcmp(f->style, "GROUP") == 0;
      if (dynamic_group != (pass == 0)) continue;
      PeriSISSM::ExternalFix what;
      what.integrator = f->time_integrate != 0;
      what.dynamic_group = dynamic_group;
      what.reservoir = f->ecouple_flag != 0;
      // a contact of fix sissm's steps (collision_limit.h) keeps its stiffness in restart
      // files but changes it only where fix sissm tells it to: it is no state of a step
      what.keeps_state = f->restart_global != 0 && !dynamic_cast<CollisionLimit *>(f);
      what.potential = f->energy_global_flag != 0 || f->virial_global_flag != 0;
      what.named_lagged =
          std::find(opt.lagged.begin(), opt.lagged.end(), f->id) != opt.lagged.end();
      const PeriSISSM::ExternalRole role = PeriSISSM::external_role(what);
      roles.push_back(role);
      const std::string name = fmt::format("{} ({})", f->id, f->style);
      if (role == PeriSISSM::ExternalRole::lagged) {
        lagged_names += (lagged_names.empty() ? "" : ", ") + name;
        continue;
      }
      if (role == PeriSISSM::ExternalRole::may_rewrite)
        rewriting_names += (rewriting_names.empty() ? "" : ", ") + name;
      implicit_fixes.push_back(f);
    }
  }
  external_mode = PeriSISSM::external_mode(roles, opt.implicit_external);

  std::string note;
  if (external_mode == PeriSISSM::ExternalMode::mixed)
    note = fmt::format("Fix sissm {}: fix {} may hold state or random numbers (an integrator, a "
                       "dynamic group, a thermostat, a fix with restart state, or named by "
                       "keyword lagged) and must act once per step: its force is lagged (taken "
                       "at the start of each step); the other fixes' forces are implicit\n",
                       id, lagged_names);
  else if (external_mode == PeriSISSM::ExternalMode::lagged && opt.implicit_external)
    note = fmt::format("Fix sissm {}: fix {} may hold state or random numbers (an integrator, a "
                       "dynamic group, a thermostat, a fix with restart state, or named by "
                       "keyword lagged) and must act once per step, and fix {} declares no "
                       "potential, so it may rewrite forces (as setforce does): the forces of "
                       "all other fixes are lagged (taken at the start of each step, as with "
                       "'external lagged')\n",
                       id, lagged_names, rewriting_names);
  if (note != external_note && comm->me == 0 && !note.empty()) utils::logmesg(lmp, note);
  external_note = note;

  // contact that limits the moves (collision-free steps) must be part of every iterate
  limiters.clear();
  contacts.clear();
  adapting.clear();
  for (Fix *f : fixes) {
    auto *limit = dynamic_cast<CollisionLimit *>(f);
    if (!limit) continue;
    const bool implicit = external_mode != PeriSISSM::ExternalMode::lagged &&
        std::find(implicit_fixes.begin(), implicit_fixes.end(), f) != implicit_fixes.end();
    // its lagged friction is built at the start of each (sub-)step when it is an iterate's force
    if (implicit) contacts.push_back(limit);
    // a contact that needs every iterate's force, while the other fixes' forces are lagged
    auto refuse_lagged = [&](const char *needs, const char *remedy) {
      error->all(FLERR,
                 "Fix sissm {}: fix {} ({}) {}, so its force must be re-evaluated at every "
                 "iterate, but the forces of the other fixes are lagged here ({}): remove that, "
                 "or {}",
                 id, f->id, f->style, needs,
                 opt.implicit_external ? "a fix that may rewrite forces is present next to a "
                                         "lagged one; hold atoms by leaving them out of fix "
                                         "sissm's group instead"
                                       : "keyword external lagged",
                 remedy);
    };
    if (limit->adapts_stiffness()) {
      if (!implicit)
        refuse_lagged("adapts its stiffness to the implicit step (kappa auto)",
                      "give kappa as a number");
      adapting.push_back(limit);
    }
    if (!limit->limits_moves()) continue;
    if (!implicit)
      refuse_lagged("makes the implicit step collision-free",
                    "turn the collision check off (ccd no)");
    limiters.push_back(limit);
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
  for (int i = 0; i < nall; i++) {
    fint[i][0] = f[i][0];
    fint[i][1] = f[i][1];
    fint[i][2] = f[i][2];
  }
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
  for (int i = first; i < first + n; i++) {
    buf[m++] = fint[i][0];
    buf[m++] = fint[i][1];
    buf[m++] = fint[i][2];
  }
  return m;
}

void FixSissm::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    fint[j][0] += buf[m++];
    fint[j][1] += buf[m++];
    fint[j][2] += buf[m++];
  }
}

/* ----------------------------------------------------------------------
   external mixed, at the start of a step (positions y^n, velocities v^n): the force of the
   lagged fixes is what the evaluation that ended the previous step added beyond the pair
   force (f - fint, at y^n and v^n) minus what the re-evaluated fixes give at y^n and v^n
   (all of them add forces independent of the force so far, solvers/external_forces.h)
------------------------------------------------------------------------- */

void FixSissm::lagged_external_force()
{
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) flagged[i][k] = (mask[i] & groupbit) ? f[i][k] - fint[i][k] : 0.0;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  for (Fix *fix : implicit_fixes) fix->post_force(0);
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit)
      for (int k = 0; k < 3; k++) flagged[i][k] -= f[i][k];
}
