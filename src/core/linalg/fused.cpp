// Choice of the bond passes' version (see fused.h).

#include "linalg/fused.h"

#include <cstdlib>
#include <cstring>

namespace PeriSISSM {

bool x86_64_v3()
{
#ifdef PERISISSM_CPU_DISPATCH
  static const bool v3 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return v3;
#else
  return false;
#endif
}

bool fused_passes()
{
  static const bool fused = [] {
    const char *choice = std::getenv("PERI_SISSM_PASSES");
    if (choice && std::strcmp(choice, "plain") == 0) return false;
    return x86_64_v3();
  }();
  return fused;
}

}  // namespace PeriSISSM
