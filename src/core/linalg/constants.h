// Mathematical constants of the core.

#ifndef PERISISSM_LINALG_CONSTANTS_H
#define PERISISSM_LINALG_CONSTANTS_H

namespace PeriSISSM {

constexpr double kPi = 3.14159265358979323846;

}    // namespace PeriSISSM

#endif    // PERISISSM_LINALG_CONSTANTS_H
