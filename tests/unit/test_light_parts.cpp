// Each light's part of the analytic light (Session::lightIrradiance): what the viewer takes out of
// the field it interpolates when it draws those lights per pixel. The parts add up to the whole, are
// the same samples a fresh session traces, and a light edit traces only the light edited.
#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/session.h"

namespace {

luxel::Scene twoLamps() {
  return luxel::loadSceneJson(
      R"({"builtin": "cornell", "lights": [
            {"type": "point", "position": [0.2, 0.45, 0.2], "intensity": 0.05},
            {"type": "spot", "position": [0.4, 0.5, 0.3], "target": [0.4, 0.0, 0.3], "intensity": 0.1, "outerConeAngle": 40}]})",
      LUXEL_TEST_TMP, "lamps.json");
}

luxel::SessionOptions options() {
  luxel::SessionOptions o;
  o.solve.method = "progressive";
  o.solve.followsChanges = true;
  return o;
}

TEST(LightParts, AddUpToTheAnalyticLightAndMatchAFreshSession) {
  luxel::Session s(twoLamps(), luxel::DiscretiseOptions{.elementBudget = 800}, options());
  const uint32_t both[] = {0, 1}, first[] = {0}, second[] = {1};
  const std::vector<luxel::Rgb> all = s.lightIrradiance(both), a = s.lightIrradiance(first), b = s.lightIrradiance(second);
  const luxel::Solution sol = s.solution();
  double total = 0.0;
  for (size_t e = 0; e < all.size(); ++e) {
    total += all[e].x;
    EXPECT_NEAR(all[e].x, a[e].x + b[e].x, 1e-6f * (1.0f + all[e].x));
    // The Cornell box's own light is an emitting face, not an analytic light: before any shot, the
    // direct irradiance is the lamps' alone.
    EXPECT_GE(sol.directIrradiance[e].x + 1e-6f, all[e].x);
  }
  EXPECT_GT(total, 0.0);

  // Move the spot: the point lamp's part is kept, to the bit, and is what a fresh session traces.
  std::vector<luxel::Light> lights = s.scene().lights;
  lights[1].position.x -= 0.1f;
  s.setLights(lights);
  EXPECT_EQ(s.lightIrradiance(first), a);
  luxel::Scene moved = twoLamps();
  moved.lights = lights;
  luxel::Session fresh(moved, luxel::DiscretiseOptions{.elementBudget = 800}, options());
  EXPECT_EQ(fresh.lightIrradiance(first), a);
  EXPECT_EQ(fresh.lightIrradiance(second), s.lightIrradiance(second));
  EXPECT_NE(s.lightIrradiance(second), b);
  const uint32_t none[] = {7};
  EXPECT_THROW(s.lightIrradiance(none), luxel::Error);
}

}  // namespace
