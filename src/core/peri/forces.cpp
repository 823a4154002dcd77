// One force evaluation of the bond terms (see forces.h).

#include "peri/forces.h"

#include "peri/elastic.h"
#include "peri/model.h"
#include "peri/stabilization.h"

namespace PeriSISSM {

void tally_energy_densities(int n, const double *w, double *total, double *peratom)
{
  for (int i = 0; i < n; i++) {
    if (total) *total += w[i];
    if (peratom) peratom[i] += w[i];
  }
}

void evaluate_bond_terms(const Model &model, const Particles &p, const Families &fam,
                         const ReferenceBox &box, int mode, double **block, ParticleFields &fields,
                         Halo &halo, const Virial &virial, std::vector<int> &broke)
{
  const bool blocks = block != nullptr;
  elastic_state_pass(model, p, fam, box, mode, blocks, fields, broke);
  const HaloField state[2] = {{fields.g, ParticleFields::NG}, {fields.k, ParticleFields::NK}};
  if (model.any_stabilization()) {
    halo.forward(state, blocks ? 2 : 1);
    stabilization_pass(model, p, fam, box, fields, virial, fields.energy);
  } else if (blocks) {
    halo.forward(state + 1, 1);
  }
  halo.forward(fields.h, 9);
  elastic_force_pass(p, fam, box, fields, virial, block);
}

}    // namespace PeriSISSM
