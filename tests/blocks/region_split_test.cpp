// The kd split's level rule, shared by both cutters (blocks/region_split.h).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "blocks/region_split.h"

namespace rockmass::blocks {
namespace {

using geometry::Box;
using geometry::Vec3;

TEST(RegionSplit, TakesTheMiddleUnlessAPlaneLiesThereThenStepsOutBy67ths) {
  const Box box{Vec3(0, 0, 0), Vec3(67, 10, 5)};
  EXPECT_EQ(longestAxis(box), 0);
  EXPECT_EQ(freeSplitLevel(
                box, 0, [](double) { return false; }, "test"),
            33.5);
  // The middle and the first level below it taken: the first level above it (34.5).
  std::vector<double> tried;
  const double level = freeSplitLevel(
      box, 0,
      [&](double x) {
        tried.push_back(x);
        return x <= 33.5;
      },
      "test");
  EXPECT_EQ(level, 34.5);
  EXPECT_EQ(tried, (std::vector<double>{33.5, 32.5, 34.5}));
}

TEST(RegionSplit, EveryLevelTakenIsAnErrorNamingTheCutter) {
  // One failure behaviour for both cutters: after kSplitAttempts levels, an error (a region
  // face in a disc would glue blocks across it).
  const Box box{Vec3(0, 0, 0), Vec3(1, 2, 1)};
  int calls = 0;
  try {
    freeSplitLevel(
        box, longestAxis(box),
        [&](double) {
          ++calls;
          return true;
        },
        "fast cutter");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("fast cutter: no free splitting plane found along y"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(calls, kSplitAttempts);
}

}  // namespace
}  // namespace rockmass::blocks
