// `luxel render --backend gl|auto|cpu`: the GL backend end to end through the CLI, the fallback of
// `auto`, and a bad backend name. GL runs skip, saying why, when no OpenGL 4.5 context exists.
#include <memory>

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
