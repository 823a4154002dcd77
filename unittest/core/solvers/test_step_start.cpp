// The start of an implicit step (solvers/step_start.h): kept for all rows, restored for the
// group, and the rows outside the group placed within the step.

#include "solvers/step_start.h"

#include <gtest/gtest.h>

#include <vector>

namespace {

using namespace PeriSISSM;

// n rows of cols doubles, row i column k = base + 10 i + k
struct Table {
  std::vector<std::vector<double>> data;
  std::vector<double *> ptr;
  Table(int n, int cols, double base) : data(n, std::vector<double>(cols)), ptr(n)
  {
    for (int i = 0; i < n; i++) {
      for (int k = 0; k < cols; k++) data[i][k] = base + 10 * i + k;
      ptr[i] = data[i].data();
    }
  }
  double **p() { return ptr.data(); }
};

TEST(StepStart, KeepThenRestoreGivesTheGroupItsStart)
{
  Table x(3, 3, 0.0), v(3, 3, 100.0), h(3, 2, 200.0);
  Table xs(3, 3, -1.0), vs(3, 3, -1.0), hs(3, 2, -1.0);
  const StepStart start{xs.p(), vs.p(), hs.p(), 2};
  keep_start(3, x.p(), v.p(), h.p(), start);
  EXPECT_EQ(xs.data, x.data);    // every row, in the group or not
  EXPECT_EQ(vs.data, v.data);
  EXPECT_EQ(hs.data, h.data);

  const std::vector<int> mask = {1, 0, 1};
  Rows rows;
  rows.n = 3;
  rows.mask = mask.data();
  rows.bit = 1;
  Table x2(3, 3, 7.0), v2(3, 3, 8.0), h2(3, 2, 9.0);
  restore_start(rows, start, x2.p(), v2.p(), h2.p());
  for (int i : {0, 2}) {
    EXPECT_EQ(x2.data[i], x.data[i]) << i;
    EXPECT_EQ(v2.data[i], v.data[i]) << i;
    EXPECT_EQ(h2.data[i], h.data[i]) << i;
  }
  EXPECT_EQ(x2.data[1], Table(3, 3, 7.0).data[1]);    // outside the group: left alone
  EXPECT_EQ(h2.data[1], Table(3, 2, 9.0).data[1]);
}

TEST(StepStart, OthersSitWhereTheirVelocityPutsThem)
{
  Table xend(2, 3, 1.0), v(2, 3, 2.0), x(2, 3, 50.0);
  const std::vector<int> mask = {0, 1};
  Rows rows;
  rows.n = 2;
  rows.mask = mask.data();
  rows.bit = 1;
  const StepStart start{xend.p(), nullptr, nullptr, 0};
  place_others(rows, start, v.p(), 0.5, 0.25, x.p());
  for (int k = 0; k < 3; k++) EXPECT_DOUBLE_EQ(x.data[0][k], (1.0 + k) - 0.75 * 0.5 * (2.0 + k));
  EXPECT_EQ(x.data[1], Table(2, 3, 50.0).data[1]);    // the group: left alone
  place_others(rows, start, v.p(), 0.5, 1.0, x.p());
  EXPECT_EQ(x.data[0], xend.data[0]);    // the end of the step: the end positions
}

TEST(StepStart, ForceAtTheStartOfTheGroupAndNoHistoryForOthers)
{
  Table f(2, 3, 1.0), fstart(2, 3, -1.0), h(2, 2, 5.0);
  const std::vector<int> mask = {0, 1};
  Rows rows;
  rows.n = 2;
  rows.mask = mask.data();
  rows.bit = 1;
  keep_start_force(rows, f.p(), fstart.p(), h.p(), 2);
  EXPECT_EQ(fstart.data[1], f.data[1]);
  EXPECT_EQ(fstart.data[0], Table(2, 3, -1.0).data[0]);       // outside: no force kept
  EXPECT_EQ(h.data[0], (std::vector<double>{5.0, 0.0}));      // and no history
  EXPECT_EQ(h.data[1], (std::vector<double>{15.0, 16.0}));    // the group's history: kept
}

}    // namespace
