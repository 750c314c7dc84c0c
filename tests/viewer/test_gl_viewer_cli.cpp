// `luxel view` as a user runs it: in a window under Xvfb (skipped, saying why, where xvfb-run is
// missing), headless, and with bad scripts and options.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "luxel/image.h"
#include "viewer_rig.h"

namespace {

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

const std::vector<std::string> kSolve = {"--elements", "3000", "--solver", "progressive", "--unshot", "1e-4"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The window's picture (an EXR screenshot: radiance, before tone mapping) against `luxel render`
// from the same camera, as GlViewer.RadiosityViewIsWhatLuxelRenderShows compares them in-process.
TEST(GlViewerCli, WindowUnderXvfbShowsWhatLuxelRenderShows) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (Debian: xvfb, xauth): no display to open a window on";
  const fs::path dir = scratchDir();
  // 150 frames: the 3,000-element Cornell box converges in well under a second of them.
  const CliRun view = luxel(dir, with({"view", "cornell", "--hidden", "--frames", "150", "--screenshot", "view.exr", "--size",
                                      "256x256", "--view", "radiosity", "--stats", "stats.json"},
                                     kSolve),
                            "exec xvfb-run -a -s '-screen 0 640x480x24' ");
  ASSERT_EQ(view.code, 0) << view.err;
  const CliRun render = luxel(dir, with({"render", "cornell", "--mode", "radiosity", "-o", "render.exr", "--size", "256x256", "-q"}, kSolve));
  ASSERT_EQ(render.code, 0) << render.err;
  const luxel::test::RegionDifference d =
      luxel::test::compareRegions(luxel::readExr(dir / "view.exr"), luxel::readExr(dir / "render.exr"), 8, 0.1, 3.0);
  EXPECT_LT(d.worst, 0.05) << "region " << d.region << ": view " << d.a << ", render " << d.b;
  const nlohmann::json stats = nlohmann::json::parse(readFile(dir / "stats.json"));
  EXPECT_EQ(stats["frames"], 149);  // the first frame has no duration
  EXPECT_NE(stats["renderer"].get<std::string>(), "");
  EXPECT_GT(stats["idle"]["frames"].get<int>() + stats["solving"]["frames"].get<int>(), 0);
}

TEST(GlViewerCli, HeadlessRunsAScriptAndSavesTheScene) {
  const fs::path dir = scratchDir();
  writeFile(dir / "walk.txt",
            "0 solve.pause\n"
            "1 key w down\n"
            "5 key w up\n"
            "6 light.add-at-camera\n"
            "7 save edited.json\n"
            "8 screenshot frame8.png\n");
  const CliRun r = luxel(dir, {"view", "cornell", "--headless", "--frames", "10", "--script", "walk.txt", "--size", "64x64",
                               "--elements", "500"});
  if (r.code != 0 && r.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "frame8.png"));
  const std::string saved = readFile(dir / "edited.json");
  EXPECT_NE(saved.find("\"base\": \"cornell\""), std::string::npos) << saved;
  EXPECT_NE(saved.find("\"type\": \"point\""), std::string::npos) << saved;  // the lamp
  // It loads, and renders.
  EXPECT_EQ(luxel(dir, {"render", "edited.json", "--camera", "viewer", "-o", "edited.png", "--size", "16x16", "--elements", "300", "-q"}).code, 0);
}

