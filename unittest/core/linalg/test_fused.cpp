// The choice of the bond passes' version: set_fused_passes() overrides what this process
// detects, and never selects the fused version where it cannot run.
#include "linalg/fused.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

TEST(FusedPasses, AvailableNeedsTheInstructionsAndNoPlainChoice)
{
  const char *choice = std::getenv("PERI_SISSM_PASSES");
  const bool plain = choice && std::string(choice) == "plain";
  EXPECT_EQ(PeriSISSM::fused_passes_available(), PeriSISSM::x86_64_v3() && !plain);
}

TEST(FusedPasses, TheSetterOverridesDetection)
{
  const bool before = PeriSISSM::fused_passes();
  PeriSISSM::set_fused_passes(false);
  EXPECT_FALSE(PeriSISSM::fused_passes());
  PeriSISSM::set_fused_passes(true);
  EXPECT_EQ(PeriSISSM::fused_passes(), PeriSISSM::x86_64_v3());
  PeriSISSM::set_fused_passes(false);
  EXPECT_FALSE(PeriSISSM::fused_passes());
  PeriSISSM::set_fused_passes(before);
  EXPECT_EQ(PeriSISSM::fused_passes(), before);
}

TEST(FusedPasses, DescriptionNamesTheVersionRun)
{
  const bool before = PeriSISSM::fused_passes();
  PeriSISSM::set_fused_passes(false);
  EXPECT_STREQ(PeriSISSM::fused_passes_description(), "without fused multiply-add");
  PeriSISSM::set_fused_passes(true);
  const std::string fused = PeriSISSM::fused_passes_description();
  EXPECT_EQ(fused.rfind("with fused multiply-add (x86-64-v3", 0) == 0, PeriSISSM::x86_64_v3());
  PeriSISSM::set_fused_passes(before);
}
