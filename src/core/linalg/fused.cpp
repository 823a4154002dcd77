// Choice of the bond passes' version (see fused.h).

#include "linalg/fused.h"

#include <cstdlib>
#include <cstring>

namespace PeriSISSM {

bool fused_passes()
{
#ifdef PERISISSM_CPU_DISPATCH
  static const bool fused = [] {
    const char *choice = std::getenv("PERI_SISSM_PASSES");
    if (choice && std::strcmp(choice, "plain") == 0) return false;
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return fused;
#else
  return false;
#endif
}

}  // namespace PeriSISSM
