// Thin glass (Material::transmittance, trace/thin_glass.h) against closed forms: the sun straight
// down on a floor under a pane. Nothing reflects but the floor, which cannot see itself, so its
// irradiance is the sun's alone: E under open sky, E times what the glass passes under a pane, per
// channel, exactly (a sun of no angular size, every sample the same).
//
// Scene values: a 4 m x 4 m floor (reflectance 0.5) cut into 0.25 m elements; panes 2 m x 2 m
// over its middle ([-1, 1] in x and z) at 1 m and 1.5 m, reflectance 0; E = 1000 lux.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

constexpr float kSun = 1000.0f;
const Rgb kGlass(0.5f, 0.25f, 1.0f);

enum class Facing { Up, Down };

void addPane(Scene& s, float y, uint32_t material, Facing facing) {
  Mesh pane;
  pane.name = "pane";
  pane.material = material;
  if (facing == Facing::Up)
    builtin::addQuad(pane, Vec3(-1, y, -1), Vec3(-1, y, 1), Vec3(1, y, 1), Vec3(1, y, -1));
  else
    builtin::addQuad(pane, Vec3(-1, y, -1), Vec3(1, y, -1), Vec3(1, y, 1), Vec3(-1, y, 1));
  s.meshes.push_back(pane);
}

// The floor, the sun, and a glass material (index 1) for the panes.
Scene floorUnderGlass(bool twoSidedGlass = false) {
  Scene s;
  s.name = "glass";
  s.materials.push_back(Material{.name = "floor", .reflectance = Rgb(0.5f)});
  s.materials.push_back(Material{.name = "glass", .reflectance = Rgb(0.0f), .twoSided = twoSidedGlass, .transmittance = kGlass});
  Mesh floor;
  floor.name = "floor";
  builtin::addQuad(floor, Vec3(-2, 0, -2), Vec3(-2, 0, 2), Vec3(2, 0, 2), Vec3(2, 0, -2));
  s.meshes.push_back(floor);
  s.lights.push_back(Light{.type = Light::Type::Directional, .name = "sun", .intensity = kSun, .direction = Vec3(0, -1, 0)});
  return s;
}

struct Solved {
  SurfaceSet set;
  Solution sol;
};

Solved solved(const Scene& scene) {
  DiscretiseOptions d;
  d.elementSize = 0.25f;
  Solved s{discretise(scene, d), {}};
  s.sol = solve(scene, s.set, SolveOptions{});
  return s;
}

// Every floor element under the panes (wholly) gets `under`, every one clear of them `open`.
void expectFloor(const Solved& s, const Rgb& under, const Rgb& open) {
  size_t inside = 0, outside = 0;
  for (size_t e = 0; e < s.set.elements.size(); ++e) {
    const Element& el = s.set.elements[e];
    if (s.set.faces[el.face].material != 0) continue;
    const float reach = std::max(std::abs(el.centroid.x), std::abs(el.centroid.z));
    const Rgb h = s.sol.irradiance[e];
    if (reach < 0.85f) {
      ++inside;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(h[c], under[c], 1e-4f * kSun) << "element " << e << " channel " << c;
    } else if (reach > 1.15f) {
      ++outside;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(h[c], open[c], 1e-4f * kSun) << "element " << e << " channel " << c;
    }
  }
  EXPECT_GT(inside, 20u);
  EXPECT_GT(outside, 20u);
}

TEST(ThinGlass, APanePassesItsTransmittanceOfTheSun) {
  for (Facing facing : {Facing::Up, Facing::Down}) {
    Scene s = floorUnderGlass();
    addPane(s, 1.0f, 1, facing);
    expectFloor(solved(s), kSun * kGlass, Rgb(kSun));
  }
}

TEST(ThinGlass, ATwoSidedPaneFiltersOnce) {
  Scene s = floorUnderGlass(/*twoSidedGlass=*/true);
  addPane(s, 1.0f, 1, Facing::Up);
  expectFloor(solved(s), kSun * kGlass, Rgb(kSun));
}

TEST(ThinGlass, TwoPanesPassTheProductAndAnOpaqueOneNothing) {
  {
    Scene s = floorUnderGlass();
    addPane(s, 1.0f, 1, Facing::Up);
    addPane(s, 1.5f, 1, Facing::Down);
    expectFloor(solved(s), kSun * kGlass * kGlass, Rgb(kSun));
  }
  {
    Scene s = floorUnderGlass();
    s.materials.push_back(Material{.name = "slate", .reflectance = Rgb(0.0f)});
    addPane(s, 1.0f, 1, Facing::Up);
    addPane(s, 1.5f, 2, Facing::Up);
    expectFloor(solved(s), Rgb(0.0f), Rgb(kSun));
  }
}

