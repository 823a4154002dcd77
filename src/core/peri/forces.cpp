// One force evaluation of the bond terms (see forces.h).

#include "peri/forces.h"

#include "peri/elastic.h"
#include "peri/model.h"
#include "peri/stabilization.h"

namespace PeriSISSM {

void evaluate_bond_terms(const Model &model, const Particles &p, const Families &fam,
                         const ReferenceBox &box, int mode, bool blocks, ParticleFields &fields,
                         Halo &halo, const Virial &virial, std::vector<int> &broke)
{
  elastic_state_pass(model, p, fam, box, mode, blocks, fields, broke);
  if (model.any_stabilization()) {
    halo.forward(fields.g, ParticleFields::NG);
    stabilization_pass(p, fam, box, fields, virial);
  }
  halo.forward(fields.h, 9);
  elastic_force_pass(p, fam, box, fields, virial);
}

void assemble_blocks(const Families &fam, int nlocal, ParticleFields &fields, Halo &halo,
                     double **block)
{
  halo.forward(fields.k, ParticleFields::NK);
  implicit_blocks(fam, nlocal, fields, block);
}

}  // namespace PeriSISSM
