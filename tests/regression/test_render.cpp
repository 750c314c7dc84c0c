// Rendering (src/render/renderer.cpp, corner_values.cpp): the two display modes agree, the light
// and the coloured walls land where the camera says, images are deterministic, the furnace renders
// flat, and nodal averaging never bleeds across materials.
//
// Scene values used:
// - builtin::cornellBox(): light radiance (17, 12, 4), light reflectance 0.78, light centre
//   (0.278, 0.5488, 0.2795); red wall (reflectance 0.63, 0.065, 0.05) at x = 0.556, green wall
//   (0.14, 0.45, 0.091) at x = 0; camera "default" at (0.278, 0.273, -0.8) looking down +z with
//   up +y, vertical fov 39.3077 deg. Looking down +z with +y up, +x is to the left of the image,
//   so the red wall is on the left. 1500 elements, 64 x 64 pixels, 16 samples per pixel.
// - builtin::furnace(0.5, 1): closed unit cube, rho = 0.5, Le = 1: radiance 1 / (1 - 0.5) = 2
//   everywhere; camera inside at (0.5, 0.5, 0.05), fov 90 deg. 32 x 32 pixels.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

struct Solved {
  Scene scene;
  SurfaceSet set;
  Solution sol;
};

Solved solveScene(Scene scene, size_t elements) {
  DiscretiseOptions d;
  d.elementBudget = elements;
  Solved s{std::move(scene), {}, {}};
  s.set = discretise(s.scene, d);
  s.sol = solve(s.scene, s.set, SolveOptions{});  // progressive, unshot 1e-3, ambient term
  return s;
}

Image renderWith(const Solved& s, RenderOptions::Mode mode, int size, int spp = 16) {
  RenderOptions o;
  o.mode = mode;
  o.camera = *s.scene.findCamera("default");
  o.width = o.height = size;
  o.samplesPerPixel = spp;
  return render(s.scene, s.set, s.sol, o);
}

Rgb meanOf(const Image& img) {
  glm::dvec3 sum(0.0);
  for (const Rgb& p : img.pixels) sum += glm::dvec3(p);
  return Rgb(sum / double(img.pixels.size()));
}

// The pixel (column, row) that the camera's centre ray through `p` lands in (renderer.cpp's
// pinhole: right = forward x up, row 0 at the top).
std::pair<int, int> project(const Camera& c, Vec3 p, int width, int height) {
  const Vec3 forward = glm::normalize(c.target - c.eye);
  const Vec3 right = glm::normalize(glm::cross(forward, c.up));
  const Vec3 up = glm::cross(right, forward);
  const Vec3 d = p - c.eye;
  const float z = glm::dot(d, forward);
  const float tanHalf = std::tan(glm::radians(c.fovY) * 0.5f);
  const float px = glm::dot(d, right) / z / (tanHalf * float(width) / float(height));
  const float py = glm::dot(d, up) / z / tanHalf;
  return {int(std::floor((px + 1.0f) * 0.5f * float(width))), int(std::floor((1.0f - py) * 0.5f * float(height)))};
}

class CornellRender : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    solved_ = new Solved(solveScene(builtin::cornellBox(), 1500));
    hq_ = new Image(renderWith(*solved_, RenderOptions::Mode::HighQuality, 64));
    radiosity_ = new Image(renderWith(*solved_, RenderOptions::Mode::Radiosity, 64));
  }
  static void TearDownTestSuite() {
    delete solved_;
    delete hq_;
    delete radiosity_;
  }
  static Solved* solved_;
  static Image* hq_;
  static Image* radiosity_;
};
Solved* CornellRender::solved_ = nullptr;
Image* CornellRender::hq_ = nullptr;
Image* CornellRender::radiosity_ = nullptr;

TEST_F(CornellRender, ModesAgreeOnTheMeanRadiance) {
  ASSERT_EQ(hq_->width, 64);
  ASSERT_EQ(hq_->height, 64);
  const Rgb a = meanOf(*hq_), b = meanOf(*radiosity_);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(a[c], 0.0f);
    EXPECT_NEAR(a[c], b[c], 0.05f * b[c]) << "channel " << c;
  }
}

TEST_F(CornellRender, LightPixelShowsTheLightsRadiance) {
  // Light centre (0.278, 0.5488, 0.2795) projects to column 32, row 9 of 64 (the light spans
  // about columns 26..37 and rows 8..10). Radiance there is Le + rho H / pi with rho = 0.78 and
  // H the light's irradiance from the box below: a little above (17, 12, 4).
  const Camera& cam = *solved_->scene.findCamera("default");
  auto [x, y] = project(cam, Vec3(0.278f, 0.5488f, 0.2795f), 64, 64);
  EXPECT_EQ(x, 32);
  EXPECT_EQ(y, 9);
  const Rgb le(17.0f, 12.0f, 4.0f);
  for (const Image* img : {hq_, radiosity_}) {
    const Rgb p = img->at(x, y);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(p[c], le[c]) << "channel " << c;
      EXPECT_LT(p[c], le[c] + 3.0f) << "channel " << c;
    }
  }
}

