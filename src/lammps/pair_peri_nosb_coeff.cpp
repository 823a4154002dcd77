/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, its coefficients.

   pair_style and pair_coeff parsed into the core's table of type-pair coefficients
   (src/core/peri/coefficients.h), which mixes the pairs not given and configures the model;
   the critical stretch of the G0 keyword (from the particle spacing, summed over all ranks);
   the coefficients in restart files.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"

#include "materials/material_file.h"
#include "peri/breaking.h"
#include "peri/coefficients.h"
#include "peri/model.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

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
   a number of pair_coeff (utils::numeric), naming the parameter when it is none
------------------------------------------------------------------------- */

static double coeff_number(const char *what, const char *str, LAMMPS *lmp)
{
  if (!utils::is_double(str))
    lmp->error->all(FLERR, "Illegal pair_coeff peri/nosb command: {} must be a number, got '{}'",
                    what, str);
  return utils::numeric(FLERR, str, false, lmp);
}

/* ----------------------------------------------------------------------
   pair_coeff I J MODEL K G horizon s00 alpha [stabilize Cs] [break yes/no] [contact yes/no]
     [membrane yes/no] [bend D|auto|no] [G0 value]   (s00 = NULL with G0)
   pair_coeff I J MODEL material FILE NAME horizon s00 alpha [keywords]: K and G from a
     material file (and G0 when s00 is NULL and the file gives one)
------------------------------------------------------------------------- */

