/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   pair_style peri/nosb: the LAMMPS glue of the core's peridynamic model (src/core/peri):
   coefficients, mixing and restart; per-atom state arrays and their halo exchange; the
   contact candidates from the neighbor list; energy and virial accounting. The model itself
   (doc/theory.rst): elastic term (peri/elastic.h), stabilization (peri/stabilization.h),
   breaking rule (peri/breaking.h), short-range contact (peri/contact.h), evaluated in the order
   of peri/forces.h. E = sum_i V_i W_i + stabilization energy; forces are the exact force
   densities f_k = -(1/V_k) dE/dy_k; pe tallies sum_i (W_i + stabilization energy density), as
   the built-in PERI styles tally densities.

   Choices (for the documentation):
   - influence function w = 1; partial volume beta = 1 up to delta - h/2, then linear down
     to 1/2 at r = delta, h = mean of the two particles' V^(1/3) (as the built-ins, with h
     from the volumes instead of the lattice); weights fixed when the families are built.
   - a particle whose K is singular (kMinShapeConditioning, peri/family.h) has no F: no
     force state of its own, W = 0; its bonds carry the partners' force states, and their
     stabilization uses the partner's F alone (a bond between two such particles is inert).
   - breaking: every force evaluation of a run checks every bond once, before F is formed,
     against the critical stretch of its type pair, s00_IJ - alpha_IJ max(s_min,i, s_min,j),
     with the smallest bond stretches s_min of the previous evaluation (kept in atom->s0, which
     atom_style peri communicates to ghosts, migrates and writes to restart files); a broken
     bond already counts as broken in that evaluation. The setup evaluation at the start of a
     run breaks nothing (refreshes s_min); nothing breaks during a minimization.
   - short-range contact as the built-ins, but only between particles that are not bonded.
   - per-atom virial: each bond's force is equal and opposite at its two ends; each end
     tallies half of (x_i - x_j) (x) (force on i), as pair peri/lps does; sum over atoms of
     the virial equals sum_i V_i tau_i (Kirchhoff stress) for affine deformations.
   - mixed types: each particle uses the material and Cs of its own type (pair_coeff I I);
     horizon, s00, alpha, break, contact of a bond come from pair_coeff I J, or, if not
     given, horizon = max, s00 and alpha of the type with the smaller s00 among the types that
     break, break and contact on if on for either type, contact stiffness from the mean K.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"
#include "fix_nosb_mesh.h"

#include "materials/material.h"
#include "materials/material_file.h"
#include "linalg/fused.h"
#include "membrane/bending.h"
#include "peri/bond_stiffness.h"
#include "peri/breaking.h"
#include "peri/contact.h"
#include "peri/forces.h"
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
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

static constexpr double MY_PI = 3.14159265358979323846;
// Default of the stabilize keyword. Zero-energy modes need a stiff control, and with the
// bond-averaged residual smooth fields hardly feel it (peri/stabilization.h). On the brittle impact
// deck (examples/impact, s00 = 5e-4) Cs >= 1.75 keeps the damage near the indenter, while
// Cs <= 1.5 lets a fragmentation avalanche run through the whole cylinder (converged in dt);
// 2 leaves a margin. Price: the explicit stable time step of an intact sc lattice with horizon
// 3a falls to ~0.6 of peri/lps's (limits measured: Cs 0.1 > 2.8e-7 s, 0.5 ~2.6e-7, 1 ~1.9e-7,
// 2 ~1.5e-7, peri/lps ~2.6e-7 for the impact material and spacing).
static constexpr double DEFAULT_CS = 2.0;

/* ---------------------------------------------------------------------- */

PairPeriNosb::PairPeriNosb(LAMMPS *lmp) :
    Pair(lmp), family(nullptr), modelid(nullptr), bulk(nullptr), shear(nullptr), cut(nullptr),
    s00(nullptr), alpha(nullptr), cs(nullptr), breakflag(nullptr), contactflag(nullptr), membraneflag(nullptr),
    kcontact(nullptr), g0(nullptr), g0_s00(nullptr), model_(new PeriSISSM::Model),
    any_break(0), any_contact(0), external_breaking(0), block_rows(nullptr), contact_groupbit(0),
    contact_crossings(0), hmax(0.0), contact_first(nullptr), contact_neigh(nullptr),
    contact_maxfirst(0), contact_maxneigh(0), contact_inum(-1), contact_margin(0.0),
    track_motion(0), follow_explicit(0), nmotion(0), xneigh(nullptr), xcontact(nullptr),
    state_nlocal(-1), nmax(0),
    gstate(nullptr), hstate(nullptr), kstate(nullptr), wdens(nullptr), s0_new(nullptr), cnormal(nullptr), cols(nullptr), any_bend(0), meshfix(nullptr),
    hinges_stale(1), comm_fields(nullptr), comm_nfields(0)
{
  single_enable = 0;
  no_virial_fdotr_compute = 1;    // forces are densities: f.r is not the virial
  restartinfo = 1;
  // the widest exchange of the halo: F, C, flag with the implicit stiffness
  comm_forward = PeriSISSM::ParticleFields::NG + PeriSISSM::ParticleFields::NK;
  comm_reverse = 6;    // the contact blocks of ghost atoms (add_contact_blocks)
}

/* ---------------------------------------------------------------------- */

