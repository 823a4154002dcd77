// Estimate of the stable explicit time step of a particle (doc/pair_peri_nosb.rst, "Stable time
// step"). Central differences (fix nve) are stable while dt < 2 / omega_max, omega_max^2 the
// largest eigenvalue of rho^-1 times the stiffness. At rest (F = I) the SISSM block of a
// particle is sum_j omega_ij (H_i + H_j + Cbar_ij I) with H_i = kappa_i (lambda + 2 mu) I, the
// P-wave modulus lambda + 2 mu being the largest stiffness of every model at rest: d_i I with
//   d_i = sum_j omega_ij (s_i + s_j),   s_i = kappa_i (lambda + 2 mu) + C_i / 2.
// As in the bond-based estimate of Silling and Askari (2005), dt < sqrt(2 rho / sum_j c V_j /
// |xi|), where the couplings to the partners are taken as large as the block itself (a
// Gershgorin bound), the estimate is
//   dt_i = kStableStepSafety sqrt(2 rho_i / d_i),
// with the safety factor calibrated against bisected limits: correspondence couples particles
// up to two horizons apart (through F_j), which the block does not see.

#ifndef PERISISSM_PERI_STABLE_STEP_H
#define PERISISSM_PERI_STABLE_STEP_H

namespace PeriSISSM {

class Material;
class Model;

// bisected fix nve limit / sqrt(2 rho / d), smallest value of the scene, ranged from 1.44
// (two-layer plate, Cs = 0.5) to 2.12 (impact deck, Cs = 0.5) over the calibration scenes,
// models and Cs (examples/benchmarks/stability/dt_estimate.py): 1.25 keeps the estimate 13%
// below the smallest of them and within a factor 1.7 of the largest
constexpr double kStableStepSafety = 1.25;

// s_i of a particle with a regular shape tensor: kappa (lambda + 2 mu) + C / 2.
// Inputs: material, Kinv (row-major K^-1; a membrane's in-plane K^+), C stabilization modulus,
//         membrane: kappa = tr(K^+) / 2 (the mean over the plane) instead of tr(K^-1) / 3.
double stable_step_stiffness(const Material &material, const double Kinv[9], double C,
                             bool membrane = false);

// dt_i from rho_i and d_i = sum_j omega_ij (s_i + s_j); +infinity when d_i <= 0.
double stable_time_step(double rho, double d);

// d_i = sum_j omega_ij (s_i + s_j) over the unbroken bonds of particle i, in slot order.
// Inputs: n bond slots, partner IDs (0 = broken), omega per slot; s per local row; row i of the
//         particle; locate(ID) the local row of any image of a partner, -1 when it is not here
//         (the bond then does not count). Id is the integer type of particle IDs.
template <class Id, class Locate>
double stable_step_coupling(int n, const Id *partner, const double *omega, const double *s, int i,
                            Locate locate)
{
  double d = 0.0;
  for (int b = 0; b < n; b++) {
    if (partner[b] == 0) continue;
    const int j = locate(partner[b]);
    if (j >= 0) d += omega[b] * (s[i] + s[j]);
  }
  return d;
}

// s of rows 0..n-1: stable_step_stiffness with the row's material, stabilization modulus and
// membrane flag (model, types) when its shape tensor is regular (kregular), else 0.
void stable_step_stiffnesses(const Model &model, int n, const int *type, const double *const *kinv,
                             const int *kregular, double *s);

// dt of rows 0..n-1: stable_time_step(rho_i, d_i), d_i from stable_step_coupling over the row's
// bond slots (npartner, partner, omega) with s and locate as there.
template <class Id, class Locate>
void stable_time_steps(int n, const double *rho, const int *npartner, const Id *const *partner,
                       const double *const *omega, const double *s, Locate locate, double *dt)
{
  for (int i = 0; i < n; i++)
    dt[i] = stable_time_step(rho[i],
                             stable_step_coupling(npartner[i], partner[i], omega[i], s, i, locate));
}

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_STABLE_STEP_H
