// The vertex gather's own mesh (render/gather_mesh.h): the solved elements split into four, as
// often as asked. The split must cover exactly what was solved, carry the solution's fields over
// unchanged as functions of position, and leave the closed forms of the furnace where they were.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "render/corner_values.h"
#include "render/gather_mesh.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

TEST(GatherMesh, SplitsBringTheElementsNearestTheWantedCount) {
  EXPECT_EQ(GatherMesh::splitsFor(2542, 10000), 1);  // 10,168 against 40,672
  EXPECT_EQ(GatherMesh::splitsFor(674, 10000), 2);   // 10,784
  EXPECT_EQ(GatherMesh::splitsFor(10082, 10000), 0);
  EXPECT_EQ(GatherMesh::splitsFor(1000, 1500), 0);  // a split would overshoot by more
  EXPECT_EQ(GatherMesh::splitsFor(1000, 0), 0);
  EXPECT_EQ(GatherMesh::splitsFor(0, 10000), 0);
  // Never more than 4 (256 a solved element), nor past kMaxGatherElements (4,194,304).
  EXPECT_EQ(GatherMesh::splitsFor(1, size_t(1) << 40), 4);
  EXPECT_EQ(GatherMesh::splitsFor(1000000, 100000000), 1);
}

// Whether p lies in the convex polygon (on its plane), within `slack` of its edges.
bool inside(const Polygon& polygon, Vec3 n, Vec3 p, float slack) {
  for (int i = 0; i < polygon.count; ++i) {
    const Vec3 a = polygon.v[size_t(i)], b = polygon.v[size_t((i + 1) % polygon.count)];
    const Vec3 inward = glm::normalize(glm::cross(n, b - a));
    if (glm::dot(p - a, inward) < -slack) return false;
  }
  return true;
}

// More triangles: the Cornell box's faces each cut in two.
Scene triangulated(Scene scene) {
  for (Mesh& mesh : scene.meshes) {
    std::vector<Face> faces;
    for (const Face& f : mesh.faces) {
      if (f.isTriangle()) {
        faces.push_back(f);
        continue;
      }
      Face a = f, b = f;
      a.v = {f.v[0], f.v[1], f.v[2], f.v[2]};
      b.v = {f.v[0], f.v[2], f.v[3], f.v[3]};
      faces.push_back(a);
      faces.push_back(b);
    }
    mesh.faces = faces;
  }
  return scene;
}

