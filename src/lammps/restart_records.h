/* -*- c++ -*- ----------------------------------------------------------
   PERI-SISSM: correspondence peridynamics with SVD-split stresses for LAMMPS.

   The two restart records of LAMMPS's fixes, written and found as Modify expects them: the
   global record (its size in bytes, then the values; rank 0 writes it) and the per-atom
   record (its length, counting itself, first; the records of an atom's fixes follow each other
   in atom->extra).
------------------------------------------------------------------------- */

#ifndef LMP_PERISISSM_RESTART_RECORDS_H
#define LMP_PERISISSM_RESTART_RECORDS_H

#include <cstdio>

namespace LAMMPS_NS {

inline void write_global_record(FILE *fp, int me, const double *list, int n)
{
  if (me != 0) return;
  const int size = n * (int) sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), n, fp);
}

// an atom's record of the nth fix with per-atom restart data (its length first)
inline double *fix_record(double **extra, int i, int nth)
{
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[i][m]);
  return &extra[i][m];
}

// a per-atom record written by pack(buf + 1), which returns how many values it wrote
template <class Pack> int pack_sized_record(double *buf, Pack &&pack)
{
  const int m = pack(&buf[1]) + 1;
  buf[0] = m;
  return m;
}

}    // namespace LAMMPS_NS

#endif
