// The collision-free part of a move (the CCD path limit): the largest fraction t in [0, t_max]
// of the straight move of every candidate's points from xref to x that additive CCD (ccd.h)
// certifies for all candidates, so that no pair's gap reaches dmin on the scaled move (each
// keeps at least s = 0.1 of its gap at xref). The caller takes the minimum over its ranks and
// over the reach of its candidates (motion_tracker.h); passing that reach as t_max gives the
// same minimum and spares the queries past it (a diverged iterate's move of metres would
// otherwise take CCD's sub-step cap in every pair). LAMMPS-free.

#ifndef PERISISSM_CONTACT_PATH_LIMIT_H
#define PERISISSM_CONTACT_PATH_LIMIT_H

#include "contact/candidate_distances.h"

namespace PeriSISSM {

// Inputs: the candidates; the positions xref (admissible) and x (the move's end) of n atoms
// (owned and ghost: all the candidates' points), indexed as the candidates' v; dmin; known:
// the candidates' distances at xref when valid (nullptr or not valid: unknown); t_max in
// [0, 1]. A pair whose gap at xref cannot close by 0.9 over [0, t] (its points' moves relative
// to their mean, or their moves, bounded as in ccd.h) keeps 0.1 of it, as CCD would certify:
// it is skipped (a near pair's lower bound that does not suffice is replaced by the distance
// in known); the far pairs of known (candidate_distances.h) are skipped together when twice
// the longest move is within 0.9 of the gap they all keep. Output: returns t <= t_max.
double path_limit(const std::vector<Candidate> &candidates, const double *const *xref,
                  const double *const *x, int n, double dmin, CandidateDistances *known,
                  double t_max = 1.0);

// Whether path_limit() would return 1 for this move without looking at a pair: every point of
// the n atoms (owned and ghost: all the candidates' points) moves from xref to x by at most a
// length l with 2 l (the most any stencil's closing() can be) within (1 - s) of the smallest gap
// in known (valid, at xref: its gap_bound()). Then every moved pair passes path_limit()'s first
// test, so t = 1 and known is left as it is. A Jacobian product's probe (a move of about 1e-7
// particle sizes) is such a move. Costs a pass over the atoms.
bool move_within_gaps(const double *const *xref, const double *const *x, int n, double dmin,
                      const CandidateDistances &known);

// The move cut to the fraction t: x = xref + t (x - xref) for the atoms i < n with
// (mask[i] & groupbit).
void scale_move(const double *const *xref, double **x, int n, const int *mask, int groupbit,
                double t);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_PATH_LIMIT_H
