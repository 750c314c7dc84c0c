// `luxel view` as a user runs it: in a window under Xvfb (skipped, saying why, where xvfb-run is
// missing), headless, and with bad scripts and options.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <regex>

#include <fmt/format.h>
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

// The texels view of a baked glb lays its lightmap UVs out on the glb's own pages: a bake on three
// pages of 128^2 shows three pages of 128^2 with the bake's own texel and invalid counts (each of
// the glb's meshes used to get a 1024^2 page of its own: 8 pages, 16 times the texels), and so
// does baking the glb again.
TEST(GlViewerCli, TexelsViewOfABakedGlbShowsItsOwnPages) {
  const fs::path dir = scratchDir();
  const CliRun bake = luxel(dir, {"bake", "cornell", "-o", "c.glb", "--lightmaps", "--lightmap-size", "128",
                                  "--texels-per-metre", "100"});
  ASSERT_EQ(bake.code, 0) << bake.err;
  const std::regex baked(R"((\d+) pages? of (\d+)², [0-9.]+ texels per metre, (\d+) texels in \d+ patches, (\d+) invalid)");
  std::smatch b;
  const std::string said = bake.out + bake.err;
  ASSERT_TRUE(std::regex_search(said, b, baked)) << said;
  EXPECT_GT(std::stoi(b[1]), 1);  // more than one page, so that pages are told apart
  const CliRun view = luxel(dir, {"view", "c.glb", "--headless", "--view", "texels", "--frames", "2", "--size", "64x64"});
  if (view.code != 0 && view.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << view.err;
  ASSERT_EQ(view.code, 0) << view.err;
  const std::regex shown(R"(texels: (\d+) on (\d+) pages? of (\d+)\^2 \(the glb's pages\) from given UVs: (\d+) invalid)");
  std::smatch v;
  const std::string out = view.out + view.err;
  ASSERT_TRUE(std::regex_search(out, v, shown)) << out;
  EXPECT_EQ(v[2].str(), b[1].str());  // pages
  EXPECT_EQ(v[3].str(), b[2].str());  // their size
  EXPECT_EQ(v[1].str(), b[3].str());  // texels
  EXPECT_EQ(v[4].str(), b[4].str());  // invalid: the view's test is the bake's own

  // Baking the glb again keeps its layout: the same pages, the same texels.
  const CliRun again = luxel(dir, {"bake", "c.glb", "-o", "again.glb", "--lightmaps"});
  ASSERT_EQ(again.code, 0) << again.err;
  const std::regex rebaked(R"((\d+) pages? of (\d+)², given uvs, (\d+) texels in \d+ patches, (\d+) invalid)");
  std::smatch r;
  const std::string saidAgain = again.out + again.err;
  ASSERT_TRUE(std::regex_search(saidAgain, r, rebaked)) << saidAgain;
  for (int i = 1; i <= 4; ++i) EXPECT_EQ(r[i].str(), b[i].str()) << i;
}

// A directional bake (LUXEL_lightmap_directional) under a normal map, in the baked view: a floor
// whose normal map has stripes tilted 12 degrees towards and away from a grazing lamp, which the
// plain lightmap cannot show (it is the same whatever the normal). The view reads the directions
// at the normal map's normal as `luxel render --mode lightmap --directional` does, from the
// lightmap's direction textures or the vertices' (--vertex-colors): within 5% per region, where
// the plain render differs by far more.
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
  // The same floor as a 40 x 40 grid, for irradiance vertex colours at its own vertices.
  {
    std::string obj = "mtllib floor.mtl\no floor\n";
    for (int j = 0; j <= 40; ++j)
      for (int i = 0; i <= 40; ++i)
        obj += fmt::format("v {} 0 {}\nvt {} {}\n", -2.0 + 0.1 * i, 2.0 - 0.1 * j, 0.05 * i, 0.05 * j);
    obj += "usemtl floor\n";
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) {
        const int a = j * 41 + i + 1, b = a + 1, c = a + 42, d = a + 41;
        obj += fmt::format("f {0}/{0} {1}/{1} {2}/{2} {3}/{3}\n", a, b, c, d);
      }
    writeFile(dir / "grid.obj", obj);
    std::string json = readFile(dir / "floor.json");
    json.replace(json.find("floor.obj"), 9, "grid.obj");
    writeFile(dir / "grid.json", json);
  }
  // Directional lightmaps, directions per vertex (LUXEL_vertex_directional, on the element
  // tessellation's vertex colours) and beside lightmaps (--vertex-colors-for: the grid's own
  // vertices, irradiance), against the same lightmap render.
  for (const std::string bake : {"--lightmaps", "--vertex-colors", "--vertex-colors-for"})
    for (const std::string mode : {"sh-l1", "dominant", "sh-l2"}) {
      const std::string scene = bake == "--vertex-colors-for" ? "grid.json" : "floor.json";
      const std::vector<std::string> what =
          bake == "--vertex-colors-for" ? std::vector<std::string>{"--lightmaps", bake, "floor"} : std::vector<std::string>{bake};
      ASSERT_EQ(luxel(dir, with({"bake", scene, "-o", "floor.glb"}, with(what, {"--directional", mode, "--elements", "1600", "-q"}))).code, 0);
      const CliRun view = luxel(dir, with({"view", "floor.glb", "--headless", "--paused", "--frames", "2", "--screenshot", "view.exr"}, camera));
      if (view.code != 0 && view.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << view.err;
      ASSERT_EQ(view.code, 0) << view.err;
      ASSERT_EQ(luxel(dir, with({"render", scene, "--mode", "lightmap", "--directional", mode, "-o", "render.exr", "-q"}, solve)).code, 0);
      const luxel::Image shown = luxel::readExr(dir / "view.exr");
      const luxel::test::RegionDifference d = luxel::test::compareRegions(shown, luxel::readExr(dir / "render.exr"), 8, 0.1);
      EXPECT_LT(d.worst, 0.05) << bake << " " << mode << ": region " << d.region << ": view " << d.a << ", render " << d.b;
      const luxel::test::RegionDifference plain = luxel::test::compareRegions(shown, luxel::readExr(dir / "plain.exr"), 8, 0.1);
      EXPECT_GT(plain.worst, 0.3) << bake << " " << mode << ": the plain lightmap should miss the stripes";
      std::printf("%s %s: worst region %.4f off the directional render, %.3f off the plain one\n", bake.c_str(), mode.c_str(),
                  d.worst, plain.worst);
    }
}