PairPeriNosb::~PairPeriNosb()
{
  if (modify->get_fix_by_id("NOSB_FAMILY")) modify->delete_fix("NOSB_FAMILY");

  memory->destroy(gstate);
  memory->destroy(hstate);
  memory->destroy(kstate);
  memory->destroy(cols);
  memory->destroy(wdens);
  memory->destroy(s0_new);
  memory->destroy(cnormal);
  memory->destroy(contact_first);
  memory->destroy(contact_neigh);
  memory->destroy(xneigh);
  memory->destroy(xcontact);

  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(modelid);
    memory->destroy(bulk);
    memory->destroy(shear);
    memory->destroy(cut);
    memory->destroy(s00);
    memory->destroy(alpha);
    memory->destroy(cs);
    memory->destroy(breakflag);
    memory->destroy(contactflag);
    memory->destroy(membraneflag);
    memory->destroy(kcontact);
    memory->destroy(g0);
    memory->destroy(g0_s00);
  }
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(modelid, n, n, "pair:model");
  memory->create(bulk, n, n, "pair:bulk");
  memory->create(shear, n, n, "pair:shear");
  memory->create(cut, n, n, "pair:cut");
  memory->create(s00, n, n, "pair:s00");
  memory->create(alpha, n, n, "pair:alpha");
  memory->create(cs, n, n, "pair:cs");
  memory->create(breakflag, n, n, "pair:breakflag");
  memory->create(contactflag, n, n, "pair:contactflag");
  memory->create(membraneflag, n, n, "pair:membraneflag");
  memory->create(kcontact, n, n, "pair:kcontact");
  memory->create(g0, n, n, "pair:g0");
  memory->create(g0_s00, n, n, "pair:g0_s00");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) g0[i][j] = g0_s00[i][j] = 0.0;
}

/* ----------------------------------------------------------------------
   pair_style peri/nosb (no arguments)
------------------------------------------------------------------------- */

void PairPeriNosb::settings(int narg, char **arg)
{
  if (narg)
    error->all(FLERR, "Illegal pair_style peri/nosb command: no arguments expected, got '{}'",
               arg[0]);
}

/* ----------------------------------------------------------------------
   parse a finite number for pair_coeff, naming the parameter on error
------------------------------------------------------------------------- */

static double coeff_number(const char *what, const char *str, Error *error)
{
  if (!utils::is_double(str))
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: {} must be a number, got '{}'",
               what, str);
  const double value = std::strtod(str, nullptr);
  if (!std::isfinite(value))
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: {} must be finite, got '{}'",
               what, str);
  return value;
}

/* ----------------------------------------------------------------------
   parse a yes/no keyword value for pair_coeff
------------------------------------------------------------------------- */

static int coeff_flag(const char *keyword, const char *str, Error *error)
{
  const std::string v(str);
  if (v == "yes" || v == "on" || v == "true" || v == "1") return 1;
  if (v == "no" || v == "off" || v == "false" || v == "0") return 0;
  error->all(FLERR, "Illegal pair_coeff peri/nosb command: {} must be yes or no, got '{}'",
             keyword, str);
  return 0;
}

/* ----------------------------------------------------------------------
   pair_coeff I J MODEL K G horizon s00 alpha [stabilize Cs] [break yes/no] [contact yes/no]
     [G0 value]   (s00 = NULL with G0)
   pair_coeff I J MODEL material FILE NAME horizon s00 alpha [keywords]: K and G from a
     material file (and G0 when s00 is NULL and the file gives one)
------------------------------------------------------------------------- */

