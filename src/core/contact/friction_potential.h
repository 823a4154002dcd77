// Lagged friction over a set of candidate pairs (candidates.h): the lagged data of the active
// pairs and the forces and diagonal blocks of their owned vertices (friction.h has the pair's
// potential; the IPC Toolkit's FrictionPotential over a friction collision set).
//
// The lagged pairs are built from the candidates at positions x^n (the active ones: within
// dmin + dhat, lambda > 0) and keep the local indices of their points, their owned vertices
// (valid while the candidates' local indices are) and x^n. The slip u of a pair is x - x^n of
// its points (implicit steps) or v dt (explicit steps, as the caller chooses in slip()). Forces
// are densities like the barrier's (barrier_potential.h): owned vertex k gets -dD/du_k / V_k.
// LAMMPS-free.

#ifndef PERISISSM_CONTACT_FRICTION_POTENTIAL_H
#define PERISISSM_CONTACT_FRICTION_POTENTIAL_H

#include "contact/candidates.h"

#include <vector>

namespace PeriSISSM {

struct LaggedPair {
  int v[4];         // local indices of the images used at the build
  int own[4];       // the owned vertices (-1: others)
  bool counts;      // this rank counts the pair
  double xn[12];    // the points' positions at the build
  FrictionPair pair;
};

// IPC's default slip speed below which friction is smoothed, 1e-3 m/s, in the velocity units
// whose angstrom and femtosecond are the given numbers (1 m/s = 1e10 A / 1e15 fs)
double default_slip_speed(double angstrom, double femtosecond);

// The lagged pairs of the candidates at positions x (their v) with the barrier's parameters.
void build_lagged_pairs(const std::vector<Candidate> &candidates, const double *const *x,
                        const BarrierParameters &prm, std::vector<LaggedPair> &lagged);

// The slip of a pair: x - x^n of its points (vel null) or vel dt
Vector12d lagged_slip(const LaggedPair &p, const double *const *x, const double *const *vel,
                      double dt);

// What one pass found (pairs this rank counts)
struct FrictionTally {
  long npairs = 0;
  double work = 0.0;    // sum mu lambda f1(y) y: the work of the friction force over the slip
};

// The friction force densities of every lagged pair's owned vertices added to f (slip as in
// lagged_slip()).
FrictionTally friction_forces(const std::vector<LaggedPair> &lagged, const double *const *x,
                              const double *const *vel, double dt, const FrictionParameters &prm,
                              const double *volume, double **f);

// The diagonal blocks of the friction Hessians (at the slip x - x^n) divided by the volumes,
// added to block (xx yy zz xy xz yz).
void friction_blocks(const std::vector<LaggedPair> &lagged, const double *const *x,
                     const FrictionParameters &prm, const double *volume, double **block);

}    // namespace PeriSISSM

#endif    // PERISISSM_CONTACT_FRICTION_POTENTIAL_H
