// Adaptive refinement: elements split where the solution's gradient is large, within the budget,
// and the area where neighbouring elements disagree shrinks. Scene: the built-in Cornell box (RGB
// reflectances and light as in src/scene/builtin/cornell_box.cpp), radiosity display.
#include <cmath>

#include <gtest/gtest.h>

#include "luxel/solve.h"
#include "mesh/corner_groups.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

// The floor area whose elements differ from a neighbour on the same surface by more than the
// refinement threshold: the area refinement exists to shrink. (A contact shadow is a true
// discontinuity, so the largest jump stays near 1; the area around it is what gets smaller.)
double areaWithLargeJumps(const SurfaceSet& set, const Solution& sol, size_t face, double threshold) {
  CornerGroups groups(set, kDefaultCreaseCosine);
  double area = 0.0;
  for (uint32_t e = 0; e < set.elements.size(); ++e) {
    if (set.elements[e].face != face) continue;
    double be = sol.radiosity[e].g, worst = 0.0;
    for (int c = 0; c < set.elements[e].polygon.count; ++c)
      for (uint32_t n : groups.at(e, c)) {
        double bn = sol.radiosity[n].g;
        worst = std::max(worst, 2.0 * std::abs(be - bn) / std::max(be + bn, 1e-9));
      }
    if (worst > threshold) area += set.elements[e].area;
  }
  return area;
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
  o.refine.budget = 1200;
  Solution after = solve(scene, refined, o);

  const SolveStats& st = after.stats;
  EXPECT_GT(st.refinedElements, 0u);
  EXPECT_LE(st.refinedElements, o.refine.budget);
  EXPECT_EQ(refined.elements.size(), coarse.elements.size() + st.refinedElements);
  EXPECT_NEAR(refined.totalArea(), area, 1e-4 * area);
  EXPECT_EQ(after.radiosity.size(), refined.elements.size());

  // What the refinement pass returns is the solution of the refined elements: a fresh solve of
  // the same surfaces (new transport, nothing carried over) agrees per element.
  SurfaceSet again = refined;
  SolveOptions plain;
  Solution fresh = solve(scene, again, plain);
  ASSERT_EQ(fresh.radiosity.size(), after.radiosity.size());
  for (size_t e = 0; e < fresh.radiosity.size(); ++e)
    ASSERT_NEAR(fresh.radiosity[e].g, after.radiosity[e].g, 5e-3 * std::max(0.05f, fresh.radiosity[e].g))
        << "element " << e;

  // The floor (face 0) carries the blocks' shadows: refinement must go there and shrink the area
  // where neighbouring elements disagree.
  size_t floorSplits = 0;
  for (const Element& e : refined.elements) floorSplits += (e.face == 0 && e.depth > 0) ? 1 : 0;
  EXPECT_GT(floorSplits, 0u);
  const double threshold = o.refine.threshold;
  EXPECT_LT(areaWithLargeJumps(refined, after, 0, threshold), 0.85 * areaWithLargeJumps(coarse, before, 0, threshold));
}

TEST(Refinement, UniformSolutionNeedsNone) {
  // The furnace is uniform: nothing exceeds the threshold, so nothing is split.
  Scene scene = builtin::furnace(0.5f, 1.0f);
  DiscretiseOptions d;
  d.elementBudget = 300;
  SurfaceSet set = discretise(scene, d);
  SolveOptions o;
  o.refine.budget = 1000;
  Solution s = solve(scene, set, o);
  EXPECT_EQ(s.stats.refinedElements, 0u);
  EXPECT_EQ(s.stats.refinePasses, 0);
}

}  // namespace
}  // namespace luxel
