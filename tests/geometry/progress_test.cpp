// Progress lines of long stages (geometry/progress.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "geometry/interrupt.h"
#include "geometry/progress.h"

namespace rockmass {
namespace {

TEST(Progress, ReportsEachTenthAndEstimatesWhatIsLeftLinearly) {
  double now = 100.0;
  std::vector<std::string> lines;
  Progress progress(
      "dda", 200.0, "steps", 30.0, [&](const std::string& l) { lines.push_back(l); },
      [&] { return now; });
  now = 110.0;
  progress.update(10.0);  // 5 %: no tenth reached, 10 s < 30 s
  EXPECT_TRUE(lines.empty());
  now = 120.0;
  progress.update(40.0, "t = 0.08 s");  // 20 %: a tenth passed
  ASSERT_EQ(lines.size(), 1u);
  // 20 s for 40 of 200 steps: 80 s left at that rate.
  EXPECT_EQ(lines[0], "dda:  20 % (40 of 200 steps), 20 s, about 80 s left, t = 0.08 s");
  progress.update(41.0);  // same tenth, no time passed
  EXPECT_EQ(lines.size(), 1u);
  now = 151.0;
  progress.update(42.0);  // 31 s since the last line: the interval
  ASSERT_EQ(lines.size(), 2u);
  now = 400.0;
  progress.update(200.0);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[2], "dda: 100 % (200 of 200 steps), 5.0 min");  // done: nothing left
}

TEST(Progress, AnInterruptionStopsTheStageAtItsNextReport) {
  Progress progress("rqd: grid", 1.0, "cells", 30.0, [](const std::string&) {});
  requestInterrupt(2);
  EXPECT_THROW(progress.update(0.5), Interrupted);
  clearInterrupt();
  EXPECT_NO_THROW(progress.update(0.6));
}

}  // namespace
}  // namespace rockmass
