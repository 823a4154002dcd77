// The arguments of fix nosb/contact: every keyword, any order, a repeated one counting last,
// the default slip speed from the units, and the message of each kind of error.
#include "contact/contact_options.h"

#include "contact/friction_potential.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

using namespace PeriSISSM;

namespace {

// the caller's converters: numbers by strtod, yes/no strictly (anything else throws, as LAMMPS
// stops); seen: every text converted, in order
struct Converters {
  std::vector<std::string> seen;
  std::function<double(const std::string &)> number = [this](const std::string &text) {
    seen.push_back(text);
    return std::strtod(text.c_str(), nullptr);
  };
  std::function<bool(const std::string &)> logical = [this](const std::string &text) {
    seen.push_back(text);
    if (text != "yes" && text != "no") throw std::runtime_error("not yes/no: " + text);
    return text == "yes";
  };
};

ContactUnits metal()
{
  ContactUnits u;
  u.angstrom = 1.0;
  u.femtosecond = 1.0e-3;    // metal units: ps
  return u;
}

std::string error_of(const std::vector<std::string> &args, ContactUnits units = metal())
{
  Converters c;
  try {
    parse_contact_options(args, c.number, c.logical, units);
  } catch (std::invalid_argument &e) {
    return e.what();
  }
  return "";
}

}    // namespace

TEST(ContactOptions, ReadsEveryKeywordInAnyOrder)
{
  Converters c;
  const auto opt = parse_contact_options({"ccd", "no", "epsv", "0.5", "friction", "0.3", "kappa",
                                          "20", "dmin", "0.001", "dhat", "0.004"},
                                         c.number, c.logical, metal());
  EXPECT_EQ(opt.dhat, 0.004);
  EXPECT_EQ(opt.dmin, 0.001);
  EXPECT_EQ(opt.kappa, 20.0);
  EXPECT_FALSE(opt.kappa_auto);
  EXPECT_EQ(opt.mu, 0.3);
  EXPECT_EQ(opt.epsv, 0.5);
  EXPECT_FALSE(opt.ccd);
  EXPECT_EQ(c.seen, (std::vector<std::string>{"no", "0.5", "0.3", "20", "0.001", "0.004"}));
}

TEST(ContactOptions, DefaultsAndTheLastRepeatCounts)
{
  Converters c;
  auto opt = parse_contact_options({"dhat", "0.01", "kappa", "auto"}, c.number, c.logical, metal());
  EXPECT_EQ(opt.dmin, 0.0);
  EXPECT_TRUE(opt.kappa_auto);
  EXPECT_EQ(opt.kappa, -1.0);
  EXPECT_EQ(opt.mu, 0.0);
  EXPECT_TRUE(opt.ccd);
  // 1e-3 m/s = 1e7 A / 1e12 ps
  EXPECT_DOUBLE_EQ(opt.epsv, 1.0e-5);
  EXPECT_EQ(opt.epsv, default_slip_speed(1.0, 1.0e-3));

  opt = parse_contact_options({"dhat", "0.01", "kappa", "auto", "kappa", "3", "dhat", "0.02"},
                              c.number, c.logical, metal());
  EXPECT_FALSE(opt.kappa_auto);
  EXPECT_EQ(opt.kappa, 3.0);
  EXPECT_EQ(opt.dhat, 0.02);
  opt = parse_contact_options({"dhat", "0.01", "kappa", "3", "kappa", "auto"}, c.number, c.logical,
                              metal());
  EXPECT_TRUE(opt.kappa_auto);
  EXPECT_EQ(opt.kappa, -1.0);
}

TEST(ContactOptions, SlipSpeedInLjUnits)
{
  ContactUnits lj;
  lj.lj = true;
  // no friction: the default is not used, any value will do
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1"}, lj), "");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1", "friction", "0.2", "epsv", "0.1"}, lj), "");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1", "friction", "0.2"}, lj),
            "Illegal fix nosb/contact command: with friction in lj units give the slip speed "
            "epsv (velocity units; IPC's default is 1e-3 m/s, which lj units cannot convert)");
  // friction 0 is none
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1", "friction", "0"}, lj), "");
}

