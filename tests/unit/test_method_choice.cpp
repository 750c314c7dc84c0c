// The solver `auto` picks (solve/method_choice.h): progressive for a small scene, the face-cluster
// hierarchy for one whose patches would make progressive shooting take minutes, and options only
// the other method reads dropped with a warning rather than refused.
#include <gtest/gtest.h>

#include <algorithm>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/solve.h"
#include "solve/method_choice.h"

namespace luxel {
namespace {

TEST(MethodChoice, TheRuleIsByPatchesAndBackend) {
  EXPECT_EQ(chooseMethod("auto", "cpu", kHierarchicalPatches), "progressive");
  EXPECT_EQ(chooseMethod("auto", "cpu", kHierarchicalPatches + 1), "hierarchical");
  EXPECT_EQ(chooseMethod("auto", "auto", kHierarchicalPatches + 1), "hierarchical");
  EXPECT_EQ(chooseMethod("auto", "gl", kHierarchicalPatches + 1), "progressive");  // no GL hierarchy
  EXPECT_EQ(chooseMethod("gather", "cpu", kHierarchicalPatches + 1), "gather");
  // Sessions that will follow moves (luxel animate) get the dynamic solver in progressive's place.
  EXPECT_EQ(chooseMethod("auto", "cpu", kHierarchicalPatches, true), "cross-redistribution");
  EXPECT_EQ(chooseMethod("auto", "gl", kHierarchicalPatches + 1, true), "cross-redistribution");
  EXPECT_EQ(chooseMethod("auto", "cpu", kHierarchicalPatches + 1, true), "hierarchical");
  EXPECT_EQ(chooseMethod("progressive", "cpu", 10, true), "progressive");
}

// The default is auto: the Cornell box (189 patches) solves progressively, seed 002's room at
// 20k faces (20,030 patches) with the hierarchy.
TEST(MethodChoice, TheDefaultSolverFollowsTheScene) {
  SolveOptions defaults;
  EXPECT_EQ(defaults.method, "auto");
  for (const auto& [name, expected] : {std::pair{"cornell", "progressive"}, std::pair{"room-20k", "hierarchical"}}) {
    const Scene scene = loadScene(name);
    SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
    const Solution s = solve(scene, surfaces, defaults);
    EXPECT_EQ(s.stats.method, expected) << name << ", " << surfaces.patches.size() << " patches";
  }
}

TEST(MethodChoice, AnOptionOfTheMethodNotChosenIsDroppedWithAWarning) {
  const Scene scene = loadScene("cornell");
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
  SolveOptions o;
  o.settings.set("receiver-points", 4);  // the hierarchy's
  const Solution s = solve(scene, surfaces, o);
  EXPECT_EQ(s.stats.method, "progressive");
  EXPECT_TRUE(std::any_of(s.stats.warnings.begin(), s.stats.warnings.end(), [](const std::string& w) {
    return w.find("receiver-points=4 is not used by solver progressive") != std::string::npos;
  }));
  o.settings = SolverSettings().set("colour", "red");  // no method `auto` chooses reads it
  EXPECT_THROW(solve(scene, surfaces, o), Error);
}

}  // namespace
}  // namespace luxel
