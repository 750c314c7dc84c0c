// `luxel animate` (apps/luxel/animate_command.cpp), run as a separate process: frames are written
// under the pattern's names, the box's turn shows in them, frame 0 is what `luxel render` makes
// of the scene at rest, the stats are one JSON line per frame, a video comes out through ffmpeg
// when it is there, and bad input fails before any work with nothing written.
//
// Scene: the built-in cornell-low (seed 001; its box spins at 30 degrees a second about the
// vertical through its centre), 32 x 24 pixels, progressive to 5% unshot (a loose stop, so each
// frame solves in a fraction of a second; the comparisons below do not depend on how converged).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/image.h"
#include "cli/cli_runner.h"

namespace {

const std::vector<std::string> kSmall = {"--size",      "32x24",    "--solver",
                                         "progressive", "--unshot", "0.05"};

std::vector<std::string> animate(std::initializer_list<std::string> first, bool quiet = true) {
  std::vector<std::string> a = {"animate"};
  a.insert(a.end(), first);
  a.insert(a.end(), kSmall.begin(), kSmall.end());
  if (quiet) a.push_back("-q");
  return a;
}

std::vector<nlohmann::json> jsonLines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

// The share of pixels whose value differs by more than 1% of the image's mean in any channel.
double differingShare(const luxel::Image& a, const luxel::Image& b) {
  double mean = 0.0;
  for (const luxel::Rgb& p : a.pixels) mean += (p.r + p.g + p.b) / 3.0;
  mean /= double(a.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (std::abs(a.pixels[i][c] - b.pixels[i][c]) > 0.01 * mean) {
        ++differing;
        break;
      }
  return double(differing) / double(a.pixels.size());
}

bool haveFfmpeg() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

TEST(AnimateCli, WritesFramesThatFollowTheBoxWithAStatsLineEach) {
  const fs::path dir = scratchDir();
  fs::create_directory(dir / "frames");
  // 3 frames a second: the box turns 10 degrees a frame.
  const CliRun r = luxel(dir, animate({"cornell-low", "--frames", "3", "--fps", "3", "-o",
                                       "frames/f%03d.exr", "--stats", "stats.jsonl"}));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"frames", "frames/f000.exr", "frames/f001.exr",
                                                    "frames/f002.exr", "stats.jsonl"}));
  std::vector<luxel::Image> frames;
  for (const char* name : {"f000.exr", "f001.exr", "f002.exr"})
    frames.push_back(luxel::readExr(dir / "frames" / name));
  ASSERT_EQ(frames[0].width, 32);
  ASSERT_EQ(frames[0].height, 24);
  // The box turning 10 degrees moves its edges and its shadows across a good part of the picture
  // (it fills about a third of it; measured 30% to 40% of pixels differ by more than 1%).
  EXPECT_GT(differingShare(frames[0], frames[1]), 0.05);
  EXPECT_GT(differingShare(frames[1], frames[2]), 0.05);

  const std::vector<nlohmann::json> stats = jsonLines(readFile(dir / "stats.jsonl"));
  ASSERT_EQ(stats.size(), 3u);
  for (size_t k = 0; k < stats.size(); ++k) {
    const nlohmann::json& s = stats[k];
    EXPECT_EQ(s.at("frame").get<int>(), int(k));
    EXPECT_DOUBLE_EQ(s.at("time").get<double>(), double(k) / 3.0);
    for (const char* ms : {"ms_update", "ms_solve", "ms_render"})
      EXPECT_GE(s.at(ms).get<double>(), 0.0) << ms;
    // Every frame shoots: the box moved, and a solver that restarts (progressive) or follows the
    // move shoots at least the light again.
    EXPECT_GE(s.at("shots").get<uint64_t>(), 1u);
    EXPECT_LE(s.at("unshot_fraction").get<double>(), 0.05);
    EXPECT_FALSE(s.contains("error"));  // only with --error
  }
}

TEST(AnimateCli, FrameZeroIsWhatRenderMakesOfTheSceneAtRest) {
  const fs::path dir = scratchDir();
  std::vector<std::string> render = {"render", "cornell-low", "-o", "render.exr",
                                     "-o",     "render.png",  "-q"};
  render.insert(render.end(), kSmall.begin(), kSmall.end());
  ASSERT_EQ(luxel(dir, render).code, 0);
  // One frame needs no number in its name.
  CliRun r = luxel(dir, animate({"cornell-low", "--frames", "1", "-o", "frame.png"}));
  ASSERT_EQ(r.code, 0) << r.err;
  r = luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "frame%d.exr"}));
  ASSERT_EQ(r.code, 0) << r.err;
  // Same scene, options and seeds: the same pixels, and the same PNG bytes (the same exposure).
  const luxel::Image still = luxel::readExr(dir / "render.exr"),
                     first = luxel::readExr(dir / "frame0.exr");
  ASSERT_EQ(still.pixels.size(), first.pixels.size());
  EXPECT_TRUE(still.pixels == first.pixels);
  EXPECT_EQ(readFile(dir / "frame.png"), readFile(dir / "render.png"));
  EXPECT_FALSE(luxel::readExr(dir / "frame1.exr").pixels == first.pixels);
}

