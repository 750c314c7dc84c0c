// `luxel bench` end to end on the "quick" suite (the built-in Cornell box at about 1,000
// elements): the JSON carries the machine, the commit and every column the benchmark issue asks
// for, the reference is computed once and then read from the cache, and bad input fails cleanly.
// The error measure itself is checked against hand-made values.
#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "luxel/bench.h"
#include "luxel/error.h"

namespace {

TEST(BenchCli, QuickSuiteWritesEveryColumnAndCachesTheReference) {
  const fs::path dir = scratchDir();
  const std::vector<std::string> args = {"bench", "quick", "--runs", "2", "--json", "q.json", "--cache", "refs"};
  CliRun first = luxel(dir, args);
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_NE(first.out.find("cornell/progressive"), std::string::npos) << first.out;

  const nlohmann::json j = nlohmann::json::parse(readFile(dir / "q.json"));
  EXPECT_EQ(j["suite"], "quick");
  EXPECT_EQ(j["runs"], 2);
  EXPECT_FALSE(j["machine"]["cpu"].get<std::string>().empty());
  EXPECT_GE(j["machine"]["hardware_threads"].get<int>(), 1);
  EXPECT_FALSE(j["date"].get<std::string>().empty());
  ASSERT_EQ(j["cases"].size(), 1u);
  const auto& c = j["cases"][0];
  EXPECT_GT(c["elements"].get<int>(), 500);
  EXPECT_GT(c["patches"].get<int>(), 10);
  const auto& t = c["seconds"]["total"];
  EXPECT_LE(t["min"].get<double>(), t["median"].get<double>());
  EXPECT_LE(t["median"].get<double>(), t["max"].get<double>());
  EXPECT_GT(c["seconds"]["form_factors"]["median"].get<double>(), 0.0);
  EXPECT_GT(c["rays"].get<double>(), 1000.0);
  EXPECT_GT(c["rays_per_second"].get<double>(), 0.0);
  // The solver's rays per second cannot beat Embree alone on the same rays by much (timing noise).
  EXPECT_GT(c["embree_raw_rays_per_second"].get<double>(), 0.0);
  EXPECT_GT(c["fraction_of_embree_raw"].get<double>(), 0.0);
  EXPECT_LT(c["fraction_of_embree_raw"].get<double>(), 1.5);
  EXPECT_GT(c["peak_memory_bytes"].get<double>(), 1e6);
  // 1,000 elements, progressive to 1% unshot: a few percent from the converged reference.
  ASSERT_TRUE(c["error"].is_number()) << c.dump();
  EXPECT_GT(c["error"].get<double>(), 0.0);
  EXPECT_LT(c["error"].get<double>(), 0.05);
  EXPECT_GT(c["reference_seconds"].get<double>(), 0.0);  // computed this time

  CliRun second = luxel(dir, args);
  ASSERT_EQ(second.code, 0) << second.err;
  const nlohmann::json j2 = nlohmann::json::parse(readFile(dir / "q.json"));
  EXPECT_EQ(j2["cases"][0]["reference_seconds"].get<double>(), 0.0);  // read from the cache
  EXPECT_EQ(j2["cases"][0]["error"].get<double>(), c["error"].get<double>());  // deterministic
}

TEST(BenchCli, UnknownSuiteAndBadOutputFail) {
  const fs::path dir = scratchDir();
  CliRun unknown = luxel(dir, {"bench", "nope", "--no-reference"});
  EXPECT_EQ(unknown.code, 1);
  EXPECT_NE(unknown.err.find("nope"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("seeds"), std::string::npos) << unknown.err;  // lists the known ones

  CliRun badDir = luxel(dir, {"bench", "quick", "--json", "missing/q.json", "--no-reference"});
  EXPECT_EQ(badDir.code, 1);
  EXPECT_NE(badDir.err.find("missing"), std::string::npos) << badDir.err;
  EXPECT_FALSE(fs::exists(dir / "missing"));

  CliRun noCase = luxel(dir, {"bench", "quick", "--case", "sibenik", "--no-reference"});
  EXPECT_EQ(noCase.code, 1);
  EXPECT_NE(noCase.err.find("sibenik"), std::string::npos) << noCase.err;
}

TEST(BenchError, NormalisedRmsAgainstHandValues) {
  luxel::SurfaceSet set;
  set.elements.resize(3);
  set.elements[2].exitance = luxel::Rgb(1.0f);  // an emitter: left out
  const std::vector<luxel::Rgb> ref = {luxel::Rgb(1.0f), luxel::Rgb(3.0f), luxel::Rgb(100.0f)};
  EXPECT_EQ(luxel::bench::normalisedRmsError(set, ref, ref), 0.0);
  // Every non-emitter 10% high: the normalised RMS is exactly 0.1, whatever the emitter does.
  const std::vector<luxel::Rgb> high = {luxel::Rgb(1.1f), luxel::Rgb(3.3f), luxel::Rgb(0.0f)};
  EXPECT_NEAR(luxel::bench::normalisedRmsError(set, high, ref), 0.1, 1e-6);
  // One element off by 1 in one channel: sqrt(1 / (3 * (1 + 9))).
  std::vector<luxel::Rgb> one = ref;
  one[0].g += 1.0f;
  EXPECT_NEAR(luxel::bench::normalisedRmsError(set, one, ref), std::sqrt(1.0 / 30.0), 1e-6);
  EXPECT_THROW(luxel::bench::normalisedRmsError(set, {luxel::Rgb(1.0f)}, ref), luxel::Error);
}

}  // namespace