void PairPeriNosb::coeff(int narg, char **arg)
{
  const bool from_file = narg > 3 && strcmp(arg[3], "material") == 0;
  const int ih = from_file ? 6 : 5;    // index of the horizon
  if (from_file && narg < 9)
    error->all(FLERR,
               "Incorrect number of args for pair_coeff peri/nosb command: expected "
               "I J MODEL material FILE NAME horizon s00 alpha [keywords], got {} arguments",
               narg);
  if (narg < 8)
    error->all(FLERR,
               "Incorrect number of args for pair_coeff peri/nosb command: expected "
               "I J MODEL K G horizon s00 alpha [stabilize Cs] [break yes/no] "
               "[contact yes/no] [G0 value] (or MODEL material FILE NAME in place of MODEL K "
               "G), got {} arguments",
               narg);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds_typelabel(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, lmp, Atom::ATOM);
  utils::bounds_typelabel(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, lmp, Atom::ATOM);

  const auto &names = PeriSISSM::material_names();
  if (std::find(names.begin(), names.end(), std::string(arg[2])) == names.end())
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: unknown model '{}' (allowed: {})",
               arg[2], PeriSISSM::material_names_joined());

  // the moduli: two numbers, or a material file's entry (with its density and G0)
  PeriSISSM::PairCoefficients c;
  c.moduli.model = arg[2];
  std::string k_text, g_text, file_material;
  double file_g0 = 0.0, file_density = 0.0;
  if (from_file) {
    const PeriSISSM::MaterialEntry entry = read_material(arg[4], arg[5]);
    c.moduli.k = entry.bulk;
    c.moduli.g = entry.shear;
    k_text = fmt::format("{:.17g}", entry.bulk);
    g_text = fmt::format("{:.17g}", entry.shear);
    file_material = arg[5];
    file_g0 = entry.g0;
    file_density = entry.density;
  } else {
    c.moduli.k = coeff_number("bulk modulus K", arg[3], lmp);
    c.moduli.g = coeff_number("shear modulus G", arg[4], lmp);
    k_text = arg[3];
    g_text = arg[4];
  }
  c.horizon = coeff_number("horizon", arg[ih], lmp);
  // s00 = NULL: the critical stretch comes from the G0 keyword (at init, see init_style)
  const bool s00_null = strcmp(arg[ih + 1], "NULL") == 0;
  c.s00 = s00_null ? 0.0 : coeff_number("s00", arg[ih + 1], lmp);
  c.alpha = coeff_number("alpha", arg[ih + 2], lmp);

  switch (PeriSISSM::check_moduli(c.moduli)) {
    case PeriSISSM::ModuliProblem::NONE:
      break;
    case PeriSISSM::ModuliProblem::MODULUS_NOT_POSITIVE:
      error->all(FLERR, "Illegal pair_coeff peri/nosb command: {} modulus s0 must be > 0, got {}",
                 arg[2], k_text);
      break;
    case PeriSISSM::ModuliProblem::BULK_NOT_POSITIVE:
      error->all(FLERR, "Illegal pair_coeff peri/nosb command: bulk modulus K must be > 0, got {}",
                 k_text);
      break;
    case PeriSISSM::ModuliProblem::SHEAR_NOT_POSITIVE:
      error->all(FLERR, "Illegal pair_coeff peri/nosb command: shear modulus G must be > 0, got {}",
                 g_text);
      break;
    case PeriSISSM::ModuliProblem::POISSON_OUT_OF_RANGE:
      error->all(FLERR,
                 "Illegal pair_coeff peri/nosb command: K = {} and G = {} give Poisson's ratio {} "
                 "outside (-1, 0.5)",
                 k_text, g_text, PeriSISSM::poisson_from_bulk_shear(c.moduli.k, c.moduli.g));
      break;
  }
  if (c.horizon <= 0.0)
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: horizon must be > 0, got {}", arg[ih]);

  double bend_one = 0.0;
  for (int iarg = ih + 3; iarg < narg; iarg += 2) {
    const std::string key = arg[iarg];
    if (key != "stabilize" && key != "break" && key != "contact" && key != "membrane" &&
        key != "bend" && key != "G0")
      error->all(FLERR,
                 "Illegal pair_coeff peri/nosb command: unknown keyword '{}' (allowed: "
                 "stabilize, break, contact, membrane, bend, G0)",
                 key);
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, "pair_coeff peri/nosb " + key, error);
    const char *value = arg[iarg + 1];
    if (key == "stabilize") {
      c.cs = coeff_number("stabilize Cs", value, lmp);
      if (c.cs < 0.0)
        error->all(FLERR, "Illegal pair_coeff peri/nosb command: stabilize Cs must be >= 0, got {}",
                   value);
    } else if (key == "break") {
      c.breaks = utils::logical(FLERR, value, false, lmp) != 0;
    } else if (key == "contact") {
      c.contact = utils::logical(FLERR, value, false, lmp) != 0;
    } else if (key == "membrane") {
      c.membrane = utils::logical(FLERR, value, false, lmp) != 0;
    } else if (key == "bend") {
      if (strcmp(value, "auto") == 0)
        bend_one = -1.0;
      else if (strcmp(value, "no") == 0)
        bend_one = 0.0;
      else {
        bend_one = coeff_number("bend D", value, lmp);
        if (bend_one <= 0.0)
          error->all(FLERR,
                     "Illegal pair_coeff peri/nosb command: bend D must be > 0 (or auto, or no), "
                     "got {}",
                     value);
      }
    } else {    // G0
      c.g0 = coeff_number("G0", value, lmp);
      if (c.g0 <= 0.0)
        error->all(FLERR, "Illegal pair_coeff peri/nosb command: G0 must be > 0, got {}", value);
    }
  }

  if (bend_one != 0.0 && !c.membrane)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: bend is a term of membranes (add "
               "'membrane yes' to the line of type {})",
               arg[0]);

  // s00 = NULL without the G0 keyword: the material file's G0, if it gives one
  if (s00_null && c.g0 == 0.0 && file_g0 > 0.0 && c.breaks) c.g0 = file_g0;
  if (c.g0 > 0.0 && !s00_null)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: s00 = {} and G0 = {} both set the critical "
               "stretch (give s00 as NULL with G0)",
               arg[ih + 1], c.g0);
  if (c.g0 > 0.0 && !c.breaks)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: G0 = {} sets the critical stretch, but "
               "bonds cannot break with 'break no'",
               c.g0);
  if (s00_null && c.g0 == 0.0)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: s00 = NULL needs the G0 keyword (the "
               "critical energy release rate that sets the critical stretch){}",
               file_material.empty() ? ""
                                     : fmt::format("; material {} gives no G0", file_material));
  if (c.breaks && !s00_null && c.s00 <= 0.0)
    error->all(FLERR,
               "Illegal pair_coeff peri/nosb command: s00 must be > 0 when bonds can break, got "
               "{} (use 'break no' to turn bond breaking off)",
               arg[ih + 1]);
  if (c.breaks && c.alpha < 0.0)
    error->all(FLERR, "Illegal pair_coeff peri/nosb command: alpha must be >= 0, got {}",
               arg[ih + 2]);

  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      coeffs->set(i, j, c);    // with G0: s00 set at init (s00_from_fracture_energy)
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
   (K, G, Cs, horizon) and the particle spacing of its two types (pair_spacing); logged when it
   is first set or changes
------------------------------------------------------------------------- */

