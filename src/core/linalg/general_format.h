/* PERI-SISSM core: a number in a message as printf's %.<digits>g (the same text as LAMMPS's
   fmt {:.<digits>g} for finite numbers), for the message texts the core builds.
*/
#ifndef PERISISSM_LINALG_GENERAL_FORMAT_H
#define PERISISSM_LINALG_GENERAL_FORMAT_H

#include <cstdio>
#include <string>

namespace PeriSISSM {

inline std::string general_format(double x, int digits)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*g", digits, x);
  return buf;
}

}    // namespace PeriSISSM

#endif
