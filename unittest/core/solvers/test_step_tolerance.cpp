// The tolerance a step can meet (solvers/step_tolerance.h): the round-off term of a particle,
// the floor it sets, which rows count, and the max over processes.

#include "solvers/step_tolerance.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <vector>

namespace {

using namespace PeriSISSM;

// Another process with larger values: max() raises each value to at least those given.
class OtherProcess : public Reductions {
 public:
  explicit OtherProcess(std::vector<double> other) : other_(std::move(other)) {}
  void max(double *values, int n) override
  {
    calls++;
    for (int k = 0; k < n && k < (int) other_.size(); k++)
      values[k] = std::fmax(values[k], other_[k]);
  }
  void sum(long long *, int) override {}
  double total_rows() const override { return 3.0; }
  int calls = 0;

 private:
  std::vector<double> other_;
};

struct ThreeParticles {
  double xs[3][3] = {{1.0, -2.0, 0.5}, {-40.0, 3.0, 1.0}, {1e5, 0.0, 0.0}};
  double bs[3][6] = {{4.0, 9.0, 1.0, 100.0, 100.0, 100.0},
                     {2.0, 1.0, 3.0, 0.0, 0.0, 0.0},
                     {1.0, 1.0, 1.0, 0.0, 0.0, 0.0}};
  double *x[3] = {xs[0], xs[1], xs[2]};
  double *b[3] = {bs[0], bs[1], bs[2]};
  int mask[3] = {1, 1, 0};    // the third, far away, is not an unknown
  double size[3] = {0.5, 2.0, 1.0};
  double rho[3] = {10.0, 4.0, 1.0};
  Rows rows;
  ThreeParticles()
  {
    rows.n = 3;
    rows.mask = mask;
    rows.bit = 1;
    rows.size = size;
    rows.density = rho;
  }
};

// |x|_max / l (1 + c max(diagonal) / rho): the off-diagonal entries do not count.
TEST(StepTolerance, RoundoffTermOfOneParticle)
{
  ThreeParticles p;
  EXPECT_DOUBLE_EQ(roundoff_term(p.x[0], p.b[0], 0.5, 10.0, 0.1), 2.0 / 0.5 * (1.0 + 0.9 / 10.0));
  EXPECT_DOUBLE_EQ(roundoff_term(p.x[1], p.b[1], 2.0, 4.0, 0.0), 20.0);
  // linear in the distance from the origin
  double far[3] = {-4e6, 2e6, 0.0};
  EXPECT_DOUBLE_EQ(roundoff_term(far, p.b[1], 2.0, 4.0, 0.5),
                   2e6 * roundoff_term(p.x[0], p.b[1], 2.0, 4.0, 0.5));    // |x|: 4e6 and 2
}

TEST(StepTolerance, FloorOfTheUnknownRows)
{
  ThreeParticles p;
  SerialReductions serial(3.0);
  const double c = 0.2;
  const double largest = 40.0 / 2.0 * (1.0 + c * 3.0 / 4.0);    // the second particle
  // a tolerance above the floor is kept
  StepTolerance t = step_tolerance(1e-6, p.rows, p.x, p.b, c, serial);
  EXPECT_EQ(t.floor, 0.5 * DBL_EPSILON * largest);
  EXPECT_EQ(t.tolerance, 1e-6);
  EXPECT_EQ(t.reach, 40.0);    // the third row is not an unknown
  EXPECT_FALSE(t.roundoff_limited(1e-6));
  // one below it is raised to the floor
  t = step_tolerance(1e-16, p.rows, p.x, p.b, c, serial);
  EXPECT_EQ(t.tolerance, t.floor);
  EXPECT_TRUE(t.roundoff_limited(1e-16));
  // tolerance 0: no floor
  t = step_tolerance(0.0, p.rows, p.x, p.b, c, serial);
  EXPECT_EQ(t.floor, 0.0);
  EXPECT_EQ(t.tolerance, 0.0);
  EXPECT_FALSE(t.roundoff_limited(0.0));
}

// The largest term and coordinate over all processes, in one max of two values.
TEST(StepTolerance, MaxOverProcesses)
{
  ThreeParticles p;
  OtherProcess other({1e6, 5e5});
  const StepTolerance t = step_tolerance(1e-16, p.rows, p.x, p.b, 0.2, other);
  EXPECT_EQ(other.calls, 1);
  EXPECT_EQ(t.floor, 0.5 * DBL_EPSILON * 1e6);
  EXPECT_EQ(t.reach, 5e5);
}

}    // namespace
