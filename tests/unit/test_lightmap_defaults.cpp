// The lightmap recipe's defaults (issue 13, item 4): a game's density on a level (5 texels per
// metre, Godot's 0.2 m texel) where about 10,000 texels gave Sponza 1.2; more on a small scene;
// pages sized to their content (a Cornell box no longer sits in a corner of a 1024 page) and as
// many as the charts need; --texels-per-metre, --elements and --lightmap-size still in charge.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "luxel/error.h"
#include "luxel/lightmap.h"
#include "scene/builtin/builtin_scenes.h"

namespace {

using luxel::Vec3;

// A level of `n` x `n` floor tiles of `side` metres, each its own mesh (a chart each), with a
// light above so that it is a scene.
luxel::Scene tiledFloor(int n, float side) {
  luxel::Scene scene;
  scene.name = "tiles";
  scene.materials.push_back(luxel::Material{});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      luxel::Mesh mesh;
      mesh.name = "tile";
      const float x = float(i) * side * 1.5f, z = float(j) * side * 1.5f;  // apart: no shared edges
      mesh.positions = {Vec3(x, 0, z), Vec3(x, 0, z + side), Vec3(x + side, 0, z + side), Vec3(x + side, 0, z)};
      mesh.faces.push_back(luxel::Face{{0, 1, 2, 3}});
      scene.meshes.push_back(std::move(mesh));
    }
  return scene;
}

double faceArea(const luxel::Scene& scene) {
  double area = 0.0;
  for (const luxel::Mesh& m : scene.meshes)
    for (const luxel::Face& f : m.faces) {
      const Vec3 a = m.positions[f.v[0]], b = m.positions[f.v[1]], c = m.positions[f.v[2]], d = m.positions[f.v[3]];
      area += 0.5 * glm::length(glm::cross(b - a, c - a)) + (f.isTriangle() ? 0.0 : 0.5 * glm::length(glm::cross(c - a, d - a)));
    }
  return area;
}

TEST(LightmapDefaults, ALevelGetsAGamesDensity) {
  // 60 x 60 tiles of 4 m: 57,600 m^2, where 10,000 texels would be 0.42 texels per metre.
  const luxel::Scene level = tiledFloor(60, 4.0f);
  EXPECT_FLOAT_EQ(luxel::defaultTexelsPerMetre(level), luxel::kGameTexelsPerMetre);
  const luxel::AtlasOptions o = luxel::lightmapAtlasOptions(level, luxel::LightmapRecipe{});
  EXPECT_FLOAT_EQ(o.texelsPerMetre, 5.0f);
  EXPECT_EQ(o.pageSize, luxel::kMaxDefaultPageSize);
  EXPECT_TRUE(o.sizePagesToContent);
  // As many pages as it needs: each tile is a cell of 20 x 20 texels, 22 apart with the gutter,
  // 46 x 46 = 2,116 to a 1024 page (2 texels of border): 3,600 tiles take two.
  const luxel::LightmapAtlas atlas = luxel::buildLightmapAtlas(level, o);
  EXPECT_EQ(atlas.pageSize, 1024);
  EXPECT_EQ(atlas.pageCount, 2);
  EXPECT_FLOAT_EQ(atlas.texelsPerMetre, 5.0f);
}

