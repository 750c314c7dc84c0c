// Texels as elements (lightmap.h, bakeLightmaps): the Cornell box baked to a lightmap agrees with
// the element solution at matched resolution; invalid texels, seams and gutters; seam edges found
// by the spatial hash exactly as by comparing all pairs, and stitched on meshes of any size.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>

#include "lightmap/seam_edges.h"
#include "luxel/bake.h"
#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/solve.h"

namespace {

// Cornell walls are about 0.55 m: N texels per wall side.
constexpr float kWall = 0.55f;

struct Baked {
  luxel::Scene scene;
  luxel::LightmapAtlas atlas;
  luxel::LightmapBake bake;
};

Baked bakeCornell(int texelsPerSide, int pageSize) {
  Baked b;
  b.scene = luxel::loadScene("cornell");
  luxel::AtlasOptions ao;
  ao.texelsPerMetre = float(texelsPerSide) / kWall;
  ao.pageSize = pageSize;
  b.atlas = luxel::buildLightmapAtlas(b.scene, ao);
  b.bake = luxel::bakeLightmaps(b.scene, b.atlas);
  return b;
}

const Baked& cornell32() {
  static const Baked b = bakeCornell(32, 256);
  return b;
}

float luminance(luxel::Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

TEST(LightmapBake, CornellTexelsAreFiniteAndCounted) {
  const Baked& b = cornell32();
  const auto& k = b.bake;
  EXPECT_EQ(k.texels, k.surfaces.surfaces.elements.size());
  EXPECT_GT(k.texels, 6000u);
  EXPECT_LT(k.texels, 12000u);
  size_t covered = 0;
  for (size_t p = 0; p < k.pages.size(); ++p)
    for (size_t i = 0; i < k.pages[p].size(); ++i) {
      const luxel::Rgb c = k.pages[p][i];
      ASSERT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
      ASSERT_GE(std::min({c.r, c.g, c.b}), 0.0f);
      covered += k.state[p][i] == luxel::LightmapBake::Solved || k.state[p][i] == luxel::LightmapBake::Filled;
    }
  EXPECT_EQ(covered, k.texels);
  std::printf("cornell 32/side: %zu texels, %zu patches, %zu invalid (%zu unfilled), %zu dilated, seams %zu edges "
              "%zu samples, max relative difference %.4f before, %.2g after; %.2f s surfaces, %.2f s validity, "
              "%.2f s solve, %.2f s post\n",
              k.texels, k.surfaces.surfaces.patches.size(), k.invalidTexels, k.unfilledTexels, k.dilatedTexels,
              k.seamEdges, k.seamSamples, k.seamMaxBefore, k.seamMaxAfter, k.secondsSurfaces, k.secondsValidity,
              k.secondsSolve, k.secondsPost);
}

// The floor under the two blocks lies inside geometry: those texels see back faces and are
// filled from their chart; every other texel is valid.
TEST(LightmapBake, TexelsInsideGeometryAreDetectedAndFilled) {
  const auto& k = cornell32().bake;
  EXPECT_GT(k.invalidTexels, 100u);
  EXPECT_EQ(k.unfilledTexels, 0u);
  const auto& set = k.surfaces.surfaces;
  const luxel::Scene& scene = cornell32().scene;
  // They lie on the floor under the blocks (measured: 187 of 6,553 texels at 32 per wall side).
  std::map<std::string, size_t> byMesh;
  for (size_t e = 0; e < set.elements.size(); ++e)
    if (!k.valid[e]) ++byMesh[scene.meshes[set.faces[set.elements[e].face].mesh].name];
  for (const auto& [name, count] : byMesh) std::printf("  invalid on %s: %zu\n", name.c_str(), count);
  EXPECT_EQ(byMesh["floor"], k.invalidTexels);
  // No leak of darkness: filled texels are as bright as the valid floor near the blocks.
  double filled = 0, n = 0;
  for (size_t e = 0; e < set.elements.size(); ++e)
    if (!k.valid[e]) {
      const auto& t = k.surfaces.texels[e];
      filled += luminance(k.pages[t.page][t.y * size_t(k.pageSize) + t.x]), ++n;
    }
  EXPECT_GT(filled / n, 0.05) << "filled texels are dark";
}

TEST(LightmapBake, SeamsAgreeAndGuttersAreDilated) {
  const auto& k = cornell32().bake;
  EXPECT_GT(k.seamSamples, 0u);  // the ceiling's pieces round the light
  EXPECT_LT(k.seamMaxAfter, 0.01f);  // measured 0.0073 (from 0.077): texels on several pairs converge slowly
  const int s = k.pageSize;
  size_t next = 0, dilated = 0;
  for (size_t p = 0; p < k.pages.size(); ++p)
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) {
        const auto st = k.state[p][size_t(y) * size_t(s) + size_t(x)];
        if (st == luxel::LightmapBake::Solved || st == luxel::LightmapBake::Filled) continue;
        bool byChart = false;
        for (int d = 0; d < 4; ++d) {
          const int xx = x + (d == 0) - (d == 1), yy = y + (d == 2) - (d == 3);
          if (xx < 0 || yy < 0 || xx >= s || yy >= s) continue;
          const auto nt = k.state[p][size_t(yy) * size_t(s) + size_t(xx)];
          byChart |= nt == luxel::LightmapBake::Solved || nt == luxel::LightmapBake::Filled;
        }
        if (!byChart) continue;
        ++next;
        dilated += st == luxel::LightmapBake::Dilated;
      }
  EXPECT_GT(next, 0u);
  EXPECT_EQ(dilated, next);
}

// Per surface, the mean irradiance over valid texels against the element solution at the same
// places, with elements as large as texels.
// Measured at 32 texels per wall side: 0.3-0.9% on the walls, floor, ceiling and light, 1.7% on
// the tall block, 2.9% on the short one (their faces are under 0.17 m: few texels). Allowed: 5%.
TEST(LightmapBake, CornellAgreesWithTheElementSolution) {
  const Baked& b = cornell32();
  const auto& k = b.bake;
  luxel::DiscretiseOptions d;
  d.elementSize = 1.0f / b.atlas.texelsPerMetre;
  luxel::SurfaceSet ref = luxel::discretise(b.scene, d);
  const luxel::Solution sol = luxel::solve(b.scene, ref, luxel::SolveOptions{});
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> elementsOf;
  for (uint32_t e = 0; e < ref.elements.size(); ++e) {
    const auto& f = ref.faces[ref.elements[e].face];
    if (f.twin >= 0 && uint32_t(f.twin) < ref.elements[e].face) continue;
    elementsOf[{f.mesh, f.meshFace}].push_back(e);
  }
  const auto& set = k.surfaces.surfaces;
  std::map<uint32_t, std::array<double, 3>> perMesh;  // sum texel, sum element, area
  for (size_t e = 0; e < set.elements.size(); ++e) {
    if (!k.valid[e]) continue;
    const auto& el = set.elements[e];
    const auto& f = set.faces[el.face];
    const auto& cands = elementsOf[{f.mesh, f.meshFace}];
    ASSERT_FALSE(cands.empty());
    uint32_t best = cands[0];
    float bd = 1e30f;
    for (uint32_t c : cands) {
      const float dd = glm::length(ref.elements[c].centroid - el.centroid);
      if (dd < bd) bd = dd, best = c;
    }
    auto& acc = perMesh[f.mesh];
    acc[0] += el.area * double(luminance(k.solution.irradiance[e]));
    acc[1] += el.area * double(luminance(sol.irradiance[best]));
    acc[2] += el.area;
  }
  double worst = 0.0;
  for (const auto& [m, acc] : perMesh) {
    const double rel = std::abs(acc[0] - acc[1]) / std::max(acc[1], 1e-12);
    std::printf("  %-12s texels %.4f elements %.4f W/m^2 (%.2f%%)\n", b.scene.meshes[m].name.c_str(),
                acc[0] / acc[2], acc[1] / acc[2], 100.0 * rel);
    if (b.scene.meshes[m].name != "light") EXPECT_LT(rel, 0.05) << b.scene.meshes[m].name;
    worst = std::max(worst, rel);
  }
  std::printf("largest per-surface difference %.2f%% (%zu texels, %zu elements)\n", 100.0 * worst, k.texels,
              ref.elements.size());
}

// The hash finds exactly the pairs the all-pairs loop finds, with the same overlaps, on edges
// built to be awkward: shared edges with vertices jittered by less than eps (near-equal, so they
// straddle any rounding grid), T-junctions (one long edge against three short ones), reversed
// edges, degenerate ones, edges of one face (never paired), long diagonals, random clutter.
TEST(SeamEdges, HashFindsExactlyWhatAllPairsFind) {
  using luxel::Vec3;
  using luxel::lightmap::SeamEdge;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float eps = 1e-4f;
  auto jitter = [&](Vec3 p) { return p + 0.2f * eps * Vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f); };
  std::vector<SeamEdge> edges;
  uint32_t face = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3 a(unit(rng) * 10.0f, unit(rng) * 10.0f, unit(rng) * 10.0f);
    const Vec3 b = a + Vec3(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f) * (i % 10 == 0 ? 8.0f : 0.5f);
    edges.push_back({face++, jitter(a), jitter(b)});  // shared, reversed
    edges.push_back({face++, jitter(b), jitter(a)});
    if (i % 3 == 0) {  // a T-junction: three pieces along the same line
      for (int k = 0; k < 3; ++k)
        edges.push_back({face++, a + (b - a) * (float(k) / 3.0f), a + (b - a) * (float(k + 1) / 3.0f)});
    }
    if (i % 7 == 0) edges.push_back({face - 1, a, b});                               // same face as the last: skipped
    if (i % 11 == 0) edges.push_back({face++, a, a + Vec3(0.5f * eps, 0.0f, 0.0f)}); // shorter than eps
    if (i % 5 == 0) edges.push_back({face++, a + (b - a) * 0.999f, b + (b - a) * 2.0f});  // overlaps by 0.1%
    const Vec3 p(unit(rng), unit(rng), unit(rng)), q(unit(rng), unit(rng), unit(rng));
    edges.push_back({face++, p * 10.0f, q * 10.0f});
  }
  const auto hashed = luxel::lightmap::overlappingEdges(edges, eps);
  std::vector<luxel::lightmap::EdgeOverlap> all;
  for (uint32_t i = 0; i < edges.size(); ++i)
    for (uint32_t j = i + 1; j < edges.size(); ++j) {
      if (edges[i].face == edges[j].face) continue;
      luxel::lightmap::EdgeOverlap o{i, j, 0.0f, 0.0f};
      if (luxel::lightmap::edgesOverlap(edges[i], edges[j], eps, &o.s0, &o.s1)) all.push_back(o);
    }
  std::printf("%zu edges: %zu overlapping pairs\n", edges.size(), all.size());
  EXPECT_GT(all.size(), 1200u);  // 600 shared pairs, 200 T-junctions of 3 and more
  ASSERT_EQ(hashed.size(), all.size());
  for (size_t k = 0; k < all.size(); ++k) {
    ASSERT_EQ(hashed[k].first, all[k].first) << k;
    ASSERT_EQ(hashed[k].second, all[k].second) << k;
    EXPECT_EQ(hashed[k].s0, all[k].s0);
    EXPECT_EQ(hashed[k].s1, all[k].s1);
  }
  EXPECT_TRUE(luxel::lightmap::overlappingEdges({}, eps).empty());
}

