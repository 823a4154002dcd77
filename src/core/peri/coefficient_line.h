// One line of pair_coeff peri/nosb read into coefficients and checked (doc/pair_peri_nosb.rst):
//
//   I J MODEL K G horizon s00 alpha [keyword value ...]
//   I J MODEL material FILE NAME horizon s00 alpha [keyword value ...]
//
// keywords stabilize Cs, deviation length|vector, break yes/no, contact yes/no, membrane yes/no,
// bend D|auto|no, bending plate|hinge, G0 value (s00 = NULL with G0). The caller reads numbers, yes/no values and
// material file entries (LAMMPS: utils::numeric, utils::logical and the potential-file path);
// the rules of the line and the wording of its errors are here, so that they can be tested
// without LAMMPS.

#ifndef PERISISSM_PERI_COEFFICIENT_LINE_H
#define PERISISSM_PERI_COEFFICIENT_LINE_H

#include "materials/material_file.h"
#include "peri/coefficients.h"

#include <functional>
#include <string>
#include <vector>

namespace PeriSISSM {

// A line as read: its coefficients, the bending keyword and its material file entry.
struct CoefficientLine {
  PairCoefficients c;           // with G0: s00 0 (set from g0 at init)
  double bend = 0.0;            // bend keyword: D > 0, -1 auto, 0 no bending
  bool length_given = false;    // deviation length was given
  bool bending_given = false;   // bending plate|hinge was given
  std::string material;         // name of the material file entry, "" when K and G are numbers
  double density = 0.0;         // that entry's density (0: none)
};

// The caller's readers. number(what, text): the number text, or an error naming what (does not
// return); logical(text): yes/no and their synonyms, or an error; material(file, name): the
// entry in the current units, or an error.
struct CoefficientReaders {
  std::function<double(const std::string &what, const std::string &text)> number;
  std::function<bool(const std::string &text)> logical;
  std::function<MaterialEntry(const std::string &file, const std::string &name)> material;
};

// The keywords after alpha, as the error of an unknown keyword lists them.
const std::vector<std::string> &coefficient_keywords();

// Reads args (all of the line, types first; the types are not read) into line, in the order of
// the arguments, with the checks of each value as it is read and then those of the whole line
// (s00 and G0, bend and membrane). A material file's G0 sets the critical stretch when s00 is
// NULL, bonds can break and no G0 keyword is given.
// Returns "" or the first problem as a LAMMPS error message ("Illegal pair_coeff peri/nosb
// command: ...", "Incorrect number of args for pair_coeff peri/nosb command: ...",
// "Illegal pair_coeff peri/nosb KEYWORD command: missing argument(s)"); line is then partial.
std::string read_coefficient_line(const std::vector<std::string> &args,
                                  const CoefficientReaders &read, CoefficientLine &line);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_COEFFICIENT_LINE_H
