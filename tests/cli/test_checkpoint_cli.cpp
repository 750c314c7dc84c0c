// Resumable bakes (issue 18): a bake killed mid-solve (SIGKILL, no chance to clean up) and run
// again with --resume writes the same file, byte for byte, as one that was never interrupted;
// and a run repeated with the same inputs and threads writes the same bytes, render and bake.
#include <sys/wait.h>

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/cli_runner.h"

namespace {

std::vector<std::string> concat(std::initializer_list<std::string> first, const std::vector<std::string>& rest) {
  std::vector<std::string> a(first);
  a.insert(a.end(), rest.begin(), rest.end());
  return a;
}

TEST(CheckpointCli, ABakeKilledMidSolveResumesToTheSameFile) {
  fs::path dir = scratchDir();
  // Progressive shooting with 64 rays per element-patch pair: seconds of form factors, so that
  // the kill, sent within milliseconds of the first checkpoint (after a quarter of a second of
  // solving), lands inside the solve.
  const std::vector<std::string> solve = {"--solver", "progressive", "--rays-per-pair", "64", "--unshot", "1e-6",
                                          "--elements", "15000", "--threads", "2", "-q"};
  CliRun r = luxel(dir, concat({"bake", "cornell", "--vertex-colors", "-o", "through.glb"}, solve));
  ASSERT_EQ(r.code, 0) << r.err;

  // Polls for at most 30 s, with its output away from the test's (a loop left running would hold it).
  const std::string killWhenCheckpointed =
      "(i=0; while [ ! -s bake.ckpt ] && [ $i -lt 6000 ]; do sleep 0.005; i=$((i+1)); done; kill -KILL $$) "
      ">/dev/null 2>&1 & ";
  r = luxel(dir,
            concat({"bake", "cornell", "--vertex-colors", "-o", "resumed.glb", "--checkpoint", "bake.ckpt",
                    "--checkpoint-interval", "0.01"},
                   solve),
            killWhenCheckpointed);
  EXPECT_EQ(r.code, -1) << "not killed: " << r.err;  // killed by the signal, before it could finish
  ASSERT_TRUE(fs::exists(dir / "bake.ckpt"));
  EXPECT_FALSE(fs::exists(dir / "resumed.glb"));

  r = luxel(dir, concat({"bake", "cornell", "--vertex-colors", "-o", "resumed.glb", "--resume", "bake.ckpt"}, solve));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(readFile(dir / "through.glb") == readFile(dir / "resumed.glb"));
  expectNoTemporaries(dir);
}

TEST(CheckpointCli, ResumingAnotherScenesCheckpointIsAnErrorBeforeAnyOutput) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "a.exr", "--solver", "progressive", "--checkpoint", "c.ckpt"}));
  ASSERT_EQ(r.code, 0) << r.err;
  r = luxel(dir, args({"render", "furnace", "-o", "b.exr", "--solver", "progressive", "--resume", "c.ckpt"}));
  expectFailure(r, dir, {"a.exr", "c.ckpt"}, {"c.ckpt", "another solve"});
  r = luxel(dir, args({"render", "cornell", "-o", "b.exr", "--resume", "missing.ckpt"}));
  expectFailure(r, dir, {"a.exr", "c.ckpt"}, {"--resume", "missing.ckpt", "no such file"});
  r = luxel(dir, args({"render", "cornell", "-o", "b.exr", "--solver", "progressive", "--refine", "100", "--checkpoint",
                       "g.ckpt"}));
  expectFailure(r, dir, {"a.exr", "c.ckpt"}, {"--refine"});
}

// Same inputs, same thread count, same bytes: an image (EXR and PNG) and lightmaps in a glb.
TEST(DeterminismCli, RepeatedRunsWriteTheSameBytes) {
  fs::path dir = scratchDir();
  for (const char* run : {"1", "2"}) {
    CliRun r = luxel(dir, {"render", "cornell", "-o", std::string("r") + run + ".exr", "-o", std::string("r") + run + ".png",
                           "--size", "64x64", "--elements", "1000", "--threads", "2", "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    r = luxel(dir, {"bake", "cornell", "--lightmaps", "-o", std::string("b") + run + ".glb", "--elements", "2000",
                    "--threads", "2", "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
  }
  for (const char* name : {"r?.exr", "r?.png", "b?.glb", "b?.lightmap0.exr"}) {
    std::string one = name, two = name;
    one[1] = '1', two[1] = '2';
    ASSERT_TRUE(fs::exists(dir / one)) << one;
    EXPECT_TRUE(readFile(dir / one) == readFile(dir / two)) << one << " and " << two << " differ";
  }
}

}  // namespace
