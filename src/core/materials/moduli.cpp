// Moduli of pair_coeff (see moduli.h).

#include "materials/moduli.h"

namespace PeriSISSM {

double poisson_from_bulk_shear(double K, double G)
{
  return (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
}

double young_from_bulk_shear(double K, double G)
{
  return 9.0 * K * G / (3.0 * K + G);
}

ModuliProblem check_moduli(const Moduli &m)
{
  const bool one = m.form() == ModuliForm::ONE_MODULUS;
  if (!(m.k > 0.0))
    return one ? ModuliProblem::MODULUS_NOT_POSITIVE : ModuliProblem::BULK_NOT_POSITIVE;
  if (one) return ModuliProblem::NONE;
  if (!(m.g > 0.0)) return ModuliProblem::SHEAR_NOT_POSITIVE;
  const double nu = poisson_from_bulk_shear(m.k, m.g);
  const LameParameters lame = lame_from_bulk_shear(m.k, m.g);
  if (!(nu > -1.0 && nu < 0.5) || !lame_parameters_admissible(lame.mu, lame.lambda))
    return ModuliProblem::POISSON_OUT_OF_RANGE;
  return ModuliProblem::NONE;
}

double bulk_modulus(const Moduli &m)
{
  return m.form() == ModuliForm::ONE_MODULUS ? 2.0 * m.k / 3.0 : m.k;
}

double young_modulus(const Moduli &m)
{
  return m.form() == ModuliForm::ONE_MODULUS ? 2.0 * m.k : young_from_bulk_shear(m.k, m.g);
}

double poisson_ratio(const Moduli &m)
{
  return m.form() == ModuliForm::ONE_MODULUS ? 0.0 : poisson_from_bulk_shear(m.k, m.g);
}

double bending_factor(const Moduli &m)
{
  const double nu = poisson_ratio(m);
  return young_modulus(m) / (12.0 * (1.0 - nu * nu));
}

std::unique_ptr<Material> make_material(const Moduli &m)
{
  if (m.form() == ModuliForm::ONE_MODULUS) return make_material(m.model, m.k, 0.0);
  const LameParameters lame = lame_from_bulk_shear(m.k, m.g);
  return make_material(m.model, lame.mu, lame.lambda);
}

}    // namespace PeriSISSM
