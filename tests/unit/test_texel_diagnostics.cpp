// Texel diagnostics (luxel/texel_diagnostics.h): overlapping given UVs and charts with no gutter
// counted exactly on layouts whose texels can be counted by hand, invalid texels under a box
// against its footprint, and luxel's own atlases of the shared scenes free of both.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/texel_diagnostics.h"

namespace fs = std::filesystem;
using luxel::Face;
using luxel::Mesh;
using luxel::Scene;
using luxel::TexelDiagnostics;
using luxel::Vec2;
using luxel::Vec3;

namespace {

// A 1 m square in the plane y = 0, facing up, at x0..x0+1, z0-1..z0.
Mesh square(const std::string& name, float x0, float z0) {
  Mesh m;
  m.name = name;
  m.positions = {Vec3(x0, 0, z0), Vec3(x0 + 1, 0, z0), Vec3(x0 + 1, 0, z0 - 1), Vec3(x0, 0, z0 - 1)};
  m.faces = {Face{{0, 1, 2, 3}}};
  return m;
}

// Two squares side by side in one mesh, each with its own UV corners (two charts): the first
// at u in [0, 0.5], the second at u in [u1, u1 + w] (over the first when u1 < 0.5); v in [0, 0.5].
Scene twoCharts(float u1, float w) {
  Scene s;
  s.name = "charts";
  s.materials.push_back(luxel::Material{.name = "white"});
  Mesh a = square("given uvs", 0, 0), b = square("b", 1, 0);
  Mesh m = a;
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  m.faces.push_back(Face{{4, 5, 6, 7}});
  m.lightmapUvs = {Vec2(0.0f, 0.0f), Vec2(0.5f, 0.0f), Vec2(0.5f, 0.5f), Vec2(0.0f, 0.5f),
                   Vec2(u1, 0.0f), Vec2(u1 + w, 0.0f), Vec2(u1 + w, 0.5f), Vec2(u1, 0.5f)};
  s.meshes.push_back(m);
  return s;
}

luxel::LightmapAtlas atlasOf(const Scene& s, bool keepOverlaps = false) {
  luxel::AtlasOptions o;
  o.pageSize = 64;
  o.keepOverlappingUvs = keepOverlaps;
  return luxel::buildLightmapAtlas(s, o);
}

}  // namespace

// The second square folded back over [0.25, 0.5] x [0, 0.5] of the first: at 64 texels a side
// 16 columns of 32 texel centres lie in both.
TEST(TexelDiagnostics, OverlappingGivenUvsAreCountedTexelByTexel) {
  const Scene s = twoCharts(0.25f, 0.5f);
  EXPECT_THROW(atlasOf(s), luxel::Error);  // a bake refuses them
  const luxel::LightmapAtlas atlas = atlasOf(s, /*keepOverlaps=*/true);
  const TexelDiagnostics d = luxel::diagnoseTexels(s, atlas);
  EXPECT_EQ(d.overlapping, 16u * 32u);
  EXPECT_EQ(d.covered, 48u * 32u);  // the union: u in [0, 0.75]
  EXPECT_EQ(d.invalid, 0u);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool inBoth = x >= 16 && x < 32 && y < 32;
      ASSERT_EQ((d.flags[0][size_t(y) * 64 + size_t(x)] & TexelDiagnostics::Overlap) != 0, inBoth) << x << ", " << y;
    }
}

// Charts that touch (u1 = 0.5): the column either side of the join reads the other chart under
// bilinear filtering, 2 x 32 texels; the atlas says so. One empty column between them is enough.
TEST(TexelDiagnostics, ChartsWithNoGutterBleed) {
  Scene s = twoCharts(0.5f, 0.25f);
  luxel::LightmapAtlas atlas = atlasOf(s);
  TexelDiagnostics d = luxel::diagnoseTexels(s, atlas);
  EXPECT_EQ(d.bleeding, 2u * 32u);
  EXPECT_EQ(d.overlapping, 0u);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      ASSERT_EQ((d.flags[0][size_t(y) * 64 + size_t(x)] & TexelDiagnostics::Bleed) != 0, x == 31 || x == 32) << x << ", " << y;
  ASSERT_EQ(atlas.warnings.size(), 1u);
  EXPECT_NE(atlas.warnings[0].find("mesh 'given uvs': 64 texels"), std::string::npos) << atlas.warnings[0];

  s = twoCharts(33.0f / 64.0f, 0.25f);
  atlas = atlasOf(s);
  d = luxel::diagnoseTexels(s, atlas);
  EXPECT_EQ(d.bleeding, 0u);
  EXPECT_TRUE(atlas.warnings.empty());
  EXPECT_EQ(d.covered, 32u * 32u + 16u * 32u);
}

