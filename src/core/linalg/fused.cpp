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

bool fused_passes_available()
{
  static const bool available = [] {
    const char *choice = std::getenv("PERI_SISSM_PASSES");
    if (choice && std::strcmp(choice, "plain") == 0) return false;
    return x86_64_v3();
  }();
  return available;
}

namespace {
  // -1: not chosen (fused_passes_available() decides), 0: plain, 1: fused
  int chosen_passes = -1;
}    // namespace

void set_fused_passes(bool fused)
{
  chosen_passes = (fused && x86_64_v3()) ? 1 : 0;
}

bool fused_passes()
{
  if (chosen_passes < 0) return fused_passes_available();
  return chosen_passes == 1;
}

const char *fused_passes_description()
{
  return fused_passes() ? "with fused multiply-add (x86-64-v3; PERI_SISSM_PASSES=plain: without)"
                        : "without fused multiply-add";
}

}    // namespace PeriSISSM