TEST(ContactOptions, ErrorMessages)
{
  const std::string usage = "(fix ID group nosb/contact dhat D [dmin d] [kappa k|auto] "
                            "[friction mu] [epsv v] [ccd yes|no])";
  const std::string illegal = "Illegal fix nosb/contact command: ";
  EXPECT_EQ(error_of({"kappa", "1"}), illegal + "keyword dhat is required " + usage);
  EXPECT_EQ(error_of({}), illegal + "keyword dhat is required " + usage);
  EXPECT_EQ(error_of({"dhat", "0.01"}),
            illegal + "keyword kappa is required (a number, or auto under fix sissm) " + usage);
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1", "stiff", "3"}),
            illegal + "unknown keyword 'stiff' " + usage);
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa"}),
            "Illegal fix nosb/contact kappa command: missing argument(s)");
  // the keyword is checked before its value is looked for
  EXPECT_EQ(error_of({"dhat", "0.01", "stiff"}), illegal + "unknown keyword 'stiff' " + usage);
  EXPECT_EQ(error_of({"dhat", "-0.005", "kappa", "1"}), illegal + "dhat must be > 0, got '-0.005'");
  EXPECT_EQ(error_of({"dhat", "0", "kappa", "1"}), illegal + "dhat must be > 0, got '0'");
  EXPECT_EQ(error_of({"dhat", "0.01", "dmin", "-1", "kappa", "1"}),
            illegal + "dmin must be >= 0, got '-1'");
  EXPECT_EQ(error_of({"dhat", "0.01", "dmin", "0", "kappa", "1"}), "");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "0"}), illegal + "kappa must be > 0, got '0'");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "inf"}), illegal + "kappa must be > 0, got 'inf'");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "nan"}), illegal + "kappa must be > 0, got 'nan'");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1", "friction", "-0.1"}),
            illegal + "friction mu must be >= 0, got '-0.1'");
  EXPECT_EQ(error_of({"dhat", "0.01", "kappa", "1", "epsv", "0"}),
            illegal + "epsv must be > 0, got '0'");
  // the first bad argument is the one reported
  EXPECT_EQ(error_of({"dhat", "-1", "kappa", "0"}), illegal + "dhat must be > 0, got '-1'");
  // a text that is not yes/no stops in the caller's converter
  Converters c;
  EXPECT_THROW(parse_contact_options({"dhat", "0.01", "kappa", "1", "ccd", "maybe"}, c.number,
                                     c.logical, metal()),
               std::runtime_error);
}

namespace {

// options and a run that pass: dhat 0.0065, dmin 0.0005, a cloth (mesh edges) and particles
// with their bond partners, fix sissm, ccd, a ghost cutoff long enough
ContactOptions good_options()
{
  ContactOptions opt;
  opt.dhat = 0.0065;
  opt.dmin = 0.0005;
  opt.kappa = 1.0;
  return opt;
}

ContactRun good_run()
{
  ContactRun run;
  run.id = "c";
  run.group = "all";
  run.mesh_vertices = 100;
  run.particles = 20;
  run.edge0 = 0.02;
  run.skin = 0.005;
  run.ghost_cutoff = CandidateRange(0.0005, 0.0065, run.edge0, run.skin).ghost_cutoff(0.005);
  run.partners = true;
  run.sissm = true;
  return run;
}

// the errors (true) and warnings (false) said, in order
std::vector<bool> kinds(const std::vector<ContactRunMessage> &said)
{
  std::vector<bool> k;
  for (const auto &m : said) k.push_back(m.error);
  return k;
}

}    // namespace