TEST_F(CornellRender, RedWallOnTheLeftGreenWallOnTheRight) {
  // Columns 2..5 of rows 20..43 see the red wall (x = 0.556) near the front, columns 58..61 the
  // green wall (x = 0): a ray through column 2 leaves the eye (x = 0.278) at 0.33 m sideways per
  // metre forward and meets x = 0.556 at z = 0.03 to 0.06, inside the box (z in [0, 0.559]).
  // Columns 0 and 63 look past the open front of the box (z < 0) into the black.
  const Camera& cam = *solved_->scene.findCamera("default");
  auto [rx, ry] = project(cam, Vec3(0.556f, 0.3f, 0.3f), 64, 64);
  auto [gx, gy] = project(cam, Vec3(0.0f, 0.3f, 0.3f), 64, 64);
  EXPECT_LT(rx, 32);  // red wall on the left
  EXPECT_GT(gx, 32);
  for (const Image* img : {hq_, radiosity_})
    for (int y = 20; y < 44; ++y) EXPECT_EQ(img->at(0, y), Rgb(0.0f)) << "outside the box, row " << y;
  for (const Image* img : {hq_, radiosity_}) {
    for (int y = 20; y < 44; ++y) {
      for (int x = 2; x < 6; ++x) {
        const Rgb p = img->at(x, y);
        EXPECT_GT(p.r, 2.0f * p.g) << "red wall pixel " << x << ", " << y;
      }
      for (int x = 58; x < 62; ++x) {
        const Rgb p = img->at(x, y);
        EXPECT_GT(p.g, 1.5f * p.r) << "green wall pixel " << x << ", " << y;
      }
    }
  }
}

TEST_F(CornellRender, RenderingIsDeterministic) {
  // The same solution rendered again, and the whole pipeline run again: identical pixels.
  Image again = renderWith(*solved_, RenderOptions::Mode::HighQuality, 64);
  ASSERT_EQ(again.pixels.size(), hq_->pixels.size());
  for (size_t i = 0; i < again.pixels.size(); ++i) ASSERT_EQ(again.pixels[i], hq_->pixels[i]) << "pixel " << i;
  Solved other = solveScene(builtin::cornellBox(), 1500);
  ASSERT_EQ(other.sol.radiosity.size(), solved_->sol.radiosity.size());
  for (size_t e = 0; e < other.sol.radiosity.size(); ++e)
    ASSERT_EQ(other.sol.radiosity[e], solved_->sol.radiosity[e]) << "element " << e;
  Image fresh = renderWith(other, RenderOptions::Mode::HighQuality, 64);
  for (size_t i = 0; i < fresh.pixels.size(); ++i) ASSERT_EQ(fresh.pixels[i], hq_->pixels[i]) << "pixel " << i;
}

TEST(FurnaceRender, EveryPixelIsTwoInBothModes) {
  Solved s = solveScene(builtin::furnace(0.5f, 1.0f), 600);
  for (RenderOptions::Mode mode : {RenderOptions::Mode::Radiosity, RenderOptions::Mode::HighQuality}) {
    Image img = renderWith(s, mode, 32);
    double worst = 0.0;
    for (const Rgb& p : img.pixels)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(p[c]) - 2.0));
    EXPECT_LT(worst, 0.02) << (mode == RenderOptions::Mode::Radiosity ? "radiosity" : "hq");
  }
}

// Coverage (what auto exposure meters on): inside the closed furnace every sample hits a surface;
// looking away from the open Cornell box, none does.
TEST(FurnaceRender, CoverageIsWholeInsideAndNoneLookingAway) {
  Solved s = solveScene(builtin::furnace(0.5f, 1.0f), 600);
  const Image inside = renderWith(s, RenderOptions::Mode::HighQuality, 8, 4);
  ASSERT_EQ(inside.coverage.size(), inside.pixels.size());
  for (float c : inside.coverage) EXPECT_EQ(c, 1.0f);
  Solved cornell = solveScene(builtin::cornellBox(), 200);
  for (Camera& cam : cornell.scene.cameras) cam.target = cam.eye + (cam.eye - cam.target);  // facing out
  const Image away = renderWith(cornell, RenderOptions::Mode::HighQuality, 8, 4);
  ASSERT_EQ(away.coverage.size(), away.pixels.size());
  for (float c : away.coverage) EXPECT_EQ(c, 0.0f);
}

