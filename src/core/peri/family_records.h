/* PERI-SISSM core: the per-atom records of the bond families as fix nosb/family keeps them.
   Rows of the arrays are atoms; Id is the integer type of atom IDs (LAMMPS's tagint: int or
   int64_t). Buffers of doubles carry an ID as the bit pattern of its value as a 64-bit integer
   (mesh/vertex_records.h id_bits, as LAMMPS's ubuf does), so that any ID survives exactly.

   Exchange and restart record (pack_family): n unbroken bonds; n x (partner ID, omega); K^-1
   (9); regular flag; vinit; lamref; owntag. Broken bonds (partner ID 0) are left out, so a row
   read back has only unbroken bonds; jlocal is not part of the record.

   Global restart record (pack_family_globals, format version kFamilyRestartVersion): version,
   built flag, maxpartner, periodic flags (3), reference box (6), tagmax0 (as ID bits).
*/
#ifndef PERISISSM_PERI_FAMILY_RECORDS_H
#define PERISISSM_PERI_FAMILY_RECORDS_H

#include "linalg/id_bits.h"
#include "peri/family.h"

#include <algorithm>

namespace PeriSISSM {

// doubles of a record after its bonds: K^-1 (9), regular, vinit, lamref, owntag
constexpr int kFamilyAtomScalars = 13;
// doubles per bond of a record: partner ID, omega
constexpr int kFamilyBondScalars = 2;

// the rows of the per-atom arrays
template <class Id> struct FamilyArrays {
  int *npartner;     // bond slots of each row (broken ones included)
  Id **partner;      // partner IDs, 0 = broken bond
  double **omega;    // weight of each bond
  int **jlocal;      // local index of each partner (closest image), -1 = broken or not here
  double **kinv;     // K^-1 (row-major 3x3)
  int *kregular;     // 1 if K is regular
  double *vinit;     // sum of omega over the initial family
  double *lamref;    // largest eigenvalue of the initial K
  Id *owntag;        // the atom's ID when its family was stored, 0 = none yet
};

// doubles of the record of a row with nbonds unbroken bonds
inline int family_record_size(int nbonds)
{
  return 1 + kFamilyAtomScalars + kFamilyBondScalars * nbonds;
}

// unbroken bonds of row i
template <class Id> int unbroken_bonds(const FamilyArrays<Id> &a, int i)
{
  int n = 0;
  for (int b = 0; b < a.npartner[i]; b++)
    if (a.partner[i][b]) n++;
  return n;
}

// row i has no family: no bonds, K^-1, regular flag, vinit, lamref and owntag zero
template <class Id> void clear_family(const FamilyArrays<Id> &a, int i)
{
  a.npartner[i] = 0;
  for (int k = 0; k < 9; k++) a.kinv[i][k] = 0.0;
  a.kregular[i] = 0;
  a.vinit[i] = 0.0;
  a.lamref[i] = 0.0;
  a.owntag[i] = 0;
}

// row j := row i (every slot, broken ones and jlocal included)
template <class Id> void copy_family(const FamilyArrays<Id> &a, int i, int j)
{
  a.npartner[j] = a.npartner[i];
  for (int b = 0; b < a.npartner[i]; b++) {
    a.partner[j][b] = a.partner[i][b];
    a.omega[j][b] = a.omega[i][b];
    a.jlocal[j][b] = a.jlocal[i][b];
  }
  for (int k = 0; k < 9; k++) a.kinv[j][k] = a.kinv[i][k];
  a.kregular[j] = a.kregular[i];
  a.vinit[j] = a.vinit[i];
  a.lamref[j] = a.lamref[i];
  a.owntag[j] = a.owntag[i];
}

// Inputs: row i. Outputs: its record in buf. Returns the doubles written.
template <class Id> int pack_family(const FamilyArrays<Id> &a, int i, double *buf)
{
  int m = 1, n = 0;
  for (int b = 0; b < a.npartner[i]; b++) {
    if (a.partner[i][b] == 0) continue;
    buf[m++] = id_bits(a.partner[i][b]);
    buf[m++] = a.omega[i][b];
    n++;
  }
  buf[0] = n;
  for (int k = 0; k < 9; k++) buf[m++] = a.kinv[i][k];
  buf[m++] = a.kregular[i];
  buf[m++] = a.vinit[i];
  buf[m++] = a.lamref[i];
  buf[m++] = id_bits(a.owntag[i]);
  return m;
}

// Inputs: a record in buf. Outputs: row i (jlocal untouched). Returns the doubles read.
template <class Id> int unpack_family(const FamilyArrays<Id> &a, int i, const double *buf)
{
  int m = 0;
  a.npartner[i] = static_cast<int>(buf[m++]);
  for (int b = 0; b < a.npartner[i]; b++) {
    a.partner[i][b] = bits_id<Id>(buf[m++]);
    a.omega[i][b] = buf[m++];
  }
  for (int k = 0; k < 9; k++) a.kinv[i][k] = buf[m++];
  a.kregular[i] = static_cast<int>(buf[m++]);
  a.vinit[i] = buf[m++];
  a.lamref[i] = buf[m++];
  a.owntag[i] = bits_id<Id>(buf[m++]);
  return m;
}

// doubles of the global restart record, and its format version (2: the first with a version)
constexpr int kFamilyGlobals = 13;
constexpr int kFamilyRestartVersion = 2;

// Inputs: whether the families exist, the largest family, the reference box, the largest atom
// ID when they were built. Outputs: the global restart record in g.
template <class Id>
void pack_family_globals(int built, int maxpartner, const ReferenceBox &box, Id tagmax0,
                         double g[kFamilyGlobals])
{
  g[0] = kFamilyRestartVersion;
  g[1] = built;
  g[2] = maxpartner;
  for (int k = 0; k < 3; k++) g[3 + k] = box.periodic[k];
  for (int k = 0; k < 6; k++) g[6 + k] = box.box[k];
  g[12] = id_bits(tagmax0);
}

// Inputs: a global restart record. Outputs: as pack_family_globals takes them (maxpartner at
// least 1). Returns false, reading nothing, when the record is of another format version.
template <class Id>
bool unpack_family_globals(const double g[kFamilyGlobals], int &built, int &maxpartner,
                           ReferenceBox &box, Id &tagmax0)
{
  if (g[0] != (double) kFamilyRestartVersion) return false;
  built = static_cast<int>(g[1]);
  maxpartner = std::max(static_cast<int>(g[2]), 1);
  for (int k = 0; k < 3; k++) box.periodic[k] = static_cast<int>(g[3 + k]);
  for (int k = 0; k < 6; k++) box.box[k] = g[6 + k];
  tagmax0 = bits_id<Id>(g[12]);
  return true;
}

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FAMILY_RECORDS_H
