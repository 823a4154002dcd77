// Every bond partner must have one image within reach: a periodic box at least two horizons
// wide in each periodic direction (the closest image of a partner would otherwise be the wrong
// one). Checked at every run, since a box can shrink or become periodic after the families
// exist. LAMMPS-free.

#ifndef PERISISSM_PERI_BOX_CHECK_H
#define PERISISSM_PERI_BOX_CHECK_H

#include "peri/family.h"

#include <string>

namespace PeriSISSM {

// Inputs:  the box (its face distances), periodic[d] != 0 for periodic directions, the largest
//          horizon.
// Outputs: "" or the error naming the first direction too narrow, its width and the horizon.
std::string periodic_box_problem(const ReferenceBox &box, const int periodic[3], double horizon);

}    // namespace PeriSISSM

#endif    // PERISISSM_PERI_BOX_CHECK_H