// A glb that luxel baked opens in the baked view, drawn as an engine would (docs/baking.md), and
// shows what `luxel render` shows of the same bake: its lightmaps (render --mode lightmap; the glb's
// are RGBM PNGs, 8 bits) or its vertex colours (render --mode radiosity; linear over the glb's
// triangles where the render is bilinear over quads). Within 5% per region, the light itself left
// out (as in GlViewer.RadiosityViewIsWhatLuxelRenderShows).
TEST(GlViewerCli, BakedGlbShowsWhatLuxelRenderShowsOfTheBake) {
  const fs::path dir = scratchDir();
  const std::vector<std::string> camera = {"--eye", "0.278,0.273,-0.75", "--target", "0.278,0.273,0.2", "--fov", "40",
                                           "--size", "256x256"};
  for (const auto& [bake, mode] : {std::pair<std::string, std::string>{"--lightmaps", "lightmap"}, {"--vertex-colors", "radiosity"}}) {
    const std::string glb = "cornell" + bake + ".glb";
    ASSERT_EQ(luxel(dir, {"bake", "cornell", "-o", glb, bake, "-q"}).code, 0);
    const CliRun view = luxel(dir, with({"view", glb, "--headless", "--paused", "--frames", "2", "--screenshot", "view" + bake + ".exr"}, camera));
    if (view.code != 0 && view.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << view.err;
    ASSERT_EQ(view.code, 0) << view.err;
    const CliRun render = luxel(dir, with({"render", "cornell", "--mode", mode, "-o", "render" + bake + ".exr", "-q"}, camera));
    ASSERT_EQ(render.code, 0) << render.err;
    const luxel::test::RegionDifference d = luxel::test::compareRegions(
        luxel::readExr(dir / ("view" + bake + ".exr")), luxel::readExr(dir / ("render" + bake + ".exr")), 8, 0.1, 3.0);
    EXPECT_LT(d.worst, 0.05) << bake << ": region " << d.region << ": view " << d.a << ", render " << d.b;
  }
  // The baked view needs a bake.
  const std::vector<std::string> before = listDir(dir);
  expectFailure(luxel(dir, {"view", "cornell", "--view", "baked", "--headless", "--frames", "1"}), dir, before,
                {"the baked view needs a glb written by luxel bake"});
}

// A directional bake (LUXEL_lightmap_directional) under a normal map, in the baked view: a floor
// whose normal map has stripes tilted 12 degrees towards and away from a grazing lamp, which the
// plain lightmap cannot show (it is the same whatever the normal). The view reads the directions
// at the normal map's normal as `luxel render --mode lightmap --directional` does: within 5% per
// region, where the plain render differs by far more.
TEST(GlViewerCli, DirectionalBakeShowsTheNormalMapAsLuxelRenderDoes) {
  const fs::path dir = scratchDir();
  // The normal map: 16 x 1, the left half tilted towards +u, the right half away (tangent space).
  const float a = 12.0f * 3.14159265f / 180.0f;
  {
    std::vector<uint8_t> rgb;
    for (int x = 0; x < 16; ++x)
      for (float v : {x < 8 ? std::sin(a) : -std::sin(a), 0.0f, std::cos(a)}) rgb.push_back(uint8_t(std::lround(255.0f * (0.5f + 0.5f * v))));
    writeFile(dir / "stripes.ppm", "P6\n16 1\n255\n" + std::string(rgb.begin(), rgb.end()));
  }
  writeFile(dir / "floor.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnorm stripes.ppm\n");
  writeFile(dir / "floor.obj", "mtllib floor.mtl\no floor\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\nvt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\n"
                               "usemtl floor\nf 1/1 2/2 3/3 4/4\n");
  writeFile(dir / "floor.json", R"({"meshes": [{"file": "floor.obj"}],
    "lights": [{"type": "point", "position": [6, 2, 0], "intensity": 20}],
    "cameras": [{"name": "top", "eye": [0, 5, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov": 50}]})");
  // Looking down at an angle: the viewer's camera turns about the vertical, so straight down has no "up".
  const std::vector<std::string> camera = {"--eye", "0,4,3", "--target", "0,0,0", "--fov", "60", "--size", "128x128"};
  const std::vector<std::string> solve = with({"--elements", "1600"}, camera);
  ASSERT_EQ(luxel(dir, with({"render", "floor.json", "--mode", "lightmap", "-o", "plain.exr", "-q"}, solve)).code, 0);
  for (const std::string mode : {"sh-l1", "dominant", "sh-l2"}) {
    ASSERT_EQ(luxel(dir, {"bake", "floor.json", "-o", "floor.glb", "--lightmaps", "--directional", mode, "--elements", "1600", "-q"}).code, 0);
    const CliRun view = luxel(dir, with({"view", "floor.glb", "--headless", "--paused", "--frames", "2", "--screenshot", "view.exr"}, camera));
    if (view.code != 0 && view.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << view.err;
    ASSERT_EQ(view.code, 0) << view.err;
    ASSERT_EQ(luxel(dir, with({"render", "floor.json", "--mode", "lightmap", "--directional", mode, "-o", "render.exr", "-q"}, solve)).code, 0);
    const luxel::Image shown = luxel::readExr(dir / "view.exr");
    const luxel::test::RegionDifference d = luxel::test::compareRegions(shown, luxel::readExr(dir / "render.exr"), 8, 0.1);
    EXPECT_LT(d.worst, 0.05) << mode << ": region " << d.region << ": view " << d.a << ", render " << d.b;
    const luxel::test::RegionDifference plain = luxel::test::compareRegions(shown, luxel::readExr(dir / "plain.exr"), 8, 0.1);
    EXPECT_GT(plain.worst, 0.3) << mode << ": the plain lightmap should miss the stripes";
  }
}

TEST(GlViewerCli, ScriptMistakesFailBeforeAnyWindowNamingTheLine) {
  const fs::path dir = scratchDir();
  writeFile(dir / "bad.txt", "0 solve.pause\n\n2 light.move 0 1\n");
  const std::vector<std::string> before = listDir(dir);
  expectFailure(luxel(dir, {"view", "cornell", "--script", "bad.txt", "--frames", "3", "--screenshot", "x.png"}), dir, before,
                {"bad.txt:3: 'light.move' expects 'LIGHT X Y Z', got 2 arguments"});
  expectFailure(luxel(dir, {"view", "cornell", "--script", "missing.txt"}), dir, before, {"cannot read the viewer script 'missing.txt'"});
  expectFailure(luxel(dir, {"view", "cornell", "--screenshot", "x.png"}), dir, before, {"--screenshot needs --frames N"});
  expectFailure(luxel(dir, {"view", "cornell", "--view", "sideways"}), dir, before, {"unknown view 'sideways'"});
  expectFailure(luxel(dir, {"view", "cornell", "--headless"}), dir, before, {"--headless needs --frames N"});
  expectFailure(luxel(dir, {"view", "no-such-scene.obj", "--headless", "--frames", "1"}), dir, before, {"no-such-scene.obj"});
}

TEST(GlViewerCli, ActionsAreListed) {
  const fs::path dir = scratchDir();
  const CliRun r = luxel(dir, {"view", "--actions"});
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* a : {"light.add-at-camera", "solve.pause", "solve.reset", "object.move", "screenshot", "save", "quit"})
    EXPECT_NE(r.out.find(a), std::string::npos) << a;
}

}  // namespace