void PairPeriNosb::coeff(int narg, char **argin)
{
  // with a material file the two words FILE NAME stand where K G would: read the entry and
  // go on with its K and G in their place
  std::vector<char *> args(argin, argin + narg);
  std::string k_text, g_text, file_material;
  double file_g0 = 0.0, file_density = 0.0;
  if (narg > 3 && strcmp(argin[3], "material") == 0) {
    if (narg < 9)
      error->all(FLERR,
                 "Incorrect number of args for pair_coeff peri/nosb command: expected "
                 "I J MODEL material FILE NAME horizon s00 alpha [keywords], got {} arguments",
                 narg);
    const auto entry = read_material(argin[4], argin[5]);
    k_text = fmt::format("{:.17g}", entry.bulk);
    g_text = fmt::format("{:.17g}", entry.shear);
    file_material = argin[5];
    file_g0 = entry.g0;
    file_density = entry.density;
    args.erase(args.begin() + 3, args.begin() + 6);
    args.insert(args.begin() + 3, {k_text.data(), g_text.data()});
    narg = (int) args.size();
  }
  char **arg = args.data();

  if (narg < 8)
    error->all(FLERR,
               "Incorrect number of args for pair_coeff peri/nosb command: expected "
               "I J MODEL K G horizon s00 alpha [stabilize Cs] [break yes/no] "
               "[contact yes/no] [G0 value] (or MODEL material FILE NAME in place of MODEL K "
               "G), got {} arguments",
               narg);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  const auto &names = PeriSISSM::material_names();
  const auto found = std::find(names.begin(), names.end(), std::string(arg[2]));
  if (found == names.end())
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: unknown model '{}' (allowed: {})",
               arg[2], PeriSISSM::material_names_joined());
  const int model_one = (int) (found - names.begin());

  const double k_one = coeff_number("bulk modulus K", arg[3], error);
  const double g_one = coeff_number("shear modulus G", arg[4], error);
  const double cut_one = coeff_number("horizon", arg[5], error);
  // s00 = NULL: the critical stretch comes from the G0 keyword (at init, see init_style)
  const bool s00_null = strcmp(arg[6], "NULL") == 0;
  const double s00_one = s00_null ? 0.0 : coeff_number("s00", arg[6], error);
  const double alpha_one = coeff_number("alpha", arg[7], error);

  // the membrane model xu has one modulus, s0, in the place of K; its G is not used
  const bool xu = strcmp(arg[2], "xu") == 0;
  if (xu && k_one <= 0.0)
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: xu modulus s0 must be > 0, got {}",
               arg[3]);
  if (k_one <= 0.0)
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: bulk modulus K must be > 0, got {}",
               arg[3]);
  if (!xu && g_one <= 0.0)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: shear modulus G must be > 0, got {}",
               arg[4]);
  const double nu = (3.0 * k_one - 2.0 * g_one) / (2.0 * (3.0 * k_one + g_one));
  const auto lame = PeriSISSM::lame_from_bulk_shear(k_one, g_one);
  if (!xu &&
      (!(nu > -1.0 && nu < 0.5) || !PeriSISSM::lame_parameters_admissible(lame.mu, lame.lambda)))
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: K = {} and G = {} give Poisson's ratio {} "
               "outside (-1, 0.5)",
               arg[3], arg[4], nu);
  if (cut_one <= 0.0)
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: horizon must be > 0, got {}",
               arg[5]);

  double cs_one = DEFAULT_CS;
  double g0_one = 0.0, bend_one = 0.0;
  int break_one = 1, contact_one = 1, membrane_one = 0;
  int iarg = 8;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "stabilize") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb stabilize", error);
      cs_one = coeff_number("stabilize Cs", arg[iarg + 1], error);
      if (cs_one < 0.0)
        error->all(FLERR,
                   "Illegal pair_coeff peri/nosb command: stabilize Cs must be >= 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "break") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb break", error);
      break_one = coeff_flag("break", arg[iarg + 1], error);
      iarg += 2;
    } else if (strcmp(arg[iarg], "contact") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb contact", error);
      contact_one = coeff_flag("contact", arg[iarg + 1], error);
      iarg += 2;
    } else if (strcmp(arg[iarg], "membrane") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb membrane", error);
      membrane_one = coeff_flag("membrane", arg[iarg + 1], error);
      iarg += 2;
    } else if (strcmp(arg[iarg], "bend") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb bend", error);
      if (strcmp(arg[iarg + 1], "auto") == 0) bend_one = -1.0;
      else if (strcmp(arg[iarg + 1], "no") == 0) bend_one = 0.0;
      else {
        bend_one = coeff_number("bend D", arg[iarg + 1], error);
        if (bend_one <= 0.0)
          error->all(FLERR,
                     "Illegal pair_coeff peri/nosb command: bend D must be > 0 (or auto, or no), "
                     "got {}",
                     arg[iarg + 1]);
      }
      iarg += 2;
    } else if (strcmp(arg[iarg], "G0") == 0) {
      if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb G0", error);
      g0_one = coeff_number("G0", arg[iarg + 1], error);
      if (g0_one <= 0.0)
        error->all(FLERR, "Illegal pair_coeff peri/nosb command: G0 must be > 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else {
      error->all(FLERR,
                 "Illegal pair_coeff peri/nosb command: unknown keyword '{}' (allowed: "
                 "stabilize, break, contact, membrane, bend, G0)",
                 arg[iarg]);
    }
  }

  if (bend_one != 0.0 && !membrane_one)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: bend is a term of membranes (add "
               "'membrane yes' to the line of type {})",
               arg[0]);

  // s00 = NULL without the G0 keyword: the material file's G0, if it gives one
  if (s00_null && g0_one == 0.0 && file_g0 > 0.0 && break_one) g0_one = file_g0;
  if (g0_one > 0.0 && !s00_null)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: s00 = {} and G0 = {} both set the critical "
               "stretch (give s00 as NULL with G0)",
               arg[6], g0_one);
  if (g0_one > 0.0 && !break_one)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: G0 = {} sets the critical stretch, but "
               "bonds cannot break with 'break no'",
               g0_one);
  if (s00_null && g0_one == 0.0)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: s00 = NULL needs the G0 keyword (the "
               "critical energy release rate that sets the critical stretch){}",
               file_material.empty() ? ""
                                     : fmt::format("; material {} gives no G0", file_material));
  if (break_one && !s00_null && s00_one <= 0.0)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: s00 must be > 0 when bonds can break, got "
               "{} (use 'break no' to turn bond breaking off)",
               arg[6]);
  if (break_one && alpha_one < 0.0)
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: alpha must be >= 0, got {}",
               arg[7]);

  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      modelid[i][j] = model_one;
      bulk[i][j] = k_one;
      shear[i][j] = g_one;
      cut[i][j] = cut_one;
      s00[i][j] = s00_one;    // with G0: set at init (s00_from_fracture_energy)
      g0[i][j] = g0_one;
      g0_s00[i][j] = 0.0;    // log the s00 it gives at the next init
      alpha[i][j] = alpha_one;
      cs[i][j] = cs_one;
      breakflag[i][j] = break_one;
      contactflag[i][j] = contact_one;
      membraneflag[i][j] = membrane_one;
      setflag[i][j] = 1;
      count++;
    }
  }
  if (count == 0)
    error->all(FLERR, "Incorrect args for pair_coeff peri/nosb command: no type pair in {} {}",
               arg[0], arg[1]);

  // the density of the file's entry, checked against the atoms of the type at init; the
  // bending modulus (a type property)
  material_density.resize(atom->ntypes + 1, 0.0);
  material_name.resize(atom->ntypes + 1);
  bend.resize(atom->ntypes + 1, 0.0);
  for (int i = std::max(ilo, jlo); i <= std::min(ihi, jhi); i++) {
    material_density[i] = file_density;
    material_name[i] = file_material;
    bend[i] = bend_one;
  }
}

