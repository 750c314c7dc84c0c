// The viewer's picture and behaviour, in a headless OpenGL 4.5 context (Mesa's llvmpipe without a
// GPU): it shows what `luxel render` computes, edits change what they should, pause stops the
// solver, reset unlights, and a saved scene loads back to the same picture.
#include <gtest/gtest.h>

#include <filesystem>

#include "luxel/import.h"
#include "luxel/render.h"
#include "viewer_rig.h"

namespace {

namespace fs = std::filesystem;
using luxel::Image;
using luxel::Scene;
using luxel::test::compareRegions;
using luxel::test::viewerRig;
using luxel::viewer::Action;
using luxel::viewer::ViewerOptions;

ViewerOptions optionsFor(const Scene& scene, int size = 128) {
  ViewerOptions o;
  o.sceneName = scene.name;
  o.sceneSpec = scene.name;
  o.discretise.elementBudget = 3000;
  o.solve.method = "progressive";
  o.solve.settings.set("unshot", 1e-4);
  o.camera = luxel::chooseCamera(scene);
  o.width = o.height = size;
  o.showUi = false;
  return o;
}

Image renderLikeLuxel(const luxel::viewer::Viewer& v, luxel::RenderOptions::Mode mode, int size) {
  luxel::RenderOptions ro;
  ro.mode = mode;
  ro.camera = v.camera().toCamera();
  ro.width = ro.height = size;
  ro.samplesPerPixel = 16;
  // The viewer interpolates the solution's indirect light, as `--indirect interpolated` does; the
  // default gather differs from both where the solution's discretisation shows (render/final_gather.h).
  ro.indirect = luxel::RenderOptions::Indirect::Interpolated;
  luxel::Session& s = const_cast<luxel::Session&>(v.session());
  return luxel::render(s.scene(), s.surfaces(), s.solution(), ro);
}

void perform(luxel::test::ViewerRig& rig, const std::string& name, std::vector<std::string> args = {}) {
  rig.viewer->perform(Action{name, std::move(args), "test"});
}

// The radiosity view interpolates the same corner values the ray caster does, over the same
// (u, v): region means differ only by how the two sample edges (one sample a pixel against 16
// jittered ones). The light itself (radiance above 3; what it lights is at most about 1) is left
// out: its edge falls on a pixel row's boundary here, which the two split differently. Measured on
// llvmpipe: 3.2% worst of 64 regions (the floor along the box's open front, an edge across the
// whole row), 5% allowed.
TEST(GlViewer, RadiosityViewIsWhatLuxelRenderShows) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell");
  auto rig = viewerRig(scene, optionsFor(scene, 256), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  perform(*rig, "view", {"radiosity"});
  rig->solve();
  const luxel::test::RegionDifference d =
      compareRegions(rig->picture(), renderLikeLuxel(*rig->viewer, luxel::RenderOptions::Mode::Radiosity, 256), 8, 0.1, 3.0);
  EXPECT_LT(d.worst, 0.05) << "region " << d.region << ": viewer " << d.a << ", luxel render " << d.b;
}

// With a spot lamp, the final view computes the lamp's light per pixel with a shadow map (or a
// shadow volume) where `luxel render --mode hq` traces shadow rays: the regions differ where a
// shadow edge crosses them. Measured on llvmpipe: within 5% (the same allowance as the radiosity
// view's), both ways.
class GlViewerShadows : public ::testing::TestWithParam<const char*> {};

TEST_P(GlViewerShadows, FinalViewWithALampIsWhatLuxelRenderHqShows) {
  std::string why;
  Scene scene = luxel::loadSceneJson(
      R"({"builtin": "cornell", "lights": [{"type": "spot", "position": [0.278, 0.5, 0.28], "target": [0.2, 0.0, 0.25],
          "intensity": 0.5, "innerConeAngle": 40, "outerConeAngle": 60}]})",
      LUXEL_TEST_TMP, "lamp.json");
  auto rig = viewerRig(scene, optionsFor(scene, 256), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  perform(*rig, "shadows", {GetParam()});
  rig->solve();
  const luxel::test::RegionDifference d =
      compareRegions(rig->picture(), renderLikeLuxel(*rig->viewer, luxel::RenderOptions::Mode::HighQuality, 256), 8, 0.1, 3.0);
  EXPECT_LT(d.worst, 0.05) << "region " << d.region << ": viewer " << d.a << ", luxel render " << d.b;
}

