/* ----------------------------------------------------------------------
   PERI-SISSM: pair_style peri/nosb, material files.

   pair_coeff I J MODEL material FILE NAME horizon s00 alpha [keywords]: K and G (and G0 when
   s00 is NULL) of material NAME in FILE, a material file in potentials/ (found as LAMMPS finds
   potential files: the path as given, then LAMMPS_POTENTIALS). The format and the unit
   conversion are the core's (src/core/materials/material_file.h); this file reads the file on
   rank 0, broadcasts it, and checks the atoms' density against the file's at init.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"
#include "utils.h"

#include "materials/material_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   the entry NAME of material file FILE in the current unit style (error if the file cannot
   be found or parsed, the name is unknown, or the units cannot be converted)
------------------------------------------------------------------------- */

PeriSISSM::MaterialEntry PairPeriNosb::read_material(const std::string &file,
                                                     const std::string &name)
{
  std::string text, path;
  int found = 0;
  if (comm->me == 0) {
    path = utils::get_potential_file_path(file);
    std::ifstream in(path);
    if (!path.empty() && in.is_open()) {
      std::ostringstream all;
      all << in.rdbuf();
      text = all.str();
      found = 1;
    }
  }
  MPI_Bcast(&found, 1, MPI_INT, 0, world);
  if (!found)
    error->all(FLERR,
               "pair_coeff peri/nosb material: cannot open material file {} (looked for it as "
               "given and in the folders of LAMMPS_POTENTIALS)",
               file);
  int length = (int) text.size();
  MPI_Bcast(&length, 1, MPI_INT, 0, world);
  text.resize(length);
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, world);

  PeriSISSM::MaterialEntry entry;
  try {
    const auto parsed = PeriSISSM::parse_material_file(text, file);
    if (comm->me == 0 && !parsed.date.empty())
      utils::logmesg(lmp, "Reading material file {} with DATE: {}\n", path, parsed.date);
    const auto *hit = parsed.find(name);
    if (!hit)
      error->all(FLERR, "pair_coeff peri/nosb material: no material '{}' in {} (it has: {})", name,
                 file, parsed.names());
    entry = PeriSISSM::convert_material(*hit, parsed.units, update->unit_style);
    if (comm->me == 0 && parsed.units != update->unit_style)
      utils::logmesg(lmp, "Material {} converted from {} to {} units\n", name, parsed.units,
                     update->unit_style);
  } catch (std::runtime_error &e) {
    error->all(FLERR, "pair_coeff peri/nosb material {} {}: {}", file, name, e.what());
  }
  if (comm->me == 0)
    utils::logmesg(lmp, "Material {} from {}: K = {:.6g}, G = {:.6g}, density = {:.6g}{}{}\n", name,
                   file, entry.bulk, entry.shear, entry.density,
                   entry.g0 > 0.0 ? fmt::format(", G0 = {:.6g}", entry.g0) : std::string(),
                   entry.source.empty() ? std::string() : "\n  source: " + entry.source);
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
  std::vector<double> lo(n + 1, INFINITY), hi(n + 1, -INFINITY);
  for (int i = 0; i < atom->nlocal; i++) {
    const int t = atom->type[i];
    lo[t] = std::min(lo[t], atom->rmass[i]);
    hi[t] = std::max(hi[t], atom->rmass[i]);
  }
  std::vector<double> glo(n + 1), ghi(n + 1);
  MPI_Allreduce(lo.data(), glo.data(), n + 1, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(hi.data(), ghi.data(), n + 1, MPI_DOUBLE, MPI_MAX, world);
  for (int t = 1; t <= n; t++) {
    const double rho = material_density[t];
    if (!(rho > 0.0) || glo[t] > ghi[t]) continue;    // no file, or no atoms of this type
    const double tol = 1.0e-6 * rho;
    if (std::fabs(glo[t] - rho) > tol || std::fabs(ghi[t] - rho) > tol) {
      if (comm->me == 0)
        error->warning(FLERR,
                       "Pair peri/nosb: atoms of type {} have density (rmass) {:.6g} ... {:.6g}, "
                       "but their material {} has {:.6g} (set type {} density {:.6g})",
                       t, glo[t], ghi[t], material_name[t], rho, t, rho);
      material_density[t] = 0.0;    // said once
    }
  }
}
