// Global reductions over all processes, as a callback: the LAMMPS glue implements them with MPI
// on its communicator, serial code and the unit tests with the identity. The core never
// includes MPI.

#ifndef PERISISSM_LINALG_REDUCTIONS_H
#define PERISISSM_LINALG_REDUCTIONS_H

namespace PeriSISSM {

class Reductions {
 public:
  // element-wise maximum over all processes, in place
  virtual void max(double *values, int n) = 0;
  // element-wise sum over all processes, in place (exact: integers)
  virtual void sum(long long *values, int n) = 0;
  // the total number of rows over all processes (bounds the number of terms of a sum)
  virtual double total_rows() const = 0;

 protected:
  // not deleted through this interface (its implementations are LAMMPS styles whose
  // destructors may throw)
  ~Reductions() = default;
};

// One process: nothing to combine.
class SerialReductions : public Reductions {
 public:
  explicit SerialReductions(double rows) : rows_(rows) {}
  void max(double *, int) override {}
  void sum(long long *, int) override {}
  double total_rows() const override { return rows_; }

 private:
  double rows_;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_LINALG_REDUCTIONS_H
