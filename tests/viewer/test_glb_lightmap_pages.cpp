// glbLightmapPages: the meshes of a scene imported from a baked glb matched to the glb's
// primitives, and so to their lightmap pages. No GL: a glb as readBakedGlb returns it, built here.
#include <gtest/gtest.h>

#include "glb_lightmap_pages.h"

namespace {

using luxel::Vec2;
using luxel::Vec3;
using luxel::viewer::BakedGlb;

// A unit square at height y, as a glb primitive on `material` and as the mesh Assimp makes of it
// (UVs with v flipped, a quad instead of two triangles).
BakedGlb::Primitive squarePrimitive(float y, int material, Vec2 uvLo, Vec2 uvHi) {
  BakedGlb::Primitive p;
  p.positions = {{0, y, 0}, {1, y, 0}, {1, y, 1}, {0, y, 1}};
  p.uv1 = {uvLo, {uvHi.x, uvLo.y}, uvHi, {uvLo.x, uvHi.y}};
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  return p;
}

luxel::Mesh squareMesh(float y, Vec2 uvLo, Vec2 uvHi) {
  luxel::Mesh m;
  m.name = "square";
  m.positions = {{0, y, 0}, {1, y, 0}, {1, y, 1}, {0, y, 1}};
  m.lightmapUvs = {{uvLo.x, 1 - uvLo.y}, {uvHi.x, 1 - uvLo.y}, {uvHi.x, 1 - uvHi.y}, {uvLo.x, 1 - uvHi.y}};
  m.faces = {luxel::Face{{0, 1, 2, 3}}};
  return m;
}

BakedGlb twoPages(int secondPageSide) {
  BakedGlb glb;
  glb.images.resize(2);
  glb.images[0].width = glb.images[0].height = 64;
  glb.images[1].width = glb.images[1].height = secondPageSide;
  glb.materials.resize(2);
  glb.materials[0].lightmap = 0;
  glb.materials[1].lightmap = 1;
  glb.hasLightmaps = true;
  return glb;
}

}  // namespace

// Two squares in the same place on two pages (a coincident copy): told apart by their UVs, whatever
// the order Assimp gives the meshes in.
TEST(GlbLightmapPages, CoincidentMeshesAreToldApartByTheirUvs) {
  BakedGlb glb = twoPages(64);
  glb.primitives = {squarePrimitive(0, 0, {0.0f, 0.0f}, {0.5f, 0.5f}), squarePrimitive(0, 1, {0.5f, 0.5f}, {1.0f, 1.0f})};
  luxel::Scene scene;
  scene.meshes = {squareMesh(0, {0.5f, 0.5f}, {1.0f, 1.0f}), squareMesh(0, {0.0f, 0.0f}, {0.5f, 0.5f})};
  const auto pages = luxel::viewer::glbLightmapPages(glb, scene);
  EXPECT_EQ(pages.meshPage, (std::vector<int>{1, 0}));
  EXPECT_EQ(pages.pageSize, 64);
  EXPECT_EQ(pages.matched, 2u);
  EXPECT_TRUE(pages.whyNot.empty()) << pages.whyNot;
}

// Pages that cannot be kept say why: nothing matched (another scene), or pages of two sizes.
TEST(GlbLightmapPages, PagesThatCannotBeKeptSayWhy) {
  BakedGlb glb = twoPages(64);
  glb.primitives = {squarePrimitive(0, 0, {0.0f, 0.0f}, {0.5f, 0.5f}), squarePrimitive(2, 1, {0.5f, 0.5f}, {1.0f, 1.0f})};
  luxel::Scene scene;
  scene.meshes = {squareMesh(5, {0.0f, 0.0f}, {0.5f, 0.5f})};  // moved: matches nothing
  auto pages = luxel::viewer::glbLightmapPages(glb, scene);
  EXPECT_EQ(pages.pageSize, 0);
  EXPECT_EQ(pages.meshPage, (std::vector<int>{-1}));
  EXPECT_NE(pages.whyNot.find("none of the scene's 1 meshes"), std::string::npos) << pages.whyNot;

  glb = twoPages(128);
  glb.primitives = {squarePrimitive(0, 0, {0.0f, 0.0f}, {0.5f, 0.5f}), squarePrimitive(2, 1, {0.5f, 0.5f}, {1.0f, 1.0f})};
  scene.meshes = {squareMesh(0, {0.0f, 0.0f}, {0.5f, 0.5f}), squareMesh(2, {0.5f, 0.5f}, {1.0f, 1.0f})};
  pages = luxel::viewer::glbLightmapPages(glb, scene);
  EXPECT_EQ(pages.matched, 2u);
  EXPECT_EQ(pages.pageSize, 0);
  EXPECT_NE(pages.whyNot.find("not all square and of one size"), std::string::npos) << pages.whyNot;
}
