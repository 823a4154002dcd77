/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, its coefficients.

   pair_coeff lines read by the core (peri/coefficient_line.h) into its table of type-pair
   coefficients (peri/coefficients.h: mixing, the model, G0, the restart section).
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"

#include "peri/breaking.h"
#include "peri/coefficient_line.h"
#include "peri/coefficients.h"
#include "peri/model.h"

#include <algorithm>
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
   pair_coeff I J MODEL K G horizon s00 alpha [keywords], or with MODEL material FILE NAME in
   place of MODEL K G: read and checked by the core (peri/coefficient_line.h) with LAMMPS's
   parsers and material files
------------------------------------------------------------------------- */

void PairPeriNosb::coeff(int narg, char **arg)
{
  PeriSISSM::CoefficientReaders read;
  read.number = [this](const std::string &what, const std::string &text) {
    if (!utils::is_double(text))
      error->all(FLERR, "Illegal pair_coeff peri/nosb command: {} must be a number, got '{}'", what,
                 text);
    return utils::numeric(FLERR, text, false, lmp);
  };
  read.logical = [this](const std::string &text) {
    return utils::logical(FLERR, text, false, lmp) != 0;
  };
  read.material = [this](const std::string &file, const std::string &name) {
    return read_material(file, name);
  };
  PeriSISSM::CoefficientLine line;
  const std::string problem =
      PeriSISSM::read_coefficient_line(std::vector<std::string>(arg, arg + narg), read, line);
  if (!problem.empty()) error->all(FLERR, problem);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds_typelabel(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, lmp, Atom::ATOM);
  utils::bounds_typelabel(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, lmp, Atom::ATOM);
  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      coeffs->set(i, j, line.c);    // with G0: s00 set at init (s00_from_fracture_energy)
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
    material_density[i] = line.density;
    material_name[i] = line.material;
    bend[i] = line.bend;
  }
}

/* ----------------------------------------------------------------------
   G0 keyword: the critical stretch of the type pairs set with G0 from the particle spacing of
   their types (core CoefficientTable::set_s00_from_g0); logged when it is first set or changes
------------------------------------------------------------------------- */

void PairPeriNosb::s00_from_fracture_energy()
{
  if (!coeffs->any_g0()) return;
  const int n = atom->ntypes;
  // per type: sum of V^(1/3) and count (index 0: all types)
  std::vector<double> local(2 * (n + 1), 0.0), total(2 * (n + 1), 0.0);
  PeriSISSM::add_spacing_sums(atom->nlocal, atom->vfrac, atom->type, local);
  MPI_Allreduce(local.data(), total.data(), 2 * (n + 1), MPI_DOUBLE, MPI_SUM, world);

  std::string log;
  int bad_i = 0, bad_j = 0;
  const bool spaced = coeffs->set_s00_from_g0(total, log, bad_i, bad_j);
  if (comm->me == 0 && !log.empty()) utils::logmesg(lmp, log);
  if (!spaced)
    error->all(FLERR,
               "pair_coeff peri/nosb G0 {} for types {} {}: no particles to take the particle "
               "spacing from",
               coeffs->at(bad_i, bad_j).g0, bad_i, bad_j);
}

/* ----------------------------------------------------------------------
   the coefficients of all type pairs (G0, mixing, mirror) and the model they configure
------------------------------------------------------------------------- */

void PairPeriNosb::configure_model()
{
  s00_from_fracture_energy();    // G0 keyword: s00 of those type pairs (before mixing)
  check_material_density();      // types whose K and G came from a material file
  coeffs->complete();
  coeffs->configure(*model_);
  any_break = coeffs->any_break() ? 1 : 0;
  any_contact = coeffs->any_contact() ? 1 : 0;
}

/* ---------------------------------------------------------------------- */

double PairPeriNosb::init_one(int i, int j)
{
  if (setflag[i][j] == 0) did_mix = true;
  return coeffs->at(i, j).horizon;
}

/* ----------------------------------------------------------------------
   proc 0 writes to restart file: the coefficients of the given type pairs and the bending
   moduli (format of peri/coefficients.h)
------------------------------------------------------------------------- */

void PairPeriNosb::write_restart(FILE *fp)
{
  const std::string bytes = PeriSISSM::coefficients_restart_bytes(*coeffs, bend);
  fwrite(bytes.data(), sizeof(char), bytes.size(), fp);
}

/* ----------------------------------------------------------------------
   proc 0 reads from restart file, bcasts the bytes it read, and every proc reads the
   coefficients from them; a file of another format version is refused (rather than read as
   garbage)
------------------------------------------------------------------------- */

void PairPeriNosb::read_restart(FILE *fp)
{
  allocate();
  std::string bytes;
  if (comm->me == 0)
    PeriSISSM::read_coefficients_restart(
        [&](void *dst, std::size_t n) {
          utils::sfread(FLERR, dst, 1, n, fp, nullptr, error);
          bytes.append((const char *) dst, n);
        },
        *coeffs, bend);
  int nbytes = (int) bytes.size();
  MPI_Bcast(&nbytes, 1, MPI_INT, 0, world);
  bytes.resize(nbytes);
  MPI_Bcast(bytes.data(), nbytes, MPI_CHAR, 0, world);
  std::size_t at = 0;
  const std::string problem = PeriSISSM::read_coefficients_restart(
      [&](void *dst, std::size_t n) {
        bytes.copy((char *) dst, n, at);    // rank 0 read as far as this reader goes
        at += n;
      },
      *coeffs, bend);
  if (!problem.empty()) error->all(FLERR, problem);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) setflag[i][j] = coeffs->given(i, j) ? 1 : 0;
}
