// Session::release: a caller that only renders after the solve gets the scene and surfaces back
// whole, with the solver's memory freed (luxel render does this before the renderer builds its own
// BVH).
#include <gtest/gtest.h>

#include "luxel/render.h"
#include "luxel/session.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

TEST(SessionRelease, TheReleasedSceneRendersAsTheSessionsDid) {
  DiscretiseOptions d;
  d.elementBudget = 400;
  SolveOptions o;
  o.method = "hierarchical";
  Session session(builtin::cornellBox(), d, {o});
  const Solution solution = session.solve();
  RenderOptions ro;
  ro.camera = session.camera();
  ro.width = ro.height = 32;
  ro.samplesPerPixel = 2;
  const Image before = render(session.scene(), session.surfaces(), solution, ro);
  const size_t elements = session.surfaces().elements.size(), faces = session.surfaces().faces.size();
  const std::string name = session.scene().name;

  const Session::Solved solved = std::move(session).release();
  EXPECT_EQ(solved.scene.name, name);
  EXPECT_EQ(solved.surfaces.elements.size(), elements);
  EXPECT_EQ(solved.surfaces.faces.size(), faces);
  const Image after = render(solved.scene, solved.surfaces, solution, ro);
  ASSERT_EQ(after.pixels.size(), before.pixels.size());
  for (size_t i = 0; i < after.pixels.size(); ++i) ASSERT_EQ(after.pixels[i], before.pixels[i]) << "pixel " << i;
}

}  // namespace
}  // namespace luxel
