/* PERI-SISSM core: the bookkeeping of bond partners by atom ID (fix nosb/family, after every
   neighbor list build). Families refer to partners by ID; these functions find each partner's
   local row, and break the bonds whose partner no longer exists or whose ID was given to a new
   atom. They work on the rows of one process; the glue gathers the IDs of all processes and
   reduces the counts. Id is the integer type of atom IDs.
*/
#ifndef PERISISSM_PERI_FAMILY_IDS_H
#define PERISISSM_PERI_FAMILY_IDS_H

#include "peri/family_records.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace PeriSISSM {

// Rows 0..n-1 with current IDs tag: a row without a family of its own (owntag 0, an atom
// created after the families) takes its ID as owntag, and its ID is appended to reused when it
// is at most tagmax0 (the largest ID when the families were built: the ID of a deleted atom
// given to a new one). Returns true when some row's owntag differs from its ID (renumbered).
template <class Id>
bool adopt_ids(const FamilyArrays<Id> &a, int n, const Id *tag, Id tagmax0, std::vector<Id> &reused)
{
  bool renumbered = false;
  for (int i = 0; i < n; i++) {
    if (a.owntag[i] == 0) {
      a.owntag[i] = tag[i];
      if (tag[i] <= tagmax0) reused.push_back(tag[i]);
    }
    if (a.owntag[i] != tag[i]) renumbered = true;
  }
  return renumbered;
}

// Breaks (partner ID 0) the bonds of rows 0..n-1 to the IDs in ids (sorted ascending); each
// row that lost a bond is appended to reshape. Returns the bonds broken.
template <class Id>
int break_bonds_to(const FamilyArrays<Id> &a, int n, const std::vector<Id> &ids,
                   std::vector<int> &reshape)
{
  int nbroken = 0;
  for (int i = 0; i < n; i++) {
    bool broke = false;
    for (int b = 0; b < a.npartner[i]; b++) {
      if (a.partner[i][b] && std::binary_search(ids.begin(), ids.end(), a.partner[i][b])) {
        a.partner[i][b] = 0;
        broke = true;
        nbroken++;
      }
    }
    if (broke) reshape.push_back(i);
  }
  return nbroken;
}

// jlocal of every bond of rows 0..n-1: -1 for a broken bond, else locate(i, id), the local row
// of the image of partner id to use for row i, or -1 when the partner is not on this process
// (then (row, slot) is appended to missing, in row and slot order).
template <class Id, class Locate>
void locate_partners(const FamilyArrays<Id> &a, int n, Locate locate,
                     std::vector<std::pair<int, int>> &missing)
{
  for (int i = 0; i < n; i++) {
    for (int b = 0; b < a.npartner[i]; b++) {
      const Id id = a.partner[i][b];
      a.jlocal[i][b] = id ? locate(i, id) : -1;
      if (id && a.jlocal[i][b] < 0) missing.emplace_back(i, b);
    }
  }
}

// Breaks the bonds of the (row, slot) pairs of missing (in row order, as locate_partners gives
// them); each row once appended to reshape.
template <class Id>
void break_missing(const FamilyArrays<Id> &a, const std::vector<std::pair<int, int>> &missing,
                   std::vector<int> &reshape)
{
  for (size_t k = 0; k < missing.size(); k++) {
    a.partner[missing[k].first][missing[k].second] = 0;
    if (k == 0 || missing[k].first != missing[k - 1].first) reshape.push_back(missing[k].first);
  }
}

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FAMILY_IDS_H
