// The luxel command-line tool (apps/luxel/main.cpp), run as a separate process: a successful render
// agrees with the library, and bad input fails with exit code 1 (2 for bad usage), a message on
// stderr naming what is wrong, and nothing written (no outputs, no temporary files).
//
// Scene values used: the built-in Cornell box (light radiance (17, 12, 4); no front wall, so light
// escapes and less is absorbed than emitted), rendered with 1500 elements at 64 x 64, 16 spp,
// hq mode, seed 7, progressive solver with unshot fraction 1e-3 (the CLI's defaults). Failure
// cases use 8 x 8 images and 200 elements to stay quick.
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/error.h"
#include "luxel/image.h"
#include "luxel/import.h"
#include "luxel/render.h"
#include "luxel/solve.h"
#include "cli/cli_runner.h"

namespace {

namespace fs = std::filesystem;

TEST(Cli, RenderWritesImagesAndStatsThatAgreeWithTheLibrary) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"render", "cornell", "-o", "out.exr", "-o", "out.png", "--size", "64x64", "--elements", "1500",
                      "--stats", "stats.json", "-q"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");  // -q: nothing but errors
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"out.exr", "out.png", "stats.json"}));
  EXPECT_GT(fs::file_size(dir / "out.png"), 100u);
  EXPECT_EQ(readFile(dir / "out.png").substr(1, 3), "PNG");

  luxel::Image cli = luxel::readExr(dir / "out.exr");
  ASSERT_EQ(cli.width, 64);
  ASSERT_EQ(cli.height, 64);

  // The same settings in-process: budget 1500, default solve options, default camera, 16 spp,
  // hq mode, seed 7.
  luxel::Scene scene = luxel::loadScene("cornell");
  luxel::DiscretiseOptions d;
  d.elementBudget = 1500;
  luxel::SurfaceSet set = luxel::discretise(scene, d);
  luxel::Solution sol = luxel::solve(scene, set, luxel::SolveOptions{});
  luxel::RenderOptions ro;
  ro.camera = *scene.findCamera("default");
  ro.width = ro.height = 64;
  luxel::Image lib = luxel::render(scene, set, sol, ro);
  glm::dvec3 cliSum(0.0), libSum(0.0);
  size_t differing = 0;
  for (size_t i = 0; i < lib.pixels.size(); ++i) {
    cliSum += glm::dvec3(cli.pixels[i]);
    libSum += glm::dvec3(lib.pixels[i]);
    differing += cli.pixels[i] != lib.pixels[i];
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(libSum[c], 0.0);
    EXPECT_NEAR(cliSum[c], libSum[c], 0.1 * libSum[c]) << "channel " << c;
  }
  // Same seeds, same options, 32-bit float EXR: the CLI and the library agree bit for bit.
  EXPECT_EQ(differing, 0u);

  nlohmann::json stats = nlohmann::json::parse(readFile(dir / "stats.json"));
  const auto elements = stats.at("elements").get<size_t>();
  EXPECT_EQ(elements, set.elements.size());
  EXPECT_GE(elements, 1050u);
  EXPECT_LE(elements, 2250u);
  EXPECT_LE(stats.at("unshot_fraction").get<double>(), 1e-3);
  EXPECT_EQ(stats.at("solver").get<std::string>(), "progressive");
  const double emitted = stats.at("energy").at("emitted").get<double>();
  const double absorbed = stats.at("energy").at("absorbed").get<double>();
  EXPECT_GT(absorbed, 0.0);
  EXPECT_GT(emitted, absorbed);  // the box is open at the front
  EXPECT_EQ(stats.at("image").at("width").get<int>(), 64);
  EXPECT_EQ(stats.at("image").at("height").get<int>(), 64);
  // mean_luminance is Rec. 709 luminance averaged over the pixels.
  double lum = 0.0;
  for (const luxel::Rgb& p : cli.pixels) lum += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
  lum /= double(cli.pixels.size());
  EXPECT_NEAR(stats.at("image").at("mean_luminance").get<double>(), lum, 1e-6 * lum);
}

TEST(Cli, MissingSceneFile) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "nowhere/missing.obj", "-o", "out.png"}));
  expectFailure(r, dir, {}, {"missing.obj", "no such file"});
  r = luxel(dir, args({"render", "absent.json", "-o", "out.png"}));
  expectFailure(r, dir, {}, {"absent.json"});
}

TEST(Cli, MalformedObj) {
  fs::path dir = scratchDir();
  std::string garbage;
  uint32_t x = 12345;
  for (int i = 0; i < 4096; ++i) {
    x = x * 1664525u + 1013904223u;
    garbage += char(x >> 24);
  }
  writeFile(dir / "broken.obj", garbage);
  CliRun r = luxel(dir, args({"render", "broken.obj", "-o", "out.png"}));
  expectFailure(r, dir, {"broken.obj"}, {"broken.obj"});
}