void PairPeriNosb::s00_from_fracture_energy()
{
  const int n = atom->ntypes;
  bool any = false;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      if (coeffs->given(i, j) && coeffs->at(i, j).g0 > 0.0) any = true;
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
      PeriSISSM::PairCoefficients &c = coeffs->at(i, j);
      if (!coeffs->given(i, j) || c.g0 <= 0.0) continue;
      double h = 0.0;
      if (!PeriSISSM::pair_spacing(total, i, j, h))
        error->all(FLERR,
                   "pair_coeff peri/nosb G0 {} for types {} {}: no particles to take the "
                   "particle spacing from",
                   c.g0, i, j);
      const double s00 =
          PeriSISSM::s00_from_fracture_energy(c.g0, c.moduli.k, c.moduli.g, c.cs, c.horizon, h);
      if (s00 != c.s00 && comm->me == 0)
        utils::logmesg(lmp,
                       "peri/nosb: types {} {}: G0 = {:.6g} gives s00 = {:.6g} (K = {:.6g}, "
                       "G = {:.6g}, Cs = {:.6g}, horizon = {:.6g} = {:.5g} h)\n",
                       i, j, c.g0, s00, c.moduli.k, c.moduli.g, c.cs, c.horizon, c.horizon / h);
      c.s00 = s00;
    }
  }
}

/* ----------------------------------------------------------------------
   the coefficients of all type pairs (G0, mixing, mirror) and the model they configure; the
   per-type-pair horizon and contact flag for init_one and the contact candidates
------------------------------------------------------------------------- */

void PairPeriNosb::configure_model()
{
  s00_from_fracture_energy();    // G0 keyword: s00 of those type pairs (before mixing)
  check_material_density();      // types whose K and G came from a material file
  coeffs->complete();
  coeffs->configure(*model_);
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) {
      cut[i][j] = coeffs->at(i, j).horizon;
      contactflag[i][j] = coeffs->at(i, j).contact ? 1 : 0;
    }
  any_break = coeffs->any_break() ? 1 : 0;
  any_contact = coeffs->any_contact() ? 1 : 0;
}

/* ---------------------------------------------------------------------- */

double PairPeriNosb::init_one(int i, int j)
{
  if (setflag[i][j] == 0) did_mix = true;
  return cut[i][j];
}

/* ----------------------------------------------------------------------
   proc 0 writes to restart file: per given type pair the model's name, the flags break,
   contact, membrane and K, G, horizon, s00, alpha, Cs; then the bending moduli per type
------------------------------------------------------------------------- */

void PairPeriNosb::write_restart(FILE *fp)
{
  const int version = RESTART_VERSION;
  fwrite(&version, sizeof(int), 1, fp);
  for (int i = 1; i <= atom->ntypes; i++) {
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (!setflag[i][j]) continue;
      const PeriSISSM::PairCoefficients &c = coeffs->at(i, j);
      const int len = (int) c.moduli.model.size() + 1;
      fwrite(&len, sizeof(int), 1, fp);
      fwrite(c.moduli.model.c_str(), sizeof(char), len, fp);
      const int iv[3] = {c.breaks ? 1 : 0, c.contact ? 1 : 0, c.membrane ? 1 : 0};
      const double dv[6] = {c.moduli.k, c.moduli.g, c.horizon, c.s00, c.alpha, c.cs};
      fwrite(iv, sizeof(int), 3, fp);
      fwrite(dv, sizeof(double), 6, fp);
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
      if (std::find(names.begin(), names.end(), std::string(name.data())) == names.end())
        error->all(FLERR,
                   "Pair peri/nosb: restart file names model '{}', which this build does not "
                   "have (allowed: {})",
                   name.data(), PeriSISSM::material_names_joined());
      PeriSISSM::PairCoefficients c;
      c.moduli.model = name.data();
      c.breaks = iv[0] != 0;
      c.contact = iv[1] != 0;
      c.membrane = iv[2] != 0;
      c.moduli.k = dv[0];
      c.moduli.g = dv[1];
      c.horizon = dv[2];
      c.s00 = dv[3];
      c.alpha = dv[4];
      c.cs = dv[5];
      coeffs->set(i, j, c);
    }
  }
  bend.assign(atom->ntypes + 1, 0.0);
  if (me == 0)
    utils::sfread(FLERR, bend.data() + 1, sizeof(double), atom->ntypes, fp, nullptr, error);
  MPI_Bcast(bend.data() + 1, atom->ntypes, MPI_DOUBLE, 0, world);
}