TEST(ContactOptions, RunChecks)
{
  const ContactOptions opt = good_options();
  ContactRun run = good_run();
  EXPECT_TRUE(check_contact_run(opt, run).empty());

  run.mesh_vertices = run.particles = 0;
  auto said = check_contact_run(opt, run);
  ASSERT_EQ(kinds(said), std::vector<bool>{true});
  EXPECT_EQ(said[0].text,
            "Fix nosb/contact c: group all holds no atom: the contact acts between the triangles "
            "of meshes read with read_mesh and between volumetric particles");

  // mesh vertices without an edge and no particle; particles alone are pairs
  run = good_run();
  run.particles = 0;
  run.edge0 = 0.0;
  said = check_contact_run(opt, run);
  ASSERT_EQ(kinds(said), std::vector<bool>{true});
  EXPECT_EQ(said[0].text,
            "Fix nosb/contact c: group all holds no mesh edge and no volumetric particle");
  run.particles = 1;
  EXPECT_TRUE(check_contact_run(opt, run).empty());

  // particles without partners: a warning, once; none without particles
  run = good_run();
  run.partners = false;
  said = check_contact_run(opt, run);
  ASSERT_EQ(kinds(said), std::vector<bool>{false});
  EXPECT_EQ(said[0].text,
            "Fix nosb/contact c: no pair_style peri/nosb, so no bond families: every two "
            "volumetric particles of group all closer than dmin + dhat repel");
  EXPECT_TRUE(run.warned_families);
  EXPECT_TRUE(check_contact_run(opt, run).empty());
  run = good_run();
  run.partners = false;
  run.particles = 0;
  EXPECT_TRUE(check_contact_run(opt, run).empty());
  EXPECT_FALSE(run.warned_families);

  // a ghost cutoff just short: CandidateRange's error, after the warning said before it
  run = good_run();
  run.partners = false;
  run.ghost_cutoff *= 1.0 - 1e-12;
  said = check_contact_run(opt, run);
  ASSERT_EQ(kinds(said), (std::vector<bool>{false, true}));
  const CandidateRange range(opt.dmin, opt.dhat, run.edge0, run.skin);
  EXPECT_EQ(said[1].text,
            "Fix nosb/contact c: " + range.ghost_cutoff_error(run.ghost_cutoff, 0.02, 0.005));
  EXPECT_NE(said[1].text.find("set comm_modify cutoff 0.087 or more"), std::string::npos)
      << said[1].text;

  // ccd no under fix sissm: a warning, once; none without fix sissm
  ContactOptions no_ccd = good_options();
  no_ccd.ccd = false;
  run = good_run();
  said = check_contact_run(no_ccd, run);
  ASSERT_EQ(kinds(said), std::vector<bool>{false});
  EXPECT_EQ(said[0].text,
            "Fix nosb/contact c: ccd no: under fix sissm the barrier is part of the implicit "
            "step, but the step is not collision-free: a pair can pass through the barrier "
            "within one step unless the step moves vertices by less than dhat");
  EXPECT_TRUE(run.warned_sissm);
  EXPECT_TRUE(check_contact_run(no_ccd, run).empty());
  run = good_run();
  run.sissm = false;
  EXPECT_TRUE(check_contact_run(no_ccd, run).empty());
  EXPECT_FALSE(run.warned_sissm);

  // kappa auto needs fix sissm; the error comes after the warnings
  ContactOptions automatic = good_options();
  automatic.kappa_auto = true;
  run = good_run();
  EXPECT_TRUE(check_contact_run(automatic, run).empty());
  run.sissm = false;
  run.partners = false;
  said = check_contact_run(automatic, run);
  ASSERT_EQ(kinds(said), (std::vector<bool>{false, true}));
  EXPECT_EQ(said[1].text,
            "Fix nosb/contact c: kappa auto needs fix sissm (the barrier's stiffness is set "
            "against the inertia of its implicit step, as in IPC); under an explicit "
            "integrator give kappa as a number (doc/fix_nosb_contact.rst, 'Choosing kappa')");
}

// The ghost cutoff of a run: the user's, or the longest pair cutoff + skin over the pairs of
// types that have one
TEST(ContactOptions, RunGhostCutoff)
{
  EXPECT_EQ(run_ghost_cutoff(0.3, nullptr, 2, 0.1), 0.3);
  // types 1, 2: cutoffs 0.5 (1-1), 0 (1-2: none), 1.5 (2-2)
  double rows[3][3] = {{0, 0, 0}, {0, 0.25, 0}, {0, 0, 2.25}};
  const double *cutsq[3] = {rows[0], rows[1], rows[2]};
  EXPECT_DOUBLE_EQ(run_ghost_cutoff(0.3, cutsq, 2, 0.1), 1.6);
  EXPECT_DOUBLE_EQ(run_ghost_cutoff(0.3, cutsq, 1, 0.1), 0.6);
  EXPECT_EQ(run_ghost_cutoff(2.0, cutsq, 2, 0.1), 2.0);
  rows[2][2] = 0.0;
  EXPECT_EQ(run_ghost_cutoff(0.7, cutsq, 2, 0.1), 0.7);
}
