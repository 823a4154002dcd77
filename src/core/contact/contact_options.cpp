/* PERI-SISSM core: the arguments of the fix nosb/contact command (see contact_options.h). */
#include "contact/contact_options.h"

#include "contact/friction_potential.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace PeriSISSM {

namespace {

  const char *const kUsage = "fix ID group nosb/contact dhat D [dmin d] [kappa k|auto] "
                             "[friction mu] [epsv v] [ccd yes|no]";

  [[noreturn]] void illegal(const std::string &what)
  {
    throw std::invalid_argument("Illegal fix nosb/contact command: " + what);
  }

}    // namespace

ContactOptions parse_contact_options(const std::vector<std::string> &args,
                                     const std::function<double(const std::string &)> &number,
                                     const std::function<bool(const std::string &)> &logical,
                                     const ContactUnits &units)
{
  ContactOptions opt;
  auto positive = [&](const std::string &text, const char *what, bool zero_ok) {
    const double v = number(text);
    if (!std::isfinite(v) || v < 0.0 || (!zero_ok && v == 0.0))
      illegal(std::string(what) + " must be " + (zero_ok ? ">=" : ">") + " 0, got '" + text + "'");
    return v;
  };
  const int narg = (int) args.size();
  for (int iarg = 0; iarg < narg; iarg += 2) {
    const std::string &key = args[iarg];
    if (key != "dhat" && key != "dmin" && key != "kappa" && key != "ccd" && key != "friction" &&
        key != "epsv")
      illegal("unknown keyword '" + key + "' (" + kUsage + ")");
    if (iarg + 2 > narg)
      throw std::invalid_argument("Illegal fix nosb/contact " + key +
                                  " command: missing argument(s)");
    const std::string &val = args[iarg + 1];
    if (key == "dhat")
      opt.dhat = positive(val, "dhat", false);
    else if (key == "dmin")
      opt.dmin = positive(val, "dmin", true);
    else if (key == "ccd")
      opt.ccd = logical(val);
    else if (key == "friction")
      opt.mu = positive(val, "friction mu", true);
    else if (key == "epsv")
      opt.epsv = positive(val, "epsv", false);
    else if (val == "auto") {
      opt.kappa_auto = true;
      opt.kappa = -1.0;
    } else {
      opt.kappa_auto = false;
      opt.kappa = positive(val, "kappa", false);
    }
  }
  if (opt.dhat < 0.0) illegal(std::string("keyword dhat is required (") + kUsage + ")");
  if (opt.epsv < 0.0) {
    if (opt.mu > 0.0 && units.lj)
      illegal("with friction in lj units give the slip speed epsv (velocity units; IPC's "
              "default is 1e-3 m/s, which lj units cannot convert)");
    opt.epsv = default_slip_speed(units.angstrom, units.femtosecond);
  }
  if (opt.kappa < 0.0 && !opt.kappa_auto)
    illegal(std::string("keyword kappa is required (a number, or auto under fix sissm) (") +
            kUsage + ")");
  return opt;
}

double run_ghost_cutoff(double user, const double *const *cutsq, int ntypes, double skin)
{
  double cut = user;
  if (cutsq)
    for (int i = 1; i <= ntypes; i++)
      for (int j = 1; j <= ntypes; j++)
        if (cutsq[i][j] > 0.0) cut = std::max(cut, std::sqrt(cutsq[i][j]) + skin);
  return cut;
}

std::vector<ContactRunMessage> check_contact_run(const ContactOptions &opt, ContactRun &run)
{
  std::vector<ContactRunMessage> said;
  const std::string fix = "Fix nosb/contact " + run.id + ": ";
  // true when the message is an error (the list ends there)
  auto say = [&](bool error, const std::string &text) {
    said.push_back({error, fix + text});
    return error;
  };
  if (run.mesh_vertices + run.particles == 0 &&
      say(true,
          "group " + run.group +
              " holds no atom: the contact acts between the triangles of meshes read with "
              "read_mesh and between volumetric particles"))
    return said;
  if (run.particles && !run.partners && !run.warned_families) {
    say(false,
        "no pair_style peri/nosb, so no bond families: every two volumetric particles of group " +
            run.group + " closer than dmin + dhat repel");
    run.warned_families = true;
  }
  if (run.mesh_vertices && !run.particles && !(run.edge0 > 0.0) &&
      say(true, "group " + run.group + " holds no mesh edge and no volumetric particle"))
    return said;
  const CandidateRange range(opt.dmin, opt.dhat, run.edge0, run.skin);
  const std::string short_cutoff = range.ghost_cutoff_error(run.ghost_cutoff, run.edge0, run.skin);
  if (!short_cutoff.empty() && say(true, short_cutoff)) return said;
  // ccd no: fix sissm's steps are not collision-free (doc/fix_nosb_contact.rst)
  if (!opt.ccd && !run.warned_sissm && run.sissm) {
    say(false,
        "ccd no: under fix sissm the barrier is part of the implicit step, but the step is not "
        "collision-free: a pair can pass through the barrier within one step unless the step "
        "moves vertices by less than dhat");
    run.warned_sissm = true;
  }
  // kappa auto: the stiffness is set against the implicit step's inertia (adaptive_stiffness.h)
  if (opt.kappa_auto && !run.sissm)
    say(true,
        "kappa auto needs fix sissm (the barrier's stiffness is set against the inertia of its "
        "implicit step, as in IPC); under an explicit integrator give kappa as a number "
        "(doc/fix_nosb_contact.rst, 'Choosing kappa')");
  return said;
}

}    // namespace PeriSISSM