// An open corner (a floor and two walls) under a sun and a uniform sky, for transfer bakes.
void writeCorner(const fs::path& dir) {
  writeFile(dir / "corner.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl back\nKd 0.7 0.35 0.3\nnewmtl left\nKd 0.3 0.6 0.35\n");
  writeFile(dir / "corner.obj", "mtllib corner.mtl\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\nv 2 2 -2\nv -2 2 -2\nv -2 2 2\n"
                                "o floor\nusemtl floor\nf 1 2 3 4\no back\nusemtl back\nf 4 3 5 6\no left\nusemtl left\nf 1 4 6 7\n");
  writeFile(dir / "corner.json", R"({"meshes": [{"file": "corner.obj"}],
    "lights": [{"type": "directional", "name": "sun", "direction": [-0.4, -1, -0.6], "intensity": 1000},
               {"type": "sky", "intensity": 30}]})");
}

// A transfer bake (LUXEL_lightmap_transfer) relit in the baked view: the open corner's sun turned
// 30 degrees about the vertical by the `sun-direction` action, towards the left wall and away from
// the back one. Before and after, the view agrees per region with `luxel render --mode lightmap
// --transfer 4` (with `--sun-direction` at the turned sun): the same dot product of the light's SH
// and each texel's transfer, the glb's 8-bit RGBM band 0 and ratios against luxel's floats. The
// turn changes the picture by far more than that tolerance, so the test would see a view that
// ignored it.
TEST(GlViewerCli, TransferBakeIsRelitWhenTheSunTurnsAsLuxelRenderRelitsIt) {
  const fs::path dir = scratchDir();
  writeCorner(dir);
  const float turn = 30.0f * 3.14159265f / 180.0f;
  const float x = -0.4f, z = -0.6f;
  const std::string turned = fmt::format("{},{},{}", x * std::cos(turn) + z * std::sin(turn), -1.0f, -x * std::sin(turn) + z * std::cos(turn));
  const std::vector<std::string> camera = {"--eye", "2.2,3.2,2.2", "--target", "-1.2,0.2,-1.2", "--fov", "50", "--size", "128x128"};
  const std::vector<std::string> bake = {"--transfer", "4", "--elements", "2000", "-q"};
  ASSERT_EQ(luxel(dir, with({"bake", "corner.json", "-o", "corner.glb", "--lightmaps"}, bake)).code, 0);
  // Then the sun back, recoloured, and the sky doubled: the light of recoloured.json.
  writeFile(dir / "turn.txt", "0 screenshot before.exr\n1 sun-direction " + turned + "\n2 screenshot after.exr\n"
                              "3 sun-direction -0.4,-1,-0.6\n3 sun-irradiance 500,250,100\n3 sky-scale 2\n4 screenshot recoloured.exr\n");
  writeFile(dir / "recoloured.json", R"({"meshes": [{"file": "corner.obj"}],
    "lights": [{"type": "directional", "direction": [-0.4, -1, -0.6], "intensity": 500, "color": [1, 0.5, 0.2]},
               {"type": "sky", "intensity": 60}]})");
  const CliRun view = luxel(dir, with({"view", "corner.glb", "--headless", "--paused", "--frames", "5", "--script", "turn.txt"}, camera));
  if (view.code != 0 && view.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << view.err;
  ASSERT_EQ(view.code, 0) << view.err;
  const std::vector<std::string> render = with(with({"render", "corner.json", "--mode", "lightmap"}, bake), camera);
  ASSERT_EQ(luxel(dir, with(render, {"-o", "render-before.exr"})).code, 0);
  ASSERT_EQ(luxel(dir, with(render, {"-o", "render-after.exr", "--sun-direction", turned})).code, 0);
  ASSERT_EQ(luxel(dir, with(with({"render", "recoloured.json", "--mode", "lightmap"}, bake), with(camera, {"-o", "render-recoloured.exr"}))).code, 0);
  const luxel::Image before = luxel::readExr(dir / "before.exr"), after = luxel::readExr(dir / "after.exr");
  for (const auto& [shown, name] : {std::pair<luxel::Image, std::string>{before, "before"}, {after, "after"},
                                    {luxel::readExr(dir / "recoloured.exr"), "recoloured"}}) {
    const luxel::test::RegionDifference d = luxel::test::compareRegions(shown, luxel::readExr(dir / ("render-" + name + ".exr")), 8, 0.1);
    EXPECT_LT(d.worst, 0.05) << name << ": region " << d.region << ": view " << d.a << ", render " << d.b;
  }
  const luxel::test::RegionDifference turnedMoved = luxel::test::compareRegions(after, before, 8, 0.1);
  EXPECT_GT(turnedMoved.worst, 0.3) << "the turned sun should relight the walls: region " << turnedMoved.region;
  const luxel::test::RegionDifference recolouredMoved = luxel::test::compareRegions(luxel::readExr(dir / "recoloured.exr"), before, 8, 0.1);
  EXPECT_GT(recolouredMoved.worst, 0.3) << "the recoloured sun and sky should relight the corner: region " << recolouredMoved.region;
}

