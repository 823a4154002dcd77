/* PERI-SISSM core: material parameter files (the .nosb files in potentials/).

   A material file is a text file in LAMMPS's potential-file conventions:

     # DATE: 2026-11-24 UNITS: si CONTRIBUTOR: ...        (first line: the unit style)
     # comments start with '#'
     # name   K        G        density   G0
     steel    1.59e11  7.75e10  7850      -      # source of the values

   one entry per line: a name, the bulk modulus K, the shear modulus G, the mass density and
   the critical energy release rate G0 ('-' when the file gives none), in the unit style of
   the UNITS: tag. The comment after an entry is its source. Names are unique in a file.

   Values are converted between the mechanical unit styles whose mass, length and time units
   are powers of ten of the SI ones (si, cgs, micro, nano); other styles (metal, real, lj,
   electron) are refused. Errors are thrown as std::runtime_error naming the file and line.
*/
#ifndef PERISISSM_CORE_MATERIAL_FILE_H
#define PERISISSM_CORE_MATERIAL_FILE_H

#include <string>
#include <utility>
#include <vector>

namespace PeriSISSM {

struct MaterialEntry {
  std::string name;
  double bulk = 0.0;       // K
  double shear = 0.0;      // G
  double density = 0.0;    // rho
  double g0 = 0.0;         // critical energy release rate; 0 = not given
  std::string source;      // the comment after the entry
  int line = 0;            // line number in the file
};

struct MaterialFile {
  std::string units;    // the UNITS: tag of the first line ("" if none)
  std::string date;     // the DATE: tag of the first line ("" if none)
  std::vector<MaterialEntry> entries;

  // the entry called name, or nullptr
  const MaterialEntry *find(const std::string &name) const;
  // the names of all entries, separated by ", "
  std::string names() const;
};

// parse the text of a material file; filename only names it in error messages
MaterialFile parse_material_file(const std::string &text, const std::string &filename);

// the entry with its values converted from unit style 'from' to 'to' (both one of si, cgs,
// micro, nano; throws std::runtime_error naming the styles otherwise)
MaterialEntry convert_material(const MaterialEntry &entry, const std::string &from,
                               const std::string &to);

// The entry NAME of material file FILE (its text, found at path) converted to unit style
// `units`, for pair_coeff peri/nosb material.
// Outputs: entry; log: the lines for the log, in order up to an error (the file's DATE, a unit
// conversion, material_summary()). Returns "" or the error message (the file cannot be parsed,
// it has no entry NAME, the units cannot be converted).
std::string read_material_entry(const std::string &text, const std::string &file,
                                const std::string &path, const std::string &name,
                                const std::string &units, MaterialEntry &entry, std::string &log);

// The log line of an entry read for pair_coeff: "Material NAME from FILE: K = .., G = ..,
// density = ..[, G0 = ..]" (6 digits), then its source on a second line when it has one.
std::string material_summary(const MaterialEntry &entry, const std::string &name,
                             const std::string &file);

// The range lo[t] .. hi[t] of the densities of n particles (rho, types 1 .. ntypes) per type t
// (vectors of ntypes + 1; lo > hi for a type without particles).
void density_ranges(int n, const double *rho, const int *type, int ntypes, std::vector<double> &lo,
                    std::vector<double> &hi);

// The warnings for types whose atoms have another density than their material's.
// Inputs:  per type t (index 0 unused): density[t] of its material (<= 0: none), the range
//          lo[t] .. hi[t] of its atoms' densities (lo > hi: no atoms), name[t] of the material.
// Outputs: (t, warning) for each type with an atom farther than 1e-6 density[t] from it.
std::vector<std::pair<int, std::string>> density_warnings(const std::vector<double> &density,
                                                          const std::vector<double> &lo,
                                                          const std::vector<double> &hi,
                                                          const std::vector<std::string> &name);

}    // namespace PeriSISSM

#endif