TEST(Cli, UnknownBuiltinOrExtension) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "cornel", "-o", "out.png"}));
  expectFailure(r, dir, {}, {"cornel"});
  writeFile(dir / "scene.xyz", "hello\n");
  r = luxel(dir, args({"render", "scene.xyz", "-o", "out.png"}));
  expectFailure(r, dir, {"scene.xyz"}, {"scene.xyz"});
  // An output extension other than .exr and .png.
  r = luxel(dir, args({"render", "cornell", "-o", "out.jpg"}));
  expectFailure(r, dir, {"scene.xyz"}, {"out.jpg", ".exr or .png"});
}

TEST(Cli, BadImageSize) {
  fs::path dir = scratchDir();
  for (const char* size : {"0x10", "10x0", "10", "-5x5", "10x10x10", "40000x10"}) {
    CliRun r = luxel(dir, {"render", "cornell", "-o", "out.png", "--size", size, "--elements", "200", "-q"});
    expectFailure(r, dir, {}, {"--size", size});
  }
}

TEST(Cli, OutputIntoMissingDirectoryWritesNothing) {
  fs::path dir = scratchDir();
  // The first output could be written, but the second cannot: neither is.
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "good.exr", "-o", "no/such/dir/out.png"}));
  expectFailure(r, dir, {}, {"no/such/dir", "does not exist"});
  EXPECT_FALSE(fs::exists(dir / "no"));
}

TEST(Cli, OutputOntoADirectoryLeavesNoTemporaryFile) {
  fs::path dir = scratchDir();
  fs::create_directory(dir / "taken.exr");  // the rename into place must fail
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "taken.exr"}));
  expectFailure(r, dir, {"taken.exr"}, {"taken.exr"});
  EXPECT_TRUE(fs::is_directory(dir / "taken.exr"));
  EXPECT_TRUE(fs::is_empty(dir / "taken.exr"));
}

TEST(Cli, UnknownOptionIsAUsageError) {
  fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "out.png", "--bogus"}));
  expectFailure(r, dir, {}, {"--bogus"}, 2);
  r = luxel(dir, {"render"});  // missing scene and output
  EXPECT_EQ(r.code, 2) << r.err;
  r = luxel(dir, {"paint", "cornell"});  // unknown subcommand
  EXPECT_EQ(r.code, 2) << r.err;
  r = luxel(dir, args({"render", "cornell", "-o", "out.png", "--spp", "0"}));  // out of range
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(listDir(dir), std::vector<std::string>{});
}

TEST(Cli, SceneWithMissingTexture) {
  fs::path dir = scratchDir();
  writeFile(dir / "scene.json", R"({ "builtin": "cornell",
    "materials": { "white": { "texture": "textures/plaster.png" } } })");
  CliRun r = luxel(dir, args({"render", "scene.json", "-o", "out.png"}));
  expectFailure(r, dir, {"scene.json"}, {"scene.json", "/materials/white/texture", "plaster.png"});
}

TEST(Cli, NegativeLightIntensity) {
  fs::path dir = scratchDir();
  writeFile(dir / "neg.json", R"({ "builtin": "cornell",
    "lights": [ { "type": "point", "position": [0.3, 0.3, 0.3], "intensity": -5 } ] })");
  CliRun r = luxel(dir, args({"render", "neg.json", "-o", "out.png"}));
  expectFailure(r, dir, {"neg.json"}, {"neg.json", "/lights/0/intensity", "negative"});
}

TEST(Cli, InfiniteLightIntensity) {
  fs::path dir = scratchDir();
  // 1e999 is valid JSON (RFC 8259 sets no range) but overflows a double.
  writeFile(dir / "inf.json", R"({ "builtin": "cornell",
    "lights": [ { "type": "point", "position": [0.3, 0.3, 0.3], "intensity": 1e999 } ] })");
  CliRun r = luxel(dir, args({"render", "inf.json", "-o", "out.png"}));
  expectFailure(r, dir, {"inf.json"}, {"inf.json", "1e999"});
  EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
  // The library's contract: a luxel::Error naming the file.
  try {
    luxel::loadSceneFile(dir / "inf.json");
    ADD_FAILURE() << "loaded a light of infinite intensity";
  } catch (const luxel::Error& e) {
    EXPECT_NE(std::string(e.what()).find("inf.json"), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-luxel exception: " << e.what();
  }
}

}  // namespace

namespace {

// --progress-trace: every report, in time order, each phase ending at 1; a missing folder is an
// error before any work.
TEST(Cli, ProgressTraceRecordsEveryPhase) {
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, args({"render", "cornell", "-o", "c.exr", "--progress-trace", "t.tsv"}));
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(readFile(dir / "t.tsv"));
  std::string line;
  double last = 0.0;
  std::map<std::string, double> endOf;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string seconds, phase, fraction;
    ASSERT_TRUE(std::getline(fields, seconds, '\t') && std::getline(fields, phase, '\t') &&
                std::getline(fields, fraction, '\t'))
        << line;
    EXPECT_GE(std::stod(seconds), last) << line;
    last = std::stod(seconds);
    endOf[phase] = std::stod(fraction);
  }
  EXPECT_EQ(endOf["solve"], 1.0);
  EXPECT_EQ(endOf["render"], 1.0);
  r = luxel(dir, args({"render", "cornell", "-o", "d.exr", "--progress-trace", "nowhere/t.tsv"}));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("nowhere"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "d.exr"));
}

}  // namespace
