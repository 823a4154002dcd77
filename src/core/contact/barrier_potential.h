// The barrier over a set of candidate pairs (candidates.h) as the forces, energies and diagonal
// stiffness blocks of their owned vertices (the IPC Toolkit's BarrierPotential over a
// collision set).
//
// Units (peridynamic atoms: f is a force density, the volume V_i of each atom given): a pair's
// energy E = kappa b(d - dmin) (times the mollifier for edges) is an energy; owned vertex k of
// the pair gets the force density -dE/dx_k / V_k and the energy density E / (n V_k) (n the
// pair's vertices, 4 or 2). Only owned vertices (Candidate::own) get shares, so a pair that
// straddles ranks is evaluated on each of them with the same positions in the same order, and
// a vertex sums its shares over the pairs in the candidates' order (by ID): the sums agree to
// the last bit however the atoms are split. LAMMPS-free.

#ifndef PERISISSM_CONTACT_BARRIER_POTENTIAL_H
#define PERISISSM_CONTACT_BARRIER_POTENTIAL_H

#include "contact/candidate_distances.h"

#include <string>

namespace PeriSISSM {

// What one pass over the candidates found (this rank)
struct BarrierTally {
  double energy_density = 0.0;    // sum of the owned vertices' energy densities
  double energy_pairs = 0.0;      // sum of the energies of the pairs this rank counts
  long nactive[3] = {0, 0, 0};    // pairs it counts within dmin + dhat, by StencilType
  long ncandidates = 0;           // pairs it counts
  double mindist = 0.0;           // the smallest distance (no larger than the one given)
  long too_close = -1;            // the first pair at or within dmin (the pass stopped there)
};

// The forces of the pairs within dmin + dhat (distances current at x) added to f of their
// owned vertices; only the near pairs of distances are looked at (candidate_distances.h: the
// far ones are beyond the range and the smallest distance). Inputs: the candidates, their
// distances at x, x, the volumes, the barrier's parameters, the smallest distance to start
// from. Outputs: f; the pairs within the range (indices, ascending) in active unless nullptr;
// returns the tally.
BarrierTally barrier_forces(const std::vector<Candidate> &candidates,
                            const CandidateDistances &distances, const double *const *x,
                            const double *volume, const BarrierParameters &prm, double mindist,
                            double **f, std::vector<int> *active = nullptr);

// The error for the pair too_close of a tally at the given distance: named by kind and IDs,
// with dmin (the barrier is infinite there)
std::string too_close_error(const Candidate &c, double distance, double dmin);

// The 3x3 diagonal blocks of the PSD-projected Hessians of the pairs listed in active (those
// within dmin + dhat at x: barrier_forces()), divided by each owned vertex's volume, added to
// block (xx yy zz xy xz yz per atom).
void barrier_blocks(const std::vector<Candidate> &candidates, const std::vector<int> &active,
                    const double *const *x, const double *volume, const BarrierParameters &prm,
                    double **block);

// The 3x3 diagonal blocks of a pair's Hessian H (nv vertices) divided by the volume of each
// owned vertex (own: local indices, -1 for the others), added to block (xx yy zz xy xz yz).
void add_diagonal_blocks(const Matrix12d &H, int nv, const int *own, const double *volume,
                         double **block);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_BARRIER_POTENTIAL_H