// A corrugated sheet: 60 strips sloping +-15 degrees in turn, each 100 quads long, lit by a sun from
// one side (45 degrees up, across the strips), so the strips get 100 cos 60 = 50 and 100 cos 30 =
// 86.6 W m^-2 in turn. With a 10 degree chart angle every strip is a chart, and its long edges are
// seams (30 degrees < the 45 degree seam angle). 6,000 quads are 24,000 edges: beyond the all-pairs
// loop's old limit of 20,000, which skipped stitching and reported 0 -> 0.
constexpr int kStrips = 60, kRows = 100;
constexpr float kStrip = 0.1f;  // width (across, in x) and length (in z) of each quad

struct Corrugated {
  luxel::Scene scene;
  luxel::LightmapAtlas atlas;
  luxel::LightmapBake bake;
  double seconds = 0.0;
};

const Corrugated& corrugated() {
  static const Corrugated c = [] {
    using luxel::Vec3;
    Corrugated c;
    const float rise = kStrip * std::tan(15.0f * 3.14159265f / 180.0f);
    c.scene.name = "corrugated";
    c.scene.materials = {luxel::Material{.name = "sheet", .reflectance = luxel::Rgb(0.5f)}};
    luxel::Mesh sheet{.name = "sheet", .material = 0};
    for (int j = 0; j <= kRows; ++j)
      for (int i = 0; i <= kStrips; ++i)
        sheet.positions.push_back(Vec3(float(i) * kStrip, float(i % 2) * rise, float(j) * kStrip));
    auto at = [](int i, int j) { return uint32_t(j * (kStrips + 1) + i); };
    for (int j = 0; j < kRows; ++j)
      for (int i = 0; i < kStrips; ++i)
        sheet.faces.push_back(luxel::Face{{at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)}});
    c.scene.meshes = {sheet};
    c.scene.lights = {luxel::Light{.type = luxel::Light::Type::Directional, .name = "sun", .intensity = 100.0f,
                                   .direction = glm::normalize(Vec3(-1.0f, -1.0f, 0.0f))}};
    luxel::AtlasOptions ao;
    ao.texelsPerMetre = 20.0f;  // 2 x 2 texels per quad
    ao.pageSize = 512;
    ao.chartAngle = 10.0f;
    c.atlas = luxel::buildLightmapAtlas(c.scene, ao);
    luxel::LightmapBakeOptions lo;
    lo.solve.settings.set("shot-budget", 1);   // the seams' disagreement is the sun's, direct: no need to converge
    lo.solve.settings.set("ambient", false);  // (nor for an ambient estimate, which would hide part of it)
    const auto t0 = std::chrono::steady_clock::now();
    c.bake = luxel::bakeLightmaps(c.scene, c.atlas, lo);
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return c;
  }();
  return c;
}

