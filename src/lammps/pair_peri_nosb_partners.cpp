/* ----------------------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   pair_style peri/nosb as BondPartners (bond_partners.h): the bond partners of its families,
   for barrier contact.
------------------------------------------------------------------------- */

#include "pair_peri_nosb.h"

#include "fix_nosb_family.h"

#include "peri/family.h"
#include "peri/model.h"

#include "atom.h"

using namespace LAMMPS_NS;

bool PairPeriNosb::partners_known() const
{
  return !family || family->built;
}

bool PairPeriNosb::were_partners(int a, int b) const
{
  const tagint *tag = atom->tag;
  if (!family || tag[a] > family->tagmax0 || tag[b] > family->tagmax0) return false;
  double xi[3];
  PeriSISSM::reference_bond(atom->x0[0], family->box, a, b, xi);
  const double delta = model().horizon(atom->type[a], atom->type[b]);
  return xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2] <= delta * delta;
}
