// Sums over all processes that do not depend on the order of the terms or on how they are
// spread over the processes.

#ifndef PERISISSM_LINALG_EXACT_SUM_H
#define PERISISSM_LINALG_EXACT_SUM_H

#include "linalg/reductions.h"

namespace PeriSISSM {

// Column sums of a table: column k of row i is t[i * stride + k] (0 <= i < n local rows,
// 0 <= k < ncol), summed over all processes with two global reductions of ncol values.
// With T the largest |term| of a column and N = red.total_rows(), every term is rounded to an
// integer multiple of 2^-q, 2^q T N < 2^61, and the integers are summed exactly: the error is
// below N 2^-q / 2, i.e. N 2^-60 (1e-12 for a million rows) relative to N T. Ordinary
// floating-point sums differ in their last bits between process counts; iterative solvers take
// their coefficients from such sums, and their iteration counts from the coefficients.
// Outputs: out[0 .. ncol-1].
void exact_sums(const double *t, int n, int stride, int ncol, Reductions &red, double *out);

// The same for one column of n contiguous terms.
double exact_sum(const double *t, int n, Reductions &red);

}    // namespace PeriSISSM

#endif    // PERISISSM_LINALG_EXACT_SUM_H
