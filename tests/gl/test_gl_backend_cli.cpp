// `luxel render --backend gl|auto|cpu`: the GL backend end to end through the CLI, the fallback of
// `auto`, and a bad backend name. GL runs skip, saying why, when no OpenGL 4.5 context exists.
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "gl/gl_test_context.h"
#include "luxel/error.h"

namespace {

bool haveGl(std::string& why) { return luxel::test::glContextOr(why) != nullptr; }

TEST(GlBackendCli, RendersOnTheGpuAndSaysSo) {
  std::string why;
  if (!haveGl(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"render", "furnace", "-o", "f.exr", "--size", "8x8", "--elements", "200", "--backend", "gl",
                         "--solver", "gather", "--hemicube-resolution", "32", "--stats", "s.json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(readFile(dir / "s.json"));
  EXPECT_EQ(j["backend"], "gl");
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  EXPECT_NE(r.out.find("on gl"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "f.exr"));
}

// `luxel animate` with a GL dynamic solver: each frame's line says where the solver's time went
// (phases_ms, gl/gpu_timeline.h), and --error, which solves each frame's reference in a context
// of its own, works beside it (the session's stats once asked the driver for its name under the
// reference's context, and threw).
TEST(GlBackendCli, AnimateTimesEachPhaseOfTheGlSolver) {
  std::string why;
  if (!haveGl(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"animate", "cornell-low", "--frames", "2", "--size", "16x16", "--elements", "400", "--backend",
                         "gl", "--solver", "cross-redistribution", "--error", "--stats", "s.jsonl", "-o", "f%d.png",
                         "-q"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<nlohmann::json> lines;
  std::istringstream in(readFile(dir / "s.jsonl"));
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(lines.size(), 2u);
  for (const nlohmann::json& l : lines) {
    ASSERT_TRUE(l.contains("phases_ms")) << l.dump();
    double cpu = 0.0;
    for (const auto& [name, p] : l["phases_ms"].items()) {
      EXPECT_GT(p["count"].get<int>(), 0) << name;
      EXPECT_GE(p["gpu"].get<double>(), 0.0) << name;
      EXPECT_GE(p["cpu"].get<double>(), 0.0) << name;
      cpu += p["cpu"].get<double>();
    }
    // The phases are parts of the frame's update and solve.
    EXPECT_LE(cpu, l["ms_update"].get<double>() + l["ms_solve"].get<double>() + 1.0) << l.dump();
    EXPECT_LT(l["error"].get<double>(), 0.05) << l.dump();
  }
  // The second frame moved the box: the cross-redistribution's passes are there, the first's not.
  EXPECT_FALSE(lines[0]["phases_ms"].contains("gather: integrate")) << lines[0].dump();
  for (const char* phase : {"shoot: hemicubes", "redistribute: reconstruct", "gather: integrate"})
    EXPECT_TRUE(lines[1]["phases_ms"].contains(phase)) << phase << " in " << lines[1].dump();
}

TEST(GlBackendCli, AutoUsesTheGpuWhenItCanAndBadNamesFail) {
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"render", "furnace", "-o", "f.exr", "--size", "8x8", "--elements", "200", "--backend", "auto",
                         "--stats", "s.json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(readFile(dir / "s.json"));
  std::string why;
  EXPECT_EQ(j["backend"], haveGl(why) ? "gl" : "cpu");
  if (j["backend"] == "cpu") EXPECT_NE(r.err.find("using the CPU backend"), std::string::npos) << r.err;

  CliRun bad = luxel(dir, {"render", "furnace", "-o", "g.exr", "--backend", "vulkan"});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("vulkan"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "g.exr"));
}

}  // namespace