// An open box (five single-sided faces facing out, no bottom) standing on a 2 m floor: the
// floor's texels whose centres lie under it see only the box's insides and are invalid; every
// other texel is valid (the box's outer faces see the floor's front). At 32 texels a metre the
// 0.5 m footprint holds 256 texel centres, give or take its perimeter's 64 texels' half.
TEST(TexelDiagnostics, TexelsUnderAnOpenBoxAreInvalid) {
  Scene s;
  s.name = "box on floor";
  s.materials.push_back(luxel::Material{.name = "white"});
  Mesh floor;
  floor.name = "floor";
  floor.positions = {Vec3(-1, 0, 1), Vec3(1, 0, 1), Vec3(1, 0, -1), Vec3(-1, 0, -1)};
  floor.faces = {Face{{0, 1, 2, 3}}};
  s.meshes.push_back(floor);
  Mesh box;
  box.name = "box";
  const float h = 0.25f;
  box.positions = {Vec3(-h, 0, h), Vec3(h, 0, h), Vec3(h, 0, -h), Vec3(-h, 0, -h),
                   Vec3(-h, 2 * h, h), Vec3(h, 2 * h, h), Vec3(h, 2 * h, -h), Vec3(-h, 2 * h, -h)};
  box.faces = {Face{{4, 5, 6, 7}},   // top, facing +y
               Face{{0, 1, 5, 4}},   // +z
               Face{{1, 2, 6, 5}},   // +x
               Face{{2, 3, 7, 6}},   // -z
               Face{{3, 0, 4, 7}}};  // -x
  s.meshes.push_back(box);
  luxel::AtlasOptions o;
  o.texelsPerMetre = 32.0f;
  o.pageSize = 128;
  const luxel::LightmapAtlas atlas = luxel::buildLightmapAtlas(s, o);
  const TexelDiagnostics d = luxel::diagnoseTexels(s, atlas);
  std::printf("open box on a floor: %zu texels, %zu invalid (footprint 256), %zu overlapping, %zu bleeding, %.3f s\n",
              d.covered, d.invalid, d.overlapping, d.bleeding, d.seconds);
  EXPECT_GE(d.invalid, 256u - 32u);
  EXPECT_LE(d.invalid, 256u + 32u);
  EXPECT_EQ(d.overlapping, 0u);
  EXPECT_EQ(d.bleeding, 0u);
  // Every invalid texel is the floor's: the floor is one chart, the first.
  for (size_t p = 0; p < d.flags.size(); ++p)
    for (size_t i = 0; i < d.flags[p].size(); ++i)
      if (d.flags[p][i] & TexelDiagnostics::Invalid) ASSERT_EQ(d.chart[p][i], atlas.faces[0][0].chart);
  // Without the validity test nothing is invalid.
  EXPECT_EQ(luxel::diagnoseTexels(s, atlas, {.validityRays = 0}).invalid, 0u);
}

// luxel's own atlases at the bake's default density keep charts apart (a gutter of 2 texels) and
// never give a texel to two faces, on every shared scene (the conference room scaled to metres,
// as its copyright file says and bench/scenes/conference.json does).
TEST(TexelDiagnostics, OwnAtlasesOfTheSharedScenesNeitherOverlapNorBleed) {
  const fs::path root(LUXEL_TEST_SCENES);
  for (const char* file : {"mcguire-cornell-box/CornellBox-Original.obj", "dabrovic-sponza/sponza.obj",
                           "sibenik-cathedral/sibenik.obj", "stanford-bunny/bunny.obj", "conference-room/conference.obj"}) {
    const fs::path path = root / file;
    if (!fs::exists(path)) GTEST_SKIP() << path << " is missing (the scenes are unzipped at configure time)";
    Scene s = luxel::loadScene(path.string());
    if (path.filename() == "conference.obj")
      for (Mesh& m : s.meshes)
        for (Vec3& p : m.positions) p *= 0.003f;
    const luxel::LightmapAtlas atlas = luxel::buildLightmapAtlas(s, luxel::lightmapAtlasOptions(s, {}));
    const TexelDiagnostics d = luxel::diagnoseTexels(s, atlas, {.validityRays = 0});
    std::printf("%s: %d pages of %d^2 at %.3g texels/m, %zu texels, %zu overlapping, %zu bleeding, %.2f s\n", file,
                atlas.pageCount, atlas.pageSize, double(atlas.texelsPerMetre), d.covered, d.overlapping, d.bleeding,
                d.seconds);
    EXPECT_GT(d.covered, 0u) << file;
    EXPECT_EQ(d.overlapping, 0u) << file;
    EXPECT_EQ(d.bleeding, 0u) << file;
  }
}
