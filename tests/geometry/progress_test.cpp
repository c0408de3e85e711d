// Progress lines of long stages (geometry/progress.h).
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
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

// The cutters report finished regions from their worker threads: 4 threads x 250 regions.
// Each line is a new tenth (the interval is an hour, so only tenths count): the shares rise
// strictly, at most 10 lines, the last at 100 % of the total the first call gave. (Calls may
// arrive out of order: a thread holding count 899 may report after one holding 900.)
TEST(SharedProgress, SerializesCallsFromSeveralThreadsAndReportsEachTenthOnce) {
  std::vector<std::string> lines;
  SharedProgress progress("blocks: cut", "regions", 3600.0, 0.0,
                          [&](const std::string& l) { lines.push_back(l); });
  std::atomic<std::size_t> finished{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      for (int k = 0; k < 250; ++k) progress(++finished, 1000);
    });
  }
  for (std::thread& t : threads) t.join();
  ASSERT_FALSE(lines.empty());
  EXPECT_LE(lines.size(), 10u);
  int previous = -1;
  for (const std::string& line : lines) {
    const int share = std::stoi(line.substr(std::string("blocks: cut: ").size()));
    EXPECT_GT(share, previous) << line;
    previous = share;
  }
  EXPECT_EQ(lines.back().rfind("blocks: cut: 100 % (", 0), 0u) << lines.back();
  EXPECT_NE(lines.back().find("of 1000 regions"), std::string::npos) << lines.back();
}

TEST(Progress, SaysNothingInItsQuietPeriod) {
  double now = 0.0;
  std::vector<std::string> lines;
  Progress progress(
      "blocks: cut", 10.0, "regions", 30.0, [&](const std::string& l) { lines.push_back(l); },
      [&] { return now; });
  progress.setQuietPeriod(10.0);
  now = 1.0;
  progress.update(9.0);  // 90 % after 1 s: a quick stage stays silent
  EXPECT_TRUE(lines.empty());
  now = 11.0;
  progress.update(9.5);  // same tenth, 11 s since the start but the quiet period spent
  EXPECT_TRUE(lines.empty());
  progress.update(10.0);  // a new tenth after the quiet period
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "blocks: cut: 100 % (10 of 10 regions), 11 s");
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