TEST(AnimateCli, StatsGoToStdoutAndErrorComparesWithAFromScratchSolve) {
  const fs::path dir = scratchDir();
  const CliRun r = luxel(dir, animate({"cornell-low", "--frames", "2", "--fps", "1", "--start",
                                       "0.5", "-o", "f%d.png", "--error"},
                                      /*quiet=*/false));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<nlohmann::json> stats = jsonLines(r.out);
  ASSERT_EQ(stats.size(), 2u) << r.out;
  EXPECT_DOUBLE_EQ(stats[0].at("time").get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(stats[1].at("time").get<double>(), 1.5);
  // Progressive starts again after a move, so each frame is a solve from scratch at its pose, and
  // the from-scratch reference (same options, same discretisation) is the same solve: the error
  // is zero to rounding. A solver that follows moves (incremental) would show its own error here.
  for (const nlohmann::json& s : stats) EXPECT_LT(s.at("error").get<double>(), 1e-6) << s.dump();
  EXPECT_NE(r.err.find("luxel: wrote f%d.png"), std::string::npos) << r.err;
}

TEST(AnimateCli, AnimatedLightsChangeTheFrames) {
  const fs::path dir = scratchDir();
  // The box held still; a point light under the ceiling goes from 0.01 to 1 W/sr over a second.
  writeFile(dir / "scene.json",
            R"({ "builtin": "cornell-low", "objects": { "box": { "animation": null } },
      "lights": [ { "type": "point", "position": [0.275, 0.5, 0.275], "intensity": 0.01,
                    "animation": { "keyframes": [ { "time": 0 }, { "time": 1, "intensity": 1 } ] } } ] })");
  const CliRun r =
      luxel(dir, animate({"scene.json", "--frames", "2", "--fps", "1", "-o", "f%d.exr"}));
  ASSERT_EQ(r.code, 0) << r.err;
  auto mean = [](const luxel::Image& img) {
    double sum = 0.0;
    for (const luxel::Rgb& p : img.pixels) sum += p.r + p.g + p.b;
    return sum / double(img.pixels.size());
  };
  // The panel gives pi x 0.030 m^2 x (8.5, 6, 2) = (0.8, 0.6, 0.2) W; the point light 4 pi x 0.01
  // = 0.13 W a channel at first and 4 pi = 12.6 W at the end: about 20 times the light in all.
  EXPECT_GT(mean(luxel::readExr(dir / "f1.exr")), 5.0 * mean(luxel::readExr(dir / "f0.exr")));
}

TEST(AnimateCli, AStillSceneWarnsAndStillWorks) {
  const fs::path dir = scratchDir();
  const CliRun r = luxel(
      dir, animate({"cornell", "--frames", "2", "-o", "f%d.exr", "--stats", "s.jsonl"}, false));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("scene 'cornell' has no animation: every frame will be the same"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(luxel::readExr(dir / "f0.exr").pixels == luxel::readExr(dir / "f1.exr").pixels);
  // Nothing moved, so the second frame had nothing to solve.
  const std::vector<nlohmann::json> stats = jsonLines(readFile(dir / "s.jsonl"));
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_EQ(stats[1].at("shots").get<uint64_t>(), 0u);
}

TEST(AnimateCli, WritesAVideoThroughFfmpeg) {
  if (!haveFfmpeg())
    GTEST_SKIP()
        << "ffmpeg is not on PATH (Debian package ffmpeg; scripts/install-deps.sh installs it)";
  const fs::path dir = scratchDir();
  const CliRun r = luxel(dir, animate({"cornell-low", "--frames", "3", "-o", "movie.mp4"}));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"movie.mp4"});
  EXPECT_EQ(readFile(dir / "movie.mp4").substr(4, 4), "ftyp");  // an ISO media file
  // ffprobe comes with ffmpeg: 3 frames of 32 x 24.
  const std::string probe =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=width,height,nb_read_frames -of csv=p=0 " +
      quote((dir / "movie.mp4").string()) + " > " +
      quote((dir.parent_path() / "probe.txt").string());
  ASSERT_EQ(std::system(probe.c_str()), 0);
  EXPECT_EQ(readFile(dir.parent_path() / "probe.txt"), "32,24,3\n");
}

TEST(AnimateCli, BadInputFailsBeforeAnyWorkAndWritesNothing) {
  const fs::path dir = scratchDir();
  const std::vector<std::string> empty;
  expectFailure(luxel(dir, animate({"cornel-low", "--frames", "2", "-o", "f%d.png"})), dir, empty,
                {"'cornel-low' is neither a built-in scene"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "frame.png"})), dir,
                empty, {"-o frame.png", "2 frames need the frame number", "%04d"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "f%s.png"})), dir, empty,
                {"-o f%s.png", "is not a frame number"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "f%d%d.png"})), dir,
                empty, {"more than one frame number"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "f%d.jpg"})), dir, empty,
                {".png or .exr"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "0", "-o", "f%d.png"})), dir, empty,
                {"--frames"}, 2);
  expectFailure(
      luxel(dir, animate({"cornell-low", "--frames", "2", "--fps", "0", "-o", "f%d.png"})), dir,
      empty, {"--fps"}, 2);
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "absent/f%d.png"})), dir,
                empty, {"directory 'absent' does not exist"});
  expectFailure(
      luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "f%d.png", "--mode", "lightmap"})),
      dir, empty, {"--mode lightmap"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "f%d.png", "--checkpoint",
                                    "c.bin"})),
                dir, empty, {"--checkpoint"});
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "f%d.png", "--error",
                                    "--refine", "100"})),
                dir, empty, {"--error with --refine"});
  // Without ffmpeg a video is refused at once, saying what it needs.
  expectFailure(luxel(dir, animate({"cornell-low", "--frames", "2", "-o", "movie.mp4"}),
                      "PATH=/nonexistent; "),
                dir, empty, {"-o movie.mp4", "needs ffmpeg", "apt-get install ffmpeg"});
}

}  // namespace