// `triangles`: how many of the solved elements are triangles.
void expectSplitCoversTheSolvedElements(const Scene& scene, int splits,
                                        size_t* triangles = nullptr) {
  DiscretiseOptions d;
  d.elementBudget = 300;
  const SurfaceSet solved = discretise(scene, d);
  const GatherMesh mesh(scene, solved, splits);
  const SurfaceSet& split = mesh.surfaces();
  ASSERT_EQ(split.elements.size(), solved.elements.size() << (2 * splits));
  EXPECT_FALSE(split.hasPatches());
  std::vector<double> areaOf(solved.elements.size(), 0.0);
  for (uint32_t e = 0; e < split.elements.size(); ++e) {
    const Element& el = split.elements[e];
    const uint32_t p = mesh.parent(e);
    ASSERT_LT(p, solved.elements.size());
    const Element& parent = solved.elements[p];
    EXPECT_EQ(el.face, parent.face);
    EXPECT_EQ(el.material, parent.material);
    EXPECT_EQ(el.patch, kNoPatch);
    EXPECT_EQ(el.polygon.count, parent.polygon.count);
    for (int c = 0; c < el.polygon.count; ++c)
      EXPECT_TRUE(inside(parent.polygon, parent.normal, el.polygon.v[size_t(c)], 1e-5f))
          << "corner " << c << " of split element " << e << " is outside its parent " << p;
    areaOf[p] += el.area;
  }
  for (size_t p = 0; p < solved.elements.size(); ++p)
    EXPECT_NEAR(areaOf[p], solved.elements[p].area, 1e-5 * solved.elements[p].area)
        << "element " << p;

  // A field linear in position, given at the solved corners, is the same function at the split
  // corners (barycentric and bilinear interpolation reproduce it on planar elements).
  const Vec3 slope(0.3f, -1.7f, 0.9f);
  const auto f = [&](Vec3 x) { return Rgb(glm::dot(slope, x) + 2.0f); };
  std::vector<Rgb> solvedCorners(solved.elements.size() * 4, Rgb(0.0f));
  for (size_t e = 0; e < solved.elements.size(); ++e)
    for (int c = 0; c < solved.elements[e].polygon.count; ++c)
      solvedCorners[e * 4 + size_t(c)] = f(solved.elements[e].polygon.v[size_t(c)]);
  const std::vector<Rgb> corners = mesh.corners(solvedCorners);
  ASSERT_EQ(corners.size(), split.elements.size() * 4);
  const float scale = glm::length(slope) * solved.sceneExtent;
  for (size_t e = 0; e < split.elements.size(); ++e)
    for (int c = 0; c < split.elements[e].polygon.count; ++c)
      EXPECT_NEAR(corners[e * 4 + size_t(c)].g, f(split.elements[e].polygon.v[size_t(c)]).g,
                  1e-5f * scale)
          << "corner " << c << " of split element " << e;

  if (triangles) *triangles = 0;
  for (const Element& e : solved.elements)
    if (triangles) *triangles += e.polygon.count == 3;
}

// The built-in box: quads, with a few triangles (98 of 300 elements); triangulated: 197 of 600.
TEST(GatherMesh, SplitElementsCoverTheSolvedElementsAndCarryFieldsOver) {
  for (int splits : {1, 2}) {
    size_t triangles = 0;
    expectSplitCoversTheSolvedElements(builtin::cornellBox(), splits, &triangles);
    expectSplitCoversTheSolvedElements(triangulated(builtin::cornellBox()), splits, &triangles);
    EXPECT_GT(triangles, 150u);
  }
}

TEST(GatherMesh, NoSplitsIsTheSolvedSetItself) {
  const Scene scene = builtin::furnace();
  const SurfaceSet solved = discretise(scene, {});
  const GatherMesh mesh(scene, solved, 0);
  EXPECT_EQ(&mesh.surfaces(), &solved);
  EXPECT_EQ(mesh.parent(17), 17u);
}

// The furnace, rho 0.5 and Le 1, solved on 150 elements and gathered on about 2,400: every pixel
// is Le / (1 - rho) = 2, whatever the gather bounces (each further bounce gathers the one before
// at every vertex), and with the gather's far hits reading the solution's direct light.
TEST(GatherMesh, TheFurnaceGatheredOnASplitMeshRendersAtItsClosedForm) {
  const Scene scene = builtin::furnace(0.5f, 1.0f);
  DiscretiseOptions d;
  d.elementBudget = 150;
  d.orientByLight = false;
  SurfaceSet surfaces = discretise(scene, d);
  SolveOptions o;
  o.method = "progressive";
  o.settings.set("unshot", 1e-6);
  const Solution solution = solve(scene, surfaces, o);
  for (int bounces : {1, 2, 3, 4}) {
    RenderOptions ro;
    ro.camera = scene.cameras[0];
    ro.width = ro.height = 24;
    ro.samplesPerPixel = 4;
    ro.indirect = RenderOptions::Indirect::VertexGather;
    ro.gatherElements = 16 * surfaces.elements.size();
    ro.gatherBounces = bounces;
    const Image image = render(scene, surfaces, solution, ro);
    for (const Rgb& p : image.pixels) ASSERT_NEAR(p.g, 2.0f, 4e-3f) << bounces << " bounces";
  }
}

}  // namespace
}  // namespace luxel
