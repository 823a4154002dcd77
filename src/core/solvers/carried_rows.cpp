// The per-atom rows of an implicit step carried across a neighbor list build (carried_rows.h).

#include "solvers/carried_rows.h"

#include <unordered_map>
#include <utility>

namespace PeriSISSM {

CarriedRows::CarriedRows(std::vector<CarriedArray> arrays)
{
  set_arrays(std::move(arrays));
}

void CarriedRows::set_arrays(std::vector<CarriedArray> arrays)
{
  arrays_ = std::move(arrays);
  width_ = 4;
  for (const CarriedArray &a : arrays_) width_ += a.cols;
}

void CarriedRows::pack(int n, const std::int64_t *id, const double *const *x)
{
  records_.resize((std::size_t) n * width_);
  for (int i = 0; i < n; i++) {
    double *r = records_.data() + (std::size_t) i * width_;
    *r++ = (double) id[i];
    for (int k = 0; k < 3; k++) *r++ = x[i][k];
    for (const CarriedArray &a : arrays_) {
      if (a.vector) {
        *r++ = a.vector[i];
        continue;
      }
      for (int k = 0; k < a.cols; k++) *r++ = a.rows[i][k];
    }
  }
}

std::vector<double> CarriedRows::departed(const std::function<bool(std::int64_t)> &owned) const
{
  std::vector<double> out;
  for (std::size_t r = 0; r < records_.size(); r += width_)
    if (!owned((std::int64_t) records_[r]))
      out.insert(out.end(), records_.begin() + r, records_.begin() + r + width_);
  return out;
}

void CarriedRows::write(int i, const double *xi, const double *record)
{
  // how far the atom moved since pack() (0 unless it was wrapped)
  const double shift[3] = {xi[0] - record[1], xi[1] - record[2], xi[2] - record[3]};
  const double *r = record + 4;
  for (const CarriedArray &a : arrays_) {
    if (a.vector) {
      a.vector[i] = *r++;
      continue;
    }
    for (int k = 0; k < a.cols; k++) {
      a.rows[i][k] = *r++;
      if (a.position && shift[k] != 0.0) a.rows[i][k] += shift[k];
    }
  }
}

int CarriedRows::unpack(int n, const std::int64_t *id, const double *const *x,
                        const std::vector<double> &arrived)
{
  std::unordered_map<std::int64_t, const double *> by_id;
  by_id.reserve((records_.size() + arrived.size()) / width_);
  const std::vector<double> *sets[2] = {&records_, &arrived};
  for (const std::vector<double> *set : sets)
    for (std::size_t r = 0; r + width_ <= set->size(); r += width_)
      by_id.emplace((std::int64_t)(*set)[r], set->data() + r);
  int missing = -1;
  for (int i = 0; i < n; i++) {
    const auto it = by_id.find(id[i]);
    if (it == by_id.end()) {
      if (missing < 0) missing = i;
      continue;
    }
    write(i, x[i], it->second);
  }
  return missing;
}

}    // namespace PeriSISSM