INSTANTIATE_TEST_SUITE_P(GlShadowMethods, GlViewerShadows, ::testing::Values("maps", "volumes"));

// Moving a spot lamp changes the picture where its light falls (before or after), and elsewhere
// only by the change in its indirect light, which is small.
TEST(GlViewer, MovingALampChangesThePictureWhereItsLightFalls) {
  std::string why;
  Scene scene = luxel::loadSceneJson(
      R"({"builtin": "cornell", "lights": [{"type": "spot", "position": [0.15, 0.5, 0.2], "direction": [0, -1, 0],
          "intensity": 0.3, "innerConeAngle": 10, "outerConeAngle": 15}]})",
      LUXEL_TEST_TMP, "lamp.json");
  auto rig = viewerRig(scene, optionsFor(scene), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const size_t lamp = rig->viewer->scene().lights.size() - 1;
  auto shots = [&] {
    rig->solve();
    perform(*rig, "view", {"direct"});
    rig->frame();
    Image direct = rig->picture();
    perform(*rig, "view", {"final"});
    rig->frame();
    return std::pair{rig->picture(), direct};
  };
  const auto [before, directBefore] = shots();
  perform(*rig, "light.move", {std::to_string(lamp), "0.40", "0.5", "0.2"});
  const auto [after, directAfter] = shots();
  // The lamp's pool of light: where either direct picture is well above the area light's own.
  double lampChange = 0.0, elsewhere = 0.0, elsewhereLevel = 0.0;
  size_t lampPixels = 0, otherPixels = 0;
  for (int y = 0; y < before.height; ++y)
    for (int x = 0; x < before.width; ++x) {
      const auto sum = [](const luxel::Rgb& c) { return double(c.x + c.y + c.z); };
      const double poolBefore = sum(directBefore.at(x, y)), poolAfter = sum(directAfter.at(x, y));
      const double change = std::abs(sum(after.at(x, y)) - sum(before.at(x, y)));
      if (std::abs(poolAfter - poolBefore) > 0.2 * std::max(poolAfter, poolBefore)) {
        lampChange += change, ++lampPixels;
      } else {
        elsewhere += change, elsewhereLevel += sum(before.at(x, y)), ++otherPixels;
      }
    }
  ASSERT_GT(lampPixels, 100u);
  ASSERT_GT(otherPixels, 1000u);
  lampChange /= double(lampPixels);
  elsewhere /= double(otherPixels);
  elsewhereLevel /= double(otherPixels);
  EXPECT_GT(lampChange, 10.0 * elsewhere);
  EXPECT_LT(elsewhere, 0.05 * elsewhereLevel);  // the lamp's bounce moved a little: a few percent
}

TEST(GlViewer, PauseStopsTheSolverAndResetUnlights) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell");
  auto rig = viewerRig(scene, optionsFor(scene), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  perform(*rig, "solve.pause");
  for (int i = 0; i < 10; ++i) rig->frame();
  EXPECT_EQ(rig->viewer->session().stats().shots, 0u);
  perform(*rig, "solve.resume");
  rig->solve();
  const uint64_t shots = rig->viewer->session().stats().shots;
  EXPECT_GT(shots, 0u);
  perform(*rig, "solve.pause");
  for (int i = 0; i < 5; ++i) rig->frame();
  EXPECT_EQ(rig->viewer->session().stats().shots, shots);
  // Reset: a new solve, nothing shot yet, so only the light itself shines.
  perform(*rig, "solve.reset");
  rig->frame();
  const Image unlit = rig->picture();
  double lit = 0.0, dark = 0.0;
  const auto& s = rig->viewer->session();
  for (int y = 0; y < unlit.height; ++y)
    for (int x = 0; x < unlit.width; ++x) {
      const luxel::Rgb& c = unlit.at(x, y);
      (c.x + c.y + c.z > 1.0f ? lit : dark) += 1.0;
      if (c.x + c.y + c.z <= 1.0f) EXPECT_EQ(c.x + c.y + c.z, 0.0f) << x << "," << y;
    }
  EXPECT_GT(lit, 0.0);    // the light's own face
  EXPECT_GT(dark, 0.8 * double(unlit.width * unlit.height));
  EXPECT_EQ(s.stats().shots, 0u);
}