/* ----------------------------------------------------------------------
   G0 keyword: the critical stretch of each type pair set with G0, from its own pair_coeff line
   (K, G, Cs, horizon) and the particle spacing h = mean V^(1/3) of the particles of its two
   types (of all particles if there are none); logged when it is first set or changes
------------------------------------------------------------------------- */

void PairPeriNosb::s00_from_fracture_energy()
{
  const int n = atom->ntypes;
  bool any = false;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      if (setflag[i][j] && g0[i][j] > 0.0) any = true;
  if (!any) return;

  // per type: sum of V^(1/3) and count (index 0: all types)
  std::vector<double> local(2 * (n + 1), 0.0), total(2 * (n + 1), 0.0);
  for (int k = 0; k < atom->nlocal; k++) {
    const double hk = cbrt(atom->vfrac[k]);
    local[2 * atom->type[k]] += hk;
    local[2 * atom->type[k] + 1] += 1.0;
    local[0] += hk;
    local[1] += 1.0;
  }
  MPI_Allreduce(local.data(), total.data(), 2 * (n + 1), MPI_DOUBLE, MPI_SUM, world);

  for (int i = 1; i <= n; i++) {
    for (int j = i; j <= n; j++) {
      if (!setflag[i][j] || g0[i][j] <= 0.0) continue;
      double hsum = total[2 * i] + (j != i ? total[2 * j] : 0.0);
      double count = total[2 * i + 1] + (j != i ? total[2 * j + 1] : 0.0);
      if (count == 0.0) {
        hsum = total[0];
        count = total[1];
      }
      if (count == 0.0)
        error->all(FLERR,
                   "pair_coeff peri/nosb G0 {} for types {} {}: no particles to take the "
                   "particle spacing from",
                   g0[i][j], i, j);
      const double h = hsum / count;
      s00[i][j] = PeriSISSM::s00_from_fracture_energy(g0[i][j], bulk[i][j], shear[i][j], cs[i][j],
                                                     cut[i][j], h);
      if (s00[i][j] != g0_s00[i][j] && comm->me == 0)
        utils::logmesg(lmp,
                       "peri/nosb: types {} {}: G0 = {:.6g} gives s00 = {:.6g} (K = {:.6g}, "
                       "G = {:.6g}, Cs = {:.6g}, horizon = {:.6g} = {:.5g} h)\n",
                       i, j, g0[i][j], s00[i][j], bulk[i][j], shear[i][j], cs[i][j], cut[i][j],
                       cut[i][j] / h);
      g0_s00[i][j] = s00[i][j];
    }
  }
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::init_style()
{
  if (!atom->peri_flag || !atom->vfrac_flag || !atom->x0)
    error->all(FLERR, "Pair style peri/nosb requires atom_style peri");
  if (atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "Pair style peri/nosb requires an atom map, see atom_modify map array");
  if (!atom->tag_enable) error->all(FLERR, "Pair style peri/nosb requires atom IDs");
  if (domain->dimension != 3) error->all(FLERR, "Pair style peri/nosb requires a 3d simulation");

  // as a sub-style of hybrid, hybrid/overlay or hybrid/scaled, types mapped to other styles
  // would get bond families with unset coefficients, and fix sissm would not see the other
  // styles' forces in its implicit residual: not supported

  if (force->pair != this)
    error->all(FLERR,
               "Pair style peri/nosb cannot be a sub-style of pair_style {}: use pair_style "
               "peri/nosb alone (several materials: pair_coeff per type pair; other "
               "interactions: fixes such as wall or indent)",
               force->pair_style);

  const int n = atom->ntypes;

  s00_from_fracture_energy();    // G0 keyword: s00 of those type pairs (before mixing)
  check_material_density();      // types whose K and G came from a material file

  // mixing of unset I,J (I != J): bond parameters from both types

  for (int i = 1; i <= n; i++) {
    for (int j = i + 1; j <= n; j++) {
      if (setflag[i][j]) continue;
      // the critical stretch comes from the weaker of the types whose bonds can break (a
      // 'break no' type has no meaningful s00)
      int weak = (s00[i][i] <= s00[j][j]) ? i : j;
      if (breakflag[i][i] != breakflag[j][j]) weak = breakflag[i][i] ? i : j;
      modelid[i][j] = modelid[i][i];
      bulk[i][j] = 0.5 * (bulk[i][i] + bulk[j][j]);
      shear[i][j] = 0.5 * (shear[i][i] + shear[j][j]);
      cut[i][j] = std::max(cut[i][i], cut[j][j]);
      s00[i][j] = s00[weak][weak];
      alpha[i][j] = alpha[weak][weak];
      cs[i][j] = 0.0;    // not used: stabilization is per particle
      breakflag[i][j] = breakflag[i][i] || breakflag[j][j];
      contactflag[i][j] = contactflag[i][i] || contactflag[j][j];
      membraneflag[i][j] = 0;    // not used: a type property
    }
  }

  // mirror, derived per-pair and per-type values, summary flags

  any_break = any_contact = 0;
  for (int i = 1; i <= n; i++) {
    for (int j = i; j <= n; j++) {
      modelid[j][i] = modelid[i][j];
      bulk[j][i] = bulk[i][j];
      shear[j][i] = shear[i][j];
      cut[j][i] = cut[i][j];
      s00[j][i] = s00[i][j];
      alpha[j][i] = alpha[i][j];
      cs[j][i] = cs[i][j];
      breakflag[j][i] = breakflag[i][j];
      contactflag[j][i] = contactflag[i][j];
      membraneflag[j][i] = membraneflag[i][j];
      const double d2 = cut[i][j] * cut[i][j];
      kcontact[i][j] = kcontact[j][i] = 15.0 * 18.0 * bulk[i][j] / (MY_PI * d2 * d2);
      if (breakflag[i][j]) any_break = 1;
      if (contactflag[i][j]) any_contact = 1;
    }
  }
  configure_model();
  check_membranes();
  hinges_stale = 1;    // bending moduli, types or meshes may have changed since the last run

  // every bond partner must have one image within reach: a periodic box at least two horizons
  // wide in each periodic direction (checked here at every run, since change_box can shrink
  // or create a periodic direction after the families exist; the closest image of a partner
  // would then be the wrong one)

  double cutmax = 0.0;
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) cutmax = std::max(cutmax, cut[i][j]);
  const double xprd = domain->xprd, yprd = domain->yprd, zprd = domain->zprd;
  const double xy = domain->triclinic ? domain->xy : 0.0;
  const double xz = domain->triclinic ? domain->xz : 0.0;
  const double yz = domain->triclinic ? domain->yz : 0.0;
  // distances between opposite faces of the (restricted triclinic) box
  const double bxc = sqrt(yprd * zprd * yprd * zprd + xy * zprd * xy * zprd +
                          (xy * yz - yprd * xz) * (xy * yz - yprd * xz));
  const double width[3] = {xprd * yprd * zprd / bxc, yprd * zprd / sqrt(zprd * zprd + yz * yz),
                           zprd};
  const int periodicity[3] = {domain->xperiodic, domain->yperiodic, domain->zperiodic};
  for (int d = 0; d < 3; d++)
    if (periodicity[d] && width[d] < 2.0 * cutmax)
      error->all(FLERR,
                 "Pair style peri/nosb: the periodic box is {:.8g} wide in {}, shorter than two "
                 "horizons (2 x {:.8g}): enlarge the box or make that direction non-periodic",
                 width[d], "xyz"[d], cutmax);

  // largest particle size, for the contact range

  double hone = 0.0;
  for (int i = 0; i < atom->nlocal; i++) hone = std::max(hone, cbrt(atom->vfrac[i]));
  MPI_Allreduce(&hone, &hmax, 1, MPI_DOUBLE, MPI_MAX, world);

  // the bond-family fix, created once (or recreated from a restart file)

  family = dynamic_cast<FixNosbFamily *>(modify->get_fix_by_id("NOSB_FAMILY"));
  if (!family)
    family = dynamic_cast<FixNosbFamily *>(modify->add_fix("NOSB_FAMILY all nosb/family"));
  family->attach(model_.get(), [this]() { neighbor_rebuilt(); });

  // a half neighbor list only for short-range contact (an implicit integrator asks again
  // for the motion tracking in its own init, which follows this one)

  if (any_contact) neighbor->add_request(this);
  track_contact_motion(0);

  // minimization: the line searches evaluate trial positions far from the path (up to
  // min_modify dmax), and bonds breaking there would change the energy being minimized

  if (update->whichflag == 2 && any_break && comm->me == 0)
    utils::logmesg(lmp,
                   "Pair peri/nosb: bonds do not break during a minimization; they are checked "
                   "again from the first step of the next run\n");

  // which version of the bond passes runs (linalg/fused.h): results of the two differ in
  // round-off, so a user comparing runs of two machines finds it here
  if (!passes_reported && comm->me == 0)
    utils::logmesg(lmp, "Pair peri/nosb: bond passes {}\n",
                   PeriSISSM::fused_passes()
                       ? "with fused multiply-add (x86-64-v3; PERI_SISSM_PASSES=plain: without)"
                       : "without fused multiply-add");
  passes_reported = 1;
}

