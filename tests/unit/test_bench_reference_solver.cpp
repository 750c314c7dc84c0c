// A benchmark case may name the solve its reference comes from (bench/reference.h), for scenes
// whose pairs no gather could hold. That solve must be the one run, and cached apart from the
// default gather's on the same elements.
#include <filesystem>

#include <gtest/gtest.h>

#include "bench/reference.h"
#include "luxel/bench.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

TEST(BenchReference, CaseSolverIsUsedAndCachedApart) {
  const Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 200;
  const SurfaceSet surfaces = discretise(scene, d);
  const std::filesystem::path cache = std::filesystem::temp_directory_path() / "luxel-test-reference-solver";
  std::filesystem::remove_all(cache);

  const bench::Reference gathered = bench::loadOrComputeReference(scene, surfaces, cache.string(), {});
  // One bounce: a progressive solve stopped after the light's own shots sees only direct light,
  // far from the converged gather, so the test can tell which solve made the reference.
  SolveOptions direct;
  direct.method = "progressive";
  direct.settings.set("shot-budget", 1.0).set("ambient", false);
  const bench::Reference shot = bench::loadOrComputeReference(scene, surfaces, cache.string(), {},
                                                              bench::Options::ReferenceKind::Cpu, direct);
  EXPECT_NE(shot.path, gathered.path);
  EXPECT_GT(shot.seconds, 0.0);  // solved, not read from the gather's file
  const double difference = bench::normalisedRmsError(surfaces, shot.radiosity, gathered.radiosity);
  EXPECT_GT(difference, 0.1) << "one shot without the ambient term cannot match the converged gather";

  // Asked again, both come from the cache unchanged.
  const bench::Reference again = bench::loadOrComputeReference(scene, surfaces, cache.string(), {},
                                                               bench::Options::ReferenceKind::Cpu, direct);
  EXPECT_EQ(again.seconds, 0.0);
  EXPECT_EQ(again.path, shot.path);
  EXPECT_EQ(bench::normalisedRmsError(surfaces, again.radiosity, shot.radiosity), 0.0);
  std::filesystem::remove_all(cache);
}

}  // namespace
}  // namespace luxel