// Rewrites the JSON chunk of glb `from` into `to` (docs: the glTF 2.0 binary container).
void editGlbJson(const fs::path& from, const fs::path& to, const std::function<void(nlohmann::json&)>& edit) {
  const std::string glb = readFile(from);
  auto u32 = [&](size_t at) { uint32_t v; std::memcpy(&v, glb.data() + at, 4); return v; };
  const uint32_t jsonLength = u32(12);
  nlohmann::json json = nlohmann::json::parse(glb.substr(20, jsonLength));
  edit(json);
  std::string text = json.dump();
  text.resize((text.size() + 3) / 4 * 4, ' ');
  const std::string rest = glb.substr(20 + jsonLength);
  std::string out = glb.substr(0, 12);
  auto put = [&](size_t at, uint32_t v) { std::memcpy(out.data() + at, &v, 4); };
  put(8, uint32_t(12 + 8 + text.size() + rest.size()));
  out += std::string(8, '\0');
  put(12, uint32_t(text.size()));
  put(16, u32(16));
  writeFile(to, out + text + rest);
}

// readBakedGlb checks LUXEL_vertex_directional too: one error naming the file, the mesh and what.
TEST(GlViewerCli, BrokenVertexDirectionsAreAnErrorNamingTheFileAndWhat) {
  const fs::path dir = scratchDir();
  writeCorner(dir);
  ASSERT_EQ(luxel(dir, {"bake", "corner.json", "-o", "corner.glb", "--vertex-colors", "--directional", "sh-l1",
                        "--elements", "300", "-q"}).code, 0);
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>> cases = {
      {[](nlohmann::json& e) { e["mode"] = "sh-l3"; }, "mode 'sh-l3' is not sh-l1, sh-l2 or dominant"},
      {[](nlohmann::json& e) { e["attributes"].erase(0); }, "has 2 attributes where sh-l1 needs 3"},
      {[](nlohmann::json& e) { e["attributes"][1] = "_NO_SUCH"; }, "attribute 1 is not one of the primitive's"},
      {[](nlohmann::json& e) { e.erase("mode"); }, "needs a string 'mode' and an array 'attributes'"},
  };
  for (const auto& [edit, message] : cases) {
    editGlbJson(dir / "corner.glb", dir / "broken.glb", [&](nlohmann::json& json) {
      edit(json["meshes"][0]["primitives"][0]["extensions"]["LUXEL_vertex_directional"]);
    });
    const std::vector<std::string> before = listDir(dir);
    expectFailure(luxel(dir, {"view", "broken.glb", "--headless", "--frames", "1"}), dir, before,
                  {"broken.glb: mesh", "LUXEL_vertex_directional " + message});
  }
}