TEST(LightmapBake, SeamsAreStitchedOnLargeMeshes) {
  const Corrugated& c = corrugated();
  const luxel::LightmapBake& k = c.bake;
  std::printf("corrugated: %zu texels, %zu seam edges, %zu samples, seams %.3f -> %.2g, stitching %.3f s of %.2f s "
              "(solve %.2f s)\n",
              k.texels, k.seamEdges, k.seamSamples, k.seamMaxBefore, k.seamMaxAfter, k.secondsSeams, c.seconds,
              k.secondsSolve);
  EXPECT_EQ(c.atlas.chartCount, size_t(kStrips));
  ASSERT_EQ(k.surfaces.surfaces.faces.size(), size_t(kStrips * kRows));  // 4 edges each: 24,000
  EXPECT_EQ(k.seamEdges, size_t((kStrips - 1) * kRows));  // every fold edge, once
  EXPECT_GE(k.seamSamples, k.seamEdges * 2);              // at least 2 samples per seam edge
  EXPECT_GT(k.seamMaxBefore, 0.3f);                       // |86.6 - 50| / 68.3 = 0.54
  EXPECT_LT(k.seamMaxAfter, 0.01f);
  EXPECT_LT(k.secondsSeams, 5.0);
}

// Vertex colours from the bake (lightmapCornerIrradiance): the folds turn by 30 degrees, so every
// vertex is on one smooth surface and all its corners agree; on a fold it holds the stitched seam,
// between the two strips' values; on the sheet's two long borders, its own strip's.
TEST(LightmapBake, CornerIrradianceFollowsTheTexels) {
  const Corrugated& c = corrugated();
  const luxel::FaceCornerValues v = luxel::lightmapCornerIrradiance(c.scene, c.atlas, c.bake, {1});
  ASSERT_EQ(v.size(), 1u);
  ASSERT_EQ(v[0].size(), size_t(kStrips * kRows * 4));
  const luxel::Mesh& sheet = c.scene.meshes[0];
  std::vector<std::vector<luxel::Rgb>> atVertex(sheet.positions.size());
  for (size_t f = 0; f < sheet.faces.size(); ++f)
    for (int k = 0; k < 4; ++k) atVertex[sheet.faces[f].v[size_t(k)]].push_back(v[0][f * 4 + size_t(k)]);
  auto vertex = [](int i, int j) { return size_t(j * (kStrips + 1) + i); };
  double fold = 0.0, low = 0.0, high = 0.0;
  int folds = 0, borders = 0;
  for (int j = 0; j <= kRows; ++j)
    for (int i = 0; i <= kStrips; ++i) {
      const auto& values = atVertex[vertex(i, j)];
      ASSERT_FALSE(values.empty());
      for (const luxel::Rgb& x : values) ASSERT_LT(std::abs(x.r - values[0].r), 1e-4f * values[0].r) << i << " " << j;
      if (i == 0) low += values[0].r, ++borders;
      else if (i == kStrips) high += values[0].r;
      else fold += values[0].r, ++folds;
    }
  fold /= folds, low /= borders, high /= borders;
  std::printf("corner irradiance: %.2f on the border of a 50 strip, %.2f on the border of an 86.6 strip, %.2f on the "
              "folds\n", low, high, fold);
  // Measured 50.00, 86.60 and 68.30: the sun's direct light (the strips, 15 degrees off level, see
  // almost nothing of each other), and the seams' average on the folds.
  EXPECT_NEAR(low, 50.0, 1.0);
  EXPECT_NEAR(high, 86.6, 1.0);
  EXPECT_NEAR(fold, 0.5 * (low + high), 1.0);
  EXPECT_THROW(luxel::lightmapCornerIrradiance(c.scene, c.atlas, c.bake, {}), luxel::Error);  // one flag per mesh
}

