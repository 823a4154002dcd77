// Generalized-alpha (Chung and Hulbert 1993) on the common problem (doc/theory.rst, "Time
// schemes"). With the high-frequency spectral radius rho_inf in [0, 1]:
//   alpha_m = (2 rho_inf - 1) / (rho_inf + 1),  alpha_f = rho_inf / (rho_inf + 1),
//   gamma = 1/2 - alpha_m + alpha_f,            beta = (1 - alpha_m + alpha_f)^2 / 4,
// the step
//   rho ((1 - alpha_m) a^{n+1} + alpha_m a^n) = f(u),   u = (1 - alpha_f) y^{n+1} + alpha_f y^n
//   y^{n+1} = y^n + h v^n + h^2 ((1/2 - beta) a^n + beta a^{n+1})
//   v^{n+1} = v^n + h ((1 - gamma) a^n + gamma a^{n+1})
// with the forces at the intermediate configuration u (and time t^{n+1-alpha_f}). Taking u as
// the unknown, a^{n+1} is affine in u and the step is rho (u - uhat) = c f(u) with
//   c    = beta h^2 (1 - alpha_f) / (1 - alpha_m)
//   uhat = y^n + (1 - alpha_f) (h v^n + h^2 (1/2 - beta - beta alpha_m / (1 - alpha_m)) a^n)
// and at the end y^{n+1} = y^n + (u - y^n) / (1 - alpha_f), a^{n+1} and v^{n+1} from the
// Newmark formulas. Second order for every rho_inf; rho_inf = 1 keeps every mode's amplitude
// (a linear oscillator's energy is conserved; with a consistent start a = f/rho it is the
// trapezoidal rule), rho_inf < 1 damps modes with h omega >> 1 to rho_inf per step while the
// slow ones keep their amplitude to third order; rho_inf = 0 annihilates them in one step.
// With set_forces_at_end(true): alpha_f = 0 and alpha_m = (rho_inf - 1) / (rho_inf + 1), the
// member of the family of Wood, Bossak and Zienkiewicz (1980), also second order with the
// spectral radius rho_inf at h omega -> infinity; the unknowns are then the end positions
// y^{n+1}, where a contact that checks every move of the unknowns keeps the step
// collision-free (the end of Chung and Hulbert's step lies beyond u on the same straight move,
// 1 / (1 - alpha_f) as far from y^n, unchecked).
// History per row: a^n, a^{n-1} and how many of them are valid; a row without a^n starts from
// a^n = f(y^n) / rho. The first iterate is u at a guessed a^{n+1} (uhat + c a, without the lagged
// force of the predictor; uhat alone where extrapolation is off), exact for a constant
// acceleration, so free fall converges at the first evaluation:
// - Chung and Hulbert's step where keyword error ends the solves (set_error_rule): the mean
//   (a^n + a^{n-1}) / 2 once both are known. Such a solve ends at an estimate of its error, and
//   what it leaves in the modes far beyond the step alternates in sign from step to step (the
//   scheme's roots there are -rho_inf); the mean cancels most of it, at the price of half a
//   step's lag in the smooth motion. Measured on examples/hanging-cloth (3038 vertices, 2 ms,
//   150 steps, defaults), evaluations per step with a^n -> the mean: rho_inf 1: 15.8 -> 10.1,
//   0.8: 10.15 -> 9.1, 0.65: 9.16 -> 9.05, 0.5: 8.7 -> 9.05.
// - Otherwise a^n. Solves held to a tolerance leave little in those modes, and the lag cost
//   more than the mean saved (tolerance 1e-6: the same cloth 27.7 against 26.8; the
//   cantilever of examples/cantilever at 1e-9 23.0 with both); with the forces at the end
//   (contact) the accelerations jump with the contact's impulses (examples/twisting-cloth 26.8
//   against 20.1, the cloth on a ball within the spread).
// (a^n alone: 30.7 instead of 35.0 evaluations per step from u = uhat, tolerance 1e-6.)

#ifndef PERISISSM_SOLVERS_GENERALIZED_ALPHA_H
#define PERISISSM_SOLVERS_GENERALIZED_ALPHA_H

#include "solvers/time_scheme.h"

namespace PeriSISSM {

class GeneralizedAlpha : public TimeScheme {
 public:
  // history columns: a^n (0-2), a^{n-1} (3-5), how many of them are valid (6: 0, 1 or 2)
  static constexpr int kColumns = 7;
  explicit GeneralizedAlpha(double rho_inf);
  std::string name() const override { return "genalpha"; }
  void set_forces_at_end(bool on) override;
  void set_error_rule(bool on) override { error_rule_ = on; }
  int history_columns() const override { return kColumns; }
  void set_step(double h) override;
  double force_time() const override { return 1.0 - alpha_f_; }
  void begin(const Rows &rows, const StepArrays &a) override;
  void iterate_velocity(int i, const StepArrays &a, double *vel) const override;
  void finish(const Rows &rows, const StepArrays &a) override;
  // the state: whether the next step extrapolates (TimeScheme::set_extrapolation)
  int state_size() const override { return 1; }
  void get_state(double *s) const override { s[0] = extrapolate_ ? 1.0 : 0.0; }
  void set_state(const double *s) override { extrapolate_ = s[0] != 0.0; }

 private:
  // a^{n+1} and v^{n+1} of one component from the unknown u (see above)
  void end_state(int i, int k, const StepArrays &a, double &acc, double &vel) const;
  double rho_inf_, alpha_m_, alpha_f_, gamma_, beta_;
  bool error_rule_ = false;
};

}    // namespace PeriSISSM

#endif    // PERISISSM_SOLVERS_GENERALIZED_ALPHA_H
