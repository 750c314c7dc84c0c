// Surfaces without patches (SurfaceSet::dropPatches): a session whose solver does not shoot from
// patches (the face-cluster hierarchy) drops them, which at one element a face is a third of the
// surfaces' memory, and solves exactly as with them; a solver that needs them refuses such a set
// instead of reading past its end.
#include <gtest/gtest.h>

#include <string>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/session.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "session/solver_host.h"
#include "solve/method_choice.h"

namespace luxel {
namespace {

SolveOptions method(const std::string& name) {
  SolveOptions o;
  o.method = name;
  return o;
}

TEST(DroppedPatches, OnlyASolverThatDoesNotShootFromPatchesLetsThemGo) {
  const Scene cornell = builtin::cornellBox();
  const SurfaceSet small = discretise(cornell, DiscretiseOptions{});
  EXPECT_TRUE(mayShootFromPatches(method("auto"), small));  // auto picks progressive here
  EXPECT_TRUE(mayShootFromPatches(method("progressive"), small));
  EXPECT_TRUE(mayShootFromPatches(method("cross-redistribution"), small));
  EXPECT_FALSE(mayShootFromPatches(method("hierarchical"), small));
  EXPECT_TRUE(mayShootFromPatches(method("no-such-solver"), small));  // the host's error says why

  const Scene room = loadScene("room-20k");
  const SurfaceSet large = discretise(room, DiscretiseOptions{});
  EXPECT_FALSE(mayShootFromPatches(method("auto"), large));  // auto picks the hierarchy
  SolveOptions onGl = method("auto");
  onGl.backend = "gl";  // no GL hierarchy: auto picks progressive on GL
  EXPECT_TRUE(mayShootFromPatches(onGl, large));
}

TEST(DroppedPatches, TheHierarchySolvesTheSameWithoutThem) {
  DiscretiseOptions d;
  d.elementBudget = 1000;
  SessionOptions dropping{method("hierarchical")};
  SessionOptions keeping = dropping;
  keeping.keepPatches = true;
  Session without(builtin::cornellBox(), d, dropping), with(builtin::cornellBox(), d, keeping);

  const SurfaceSet& s = without.surfaces();
  EXPECT_FALSE(s.hasPatches());
  EXPECT_EQ(s.patches.capacity(), 0u);  // freed, not only emptied
  for (const Element& e : s.elements) ASSERT_EQ(e.patch, kNoPatch);
  EXPECT_TRUE(with.surfaces().hasPatches());

  const Solution a = without.solve(), b = with.solve();
  EXPECT_EQ(a.stats.patches, 0u);
  EXPECT_EQ(b.stats.patches, with.surfaces().patches.size());
  ASSERT_EQ(a.irradiance.size(), b.irradiance.size());
  for (size_t e = 0; e < a.irradiance.size(); ++e) {
    ASSERT_EQ(a.irradiance[e].r, b.irradiance[e].r) << "element " << e;
    ASSERT_EQ(a.irradiance[e].g, b.irradiance[e].g) << "element " << e;
    ASSERT_EQ(a.irradiance[e].b, b.irradiance[e].b) << "element " << e;
  }
}

TEST(DroppedPatches, ASolverThatShootsFromPatchesRefusesASetWithout) {
  const Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
  surfaces.dropPatches();
  try {
    solve(scene, surfaces, method("progressive"));
    FAIL() << "progressive solved surfaces without patches";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shoots from patches"), std::string::npos) << e.what();
  }
  // Auto counts the elements instead (never fewer than the patches were, so a set dropped for
  // the hierarchy keeps it): here 10,000, which pick the hierarchy.
  ASSERT_GT(surfaces.elements.size(), kHierarchicalPatches);
  EXPECT_EQ(solve(scene, surfaces, method("auto")).stats.method, "hierarchical");
}

TEST(DroppedPatches, AnElementSplitsWithoutThem) {
  const Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
  surfaces.dropPatches();
  const size_t before = surfaces.elements.size();
  const float area = surfaces.elements[0].area;
  surfaces.splitElement(0, scene);
  ASSERT_EQ(surfaces.elements.size(), before + 3);
  float children = surfaces.elements[0].area;
  for (size_t c = before; c < before + 3; ++c) {
    EXPECT_EQ(surfaces.elements[c].patch, kNoPatch);
    children += surfaces.elements[c].area;
  }
  EXPECT_NEAR(children, area, 1e-5f * area);
  EXPECT_FALSE(surfaces.hasPatches());
}

}  // namespace
}  // namespace luxel