/* ----------------------------------------------------------------------
   membrane types: their atoms must be vertices of a mesh read with read_mesh (the membrane
   correspondence needs the mesh's normals and thickness)
------------------------------------------------------------------------- */

void PairPeriNosb::check_membranes()
{
  // (asked for in every deck: after read_restart, find() re-creates the mesh fix from the
  // file's data before LAMMPS discards it)
  FixNosbMesh *mesh = FixNosbMesh::find(lmp);
  meshfix = mesh;
  const int n = atom->ntypes;
  bend.resize(n + 1, 0.0);
  bend_auto_factor.assign(n + 1, 0.0);
  any_bend = 0;
  for (int t = 1; t <= n; t++) {
    if (bend[t] == 0.0) continue;
    any_bend = 1;
    // E and nu of the type's material (xu: E = 2 s0, nu = 0)
    const bool xu = PeriSISSM::material_names()[modelid[t][t]] == "xu";
    const double K = bulk[t][t], G = shear[t][t];
    const double E = xu ? 2.0 * K : 9.0 * K * G / (3.0 * K + G);
    const double nu = xu ? 0.0 : (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
    bend_auto_factor[t] = E / (12.0 * (1.0 - nu * nu));
  }
  if (!model_->any_membrane()) return;
  tagint bad = 0;
  int badtype = 0;
  for (int i = 0; i < atom->nlocal && !bad; i++) {
    if (!model_->membrane(atom->type[i])) continue;
    if (!mesh || mesh->mesh[i] == 0) {
      bad = atom->tag[i];
      badtype = atom->type[i];
    }
  }
  tagint anybad = 0;
  MPI_Allreduce(&bad, &anybad, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if (anybad) {
    if (bad == anybad)
      error->one(FLERR,
                 "Pair peri/nosb: atom {} is of type {}, a membrane type (pair_coeff ... "
                 "membrane yes), but not a vertex of a mesh read with read_mesh: membrane "
                 "particles are made by read_mesh",
                 bad, badtype);
    MPI_Barrier(world);
    error->all(FLERR, "Pair peri/nosb: an atom of a membrane type is not a mesh vertex");
  }
}

/* ---------------------------------------------------------------------- */

bool PairPeriNosb::has_unbent_membranes() const
{
  if (!model_ || !model_->any_membrane()) return false;
  for (int t = 1; t <= atom->ntypes; t++)
    if (membraneflag[t][t] && (t >= (int) bend.size() || bend[t] == 0.0)) return true;
  return false;
}

/* ---------------------------------------------------------------------- */

double PairPeriNosb::init_one(int i, int j)
{
  if (setflag[i][j] == 0) did_mix = true;
  return cut[i][j];
}

/* ----------------------------------------------------------------------
   the core's model from the (mixed and mirrored) coefficients: per type the material, Cs and
   K of pair_coeff I I; per type pair the horizon, contact and breaking rule
------------------------------------------------------------------------- */

void PairPeriNosb::configure_model()
{
  const int n = atom->ntypes;
  model_->set_ntypes(n);
  for (int i = 1; i <= n; i++) {
    const std::string &name = PeriSISSM::material_names()[modelid[i][i]];
    if (name == "xu") {
      // one modulus s0 (in K's place): mu = s0, lambda = 0, so its bulk modulus is 2 s0 / 3
      model_->set_type(i, PeriSISSM::make_material(name, bulk[i][i], 0.0), cs[i][i],
                       2.0 * bulk[i][i] / 3.0);
    } else {
      const auto lame = PeriSISSM::lame_from_bulk_shear(bulk[i][i], shear[i][i]);
      model_->set_type(i, PeriSISSM::make_material(name, lame.mu, lame.lambda), cs[i][i],
                       bulk[i][i]);
    }
    model_->set_membrane(i, membraneflag[i][i] != 0);
    for (int j = i; j <= n; j++) model_->set_pair(i, j, cut[i][j], contactflag[i][j], kcontact[i][j]);
  }
  model_->breaking().configure(
      n, [this](int i, int j) { return breakflag[i][j] != 0; },
      [this](int i, int j) { return s00[i][j]; }, [this](int i, int j) { return alpha[i][j]; });
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::grow_peratom()
{
  if (model_->any_membrane() && !cnormal && nmax > 0)
    memory->create(cnormal, 3 * nmax, "pair:cnormal");
  if (atom->nmax <= nmax) return;
  using PeriSISSM::ParticleFields;
  nmax = atom->nmax;
  memory->destroy(gstate);
  memory->destroy(hstate);
  memory->destroy(kstate);
  memory->destroy(cols);
  memory->destroy(wdens);
  memory->destroy(s0_new);
  memory->destroy(cnormal);
  memory->create(kstate, nmax * ParticleFields::NK, "pair:kstate");
  memory->create(gstate, nmax * ParticleFields::NG, "pair:gstate");
  memory->create(hstate, nmax * 9, "pair:hstate");
  memory->create(cols, nmax * ParticleFields::NCOLS, "pair:cols");
  memory->create(wdens, nmax, "pair:wdens");
  memory->create(s0_new, nmax, "pair:s0_new");
  if (model_->any_membrane()) memory->create(cnormal, 3 * nmax, "pair:cnormal");
}

/* ----------------------------------------------------------------------
   the atoms as the core sees them
------------------------------------------------------------------------- */

PeriSISSM::Particles PairPeriNosb::particles() const
{
  PeriSISSM::Particles p;
  p.nlocal = atom->nlocal;
  p.nall = atom->nlocal + atom->nghost;
  p.x = atom->x[0];
  p.x0 = atom->x0[0];
  p.volume = atom->vfrac;
  p.type = atom->type;
  p.smin = atom->s0;
  p.f = atom->f[0];
  return p;
}

/* ----------------------------------------------------------------------
   the core's halo callback: a forward communication of one per-atom field
------------------------------------------------------------------------- */

namespace LAMMPS_NS {
class NosbHalo : public PeriSISSM::Halo {
 public:
  explicit NosbHalo(PairPeriNosb *pair) : pair_(pair) {}
  void forward(const PeriSISSM::HaloField *fields, int n) override
  {
    pair_->comm_fields = fields;
    pair_->comm_nfields = n;
    pair_->comm->forward_comm(pair_);
  }

 private:
  PairPeriNosb *pair_;
};
}    // namespace LAMMPS_NS

/* ---------------------------------------------------------------------- */

void PairPeriNosb::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow_peratom();
  if (!family->built) return;

  if (any_contact) compute_contact(eflag, vflag);

  // Bonds break in every force evaluation of a run, but not in the setup evaluation at the
  // start of a run (it only refreshes s_min): a run split into several (or by a restart) then
  // breaks exactly the bonds the unsplit run breaks. Nothing breaks, and s_min is left alone,
  // during a minimization (see init_style).

  using PeriSISSM::BreakingRule;
  const int nobreak = !any_break || external_breaking || update->whichflag == 2;
  const int mode = nobreak ? BreakingRule::NOBREAK
                           : update->setupflag ? BreakingRule::S0ONLY : BreakingRule::BREAK;
  const PeriSISSM::Particles p = particles();
  PeriSISSM::ParticleFields fields;
  fields.g = gstate;
  fields.h = hstate;
  fields.k = kstate;
  fields.w = wdens;
  fields.energy = eflag_either;
  fields.smin_new = s0_new;
  fields.normal = cnormal;
  fields.cols = cols;
  PeriSISSM::Virial vir;
  if (vflag_either) {
    if (vflag_global) vir.global = virial;
    if (vflag_atom) vir.peratom = vatom;
  }
  NosbHalo halo(this);
  broke.clear();
  PeriSISSM::evaluate_bond_terms(*model_, p, family->view(), family->box, mode, block_rows,
                                 fields, halo, vir, broke);
  family->forget_broken(broke);
  if (any_contact && block_rows) add_contact_blocks();
  if (any_bend && meshfix) compute_bending();

  if (eflag_either) {
    const int nlocal = atom->nlocal;
    for (int i = 0; i < nlocal; i++) {
      if (eflag_global) eng_vdwl += wdens[i];
      if (eflag_atom) eatom[i] += wdens[i];
    }
  }
  state_nlocal = atom->nlocal;
}

/* ---------------------------------------------------------------------- */

bool PairPeriNosb::state_current() const
{
  return gstate && state_nlocal == atom->nlocal;
}

/* ---------------------------------------------------------------------- */

const double *PairPeriNosb::deformation_gradient(int i) const
{
  return gstate + PeriSISSM::ParticleFields::NG * i;
}

/* ----------------------------------------------------------------------
   ImplicitForces: the bond-projected stiffness (the evaluation with blocks sent H+ to the ghosts)
------------------------------------------------------------------------- */

void PairPeriNosb::bond_springs(PeriSISSM::BondSprings &springs)
{
  PeriSISSM::ParticleFields fields;
  fields.k = kstate;
  PeriSISSM::bond_springs(family->view(), particles(), fields, springs);
}

/* ----------------------------------------------------------------------
   ImplicitForces: a step and its evaluations
------------------------------------------------------------------------- */

void PairPeriNosb::begin_implicit_step(int groupbit)
{
  external_breaking = 1;
  contact_groupbit = groupbit;
  contact_crossings = 0;
}

void PairPeriNosb::end_implicit_step()
{
  external_breaking = 0;
  contact_groupbit = 0;
}

void PairPeriNosb::evaluate(double **block)
{
  block_rows = block;
  compute(0, 0);
  block_rows = nullptr;
}

// only short-range contact writes forces on ghost atoms (bond forces are summed by the owner of
// each bond's end); the same answer on every rank, as the reverse communication it decides on
// needs
bool PairPeriNosb::ghost_forces() const
{
  return any_contact && force->newton_pair;
}

/* ----------------------------------------------------------------------
   ImplicitForces: no unbroken bond joins an owned atom of the group with one outside it, and no
   short-range contact acted between them in the evaluations of this step (all ranks)
------------------------------------------------------------------------- */

bool PairPeriNosb::group_coupled(int groupbit)
{
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  int coupled = contact_crossings > 0;
  // group all: every atom is in it, no bond leaves it (and no pass over the bonds is needed)
  const bool every_atom = groupbit == group->bitmask[0];
  for (int i = 0; i < nlocal && !coupled && !every_atom; i++) {
    if (!(mask[i] & groupbit)) continue;
    const int *jl = family->jlocal[i];
    for (int b = 0; b < family->npartner[i]; b++)
      if (jl[b] >= 0 && !(mask[jl[b]] & groupbit)) {
        coupled = 1;
        break;
      }
  }
  int any;
  MPI_Allreduce(&coupled, &any, 1, MPI_INT, MPI_MAX, world);
  return any != 0;
}

void PairPeriNosb::check_motion(int converged)
{
  family->check_motion(converged);
}

/* ---------------------------------------------------------------------- */

int PairPeriNosb::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                    int * /*pbc*/)
{
  int m = 0;
  for (int ii = 0; ii < n; ii++)
    for (int q = 0; q < comm_nfields; q++) {
      const int width = comm_fields[q].width;
      const double *row = comm_fields[q].rows + (bigint) width * list[ii];
      for (int k = 0; k < width; k++) buf[m++] = row[k];
    }
  return m;
}

/* ---------------------------------------------------------------------- */

void PairPeriNosb::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  const int last = first + n;
  for (int i = first; i < last; i++)
    for (int q = 0; q < comm_nfields; q++) {
      const int width = comm_fields[q].width;
      double *row = comm_fields[q].rows + (bigint) width * i;
      for (int k = 0; k < width; k++) row[k] = buf[m++];
    }
}

