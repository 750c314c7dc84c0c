// Hostile and unlucky command lines (issue 18): each fails before any work with exit code 1 (2 for
// bad usage), a message naming what is wrong, and nothing written; or, where the failure can only
// come at the end (a full disk), nothing half-written and no temporary file left behind.
//
// Values used: the built-in Cornell box's default camera looks from z = -0.8 at the box (x, y
// about 0.28); Embree rejects ray origins beyond ~1.8e18, so an eye at z = -1e20 once aborted it.
#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "cli/cli_runner.h"

namespace {

TEST(HostileCli, ACameraBeyondTheFloatRangeIsAnErrorNotACrash) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "out.png", "--eye", "0.278,0.273,-1e20"}));
  expectFailure(r, dir, {}, {"eye", "1e+20"});
}

TEST(HostileCli, AnImageTooBigForMemoryIsRefusedBeforeTheSolve) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"render", "cornell", "-o", "out.png", "--size", "32768x32768", "--elements", "200", "-q"});
  expectFailure(r, dir, {}, {"32768x32768", "megapixels"});
}

TEST(HostileCli, OutputsAreCheckedBeforeAnyIsWritten) {
  fs::path dir = scratchDir();
  fs::create_directory(dir / "taken.png");
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "a.exr", "-o", "taken.png"}));
  expectFailure(r, dir, {"taken.png"}, {"taken.png", "directory"});
  r = luxel(dir, args({"render", "cornell", "-o", "a.exr", "--stats", "nodir/s.json"}));
  expectFailure(r, dir, {"taken.png"}, {"--stats", "nodir", "does not exist"});
  // The image and the statistics must not overwrite each other.
  r = luxel(dir, args({"render", "cornell", "-o", "a.png", "--stats", "./a.png"}));
  expectFailure(r, dir, {"taken.png"}, {"same file"});
  // A name too long for the temporary file written beside it.
  r = luxel(dir, args({"render", "cornell", "-o", std::string(250, 'x') + ".png"}));
  expectFailure(r, dir, {"taken.png"}, {"file name is 254 bytes"});
}

TEST(HostileCli, AFullDiskLeavesNoOutputAndNoTemporaryFile) {
  fs::path dir = scratchDir();
  // A file size limit of 8 KiB: the 512 x 512 PNG (over 100 KB) cannot be written whole. With
  // SIGXFSZ ignored, the write fails with EFBIG instead of killing the process.
  CliRun r = luxel(dir, {"render", "cornell", "-o", "big.png", "--size", "512x512", "--elements", "200", "--spp", "1", "-q"},
                   "trap '' XFSZ; ulimit -f 8; ");
  expectFailure(r, dir, {}, {"big.png", "write failed"});
  // 512 bytes (sh counts 512-byte blocks): the 8 x 8 PNG fits, the statistics (~800 bytes) do not.
  // The image is whole and stays; the statistics are not installed short, and the run fails.
  r = luxel(dir, {"render", "cornell", "-o", "a.png", "--stats", "s.json", "--size", "8x8", "--elements", "200", "-q"},
            "trap '' XFSZ; ulimit -f 1; ");
  expectFailure(r, dir, {"a.png"}, {"s.json", "write failed"});
}

TEST(HostileCli, NumbersOutOfRangeOrNotFiniteAreUsageErrors) {
  fs::path dir = scratchDir();
  const std::vector<std::vector<std::string>> bad = {
      {"--element-size", "-1"}, {"--element-size", "nan"}, {"--element-size", "0"}, {"--elements", "0"},
      {"--elements", "-1"},     {"--refine", "-1"},        {"--fov", "nan"},        {"--exposure", "nan"},
      {"--sky", "nan"},         {"--sky", "inf"}};
  for (const auto& option : bad) {
    CliRun r = luxel(dir, {"render", "cornell", "-o", "a.png", "--size", "8x8", option[0], option[1], "-q"});
    expectFailure(r, dir, {}, {option[0]}, 2);
    EXPECT_EQ(r.err.find("18446744073709551615"), std::string::npos) << r.err;
  }
}

TEST(HostileCli, ALightmapDensityTooHighForMemoryIsRefused) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"bake", "cornell", "--lightmaps", "--texels-per-metre", "1e4", "-o", "a.glb", "-q"});
  expectFailure(r, dir, {}, {"texels per metre", "over the limit"});
}

TEST(HostileCli, EmissionThatWouldOverflowIsRefused) {
  fs::path dir = scratchDir();
  writeFile(dir / "hot.obj", "mtllib hot.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl hot\nf 1 2 3 4\n");
  writeFile(dir / "hot.mtl", "newmtl hot\nKd 0.5 0.5 0.5\nKe 2e38 2e38 2e38\n");
  CliRun r = luxel(dir, args({"render", "hot.obj", "-o", "a.exr"}));
  expectFailure(r, dir, {"hot.mtl", "hot.obj"}, {"hot", "emission", "over the limit"});
}

// Sanitizers reserve terabytes of address space: ulimit -v would stop them before main().
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

TEST(HostileCli, RunningOutOfMemorySaysWhatAndWhatToReduce) {
  if (kSanitized) GTEST_SKIP() << "ulimit -v and sanitizers do not mix";
  fs::path dir = scratchDir();
  // 400 MB of address space: the scene loads, two million elements do not fit. It said
  // "luxel: error: std::bad_alloc".
  CliRun r = luxel(dir, {"render", "cornell", "-o", "a.png", "--size", "8x8", "--elements", "2000000", "--threads", "2", "-q"},
                   "ulimit -v 400000; ");
  expectFailure(r, dir, {}, {"out of memory while solving scene 'cornell' (--elements 2000000)", "use fewer elements (--elements"});
  r = luxel(dir, {"bake", "cornell", "-o", "a.glb", "--elements", "2000000", "--threads", "2", "-q"}, "ulimit -v 400000; ");
  expectFailure(r, dir, {}, {"out of memory while baking scene 'cornell' (--elements 2000000)", "use fewer elements"});
}

TEST(HostileCli, SigtermEndsTheRunWithoutLeavingFiles) {
  fs::path dir = scratchDir();
  // Killed a moment after it starts, wherever it is: solving, rendering or writing.
  CliRun r = luxel(dir, {"render", "cornell", "-o", "big.exr", "--size", "2048x2048", "--spp", "64", "--elements", "2000", "-q"},
                   "(sleep 1; kill -TERM $$) >/dev/null 2>&1 & ");
  EXPECT_NE(r.code, 0);
  for (const std::string& name : listDir(dir)) EXPECT_EQ(name.rfind(".", 0), std::string::npos) << "left behind: " << name;
  EXPECT_FALSE(fs::exists(dir / "big.exr") && fs::file_size(dir / "big.exr") == 0);
}

}  // namespace
