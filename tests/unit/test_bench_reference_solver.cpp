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

// A hierarchical case drops its surfaces' patches (as luxel render does), and its stats say 0
// patches; the reference's size is still that of the surfaces cut again, patches and all. Read
// from the stats, a case too large for a gather went on to build one, and failed.
TEST(BenchReference, AHierarchicalCaseIsSizedByTheSurfacesAsCut) {
  bench::Case c;
  c.name = "cornell/hierarchical";
  c.scene = "cornell";
  c.discretise.elementBudget = 400;
  c.solve.method = "hierarchical";
  c.maxReferencePairs = 1000;  // far fewer than 400 elements x their patches
  bench::Options o;
  o.runs = 1;
  o.hardwareLimit = false;
  o.cacheDir = (std::filesystem::temp_directory_path() / "luxel-test-reference-size").string();
  const bench::CaseResult r = bench::runCase(c, o);
  EXPECT_GT(r.patches, 0u);
  EXPECT_FALSE(r.error.has_value());
  EXPECT_NE(r.errorNote.find("no reference"), std::string::npos) << r.errorNote;
}

}  // namespace
}  // namespace luxel
