/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, material files.

   pair_coeff I J MODEL material FILE NAME ...: the file found as LAMMPS finds potential files,
   read on rank 0 and broadcast, its entry read by the core (materials/material_file.h); the
   atoms' density checked against the file's at init.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"
#include "utils.h"

#include "materials/material_file.h"

#include <algorithm>
#include <fstream>
#include <iterator>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   the entry NAME of material file FILE in the current unit style (core read_material_entry();
   error if the file cannot be found or the entry not read)
------------------------------------------------------------------------- */

PeriSISSM::MaterialEntry PairPeriNosb::read_material(const std::string &file,
                                                     const std::string &name)
{
  std::string text, path;
  int length = -1;    // -1: not found
  if (comm->me == 0) {
    path = utils::get_potential_file_path(file);
    std::ifstream in(path);
    if (!path.empty() && in.is_open()) {
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      length = (int) text.size();
    }
  }
  MPI_Bcast(&length, 1, MPI_INT, 0, world);
  if (length < 0)
    error->all(FLERR,
               "pair_coeff peri/nosb material: cannot open material file {} (looked for it as "
               "given and in the folders of LAMMPS_POTENTIALS)",
               file);
  text.resize(length);
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, world);

  PeriSISSM::MaterialEntry entry;
  std::string log;
  const std::string problem =
      PeriSISSM::read_material_entry(text, file, path, name, update->unit_style, entry, log);
  if (comm->me == 0) utils::logmesg(lmp, log);
  if (!problem.empty()) error->all(FLERR, problem);
  return entry;
}

/* ----------------------------------------------------------------------
   warn once per type whose pair_coeff I I took a material from a file and whose atoms have
   another density (rmass) than the file's
------------------------------------------------------------------------- */

void PairPeriNosb::check_material_density()
{
  const int n = atom->ntypes;
  if ((int) material_density.size() <= n) return;
  if (std::none_of(material_density.begin(), material_density.end(), [](double d) {
        return d > 0.0;
      }))
    return;
  std::vector<double> lo, hi, glo(n + 1), ghi(n + 1);
  PeriSISSM::density_ranges(atom->nlocal, atom->rmass, atom->type, n, lo, hi);
  MPI_Allreduce(lo.data(), glo.data(), n + 1, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(hi.data(), ghi.data(), n + 1, MPI_DOUBLE, MPI_MAX, world);
  for (const auto &w : PeriSISSM::density_warnings(material_density, glo, ghi, material_name)) {
    if (comm->me == 0) error->warning(FLERR, w.second);
    material_density[w.first] = 0.0;    // said once
  }
}
