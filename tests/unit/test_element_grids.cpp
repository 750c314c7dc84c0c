// Prescribed element grids (Mesh::elementGrids, src/mesh/discretise.cpp): a hinted face gets
// exactly its grid, its elements tile it, its patches are blocks of about elementsPerPatchSide
// elements that partition its elements, and faces without a grid are cut as if the hinted ones
// were not there (with what they leave of the budget). Turned-round and two-sided faces keep the
// grid on the same places; a quad cut in two falls back to the automatic cut; validate() rejects
// malformed grids.
//
// Scene values used: reflectance 0.5 everywhere; a 2 x 1 parallelogram with a 0.5 shear in
// z = 0; a 3 x 7 rectangle cut 3 x 7 (unit-square elements, whichever way it is wound); a right
// triangle with 4 m legs; a point light of 100 W/sr 1 m behind a face to make orientation repair
// turn it round.
#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/surface.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"

namespace luxel {
namespace {

using Grid = std::array<uint16_t, 2>;

Scene oneMaterialScene(bool twoSided = false) {
  Scene s;
  s.name = "grids";
  s.materials.push_back(Material{.name = "grey", .reflectance = Rgb(0.5f), .twoSided = twoSided});
  return s;
}

float faceArea(const SurfaceFace& f) { return Polygon{f.corners, f.triangle ? 3 : 4}.area(); }

// Every element in exactly one patch, the one it names; patch areas are their elements' sums.
void expectPatchesPartitionElements(const SurfaceSet& set) {
  std::vector<int> seen(set.elements.size(), 0);
  for (uint32_t p = 0; p < set.patches.size(); ++p) {
    double area = 0.0;
    for (uint32_t e : set.patches[p].elements) {
      ASSERT_LT(e, set.elements.size());
      ++seen[e];
      EXPECT_EQ(set.elements[e].patch, p);
      EXPECT_EQ(set.elements[e].face, set.patches[p].face);
      area += set.elements[e].area;
    }
    EXPECT_NEAR(area, set.patches[p].area, 1e-4 * set.patches[p].area) << "patch " << p;
  }
  for (size_t e = 0; e < seen.size(); ++e) EXPECT_EQ(seen[e], 1) << "element " << e;
}

void expectElementsTileFaces(const SurfaceSet& set) {
  std::vector<double> sums(set.faces.size(), 0.0);
  for (const Element& e : set.elements) sums[e.face] += e.area;
  for (size_t f = 0; f < set.faces.size(); ++f)
    EXPECT_NEAR(sums[f], faceArea(set.faces[f]), 1e-4 * faceArea(set.faces[f])) << "face " << f;
}

TEST(ElementGrids, QuadGetsExactlyItsGridInBalancedBlocks) {
  Scene s = oneMaterialScene();
  Mesh m;
  m.name = "parallelogram";
  builtin::addGridQuad(m, Vec3(0), Vec3(2, 0, 0), Vec3(0.5f, 1, 0), 13, 5);
  s.meshes.push_back(m);
  s.validate();
  SurfaceSet set = discretise(s, DiscretiseOptions{});
  ASSERT_EQ(set.elements.size(), 65u);
  // 13 along s in ceil(13/8) = 2 blocks of 7 and 6; 5 along t in one block.
  ASSERT_EQ(set.patches.size(), 2u);
  EXPECT_EQ(set.patches[0].elements.size(), 35u);
  EXPECT_EQ(set.patches[1].elements.size(), 30u);
  // A parallelogram's uniform grid has equal cells.
  for (const Element& e : set.elements) EXPECT_NEAR(e.area, 2.0f / 65.0f, 1e-5f);
  expectElementsTileFaces(set);
  expectPatchesPartitionElements(set);
  // Each patch is the parameter rectangle of its block, the bounds of its elements.
  for (const Patch& p : set.patches) {
    Vec2 lo(1e9f), hi(-1e9f);
    for (uint32_t e : p.elements)
      for (const Vec2& c : set.elements[e].param) lo = glm::min(lo, c), hi = glm::max(hi, c);
    const SurfaceFace& f = set.faces[p.face];
    const Vec2 corners[4] = {lo, Vec2(hi.x, lo.y), hi, Vec2(lo.x, hi.y)};
    for (int i = 0; i < 4; ++i)
      EXPECT_LT(glm::length(p.polygon.v[i] - f.position(corners[i])), 1e-5f);
  }
}

TEST(ElementGrids, BlockSizesDifferByAtMostOne) {
  Scene s = oneMaterialScene();
  Mesh m;
  m.name = "wall";
  builtin::addGridQuad(m, Vec3(0), Vec3(4.1f, 0, 0), Vec3(0, 4.1f, 0), 41, 41);
  s.meshes.push_back(m);
  SurfaceSet set = discretise(s, DiscretiseOptions{});
  ASSERT_EQ(set.elements.size(), 41u * 41u);
  ASSERT_EQ(set.patches.size(), 36u);  // ceil(41 / 8) = 6 blocks a side, of 6 or 7 elements
  std::set<size_t> sizes;
  for (const Patch& p : set.patches) sizes.insert(p.elements.size());
  for (size_t n : sizes) EXPECT_TRUE(n == 36 || n == 42 || n == 49) << n;
  // Elements are squares of 0.1 m.
  for (const Element& e : set.elements) EXPECT_NEAR(e.area, 0.01f, 1e-6f);
  expectPatchesPartitionElements(set);

  DiscretiseOptions one;
  one.elementsPerPatchSide = 1;  // every element its own patch
  EXPECT_EQ(discretise(s, one).patches.size(), 41u * 41u);
}

TEST(ElementGrids, TrianglesGetNSquaredElements) {
  for (int n : {1, 5, 8, 12, 11}) {
    Scene s = oneMaterialScene();
    Mesh m;
    m.name = "triangle";
    m.positions = {Vec3(0), Vec3(4, 0, 0), Vec3(0, 4, 0)};
    m.faces.push_back(Face{{0, 1, 2, 2}});
    m.elementGrids.push_back({uint16_t(n), uint16_t(n)});
    s.meshes.push_back(m);
    s.validate();
    SurfaceSet set = discretise(s, DiscretiseOptions{});
    ASSERT_EQ(set.elements.size(), size_t(n * n)) << n;
    // One patch up to 8 a side; beyond, P^2 patches with P the smallest divisor of n that keeps
    // n / P <= 8: 12 -> 2 x 2 patches of 36, 11 (prime) -> 121 patches of one.
    const size_t patches = n <= 8 ? 1 : n == 12 ? 4 : 121;
    EXPECT_EQ(set.patches.size(), patches) << n;
    for (const Element& e : set.elements) EXPECT_NEAR(e.area, 8.0f / float(n * n), 1e-4f) << n;
    expectElementsTileFaces(set);
    expectPatchesPartitionElements(set);
  }
}

// The unhinted faces get the same elements with or without hinted faces beside them, when the
// budget grows by what the hinted faces take.
TEST(ElementGrids, HintedFacesLeaveTheBudgetSearchAlone) {
  auto build = [](bool withHinted) {
    Scene s = oneMaterialScene();
    Mesh free;
    free.name = "free";
    builtin::addQuad(free, Vec3(0), Vec3(3, 0, 0), Vec3(3, 2, 0), Vec3(0, 2, 0));
    builtin::addQuad(free, Vec3(0, 0, 1), Vec3(0, 2, 1), Vec3(1, 2, 1), Vec3(1, 0, 1));
    s.meshes.push_back(free);
    if (withHinted) {
      Mesh fixed;
      fixed.name = "fixed";
      builtin::addGridQuad(fixed, Vec3(5, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 30, 20);
      s.meshes.push_back(fixed);
    }
    return s;
  };
  auto countsOfMesh = [](const SurfaceSet& set, uint32_t mesh) {
    std::vector<size_t> n;
    for (const Element& e : set.elements)
      if (set.faces[e.face].mesh == mesh) {
        if (n.size() <= e.face) n.resize(e.face + 1, 0);
        ++n[e.face];
      }
    return n;
  };
  DiscretiseOptions plain;
  plain.elementBudget = 500;
  DiscretiseOptions more = plain;
  more.elementBudget = 500 + 600;
  SurfaceSet a = discretise(build(false), plain);
  SurfaceSet b = discretise(build(true), more);
  EXPECT_EQ(countsOfMesh(a, 0), countsOfMesh(b, 0));
  EXPECT_EQ(b.elements.size(), a.elements.size() + 600);
  EXPECT_FLOAT_EQ(a.elementSize, b.elementSize);

  // A budget the hinted faces use up still gives every free face at least one element, and the
  // hinted face its grid.
  DiscretiseOptions tiny;
  tiny.elementBudget = 100;
  SurfaceSet c = discretise(build(true), tiny);
  size_t fixed = 0, free = 0;
  for (const Element& e : c.elements) (c.faces[e.face].mesh == 1 ? fixed : free)++;
  EXPECT_EQ(fixed, 600u);
  EXPECT_GE(free, 2u);
  EXPECT_LE(free, 16u);

  // A given element size cuts the free faces only.
  DiscretiseOptions sized;
  sized.elementSize = 0.5f;
  SurfaceSet d = discretise(build(true), sized);
  fixed = 0;
  for (const Element& e : d.elements) fixed += d.faces[e.face].mesh == 1;
  EXPECT_EQ(fixed, 600u);
  EXPECT_EQ(d.elements.size(), 600u + 24u + 8u);  // 3 x 2 m at 0.5 m, 1 x 2 m at 0.5 m
}

// Unit-square elements on a 3 x 7 rectangle cut 3 x 7: checks the grid stays on the right axes.
void expectUnitSquares(const SurfaceSet& set, size_t count) {
  ASSERT_EQ(set.elements.size(), count);
  for (const Element& e : set.elements) {
    EXPECT_NEAR(e.area, 1.0f, 1e-4f);
    EXPECT_NEAR(glm::length(e.polygon.v[1] - e.polygon.v[0]), 1.0f, 1e-4f);
    EXPECT_NEAR(glm::length(e.polygon.v[3] - e.polygon.v[0]), 1.0f, 1e-4f);
  }
}

TEST(ElementGrids, TurnedRoundFacesKeepTheirGridInPlace) {
  Scene s = oneMaterialScene();
  Mesh m;
  m.name = "rect";
  builtin::addGridQuad(m, Vec3(0), Vec3(3, 0, 0), Vec3(0, 7, 0), 3, 7);  // front +z
  s.meshes.push_back(m);
  s.lights.push_back(Light{.type = Light::Type::Point,
                           .intensity = 100.0f,
                           .position = Vec3(1.5f, 3.5f, -1.0f)});  // behind it
  SurfaceSet set = discretise(s, DiscretiseOptions{});
  ASSERT_EQ(set.flippedFaces, 1u);
  EXPECT_NEAR(set.faces[0].normal.z, -1.0f, 1e-5f);
  expectUnitSquares(set, 21);
}

TEST(ElementGrids, TwoSidedBackFacesCopyTheGrid) {
  Scene s = oneMaterialScene(true);
  Mesh m;
  m.name = "panel";
  builtin::addGridQuad(m, Vec3(0), Vec3(3, 0, 0), Vec3(0, 7, 0), 3, 7);
  s.meshes.push_back(m);
  SurfaceSet set = discretise(s, DiscretiseOptions{});
  ASSERT_EQ(set.faces.size(), 2u);
  expectUnitSquares(set, 42);
  expectElementsTileFaces(set);
  expectPatchesPartitionElements(set);
}

TEST(ElementGrids, QuadsCutInTwoFallBackToTheAutomaticCut) {
  Scene s = oneMaterialScene();
  Mesh m;
  m.name = "bent";
  builtin::addGridQuad(m, Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), 5, 5);
  m.positions[2].z = 0.2f;  // lift the third corner off the plane
  s.meshes.push_back(m);
  s.validate();
  DiscretiseOptions o;
  o.elementBudget = 200;
  SurfaceSet set = discretise(s, o);
  EXPECT_EQ(set.splitQuads, 1u);
  ASSERT_EQ(set.faces.size(), 2u);
  EXPECT_GT(set.elements.size(), 50u);  // the budget's, not the grid's 25
  expectElementsTileFaces(set);
}

TEST(ElementGrids, ValidateRejectsMalformedGrids) {
  auto scene = [](std::vector<Grid> grids, bool triangle = false) {
    Scene s = oneMaterialScene();
    Mesh m;
    m.name = "m";
    m.positions = {Vec3(0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    m.faces = {Face{{0, 1, 2, triangle ? 2u : 3u}}, Face{{0, 2, 3, 3}}};
    m.elementGrids = grids;
    s.meshes.push_back(m);
    return s;
  };
  EXPECT_NO_THROW(scene({}).validate());
  EXPECT_NO_THROW(scene({{0, 0}, {4, 4}}).validate());
  EXPECT_NO_THROW(scene({{2, 3}, {0, 0}}).validate());
  EXPECT_THROW(scene({{2, 3}}).validate(), Error);          // one grid for two faces
  EXPECT_THROW(scene({{0, 3}, {0, 0}}).validate(), Error);  // half a grid
  EXPECT_THROW(scene({{0, 0}, {2, 3}}).validate(), Error);  // a triangle needs n x n
  EXPECT_THROW(scene({{2, 3}, {1, 1}}, true).validate(), Error);
  EXPECT_THROW(discretise(scene({{2, 3}}), DiscretiseOptions{}), Error);
}

}  // namespace
}  // namespace luxel