// A mesh whose given lightmap UVs are all (0,0) baked black: every face was a point in texel
// space. Now it is unwrapped by luxel, says so among the solve's warnings, and its faces are lit.
TEST(LightmapBake, GivenUvsOfNoAreaAreUnwrappedAndLit) {
  luxel::Scene scene = luxel::loadScene("cornell");
  luxel::Mesh& mesh = scene.meshes[0];
  mesh.lightmapUvs.assign(mesh.positions.size(), luxel::Vec2(0.0f, 0.0f));
  luxel::LightmapRecipe recipe;
  recipe.texelBudget = 3000;
  const luxel::BakedLightmaps baked = luxel::bakeLightmaps(scene, recipe);
  const auto& warnings = baked.bake.solution.stats.warnings;
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("mesh '" + mesh.name + "'"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("unwrapped by luxel"), std::string::npos) << warnings[0];
  // Each face's centre texel holds light, and faces hold texels of their own.
  const int size = baked.bake.pageSize;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& uv = baked.atlas.faces[0][f];
    EXPECT_FALSE(uv.conservative) << "face " << f;
    const luxel::Vec2 c = 0.25f * (uv.texel[0] + uv.texel[1] + uv.texel[2] + uv.texel[3]);
    const int x = std::clamp(int(c.x), 0, size - 1), y = std::clamp(int(c.y), 0, size - 1);
    EXPECT_GT(luminance(baked.bake.pages[uv.page][size_t(y) * size_t(size) + size_t(x)]), 0.0f) << "face " << f;
  }
}

TEST(LightmapBake, RgbmRoundTrips) {
  luxel::Image im(4, 1);
  im.pixels = {luxel::Rgb(0.0f), luxel::Rgb(0.5f, 0.25f, 0.1f), luxel::Rgb(3.0f, 1.0f, 0.0f), luxel::Rgb(7.9f)};
  EXPECT_EQ(luxel::rgbmRange(im), 8.0f);
  EXPECT_GT(luxel::encodeRgbmPng(im, 8.0f).size(), 8u);
}

}  // namespace