// A default must not fail: a scene too large for 5 texels per metre within kMaxLightmapTexels (a
// file in millimetres, say) gets the density of kDefaultMaxTexels and a warning that says why
// and what to do; a given density over the limit is still refused.
TEST(LightmapDefaults, AHugeSceneGetsAWarningNotAFailure) {
  const luxel::Scene huge = tiledFloor(60, 400.0f);  // 5.76e8 m^2: 1.4e10 texels at 5 per metre
  const float density = luxel::defaultTexelsPerMetre(huge);
  EXPECT_NEAR(double(density), std::sqrt(luxel::kDefaultMaxTexels / faceArea(huge)), 1e-4 * density);
  luxel::AtlasOptions o;
  EXPECT_NO_THROW(o = luxel::lightmapAtlasOptions(huge, luxel::LightmapRecipe{}));
  EXPECT_FLOAT_EQ(o.texelsPerMetre, density);
  const std::string why = luxel::defaultDensityWarning(huge);
  EXPECT_NE(why.find("'tiles'"), std::string::npos) << why;
  EXPECT_NE(why.find("5.76e+08 m2"), std::string::npos) << why;
  EXPECT_NE(why.find("not in metres"), std::string::npos) << why;
  EXPECT_NE(why.find("--texels-per-metre"), std::string::npos) << why;
  // A level at the game density says nothing.
  EXPECT_EQ(luxel::defaultDensityWarning(tiledFloor(60, 4.0f)), "");
  luxel::LightmapRecipe given;
  given.texelsPerMetre = 5.0f;
  EXPECT_THROW(luxel::lightmapAtlasOptions(huge, given), luxel::Error);
}

TEST(LightmapDefaults, ASmallSceneGetsAboutTenThousandTexels) {
  // The built-in Cornell box (0.56 m): 10,000 texels over its faces, far finer than 5 per metre.
  const luxel::Scene box = luxel::builtin::cornellBox();
  const float expected = float(std::sqrt(10000.0 / faceArea(box)));
  EXPECT_GT(expected, 5.0f * luxel::kGameTexelsPerMetre);
  EXPECT_NEAR(luxel::defaultTexelsPerMetre(box), expected, 1e-3f * expected);
}

TEST(LightmapDefaults, PagesAreSizedToTheirContent) {
  const luxel::Scene box = luxel::builtin::cornellBox();
  const luxel::AtlasOptions o = luxel::lightmapAtlasOptions(box, luxel::LightmapRecipe{});
  const luxel::LightmapAtlas atlas = luxel::buildLightmapAtlas(box, o);
  // About 10,000 texels with gutters and shelf waste: one page of 256 (65,536), not 1024.
  EXPECT_EQ(atlas.pageCount, 1);
  EXPECT_LE(atlas.pageSize, 256);
  // ... and the smallest power of two that holds it: half that size needs more pages.
  luxel::AtlasOptions half = o;
  half.pageSize = atlas.pageSize / 2;
  half.sizePagesToContent = false;
  EXPECT_GT(luxel::buildLightmapAtlas(box, half).pageCount, 1);
}

TEST(LightmapDefaults, GivenValuesStayInCharge) {
  const luxel::Scene box = luxel::builtin::cornellBox();
  luxel::LightmapRecipe r;
  r.texelsPerMetre = 12.0f;
  r.pageSize = 512;
  luxel::AtlasOptions o = luxel::lightmapAtlasOptions(box, r);
  EXPECT_FLOAT_EQ(o.texelsPerMetre, 12.0f);
  EXPECT_EQ(o.pageSize, 512);
  EXPECT_FALSE(o.sizePagesToContent);
  EXPECT_EQ(luxel::buildLightmapAtlas(box, o).pageSize, 512);  // though a 64 page would hold it
  // A texel budget (--elements) over the game density: 400 texels on a 25,600 m^2 level.
  r = {};
  r.texelBudget = 400;
  const luxel::Scene level = tiledFloor(40, 4.0f);
  EXPECT_NEAR(luxel::lightmapAtlasOptions(level, r).texelsPerMetre, std::sqrt(400.0 / faceArea(level)), 1e-4);
  // Nonsense is refused, naming it.
  r = {};
  r.pageSize = -1;
  EXPECT_THROW(luxel::lightmapAtlasOptions(box, r), luxel::Error);
  luxel::AtlasOptions fit;  // fitted density with pages sized to content: contradictory
  fit.sizePagesToContent = true;
  EXPECT_THROW(luxel::buildLightmapAtlas(box, fit), luxel::Error);
}

}  // namespace
