// `luxel bench dynamic` end to end on cornell-low, 5 frames, on the CPU: every field the dynamic
// radiosity issue (15) asks of a case is in the JSON, the errors are what a 1e-3 stopping rule
// leaves, and the suite's own options are refused with other suites. No assertion on speed.
#include <cmath>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/import.h"

namespace {

TEST(BenchDynamicCli, FiveFramesOfCornellLowWriteEveryField) {
  const fs::path dir = scratchDir();
  CliRun run = luxel(dir, {"bench", "dynamic", "--frames", "5", "--scenes", "cornell-low", "--backends", "cpu", "--json",
                           "d.json", "--cache", "refs"});
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("cornell-low/cross-redistribution/cpu"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("1 degree a frame"), std::string::npos) << run.out;  // the motion is stated

  const nlohmann::json j = nlohmann::json::parse(readFile(dir / "d.json"));
  EXPECT_EQ(j["suite"], "dynamic");
  EXPECT_EQ(j["frames"], 5);
  EXPECT_EQ(j["degrees_per_frame"], 1.0);
  EXPECT_EQ(j["frames_per_second"], 30.0);
  EXPECT_EQ(j["error_frames"], "every frame");
  EXPECT_FALSE(j["machine"]["cpu"].get<std::string>().empty());
  EXPECT_FALSE(j["date"].get<std::string>().empty());
  ASSERT_EQ(j["cases"].size(), 3u) << j.dump(1);

  // 001 Tables 5.2a and 5.1, low quality column.
  const std::map<std::string, std::pair<double, double>> seed = {
      {"progressive", {49, 0.0149107}}, {"incremental", {14, 0.0197874}}, {"cross-redistribution", {7, 0.0147345}}};
  std::map<std::string, double> factors;
  for (const auto& c : j["cases"]) {
    SCOPED_TRACE(c.dump());
    const std::string method = c["method"];
    ASSERT_TRUE(seed.count(method));
    EXPECT_EQ(c["scene"], "cornell-low");
    EXPECT_EQ(c["backend"], "cpu");
    EXPECT_EQ(c["frames"], 5);
    EXPECT_EQ(c["degrees_per_frame"], 1.0);  // read from the scene's animation
    // 2,734 static elements and 270 on the box (docs/seed-scenes.md).
    EXPECT_EQ(c["elements"], 3004);
    EXPECT_EQ(c["moving_elements"], 270);
    const double median = c["ms_per_frame"]["median"], p95 = c["ms_per_frame"]["p95"];
    EXPECT_GT(median, 0.0);
    EXPECT_GE(p95, median);
    ASSERT_EQ(c["frame_ms"].size(), 5u);
    EXPECT_EQ(c["error_frames"], nlohmann::json({1, 2, 3, 4, 5}));
    ASSERT_EQ(c["errors"].size(), 5u);
    // Every method stops at 1e-3 of the power unshot; its reference at 1e-6 on the same factors.
    // A few times 1e-3 apart at most (test_dynamic_radiosity.cpp: within 3e-3 after 200 random
    // moves); 0.05 is the bound the brief set, far above it.
    for (const auto& e : c["errors"]) {
      EXPECT_TRUE(std::isfinite(e.get<double>()));
      EXPECT_GT(e.get<double>(), 0.0);
      EXPECT_LT(e.get<double>(), 0.05);
    }
    EXPECT_LE(c["error"]["median"].get<double>(), c["error"]["max"].get<double>());
    EXPECT_LT(c["error"]["max"].get<double>(), 0.05);
    ASSERT_EQ(c["settle_error"].size(), 4u);
    for (const auto& e : c["settle_error"]) EXPECT_LT(e.get<double>(), 0.01);  // the 1%
    EXPECT_EQ(c["seed_gtx670_ms"].get<double>(), seed.at(method).first);
    EXPECT_EQ(c["seed_error"].get<double>(), seed.at(method).second);
    ASSERT_TRUE(c["speedup_over_progressive"].is_number());
    EXPECT_GT(c["speedup_over_progressive"].get<double>(), 0.0);
    if (method == "progressive") {
      EXPECT_EQ(c["speedup_over_progressive"].get<double>(), 1.0);
      EXPECT_TRUE(c["factors_recomputed_per_frame"].is_null());
    } else {
      ASSERT_TRUE(c["factors_recomputed_per_frame"].is_number());
      factors[method] = c["factors_recomputed_per_frame"];
    }
  }
  // Cross-redistribution recomputes only what the box's old and new places touch; incremental
  // every patch's column (counts, not times: deterministic).
  // Issue 15's targets, judged on each dynamic method against 001's cross-redistribution figures
  // (the verdicts are timings: only their presence is checked, and the figures they compare).
  ASSERT_EQ(j["targets"].size(), 2u);
  for (const auto& t : j["targets"]) {
    EXPECT_EQ(t["scene"], "cornell-low");
    EXPECT_NE(t["method"], "progressive");
    EXPECT_EQ(t["seed_ms"].get<double>(), 7.0);
    EXPECT_EQ(t["seed_error"].get<double>(), 0.0147345);
    EXPECT_EQ(t["seed_speedup"].get<double>(), 7.0);  // 49 / 7
    EXPECT_TRUE(t["time_met"].is_boolean() && t["speedup_met"].is_boolean());
    EXPECT_EQ(t["settle_met"], t["settle_error"].get<double>() <= 0.01);
  }
  ASSERT_EQ(factors.size(), 2u);
  EXPECT_GT(factors["cross-redistribution"], 0.0);
  EXPECT_LT(factors["cross-redistribution"], factors["incremental"]);
}

TEST(BenchDynamicCli, ItsOptionsBelongToItAlone) {
  const fs::path dir = scratchDir();
  CliRun runs = luxel(dir, {"bench", "dynamic", "--runs", "3"});
  EXPECT_EQ(runs.code, 1);
  EXPECT_NE(runs.err.find("--frames"), std::string::npos) << runs.err;
  CliRun frames = luxel(dir, {"bench", "quick", "--frames", "3", "--no-reference"});
  EXPECT_EQ(frames.code, 1);
  EXPECT_NE(frames.err.find("dynamic"), std::string::npos) << frames.err;
  CliRun scene = luxel(dir, {"bench", "dynamic", "--scenes", "cornell"});
  EXPECT_NE(scene.code, 0);
  CliRun none = luxel(dir, {"bench", "dynamic", "--scenes", "cornell-low", "--case", "nothing"});
  EXPECT_EQ(none.code, 1);
  EXPECT_NE(none.err.find("no case"), std::string::npos) << none.err;
}

// The suite plays each scene's own animation: frame k is rest * rotate(k degrees, y) about the
// box's centre (its origin), counter-clockwise seen from above.
TEST(BenchDynamic, TheBoxTurnsOneDegreeAFrameAboutItsVerticalAxis) {
  for (const char* name : {"indirect-light", "cornell-large", "cornell-small", "cornell-low"}) {
    const luxel::Scene scene = luxel::loadScene(name);
    const uint32_t box = scene.dynamicObjects().at(0);
    const glm::mat4 rest = scene.objects[box].transform;
    for (int k : {0, 1, 90, 100}) {
      const glm::mat4 expected = rest * glm::rotate(glm::mat4(1.0f), glm::radians(float(k)), luxel::Vec3(0, 1, 0));
      const glm::mat4 pose = luxel::bench::dynamicPose(scene, k);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(pose[c][r], expected[c][r], 1e-5f) << name << " frame " << k;
    }
    // A point one unit along the box's x goes to -z after a quarter turn (right-handed about y).
    const luxel::Vec3 centre(rest[3]), side(luxel::bench::dynamicPose(scene, 90) * glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(glm::length(side - (centre + luxel::Vec3(0, 0, -1))), 0.0f, 1e-5f) << name;
  }
  luxel::Scene still = luxel::loadScene("cornell-low");
  still.animation = {};
  EXPECT_THROW(luxel::bench::dynamicPose(still, 1), luxel::Error);
}

}  // namespace
