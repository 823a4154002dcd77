/* PERI-SISSM core: an atom ID carried in a buffer of doubles as the bit pattern of its value as
   a 64-bit integer (as LAMMPS's ubuf does), so that any ID survives exactly. Id is the integer
   type of atom IDs (LAMMPS's tagint: int or int64_t). Used by the per-atom records of mesh
   vertices (mesh/vertex_records.h) and of bond families (peri/family_records.h).
*/
#ifndef PERISISSM_LINALG_ID_BITS_H
#define PERISISSM_LINALG_ID_BITS_H

#include <cstdint>
#include <cstring>

namespace PeriSISSM {

// an ID as a double carrying its 64-bit integer bits, and back
template <class Id> double id_bits(Id id)
{
  const int64_t v = static_cast<int64_t>(id);
  double d;
  std::memcpy(&d, &v, sizeof(d));
  return d;
}

template <class Id> Id bits_id(double d)
{
  int64_t v;
  std::memcpy(&v, &d, sizeof(v));
  return static_cast<Id>(v);
}

}    // namespace PeriSISSM

#endif    // PERISISSM_LINALG_ID_BITS_H