TEST(GlViewer, ASavedSceneLoadsBackToTheSamePicture) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell-small");
  auto rig = viewerRig(scene, optionsFor(scene), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  rig->solve();
  perform(*rig, "object.rotate", {"box", "0", "1", "0", "30"});
  perform(*rig, "light.add", {"0.08", "0.48", "0.45", "0.05"});  // near the ceiling, clear of the box
  rig->solve();
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "viewer-save";
  fs::create_directories(dir);
  perform(*rig, "save", {(dir / "edited.json").string()});
  const Image edited = rig->picture();
  const luxel::Camera cam = rig->viewer->camera().toCamera();
  rig->viewer.reset();

  const Scene reloaded = luxel::loadSceneFile(dir / "edited.json");
  ViewerOptions o = optionsFor(reloaded);
  o.camera = *reloaded.findCamera("viewer");
  rig->viewer = std::make_unique<luxel::viewer::Viewer>(reloaded, o);
  rig->solve();
  // The edited solve followed the moves (cross-redistribution), the reloaded one solved from
  // scratch: both stop at the same unshot threshold, so they agree within it.
  const luxel::test::RegionDifference d = compareRegions(rig->picture(), edited, 8);
  EXPECT_LT(d.worst, 0.01) << "region " << d.region << ": reloaded " << d.a << ", edited " << d.b;
  EXPECT_LT(glm::length(rig->viewer->camera().position() - cam.eye), 1e-5f);
}

// The GL backend solves in the viewer's own context (borrowed): the solver's hemicube passes and
// the viewer's drawing take turns in it, each setting the state it needs, and the picture is
// still what luxel render makes of the same solution.
TEST(GlViewer, SolvesOnTheGpuInTheViewersContext) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell");
  ViewerOptions o = optionsFor(scene, 256);
  o.discretise.elementBudget = 1500;
  o.solve.backend = "gl";
  o.solve.settings = {};
  o.solve.settings.set("unshot", 1e-3).set("hemicube-resolution", 64);
  auto rig = viewerRig(scene, o, why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  ASSERT_EQ(rig->viewer->session().backend(), "gl");
  perform(*rig, "view", {"radiosity"});
  rig->solve();
  EXPECT_GT(rig->viewer->session().stats().hemicubes, 0u);
  const luxel::test::RegionDifference d =
      compareRegions(rig->picture(), renderLikeLuxel(*rig->viewer, luxel::RenderOptions::Mode::Radiosity, 256), 8, 0.1, 3.0);
  EXPECT_LT(d.worst, 0.05) << "region " << d.region << ": viewer " << d.a << ", luxel render " << d.b;
}

// The unshot view shows where progressive shooting has work left, and nothing for a gathering
// solver, which keeps no unshot radiosity.
TEST(GlViewer, UnshotViewShowsWhereTheSolveHasWorkLeft) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell");
  for (const char* method : {"progressive", "gather"}) {
    ViewerOptions o = optionsFor(scene, 64);
    o.solve.method = method;
    o.solve.settings = {};
    o.mode = luxel::viewer::ViewMode::Unshot;
    auto rig = viewerRig(scene, o, why);
    if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
    rig->frame();  // one step: most of the light is still to be shot
    rig->frame();
    const Image heat = rig->picture();
    size_t coloured = 0;
    for (const luxel::Rgb& c : heat.pixels) coloured += c.x + c.y + c.z > 0.0f;
    if (std::string(method) == "progressive")
      EXPECT_GT(coloured, heat.pixels.size() / 2) << method;
    else
      EXPECT_EQ(coloured, 0u) << method;
  }
}

