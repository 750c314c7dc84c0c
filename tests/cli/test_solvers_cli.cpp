// `luxel solvers` and the solver options on the command line: the registry as a user sees it.
#include <gtest/gtest.h>

#include <set>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "luxel/solver.h"

namespace {

TEST(SolversCli, JsonListsEveryRegisteredSolverWithItsOptions) {
  const fs::path dir = scratchDir();
  const CliRun r = luxel(dir, {"solvers", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json list = nlohmann::json::parse(r.out);
  const std::vector<luxel::SolverDescription> registered = luxel::registeredSolvers();
  ASSERT_EQ(list.size(), registered.size());
  std::set<std::pair<std::string, std::string>> seen;
  for (size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& s = list[i];
    EXPECT_EQ(s.at("name"), registered[i].name);
    EXPECT_EQ(s.at("backend"), registered[i].backend);
    EXPECT_FALSE(s.at("description").get<std::string>().empty());
    ASSERT_EQ(s.at("options").size(), registered[i].options.size());
    for (const nlohmann::json& o : s.at("options")) {
      EXPECT_TRUE(o.contains("name") && o.contains("default") && o.contains("help")) << o.dump();
      EXPECT_FALSE(o.at("help").get<std::string>().empty()) << o.dump();
    }
    seen.emplace(registered[i].name, registered[i].backend);
  }
  // The four solvers luxel ships.
  for (const auto& key : std::vector<std::pair<std::string, std::string>>{
           {"progressive", "cpu"}, {"gather", "cpu"}, {"progressive", "gl"}, {"gather", "gl"}})
    EXPECT_TRUE(seen.count(key)) << key.first << " on " << key.second;
}

TEST(SolversCli, TextListNamesEachSolverAndDefault) {
  const fs::path dir = scratchDir();
  const CliRun r = luxel(dir, {"solvers"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("progressive --backend cpu"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("gather --backend gl"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("unshot=... "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(default 0.001)"), std::string::npos) << r.out;
}

// --set reaches the solver: a shot budget of 3 stops after exactly 3 shots.
TEST(SolversCli, SetReachesTheSolver) {
  const fs::path dir = scratchDir();
  const CliRun r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--size", "16x16", "--spp", "1", "--elements", "300",
                               "--set", "shot-budget=3", "--stats", "s.json", "-q"});
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(readFile(dir / "s.json"));
  EXPECT_EQ(stats.at("shots"), 3);
  EXPECT_EQ(stats.at("solver"), "progressive");
}

TEST(SolversCli, AnOptionTheSolverDoesNotReadIsAnError) {
  const fs::path dir = scratchDir();
  // --unshot is progressive's; gather stops on its residual.
  CliRun r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--solver", "gather", "--unshot", "0.01"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("solver gather on cpu has no option 'unshot'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("residual"), std::string::npos) << r.err;  // it lists what it reads
  EXPECT_FALSE(fs::exists(dir / "c.exr"));
  // A hemicube option on the CPU backend.
  r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--hemicube-resolution", "32"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no option 'hemicube-resolution'"), std::string::npos) << r.err;
  // A name no solver has, and a value out of range.
  r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--set", "colour=red"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no option 'colour'"), std::string::npos) << r.err;
  r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--set", "rays-per-pair=0"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("rays-per-pair=0: must be in 1..256"), std::string::npos) << r.err;
  r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--set", "unshot"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("expected NAME=VALUE"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "c.exr"));
}

TEST(SolversCli, UnknownSolverOrBackendListsWhatExists) {
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--solver", "photon-map"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown solver 'photon-map' (registered: progressive/cpu, gather/cpu, hierarchical/cpu, incremental/cpu, cross-redistribution/cpu, progressive/gl, gather/gl, incremental/gl, cross-redistribution/gl)"),
            std::string::npos)
      << r.err;
  r = luxel(dir, {"render", "cornell", "-o", "c.exr", "--backend", "vulkan"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown backend 'vulkan' (expected cpu, gl or auto)"), std::string::npos) << r.err;
}

}  // namespace

namespace {

// --backend auto without a usable EGL (glvnd given no vendor library): the CPU solves, with a
// warning saying why, and options only the GL solver reads are dropped with a warning each.
TEST(SolversCli, AutoFallsBackToTheCpuAndWarnsAboutGlOnlyOptions) {
  const fs::path dir = scratchDir();
  const std::string cmd = "cd " + quote(dir.string()) + " && __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent " +
                          quote(LUXEL_CLI) +
                          " render cornell -o c.exr --size 16x16 --spp 1 --elements 300 --backend auto"
                          " --hemicube-resolution 32 --stats s.json >/dev/null 2>err.txt";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << readFile(dir / "err.txt");
  const std::string err = readFile(dir / "err.txt");
  EXPECT_NE(err.find("using the CPU backend"), std::string::npos) << err;
  EXPECT_NE(err.find("option hemicube-resolution=32 is not used by solver progressive on cpu; ignored"),
            std::string::npos)
      << err;
  const nlohmann::json stats = nlohmann::json::parse(readFile(dir / "s.json"));
  EXPECT_EQ(stats.at("backend"), "cpu");
  EXPECT_EQ(stats.at("warnings").size(), 2u);
}

}  // namespace

namespace {

// A scene without any light solves to black: luxel says so, names the scene and how to add light,
// and --sky / --sun add it from the command line.
TEST(LightlessScene, WarnsAndTheCommandLineCanAddASkyOrASun) {
  const fs::path dir = scratchDir();
  // A floor and a wall, no emission, no lights.
  writeFile(dir / "room.obj", "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 0 -1.5\nv 1 0 -1.5\nv 1 2 -1.5\nv -1 2 -1.5\n"
                              "f 1 4 3 2\nf 5 6 7 8\n");
  CliRun r = luxel(dir, {"render", "room.obj", "-o", "a.exr", "--size", "16x16", "--spp", "1", "--stats", "a.json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("scene 'room' has no light, so it solves to black"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--sky RADIANCE"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(readFile(dir / "a.json")).at("image").at("mean_luminance"), 0.0);

  r = luxel(dir, {"render", "room.obj", "-o", "b.exr", "--size", "16x16", "--spp", "1", "--stats", "b.json", "--sky",
                  "1000", "--sun", "0.3,-1,-0.2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("has no light"), std::string::npos) << r.err;
  EXPECT_GT(nlohmann::json::parse(readFile(dir / "b.json")).at("image").at("mean_luminance").get<double>(), 1.0);

  r = luxel(dir, {"bake", "room.obj", "-o", "c.glb", "--lightmaps"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("has no light"), std::string::npos) << r.err;

  r = luxel(dir, {"render", "room.obj", "-o", "d.exr", "--sun", "0,0,0"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--sun '0,0,0': expected a direction X,Y,Z, not zero"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "d.exr"));
}

TEST(LightlessScene, VersionFlag) {
  const CliRun r = luxel(scratchDir(), {"--version"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, "luxel 0.1.0\n");
}

}  // namespace