/* ----------------------------------------------------------------------
   proc 0 writes to restart file
------------------------------------------------------------------------- */

void PairPeriNosb::write_restart(FILE *fp)
{
  const int version = RESTART_VERSION;
  fwrite(&version, sizeof(int), 1, fp);
  for (int i = 1; i <= atom->ntypes; i++) {
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) {
        const std::string &name = PeriSISSM::material_names()[modelid[i][j]];
        const int len = (int) name.size() + 1;
        fwrite(&len, sizeof(int), 1, fp);
        fwrite(name.c_str(), sizeof(char), len, fp);
        fwrite(&breakflag[i][j], sizeof(int), 1, fp);
        fwrite(&contactflag[i][j], sizeof(int), 1, fp);
        fwrite(&membraneflag[i][j], sizeof(int), 1, fp);
        fwrite(&bulk[i][j], sizeof(double), 1, fp);
        fwrite(&shear[i][j], sizeof(double), 1, fp);
        fwrite(&cut[i][j], sizeof(double), 1, fp);
        fwrite(&s00[i][j], sizeof(double), 1, fp);
        fwrite(&alpha[i][j], sizeof(double), 1, fp);
        fwrite(&cs[i][j], sizeof(double), 1, fp);
      }
    }
  }
  bend.resize(atom->ntypes + 1, 0.0);
  fwrite(bend.data() + 1, sizeof(double), atom->ntypes, fp);
}