TEST(CornerValues, DoNotBleedAcrossMaterials) {
  // Per-element value 1 on the red wall (material 1), 0 elsewhere: every corner of a red-wall
  // element averages red-wall elements only, so is exactly 1, and every other corner exactly 0,
  // including those of back-wall, floor and ceiling elements that touch the red wall.
  Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 1500;
  SurfaceSet set = discretise(scene, d);
  std::vector<Rgb> values(set.elements.size(), Rgb(0.0f));
  size_t red = 0;
  for (size_t e = 0; e < set.elements.size(); ++e)
    if (set.elements[e].material == 1) values[e] = Rgb(1.0f), ++red;
  ASSERT_GT(red, 0u);
  std::vector<Rgb> corners = elementCornerValues(set, values);
  ASSERT_EQ(corners.size(), 4 * set.elements.size());
  const float redX = 0.55f;  // the red wall spans x 0.5496..0.556
  size_t touching = 0;
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const Element& el = set.elements[e];
    const float want = el.material == 1 ? 1.0f : 0.0f;
    for (int c = 0; c < el.polygon.count; ++c) {
      ASSERT_EQ(corners[4 * e + size_t(c)], Rgb(want)) << "element " << e << " corner " << c;
      if (el.material != 1 && el.polygon.v[c].x > redX) ++touching;
    }
  }
  EXPECT_GT(touching, 0u);  // other walls' elements do meet the red wall
}

// A two-sided panel (material twoSided: a twin face with its own elements lies on the same plane,
// facing the other way) seen face-on fills the image from either side. Scene: a closed
// 4 x 2 x 2 box (reflectance 0.5), an emitting 1 x 1 panel (Le = 10) at x = 0.5 facing +x, and
// the two-sided 1.6 x 1.6 panel (reflectance 0.5) at x = 2; cameras at x = 1.2 (lit side) and
// x = 2.8 (back), looking along the x axis at the panel's centre with a 40 deg field of view, so
// every pixel sees the panel (half-width 0.29 m of the 0.8 m it spans about the centre).
TEST(TwoSidedRender, BothSidesOfAPanelAreVisible) {
  Scene s;
  s.name = "two-sided panel";
  s.materials = {Material{.name = "wall", .reflectance = Rgb(0.5f)},
                 Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(10.0f)},
                 Material{.name = "panel", .reflectance = Rgb(0.5f), .twoSided = true}};
  Mesh box, lamp, panel;
  builtin::addInwardBox(box, Vec3(0.0f), Vec3(4.0f, 2.0f, 2.0f));
  lamp.material = 1;
  builtin::addQuad(lamp, Vec3(0.5f, 0.5f, 0.5f), Vec3(0.5f, 1.5f, 0.5f), Vec3(0.5f, 1.5f, 1.5f),
                   Vec3(0.5f, 0.5f, 1.5f));  // facing +x
  panel.material = 2;
  builtin::addQuad(panel, Vec3(2, 0.2f, 0.2f), Vec3(2, 0.2f, 1.8f), Vec3(2, 1.8f, 1.8f),
                   Vec3(2, 1.8f, 0.2f));  // facing -x, towards the lamp
  s.meshes = {box, lamp, panel};
  s.cameras.push_back(Camera{.name = "default", .eye = Vec3(1.2f, 1, 1), .target = Vec3(2, 1, 1), .fovY = 40});
  Solved solved = solveScene(s, 3000);
  for (RenderOptions::Mode mode : {RenderOptions::Mode::Radiosity, RenderOptions::Mode::HighQuality}) {
    double mean[2] = {0.0, 0.0};
    for (int side = 0; side < 2; ++side) {
      solved.scene.cameras[0].eye = Vec3(side == 0 ? 1.2f : 2.8f, 1, 1);
      Image img = renderWith(solved, mode, 32);
      int black = 0;
      for (const Rgb& p : img.pixels) {
        black += p.g <= 0.0f;
        mean[side] += p.g / double(img.pixels.size());
      }
      EXPECT_EQ(black, 0) << (side == 0 ? "lit side" : "back") << ", mode " << int(mode);
    }
    // Lit side: about rho H / pi = 0.5 * 4 / pi; the back gets a few per cent of that.
    EXPECT_GT(mean[0], 0.4);
    EXPECT_GT(mean[1], 0.0);
    EXPECT_LT(mean[1], 0.3 * mean[0]);
  }
}

}  // namespace
}  // namespace luxel
