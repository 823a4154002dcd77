/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   What barrier contact (fix nosb/contact) needs from a bonded force model: which particles are
   or were bond partners, so that no contact pair is made of two of them. pair_style peri/nosb
   implements it (pair_peri_nosb_partners.cpp: its families, broken bonds included); fix
   nosb/contact obtains it with dynamic_cast from force->pair_match("peri/nosb", 1) and sees
   nothing else of the pair.
------------------------------------------------------------------------- */

#ifndef LMP_PERISISSM_BOND_PARTNERS_H
#define LMP_PERISISSM_BOND_PARTNERS_H

namespace LAMMPS_NS {

class BondPartners {
 public:
  // the partners are known: the bond families were built (at the first run's setup; kept in
  // restart files), or the model has none
  virtual bool partners_known() const = 0;
  // whether local atoms a and b (owned or ghost) are or were bond partners: their reference
  // distance (x0, minimum image in the box the families were built in) within the horizon of
  // their types, the test the families were built with (so broken bonds count too); atoms made
  // after the families were built are no one's partners
  virtual bool were_partners(int a, int b) const = 0;

 protected:
  ~BondPartners() = default;
};

}    // namespace LAMMPS_NS

#endif