// The texels view lays the atlas a bake would make on the faces: two 1 m squares seen from above,
// the second's given lightmap UVs folded back over the right half of the first's. Three quarters
// of the squares' area is overlap (the second square whole, half the first), drawn magenta; the
// rest is its chart's checker; nothing is invalid. The camera's slight tilt (7 degrees) moves the
// share of pixels by about a percent.
TEST(GlViewer, TexelsViewShowsOverlappingUvs) {
  std::string why;
  Scene scene;
  scene.name = "folded uvs";
  scene.materials.push_back(luxel::Material{.name = "white"});
  luxel::Mesh m;
  m.name = "squares";
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, -1}, {1, 0, 0}, {2, 0, 0}, {2, 0, -1}, {1, 0, -1}};
  m.faces = {luxel::Face{{0, 1, 2, 3}}, luxel::Face{{4, 5, 6, 7}}};
  m.lightmapUvs = {{0, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}, {0.25f, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0.25f, 0.5f}};
  scene.meshes.push_back(m);
  ViewerOptions o = optionsFor(scene, 96);
  o.camera = luxel::Camera{"above", {1.0f, 4.0f, 0.0f}, {1.0f, 0.0f, -0.5f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  o.mode = luxel::viewer::ViewMode::Texels;
  auto rig = viewerRig(scene, o, why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  rig->frame();
  const Image picture = rig->picture();
  size_t squares = 0, overlap = 0, invalid = 0;
  for (const luxel::Rgb& c : picture.pixels) {
    if (c.x + c.y + c.z <= 0.0f) continue;  // the background
    ++squares;
    overlap += c.x > 0.6f && c.y < 0.01f && c.z > 0.6f;  // magenta, either shade of the checker
    invalid += c.x > 0.6f && c.y < 0.01f && c.z < 0.01f;
  }
  const double share = double(overlap) / double(squares);
  std::printf("texels view: %zu pixels on the squares, %.3f of them overlap (0.75 by area)\n", squares, share);
  EXPECT_GT(squares, picture.pixels.size() / 8);
  EXPECT_NEAR(share, 0.75, 0.05);
  EXPECT_EQ(invalid, 0u);
  // A click picks what the view shows: the squares' mesh at the picture's centre, nothing in a
  // corner, which shows the background.
  EXPECT_EQ(rig->viewer->pick(rig->width / 2, rig->height / 2), "squares");
  EXPECT_EQ(rig->viewer->pick(0, 0), "");
}

// Blinn-Phong highlights (Material::specular, shininess; display only) appear on the glossy
// materials of McGuire's glossy box and nowhere else, and shading the lamp per vertex gives nearly
// the per-pixel picture on a fine cut (Gouraud over small elements).
TEST(GlViewer, HighlightsOnlyOnGlossyMaterialsAndPerVertexShading) {
  const std::string obj = std::string(LUXEL_TEST_SCENES) + "/mcguire-cornell-box/CornellBox-Glossy.obj";
  if (!fs::exists(obj)) GTEST_SKIP() << "no " << obj << " (../shared/scenes unzipped at configure time)";
  const std::string lamp = R"(, "replaceLights": true, "lights": [{"type": "point", "position": [-0.3, 1.2, 1.0], "intensity": 6}])";
  const Scene glossy = luxel::loadSceneJson("{\"base\": \"" + obj + "\"" + lamp + "}", LUXEL_TEST_TMP, "glossy.json");
  const Scene matte = luxel::loadSceneJson("{\"base\": \"" + obj + "\"" + lamp +
                                           R"(, "materials": {"sphere": {"shininess": 0}, "shortBox": {"shininess": 0}}})",
                                           LUXEL_TEST_TMP, "matte.json");
  std::string why;
  // `lampOnly`: the direct view with the solver paused from the start: the lamp's light alone.
  auto picture = [&](const Scene& scene, bool perVertex, size_t elements = 3000, bool lampOnly = false) {
    ViewerOptions o = optionsFor(scene, 160);
    o.discretise.elementBudget = elements;
    o.paused = lampOnly;
    if (lampOnly) o.mode = luxel::viewer::ViewMode::Direct;
    auto rig = viewerRig(scene, o, why);
    if (!rig) return Image();
    if (perVertex) perform(*rig, "shading", {"vertex"});
    if (lampOnly)
      rig->frame();
    else
      rig->solve();
    return rig->picture();
  };
  const Image a = picture(glossy, false);
  if (a.pixels.empty()) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const Image b = picture(matte, false);
  double most = 0.0, mean = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const luxel::Rgb d = a.pixels[i] - b.pixels[i];
    most = std::max(most, double(d.x + d.y + d.z));
    mean += double(b.pixels[i].x + b.pixels[i].y + b.pixels[i].z) / double(a.pixels.size());
    EXPECT_GE(d.x, 0.0f);  // a highlight only adds light
  }
  EXPECT_GT(most, 0.5 * mean);  // a highlight there is
  // The red left wall (Ks 0) is the same to the bit: the solve is diffuse and the same.
  for (int y = a.height / 3; y < 2 * a.height / 3; ++y)
    for (int x = a.width / 6; x < a.width / 4; ++x) EXPECT_EQ(a.at(x, y), b.at(x, y)) << x << "," << y;
  // Per vertex, the lamp's light is exact at the element corners and linear between them: the
  // difference from per-pixel shading (the lamp's 1/r^2 and the shadows' edges) falls as the
  // elements shrink.
  const luxel::test::RegionDifference coarse =
      compareRegions(picture(glossy, true, 3000, true), picture(glossy, false, 3000, true), 8, 0.1, 3.0);
  const luxel::test::RegionDifference fine =
      compareRegions(picture(glossy, true, 30000, true), picture(glossy, false, 30000, true), 8, 0.1, 3.0);
  EXPECT_GT(coarse.worst, 0.0);
  EXPECT_LT(fine.worst, 0.5 * coarse.worst) << "3,000 elements: " << coarse.worst << ", 30,000: " << fine.worst;
}

// Held keys walk at a fifth of the scene's size a second, on the ground; a tap moves one frame's worth.
TEST(GlViewer, KeysWalkAtTheScenesSpeed) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell");
  auto rig = viewerRig(scene, optionsFor(scene, 64), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  perform(*rig, "solve.pause");
  const luxel::viewer::ViewCamera& cam = rig->viewer->camera();
  const luxel::Vec3 start = cam.position(), forward = cam.forward();
  perform(*rig, "key", {"w", "down"});
  for (int i = 0; i < 30; ++i) rig->frame();  // 30 frames of 1/60 s
  perform(*rig, "key", {"w", "up"});
  rig->frame();
  const float expected = 0.5f * cam.walkSpeed();
  EXPECT_NEAR(glm::dot(cam.position() - start, forward), expected, 1e-4f * expected);
  const luxel::Vec3 afterWalk = cam.position();
  perform(*rig, "key", {"d", "tap"});
  rig->frame();
  rig->frame();
  EXPECT_NEAR(glm::length(cam.position() - afterWalk), cam.walkSpeed() / 60.0f, 1e-3f * cam.walkSpeed());
}

TEST(GlViewer, BadEditsSayWhatIsWrongAndChangeNothing) {
  std::string why;
  const Scene scene = luxel::builtinScene("cornell");
  auto rig = viewerRig(scene, optionsFor(scene), why);
  if (!rig) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  const size_t lights = rig->viewer->scene().lights.size();
  EXPECT_THROW(perform(*rig, "light.move", {"7", "0", "0", "0"}), luxel::Error);
  EXPECT_THROW(perform(*rig, "object.move", {"nothing", "0", "0", "1"}), luxel::Error);
  EXPECT_THROW(perform(*rig, "selected.move", {"0", "0", "1"}), luxel::Error);
  EXPECT_THROW(perform(*rig, "view", {"sideways"}), luxel::Error);
  EXPECT_THROW(perform(*rig, "light.add", {"0", "0", "0", "-1"}), luxel::Error);
  EXPECT_EQ(rig->viewer->scene().lights.size(), lights);
  rig->frame();  // still drawing
}

}  // namespace
