/* PERI-SISSM core: the arguments of the fix nosb/contact command.

     fix ID group nosb/contact dhat D [dmin d] [kappa k|auto] [friction mu] [epsv v] [ccd yes|no]

   dhat and kappa are required, each keyword may come in any order (a repeated one counts last).
   Numbers and yes/no are converted by the caller's functions (LAMMPS parses them), in the order
   of the arguments. epsv defaults to IPC's 1e-3 m/s in the deck's units, which lj units cannot
   convert: there it must be given when there is friction. An error is thrown as
   std::invalid_argument with the message "Illegal fix nosb/contact command: ...", naming the
   keyword and the value.

   At every run's init the options are checked against the run (check_contact_run()): the
   group must hold mesh edges or volumetric particles, the ghost cutoff must cover the
   candidates' range (CandidateRange, candidates.h) and kappa auto needs fix sissm; particles
   without a model of bond partners, and ccd no under fix sissm, are warned about once.
*/
#ifndef PERISISSM_CONTACT_CONTACT_OPTIONS_H
#define PERISISSM_CONTACT_CONTACT_OPTIONS_H

#include "contact/candidates.h"

#include <functional>
#include <string>
#include <vector>

namespace PeriSISSM {

struct ContactOptions {
  double dhat = -1.0;         // barrier thickness (> 0)
  double dmin = 0.0;          // offset of the barrier (>= 0)
  double kappa = -1.0;        // stiffness (> 0; -1 with kappa auto)
  bool kappa_auto = false;    // kappa auto: IPC's adaptive stiffness
  double mu = 0.0;            // friction coefficient (0: no friction)
  double epsv = -1.0;         // slip speed below which friction is smoothed (> 0)
  bool ccd = true;            // fix sissm limits its moves (continuous collision detection)
};

// What the deck's units say about the default slip speed: lj units (no metre), else the values
// of 1 A and 1 fs in them
struct ContactUnits {
  bool lj = false;
  double angstrom = 1.0;
  double femtosecond = 1.0;
};

// Inputs: args (the arguments after "fix ID group nosb/contact"); number(text) -> a number,
// logical(text) -> yes/no (both throw or stop on text that is neither); the units.
// Outputs: the options, epsv set. Throws std::invalid_argument on a missing, unknown or invalid
// argument (dhat, kappa and epsv must be > 0, dmin and friction >= 0, all finite).
ContactOptions parse_contact_options(const std::vector<std::string> &args,
                                     const std::function<double(const std::string &)> &number,
                                     const std::function<bool(const std::string &)> &logical,
                                     const ContactUnits &units);

// The ghost cutoff a run will have (LAMMPS's Comm::get_comm_cutoff(), known only after the
// fixes' init): the larger of the user's (comm_modify cutoff) and, for every pair of types with
// a cutoff, that cutoff + skin. cutsq: the squared pair cutoffs, 1-based up to ntypes (nullptr:
// no pair style).
double run_ghost_cutoff(double user, const double *const *cutsq, int ntypes, double skin);

// What a run's init found (the same on all ranks), and which warnings were said
struct ContactRun {
  std::string id, group;           // the fix's ID and its group's name
  long long mesh_vertices = 0;     // the group's mesh vertices (all ranks)
  long long particles = 0;         // the group's volumetric particles (all ranks)
  double edge0 = 0.0;              // the longest mesh edge (0: none)
  double skin = 0.0;               // the neighbor skin
  double ghost_cutoff = 0.0;       // the ghost cutoff the run will have
  bool partners = false;           // a model of bond partners (pair peri/nosb)
  bool sissm = false;              // a fix sissm integrates
  bool warned_families = false;    // the no-partners warning was said (in this or an earlier run)
  bool warned_sissm = false;       // the ccd-no warning was said (in this or an earlier run)
};

// A message of check_contact_run(): an error or a warning, "Fix nosb/contact ID: ..."
struct ContactRunMessage {
  bool error;
  std::string text;
};

// The messages for a run with the options, in the order they are to be given: warnings (each
// once: those said are marked in run) up to the first error, which ends the list. The ghost
// cutoff is checked against CandidateRange(opt.dmin, opt.dhat, run.edge0, run.skin).
std::vector<ContactRunMessage> check_contact_run(const ContactOptions &opt, ContactRun &run);

}    // namespace PeriSISSM

#endif
