// Viewer scripts: what a test or a demo replays. Mistakes fail when the script is read, naming the
// file and line, before any window opens.
#include <gtest/gtest.h>

#include "error_message.h"
#include "frame_stats.h"
#include "luxel/error.h"
#include "view_script.h"

namespace {

using luxel::viewer::parseScript;

// The error `f` throws contains `part`.
template <class F>
void expectError(F f, const std::string& part) {
  const std::string message = luxel::test::errorOf(f);
  EXPECT_NE(message.find(part), std::string::npos) << "message: " << message << "\nexpected to contain: " << part;
}

TEST(ViewScript, ReadsFramesTimesActionsAndArguments) {
  const auto entries = parseScript(
      "# walk in, then light it\n"
      "0 camera 0 1 3.5  0 1 0\n"
      "\n"
      "10  key w down   # forward\n"
      "20 key w up\n"
      "0.5s light.add-at-camera\n"
      "2s screenshot out/a.png\n",
      "walk.txt");
  ASSERT_EQ(entries.size(), 5u);
  EXPECT_EQ(entries[0].frame, 0);
  EXPECT_EQ(entries[0].action.name, "camera");
  EXPECT_EQ(entries[0].action.args.size(), 6u);
  EXPECT_EQ(entries[1].frame, 10);
  EXPECT_EQ(entries[1].action.args, (std::vector<std::string>{"w", "down"}));
  EXPECT_EQ(entries[1].action.where, "walk.txt:4");
  EXPECT_DOUBLE_EQ(entries[3].seconds, 0.5);
  EXPECT_EQ(entries[3].frame, -1);
  EXPECT_EQ(entries[4].action.args[0], "out/a.png");
}

TEST(ViewScript, NamesTheLineOfEachMistake) {
  expectError([&] { parseScript("0 solve.pause\n3 lihgt.add\n", "s.txt"); }, "s.txt:2: unknown viewer action 'lihgt.add'");
  expectError([&] { parseScript("1 light.move 0 1 2\n", "s.txt"); }, "s.txt:1: 'light.move' expects 'LIGHT X Y Z', got 3 arguments");
  expectError([&] { parseScript("5 solve.pause\n4 solve.resume\n", "s.txt"); }, "s.txt:2: frame 4 comes before the line above's");
  expectError([&] { parseScript("soon quit\n", "s.txt"); }, "s.txt:1: 'soon' is not a frame number");
  expectError([&] { parseScript("-1 quit\n", "s.txt"); }, "s.txt:1: '-1' is not a frame number");
  expectError([&] { parseScript("1e9s quit\n", "s.txt"); }, "s.txt:1: '1e9s' is not a time");
  expectError([&] { parseScript("7\n", "s.txt"); }, "s.txt:1: '7' with no action after it");
}

TEST(ViewScript, NumbersInArgumentsAreChecked) {
  const luxel::viewer::Action a{"light.move", {"0", "1", "nan", "x"}, "s.txt:3"};
  EXPECT_EQ(luxel::viewer::argInt(a, 0), 0);
  EXPECT_FLOAT_EQ(luxel::viewer::argFloat(a, 1), 1.0f);
  expectError([&] { luxel::viewer::argFloat(a, 2); }, "s.txt:3: 'light.move': argument 3 'nan' is not a finite number");
  expectError([&] { luxel::viewer::argInt(a, 3); }, "argument 4 'x' is not an integer");
}

TEST(FrameStats, NearestRankPercentiles) {
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(double(101 - i));  // 100 .. 1, unsorted
  const luxel::viewer::Percentiles p = luxel::viewer::percentiles(v);
  EXPECT_DOUBLE_EQ(p.median, 50.0);
  EXPECT_DOUBLE_EQ(p.p95, 95.0);
  EXPECT_DOUBLE_EQ(p.max, 100.0);
  EXPECT_DOUBLE_EQ(p.mean, 50.5);
  EXPECT_DOUBLE_EQ(luxel::viewer::percentiles({7.0}).p95, 7.0);
  EXPECT_DOUBLE_EQ(luxel::viewer::percentiles({}).median, 0.0);
}

TEST(FrameStats, IdleFramesPerSecondCountOnlyIdleFrames) {
  luxel::viewer::FrameStats s;
  for (int i = 0; i < 10; ++i) s.addFrame({.frameMs = 20.0, .solving = false});
  for (int i = 0; i < 10; ++i) s.addFrame({.frameMs = 100.0, .solving = true});
  EXPECT_NEAR(s.idleFps(), 50.0, 1e-9);
}

}  // namespace