/* ----------------------------------------------------------------------
   proc 0 reads from restart file, bcasts; the model is stored by name, and a file of another
   format version is refused (rather than read as garbage)
------------------------------------------------------------------------- */

void PairPeriNosb::read_restart(FILE *fp)
{
  allocate();
  const int me = comm->me;
  int version = 0;
  if (me == 0) utils::sfread(FLERR, &version, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&version, 1, MPI_INT, 0, world);
  if (version != RESTART_VERSION)
    error->all(FLERR,
               "Pair peri/nosb: the restart file holds pair data of format version {}, this "
               "build reads version {}: write the restart file again with this build (or use "
               "the build that wrote it)",
               version, (int) RESTART_VERSION);
  for (int i = 1; i <= atom->ntypes; i++) {
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (!setflag[i][j]) continue;
      int len = 0;
      if (me == 0) utils::sfread(FLERR, &len, sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&len, 1, MPI_INT, 0, world);
      if (len < 1 || len > 256)
        error->all(FLERR, "Pair peri/nosb: restart file is corrupt (model name of {} chars)", len);
      std::vector<char> name(len);
      int iv[3];
      double dv[6];
      if (me == 0) {
        utils::sfread(FLERR, name.data(), sizeof(char), len, fp, nullptr, error);
        utils::sfread(FLERR, iv, sizeof(int), 3, fp, nullptr, error);
        utils::sfread(FLERR, dv, sizeof(double), 6, fp, nullptr, error);
      }
      MPI_Bcast(name.data(), len, MPI_CHAR, 0, world);
      MPI_Bcast(iv, 3, MPI_INT, 0, world);
      MPI_Bcast(dv, 6, MPI_DOUBLE, 0, world);
      name[len - 1] = '\0';
      const auto &names = PeriSISSM::material_names();
      const auto found = std::find(names.begin(), names.end(), std::string(name.data()));
      if (found == names.end())
        error->all(FLERR,
                   "Pair peri/nosb: restart file names model '{}', which this build does not "
                   "have (allowed: {})",
                   name.data(), PeriSISSM::material_names_joined());
      modelid[i][j] = (int) (found - names.begin());
      breakflag[i][j] = iv[0];
      contactflag[i][j] = iv[1];
      membraneflag[i][j] = iv[2];
      bulk[i][j] = dv[0];
      shear[i][j] = dv[1];
      cut[i][j] = dv[2];
      s00[i][j] = dv[3];
      alpha[i][j] = dv[4];
      cs[i][j] = dv[5];
    }
  }
  bend.assign(atom->ntypes + 1, 0.0);
  if (me == 0) utils::sfread(FLERR, bend.data() + 1, sizeof(double), atom->ntypes, fp, nullptr, error);
  MPI_Bcast(bend.data() + 1, atom->ntypes, MPI_DOUBLE, 0, world);
}

/* ---------------------------------------------------------------------- */

double PairPeriNosb::memory_usage()
{
  using PeriSISSM::ParticleFields;
  double bytes = (double) nmax * (ParticleFields::NG + ParticleFields::NK + 9 + 2 + ParticleFields::NCOLS) *
      sizeof(double);
  bytes += (double) (contact_maxfirst + contact_maxneigh) * sizeof(int);
  bytes += (double) hinges.capacity() * sizeof(Hinge);
  const double n = atom->ntypes + 1;
  bytes += n * n * (11.0 * sizeof(double) + 5.0 * sizeof(int));
  return bytes;
}
