// Bond breaking (see breaking.h).

#include "peri/breaking.h"

namespace PeriSISSM {

double s00_from_fracture_energy(double g0, double k, double g, double cs, double delta, double h,
                                bool length)
{
  const double stabilization = length ? kG0CoefL * cs * k : kG0CoefS * cs * k * delta / h;
  const double modulus = kG0CoefM * (k + 4.0 * g / 3.0) + stabilization;
  return sqrt(g0 / (modulus * delta));
}

}    // namespace PeriSISSM
