// The per-atom rows of an implicit step carried across a neighbor list build inside the step
// (doc/fix_sissm.rst, "Contact"), where atoms may change ranks and local indices: each owned
// atom's values are packed into one record that starts with its ID, and written back by ID
// afterwards; the caller brings the records of the atoms that changed ranks to their new
// owners (departed(), then unpack() with what the other ranks sent). Rows of positions move
// by as much as the atom's own position moved in between (a periodic wrap), and are written
// back unchanged (bit for bit) when it did not move. IDs travel as doubles: exact up to 2^53.
// LAMMPS-free.

#ifndef PERISISSM_SOLVERS_CARRIED_ROWS_H
#define PERISISSM_SOLVERS_CARRIED_ROWS_H

#include <cstdint>
#include <functional>
#include <vector>

namespace PeriSISSM {

struct CarriedArray {
  double **rows = nullptr;     // rows[i][0 .. cols - 1] of atom i, or
  double *vector = nullptr;    // vector[i] (cols 1)
  int cols = 1;
  bool position = false;    // rows of positions (cols 3), moved with x[i]
};

class CarriedRows {
 public:
  explicit CarriedRows(std::vector<CarriedArray> arrays);
  // doubles per record: the ID, the position and the columns of every array
  int width() const { return width_; }
  // Inputs: n owned atoms, their IDs and positions. Keeps one record per atom.
  void pack(int n, const std::int64_t *id, const double *const *x);
  // the records kept by pack() of the atoms for which owned(ID) is false, one after the other
  std::vector<double> departed(const std::function<bool(std::int64_t)> &owned) const;
  // Inputs: n owned atoms, their IDs and positions (the arrays reallocated as needed, at least
  // n rows), the records other ranks sent (`arrived`, whole records). Output: each atom's rows
  // from the record with its ID among those kept and those arrived. Returns the index of the
  // first atom without a record, -1 when every atom has one.
  int unpack(int n, const std::int64_t *id, const double *const *x,
             const std::vector<double> &arrived);
  // the arrays to write unpack() into, when reallocation moved them
  void set_arrays(std::vector<CarriedArray> arrays);

 private:
  std::vector<CarriedArray> arrays_;
  int width_ = 1;
  std::vector<double> records_;
  void write(int i, const double *xi, const double *record);
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_CARRIED_ROWS_H