// readBakedGlb checks LUXEL_lightmap_transfer before anything is drawn: a broken extension is one
// error naming the file, the material and what is wrong; the actions check their numbers.
TEST(GlViewerCli, BrokenTransferBakeIsAnErrorNamingTheFileAndWhat) {
  const fs::path dir = scratchDir();
  writeCorner(dir);
  ASSERT_EQ(luxel(dir, {"bake", "corner.json", "-o", "corner.glb", "--lightmaps", "--transfer", "2", "--elements", "300", "-q"}).code, 0);
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>> cases = {
      {[](nlohmann::json& e) { e["bands"] = 5; }, "bands is 5, not 2, 3 or 4"},
      {[](nlohmann::json& e) { e["ratioScale"].erase(0); }, "ratioScale is not an array of 3 numbers"},
      {[](nlohmann::json& e) { e["ratioScale"][1] = 0; }, "ratioScale[1] is 0, not above 0"},
      {[](nlohmann::json& e) { e["ratios"][0]["index"] = 999; }, "ratios[0].index 999 is not one of the file's"},
      {[](nlohmann::json& e) { e["ratios"].erase(0); }, "ratios is not an array of 3 textures"},
      {[](nlohmann::json& e) { e["band0"]["texCoord"] = 0; }, "band0.texCoord is 0"},
      {[](nlohmann::json& e) { e["sky"][2] = {1, 2}; }, "sky[2] is not an array of 3 numbers"},
      {[](nlohmann::json& e) { e["suns"][0]["direction"] = {0, 0, 0}; }, "suns[0].direction is zero"},
      {[](nlohmann::json& e) { e.erase("suns"); }, "has no 'suns'"},
  };
  for (const auto& [edit, message] : cases) {
    editGlbJson(dir / "corner.glb", dir / "broken.glb", [&](nlohmann::json& json) {
      for (nlohmann::json& m : json["materials"])
        if (m.contains("extensions") && m["extensions"].contains("LUXEL_lightmap_transfer")) {
          edit(m["extensions"]["LUXEL_lightmap_transfer"]);
          break;  // the first only
        }
    });
    const std::vector<std::string> before = listDir(dir);
    expectFailure(luxel(dir, {"view", "broken.glb", "--headless", "--frames", "1"}), dir, before,
                  {"broken.glb: material", "LUXEL_lightmap_transfer: " + message});
  }
  // The light of every material is one: the second material's suns edited alone disagree.
  editGlbJson(dir / "corner.glb", dir / "broken.glb", [&](nlohmann::json& json) {
    int seen = 0;
    for (nlohmann::json& m : json["materials"])
      if (m.contains("extensions") && m["extensions"].contains("LUXEL_lightmap_transfer") && seen++ == 1)
        m["extensions"]["LUXEL_lightmap_transfer"]["suns"][0]["irradiance"] = {1, 1, 1};
  });
  std::vector<std::string> before = listDir(dir);
  expectFailure(luxel(dir, {"view", "broken.glb", "--headless", "--frames", "1"}), dir, before,
                {"broken.glb: material", "differ from material"});
  // Actions: a direction that is not one, and a glb without a transfer.
  writeFile(dir / "bad.txt", "0 sun-direction 0,0,0\n");
  writeFile(dir / "short.txt", "0 sun-direction 1,2\n");
  ASSERT_EQ(luxel(dir, {"bake", "corner.json", "-o", "plain.glb", "--lightmaps", "--elements", "300", "-q"}).code, 0);
  before = listDir(dir);
  const CliRun zero = luxel(dir, {"view", "corner.glb", "--headless", "--frames", "2", "--script", "bad.txt", "--size", "32x32"});
  if (zero.code != 0 && zero.err.find("OpenGL 4.5") != std::string::npos) GTEST_SKIP() << "no OpenGL 4.5 context: " << zero.err;
  expectFailure(zero, dir, before, {"bad.txt:1: sun-direction: the direction is zero"});
  expectFailure(luxel(dir, {"view", "corner.glb", "--headless", "--frames", "2", "--script", "short.txt", "--size", "32x32"}), dir, before,
                {"short.txt:1: sun-direction: '1,2' is not X,Y,Z"});
  expectFailure(luxel(dir, {"view", "plain.glb", "--headless", "--frames", "2", "--script", "bad.txt", "--size", "32x32"}), dir, before,
                {"bad.txt:1: sun-direction: '", "holds no transfer bake to relight"});
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
