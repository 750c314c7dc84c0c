// The shadow volumes' casters with adjacency (viewer/shadow_casters.h): every edge of a closed
// surface has its neighbour, so volumes get sides along silhouettes only; a border, a
// non-manifold edge or two faces wound the same way leave the side in.
#include <gtest/gtest.h>

#include "scene/builtin/builtin_scenes.h"
#include "shadow_casters.h"

namespace luxel {
namespace {

// Edges with no proper neighbour: their neighbour slot names the triangle's own third corner.
size_t unpairedEdges(const viewer::CasterMesh& m) {
  size_t n = 0;
  for (size_t t = 0; t * 6 < m.adjacency.size(); ++t) {
    const uint32_t* a = &m.adjacency[t * 6];
    n += (a[1] == a[4]) + (a[3] == a[0]) + (a[5] == a[2]);
  }
  return n;
}

SurfaceSet oneElementAFace(Scene scene) {
  scene.name = "casters";
  if (scene.materials.empty()) scene.materials.push_back(Material{.name = "grey", .reflectance = Rgb(0.5f)});
  return discretise(scene, DiscretiseOptions{.elementSize = 100.0f, .orientByLight = false});
}

TEST(ShadowCasters, AClosedBoxHasANeighbourAcrossEveryEdge) {
  Scene scene;
  Mesh box{.name = "box"};
  builtin::addInwardBox(box, Vec3(0.0f), Vec3(1.0f, 2.0f, 3.0f));
  scene.meshes.push_back(box);
  const viewer::CasterMesh m = viewer::casterMesh(oneElementAFace(scene));
  EXPECT_EQ(m.vertices.size(), 8u) << "the faces' corners welded";
  ASSERT_EQ(m.adjacency.size(), 12u * 6u);
  EXPECT_EQ(unpairedEdges(m), 0u);
  // Each neighbour is another triangle's corner: never one of the triangle's own three.
  for (size_t t = 0; t < 12; ++t) {
    const uint32_t* a = &m.adjacency[t * 6];
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = a[2 * k + 1];
      EXPECT_TRUE(n != a[0] && n != a[2] && n != a[4]) << "triangle " << t << " edge " << k;
    }
  }
}

TEST(ShadowCasters, BordersAndDoubledFacesKeepTheirSides) {
  Scene open;
  Mesh quad{.name = "quad"};
  builtin::addQuad(quad, {0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1});
  open.meshes.push_back(quad);
  const viewer::CasterMesh q = viewer::casterMesh(oneElementAFace(open));
  EXPECT_EQ(q.vertices.size(), 4u);
  // Two triangles: the diagonal is shared, the four sides are the border.
  EXPECT_EQ(unpairedEdges(q), 4u);
  // The same quad twice, wound the same way: every edge is shared by two triangles running the
  // same way, so none is a proper neighbour.
  Scene doubled = open;
  doubled.meshes.push_back(quad);
  const viewer::CasterMesh d = viewer::casterMesh(oneElementAFace(doubled));
  EXPECT_EQ(unpairedEdges(d), 12u);
}

}  // namespace
}  // namespace luxel
