// Material::specular and shininess, the viewer's display-only highlight (scene.h): validated like
// the other material values, and never read by the solve, the renders or the bakes, which stay
// bit for bit what they were without it.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/bake.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/render.h"
#include "luxel/solve.h"
#include "luxel/surface.h"
#include "error_message.h"

namespace luxel {
namespace {

using luxel::test::errorOf;
namespace fs = std::filesystem;

bool sameBits(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgb)) == 0;
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(MaterialSpecular, ValidateRejectsNanNegativeAndOutOfRange) {
  const Scene good = builtinScene("cornell");
  auto with = [&](Rgb specular, float shininess) {
    Scene s = good;
    s.materials[1].specular = specular;
    s.materials[1].shininess = shininess;
    return s;
  };
  auto error = [&](Rgb specular, float shininess) {
    return errorOf([&] { with(specular, shininess).validateMaterials(); });
  };
  const std::string where = "scene '" + good.name + "': material '" + good.materials[1].name + "': ";
  EXPECT_NO_THROW(with(Rgb(0.5f), 32.0f).validate());
  EXPECT_NO_THROW(with(Rgb(1.0f), kMaxShininess).validate());
  EXPECT_EQ(error(Rgb(0.5f, 1.5f, 0.5f), 32.0f), where + "specular 1.5 is outside [0,1]");
  EXPECT_EQ(error(Rgb(-0.5f), 32.0f), where + "specular -0.5 is outside [0,1]");
  EXPECT_EQ(error(Rgb(std::nanf("")), 32.0f), where + "specular nan is outside [0,1]");
  EXPECT_EQ(error(Rgb(0.5f), -1.0f), where + "shininess -1 is outside [0, 10000]");
  EXPECT_EQ(error(Rgb(0.5f), 20000.0f), where + "shininess 20000 is outside [0, 10000]");
  EXPECT_EQ(error(Rgb(0.5f), std::numeric_limits<float>::infinity()), where + "shininess inf is outside [0, 10000]");
  EXPECT_EQ(error(Rgb(0.5f), std::nanf("")), where + "shininess nan is outside [0, 10000]");
}

TEST(MaterialSpecular, HasSpecularNeedsAColourAndAnExponent) {
  Material m;
  EXPECT_FALSE(m.hasSpecular());
  m.specular = Rgb(0.0f, 0.0f, 0.1f);
  EXPECT_FALSE(m.hasSpecular());  // exponent 0: no highlight
  m.shininess = 16.0f;
  EXPECT_TRUE(m.hasSpecular());
  m.specular = Rgb(0.0f);
  EXPECT_FALSE(m.hasSpecular());
}

// The Cornell box, with a point and a spot light for the per-pixel direct light, solved, rendered
// both ways, baked to vertex colours and to a lightmap, with and without a highlight on every
// material: the same bits everywhere but in the hq render's highlights (render/glossy_lobe.h),
// which only add light, and without them the same bits there too.
TEST(MaterialSpecular, OnlyTheHqRendersHighlightsDifferWithAndWithoutIt) {
  Scene plain = builtinScene("cornell");
  Vec3 lo(1e30f), hi(-1e30f);
  for (const Mesh& m : plain.meshes)
    for (const Vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const Vec3 centre = 0.5f * (lo + hi), size = hi - lo;
  plain.lights.push_back(Light{.type = Light::Type::Point, .name = "bulb", .color = Rgb(1.0f, 0.9f, 0.8f),
                               .intensity = 2.0f, .position = centre + Vec3(0.0f, 0.3f * size.y, 0.0f)});
  plain.lights.push_back(Light{.type = Light::Type::Spot, .name = "spot", .intensity = 3.0f,
                               .position = centre + Vec3(0.2f * size.x, 0.4f * size.y, 0.0f),
                               .direction = {0.0f, -1.0f, 0.0f}, .innerConeAngle = 0.3f, .outerConeAngle = 0.6f});
  Scene shiny = plain;
  for (Material& m : shiny.materials) m.specular = Rgb(0.9f, 0.5f, 0.25f), m.shininess = 48.0f;
  shiny.validate();

  struct Out {
    Solution solution;
    Image hq, hqDiffuse, radiosity, lightmapped;
    std::string glb;
    std::vector<std::vector<Rgb>> pages;
  };
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "material-specular";
  fs::create_directories(dir);
  auto run = [&](const Scene& scene, const std::string& name) {
    Out o;
    DiscretiseOptions d;
    d.elementBudget = 1200;
    SurfaceSet surfaces = discretise(scene, d);
    SolveOptions so;
    so.method = "progressive";
    o.solution = solve(scene, surfaces, so);
    RenderOptions ro;
    ro.camera = scene.cameras.empty() ? Camera{.eye = centre + Vec3(0, 0, 2.5f * size.z), .target = centre}
                                      : scene.cameras[0];
    ro.width = ro.height = 48;
    ro.samplesPerPixel = 2;
    o.hq = render(scene, surfaces, o.solution, ro);
    ro.glossyRays = 0;
    o.hqDiffuse = render(scene, surfaces, o.solution, ro);
    ro.mode = RenderOptions::Mode::Radiosity;
    o.radiosity = render(scene, surfaces, o.solution, ro);
    GlbOptions go;
    go.vertexColors = bakedRadiance(scene, surfaces, o.solution);
    writeGlb(scene, dir / (name + ".glb"), go);
    o.glb = fileBytes(dir / (name + ".glb"));
    AtlasOptions ao;
    ao.texelsPerMetre = 16.0f / std::max(size.x, 1e-6f);
    ao.pageSize = 128;
    const LightmapAtlas atlas = buildLightmapAtlas(scene, ao);
    const LightmapBake bake = bakeLightmaps(scene, atlas);
    o.pages = bake.pages;
    o.lightmapped = renderLightmapped(scene, atlas, bake, ro);
    return o;
  };
  const Out a = run(plain, "plain"), b = run(shiny, "shiny");
  double lit = 0.0;
  for (const Rgb& p : a.hq.pixels) lit += p.r + p.g + p.b;
  EXPECT_GT(lit, 0.0);
  EXPECT_TRUE(sameBits(a.solution.radiosity, b.solution.radiosity));
  EXPECT_TRUE(sameBits(a.solution.irradiance, b.solution.irradiance));
  EXPECT_TRUE(sameBits(a.hq.pixels, a.hqDiffuse.pixels));
  EXPECT_TRUE(sameBits(a.hqDiffuse.pixels, b.hqDiffuse.pixels));
  size_t brighter = 0;
  for (size_t i = 0; i < b.hq.pixels.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_GE(b.hq.pixels[i][ch], b.hqDiffuse.pixels[i][ch]) << "pixel " << i;
    brighter += b.hq.pixels[i].r > b.hqDiffuse.pixels[i].r;
  }
  EXPECT_GT(brighter, b.hq.pixels.size() / 2) << "highlights on every material";
  EXPECT_TRUE(sameBits(a.radiosity.pixels, b.radiosity.pixels));
  EXPECT_FALSE(a.glb.empty());
  EXPECT_EQ(a.glb, b.glb);
  ASSERT_FALSE(a.pages.empty());
  ASSERT_EQ(a.pages.size(), b.pages.size());
  for (size_t p = 0; p < a.pages.size(); ++p) EXPECT_TRUE(sameBits(a.pages[p], b.pages[p])) << "page " << p;
  EXPECT_TRUE(sameBits(a.lightmapped.pixels, b.lightmapped.pixels));
}

}  // namespace
}  // namespace luxel
