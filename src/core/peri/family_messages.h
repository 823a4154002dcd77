// The texts fix nosb/family prints about its bond families, built from numbers: the summary of
// a build and the errors and warnings of the bookkeeping by atom ID (peri/family_build.h,
// peri/family_ids.h). IDs and counts are 64-bit integers (LAMMPS's tagint and bigint).

#ifndef PERISISSM_PERI_FAMILY_MESSAGES_H
#define PERISISSM_PERI_FAMILY_MESSAGES_H

#include <cstdint>
#include <string>

namespace PeriSISSM {

// Summary of a build: bonds (slots stored over all particles), bonds per particle (0 without
// particles) and the particles with a singular shape tensor; one line each, after a title.
std::string family_summary(int64_t bonds, int64_t natoms, int64_t singular);

// Error: particle id twice in the family of particle of (order_family; a periodic box shorter
// than two horizons).
std::string partner_twice_message(int64_t id, int64_t of);

// Error: particles a and b at the same reference position (store_family).
std::string same_position_message(int64_t a, int64_t b);

// Error: particle IDs changed after the families were built (adopt_ids).
std::string renumbered_message();

// Warning: nreused new particles took IDs of deleted ones; nbroken bond ends to them break
// (break_bonds_to).
std::string reused_ids_message(int64_t nreused, int64_t nbroken);

// Warning: nbroken bond ends lost their partner (break_missing).
std::string lost_partners_message(int64_t nbroken);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_FAMILY_MESSAGES_H
