// The check of an explicit run's time step against the stable-step estimate of peri/nosb
// (peri/stable_step.h; doc/pair_peri_nosb.rst, "Stable time step"). At the setup of a run, fix
// nosb/family takes the particles that a fix moves by their forces with an explicit scheme
// (explicit_integrator), the smallest estimate over them and how many lie below the time step
// (step_excess, reduced over processes by the glue), and warns once with step_warning.

#ifndef PERISISSM_PERI_STEP_CHECK_H
#define PERISISSM_PERI_STEP_CHECK_H

#include <cstdint>
#include <string>

namespace PeriSISSM {

// Whether a fix of this style that sets LAMMPS's time_integrate flag moves its atoms by their
// forces with an explicit scheme, whose stability the estimate bounds: every such style except
// sissm (implicit), move (prescribed positions), nve/noforce (positions from the velocities
// alone) and the rigid-body styles rigid* (a particle of a body does not vibrate on its bonds).
bool explicit_integrator(const std::string &style);

// The particles of a check: the smallest estimate among them (+infinity without any), how many
// have an estimate below the time step, and how many there are.
struct StepExcess {
  double smallest;
  int64_t above;
  int64_t counted;
};

// StepExcess of rows 0..n-1 with estimates dt, counting the rows whose mask has a bit of bits,
// for time step step.
StepExcess step_excess(int n, const double *dt, const int *mask, int bits, double step);

// Warning: time step step above the smallest estimate smallest of above of the total particles
// integrated by the fixes named in fixes (e.g. "integrate (nve)").
std::string step_warning(double step, double smallest, int64_t above, int64_t total,
                         const std::string &fixes);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_STEP_CHECK_H
