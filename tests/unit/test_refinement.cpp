// Adaptive refinement: elements split where the solution's gradient is large, within the budget,
// and the split makes neighbouring elements agree better. Scene: the built-in Cornell box (RGB
// reflectances and light as in src/scene/builtin/cornell_box.cpp), radiosity display.
#include <cmath>

#include <gtest/gtest.h>

#include "luxel/solve.h"
#include "mesh/corner_groups.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

// The largest relative radiosity jump between elements that share a corner on one surface.
double worstNeighbourJump(const SurfaceSet& set, const Solution& sol, size_t face) {
  CornerGroups groups(set, kDefaultCreaseCosine);
  double worst = 0.0;
  for (uint32_t e = 0; e < set.elements.size(); ++e) {
    if (set.elements[e].face != face) continue;
    double be = sol.radiosity[e].g;
    for (int c = 0; c < set.elements[e].polygon.count; ++c)
      for (uint32_t n : groups.at(e, c)) {
        double bn = sol.radiosity[n].g;
        worst = std::max(worst, std::abs(be - bn) / std::max(be + bn, 1e-9));
      }
  }
  return worst;
}

TEST(Refinement, SplitsWhereTheGradientIsLargeWithinBudget) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 800;
  SurfaceSet coarse = discretise(scene, d);
  SurfaceSet refined = coarse;
  const double area = coarse.totalArea();

  SolveOptions o;
  Solution before = solve(scene, coarse, o);
  o.refineBudget = 1200;
  Solution after = solve(scene, refined, o);

  const SolveStats& st = after.stats;
  EXPECT_GT(st.refinedElements, 0u);
  EXPECT_LE(st.refinedElements, o.refineBudget);
  EXPECT_EQ(refined.elements.size(), coarse.elements.size() + st.refinedElements);
  EXPECT_NEAR(refined.totalArea(), area, 1e-4 * area);
  EXPECT_EQ(after.radiosity.size(), refined.elements.size());

  // The floor (face 0) carries the blocks' shadows: refinement must go there and make
  // neighbouring elements agree better than before.
  size_t floorSplits = 0;
  for (const Element& e : refined.elements) floorSplits += (e.face == 0 && e.depth > 0) ? 1 : 0;
  EXPECT_GT(floorSplits, 0u);
  EXPECT_LT(worstNeighbourJump(refined, after, 0), worstNeighbourJump(coarse, before, 0));
}

TEST(Refinement, UniformSolutionNeedsNone) {
  // The furnace is uniform: nothing exceeds the threshold, so nothing is split.
  Scene scene = builtin::furnace(0.5f, 1.0f);
  DiscretiseOptions d;
  d.elementBudget = 300;
  SurfaceSet set = discretise(scene, d);
  SolveOptions o;
  o.refineBudget = 1000;
  Solution s = solve(scene, set, o);
  EXPECT_EQ(s.stats.refinedElements, 0u);
  EXPECT_EQ(s.stats.refinePasses, 0);
}

}  // namespace
}  // namespace luxel