// What a render shows under the pane: the floor's radiance rho / pi E T, per pixel from the pixels'
// own shadow rays (looking down from between the pane and the floor).
// The renderers' tracer holds a two-sided face's sides a ray offset apart, and a slanting ray
// meets both: they filter once. The sun at 45 degrees puts the pane's shadow on x in [0, 2].
TEST(ThinGlass, TheRenderShowsTheFilteredSunlight) {
  for (bool twoSided : {false, true}) {
    Scene s = floorUnderGlass(twoSided);
    s.lights[0].direction = glm::normalize(Vec3(1, -1, 0));
    addPane(s, 1.0f, 1, Facing::Up);
    const Solved solution = solved(s);
    RenderOptions o;
    o.width = o.height = 32;
    o.camera = Camera{.eye = Vec3(1, 0.5f, 0), .target = Vec3(1, 0, 0), .up = Vec3(0, 0, 1), .fovY = 60.0f};
    for (RenderOptions::Indirect indirect : {RenderOptions::Indirect::None, RenderOptions::Indirect::VertexGather}) {
      o.indirect = indirect;
      const Image image = render(s, solution.set, solution.sol, o);
      const Rgb expected = (0.5f / std::numbers::pi_v<float>)*kSun * std::sqrt(0.5f) * kGlass;
      for (size_t pixel : {size_t(16 * 32 + 16), size_t(12 * 32 + 20), size_t(20 * 32 + 9)})
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(image.pixels[pixel][c], expected[c], 1e-3f * expected[c] + 1e-3f)
              << "pixel " << pixel << " channel " << c << (twoSided ? ", two-sided" : "");
    }
  }
}

}  // namespace
}  // namespace luxel

namespace luxel {
namespace {

// A lamp 2 m over the floor's middle passes the pane (E = I / h^2 under it, times the glass); an
// emitting surface there does not: the solvers carry surfaces' light only through form factors,
// which glass blocks, and the render's own shadow rays agree with them.
TEST(ThinGlass, LampsPassGlassAndEmittingSurfacesDoNot) {
  RenderOptions o;
  o.width = o.height = 32;
  o.indirect = RenderOptions::Indirect::None;
  o.camera = Camera{.eye = Vec3(0, 0.5f, 0), .target = Vec3(0, 0, 0), .up = Vec3(0, 0, 1), .fovY = 10.0f};
  const size_t centre = 16 * 32 + 16;
  {
    Scene s = floorUnderGlass();
    s.lights[0] = Light{.type = Light::Type::Point, .name = "lamp", .intensity = 400.0f, .position = Vec3(0, 2, 0)};
    addPane(s, 1.0f, 1, Facing::Up);
    const Solved solution = solved(s);
    const Image image = render(s, solution.set, solution.sol, o);
    const Rgb expected = (0.5f / std::numbers::pi_v<float>)*(400.0f / 4.0f) * kGlass;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.pixels[centre][c], expected[c], 2e-3f * expected[c]) << "channel " << c;
  }
  // The emitting surface's light under the pane is what it is under an opaque pane: the same
  // rays blocked (the estimate is near 0, not 0: the direct light's control variate), to the bit.
  Rgb seen[2];
  for (int glass = 0; glass < 2; ++glass) {
    Scene s = floorUnderGlass();
    s.lights.clear();
    if (!glass) s.materials[1].transmittance = Rgb(0.0f);
    s.materials.push_back(Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(100.0f)});
    Mesh lamp;
    lamp.name = "lamp";
    lamp.material = 2;
    builtin::addQuad(lamp, Vec3(-1, 2, -1), Vec3(1, 2, -1), Vec3(1, 2, 1), Vec3(-1, 2, 1));  // facing down
    s.meshes.push_back(lamp);
    addPane(s, 1.0f, 1, Facing::Up);
    const Solved solution = solved(s);
    seen[glass] = render(s, solution.set, solution.sol, o).pixels[centre];
  }
  EXPECT_EQ(seen[1], seen[0]);
  EXPECT_LT(glm::length(seen[1]), 1.0f);  // against 3.8 a channel with no pane (rho / pi M F, F = 0.239)
}

}  // namespace
}  // namespace luxel
