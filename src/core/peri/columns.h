// The fused bond passes' copy of a 3x3 per particle by columns (ParticleFields::cols): four
// doubles per column, so that a partner's matrix comes in three 4-wide loads and M xi is three
// 4-wide multiply-adds (linalg/double4.h) instead of nine scalar ones. Filled at the start of
// the pass that reads it, for the owned and the ghost rows.

#ifndef PERISISSM_PERI_COLUMNS_H
#define PERISISSM_PERI_COLUMNS_H

#include "linalg/double4.h"
#include "peri/family.h"
#include "peri/fields.h"

namespace PeriSISSM {

// From rows of width doubles, a row-major 3x3 first: column c of row r's matrix into
// cols[NCOLS r + 4c .. +2]; lane 3 of the columns 0, 1, 2 gets row[9 + 0], row[9 + 1], 0 for
// rows of width 11 (fields.g: C and the regular flag), 0 for rows of width 9 (fields.h).
inline void fill_columns(const double *rows, int width, int n, double *cols)
{
  constexpr int NC = ParticleFields::NCOLS;
  for (int r = 0; r < n; r++) {
    const double *a = rows + static_cast<long>(width) * r;
    double *c = cols + static_cast<long>(NC) * r;
    for (int col = 0; col < 3; col++) {
      for (int k = 0; k < 3; k++) c[4 * col + k] = a[3 * k + col];
      c[4 * col + 3] = (width > 9 + col) ? a[9 + col] : 0.0;
    }
  }
}

#ifdef PERISISSM_CPU_DISPATCH
// The reference bond xi = X_j - X_i of the 4-wide passes, each component broadcast into every
// lane of x0, x1, x2 (from the partner's reference position rj and splats ri0, ri1, ri2 of
// the particle's); its minimum image in a periodic box (PBC)
template <int PBC>
PERISISSM_FUSED_TARGET [[gnu::always_inline]] inline void
bond_xi(const double *rj, Double4 ri0, Double4 ri1, Double4 ri2, const ReferenceBox &box,
        Double4 &x0, Double4 &x1, Double4 &x2)
{
  x0 = bcast(rj) - ri0;
  x1 = bcast(rj + 1) - ri1;
  x2 = bcast(rj + 2) - ri2;
  if (PBC) {
    double y0 = lane0(x0), y1 = lane0(x1), y2 = lane0(x2);
    box.image(y0, y1, y2);
    x0 = splat(y0);
    x1 = splat(y1);
    x2 = splat(y2);
  }
}
#endif

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_COLUMNS_H
