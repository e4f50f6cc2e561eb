// The progress bar (core/include/femup/core/progress.h): its line, its silence when
// the output is not a terminal, and updates from several threads.
#include "femup/core/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <sstream>
#include <thread>
#include <vector>

namespace femup {
namespace {

TEST(ProgressBar, FormatShowsCountPercentElapsedAndEta) {
  const std::string line = ProgressBar::Format("noise draws", 500, 1000, 2.0, 10);
  EXPECT_EQ(line, "noise draws [#####-----]  50%  500/1000  elapsed 2.0 s  ETA 2.0 s");
}

TEST(ProgressBar, FormatAtTheEndsAndLongTimes) {
  EXPECT_NE(ProgressBar::Format("x", 0, 10, 0.0).find("ETA ?"), std::string::npos);
  EXPECT_NE(ProgressBar::Format("x", 0, 10, 0.0).find("  0%"), std::string::npos);
  const std::string done = ProgressBar::Format("x", 10, 10, 125.0, 4);
  EXPECT_EQ(done, "x [####] 100%  10/10  elapsed 2 min 05 s  ETA 0.0 s");
  EXPECT_NE(ProgressBar::Format("x", 1, 4, 1200.0).find("ETA 1 h 00 min"),
            std::string::npos);
}

TEST(ProgressBar, WritesNothingWhenNotATerminal) {
  std::ostringstream out;
  {
    ProgressBar bar("work", &out, /*is_terminal=*/false);
    bar.Update(1, 2);
    bar.Callback()(2, 2);
    bar.Finish();
  }
  EXPECT_TRUE(out.str().empty()) << out.str();
}

TEST(ProgressBar, DrawsOnATerminalAndEndsTheLine) {
  std::ostringstream out;
  {
    ProgressBar bar("work", &out, /*is_terminal=*/true, /*min_interval_seconds=*/0.0);
    bar.Update(1, 2);
    EXPECT_NE(out.str().find("50%"), std::string::npos) << out.str();
    EXPECT_EQ(out.str().front(), '\r');
    bar.Update(2, 2);
  }  // the destructor ends the line
  EXPECT_NE(out.str().find("100%  2/2"), std::string::npos) << out.str();
  EXPECT_EQ(out.str().back(), '\n');
}

TEST(ProgressBar, ThrottlesRedrawsButAlwaysDrawsTheLastItem) {
  std::ostringstream out;
  ProgressBar bar("work", &out, true, /*min_interval_seconds=*/3600.0);
  for (int i = 1; i <= 100; ++i) bar.Update(i, 100);
  bar.Finish();
  const std::string s = out.str();
  // The first update and the last one: two lines.
  EXPECT_EQ(std::count(s.begin(), s.end(), '\r'), 2) << s;
  EXPECT_NE(s.find("100/100"), std::string::npos);
  bar.Update(100, 100);  // after Finish: nothing more
  EXPECT_EQ(out.str(), s);
}

TEST(ProgressBar, ParallelUpdatesNeverGoBackwards) {
  std::ostringstream out;
  ProgressBar bar("work", &out, true, 0.0);
  std::vector<std::thread> pool;
  std::atomic<int> done{0};
  for (int t = 0; t < 4; ++t) {
    pool.emplace_back([&]() {
      for (int i = 0; i < 250; ++i) bar.Update(++done, 1000);
    });
  }
  for (auto& t : pool) t.join();
  bar.Finish();
  const std::string s = out.str();
  EXPECT_NE(s.find("1000/1000"), std::string::npos);
  // The counts drawn increase.
  int last = 0;
  for (std::size_t at = s.find("%  "); at != std::string::npos;
       at = s.find("%  ", at + 1)) {
    const int shown = std::stoi(s.substr(at + 3));
    EXPECT_GT(shown, last);
    last = shown;
  }
}

}  // namespace
}  // namespace femup
