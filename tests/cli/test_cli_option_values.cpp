// Options that take several values (-o, --set, --vertex-colors-for) take one word per use: CLI11
// lets a vector option take every word up to the next option, so `luxel render -o a.png cornell`
// took the scene for a second output and failed with "scene is required".
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/cli_runner.h"

namespace {

TEST(CliOptionValues, TheSceneAfterAnOutputIsTheScene) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "-o", "a.png", "cornell"}));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"a.png"});
  r = luxel(dir, args({"render", "--set", "unshot=0.01", "cornell", "-o", "b.png"}));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "b.png"));
  r = luxel(dir, {"bake", "--lightmaps", "--vertex-colors-for", "*", "cornell", "-o", "c.glb", "--elements", "200", "-q"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "c.glb"));
}

TEST(CliOptionValues, TwoWordsAfterOneOutputAreAUsageError) {
  fs::path dir = scratchDir();
  // b.png is the scene now, and cornell a word too many: bad usage, nothing written.
  CliRun r = luxel(dir, args({"render", "-o", "a.png", "b.png", "cornell"}));
  expectFailure(r, dir, {}, {"cornell"}, 2);
}

}  // namespace
