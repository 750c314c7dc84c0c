// The vertex gather's own mesh (render/gather_mesh.h): the solved elements split into four, as
// often as asked. The split must cover exactly what was solved, carry the solution's fields over
// unchanged as functions of position, and leave the closed forms of the furnace where they were.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "luxel/render.h"
#include "luxel/solve.h"
#include "render/corner_values.h"
#include "render/direct_light.h"
#include "render/final_gather.h"
#include "render/gather_mesh.h"
#include "scene/builtin/builtin_scenes.h"
#include "trace/element_polygons.h"

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

// Elements larger than maxArea are split until they are not, the rest kept whole: the Cornell box
// solved with its faces whole (a wall of 0.3 m^2 one element), the largest split into pieces
// under a fortieth of a square metre, the small ones (the light, the blocks' sides) whole.
TEST(GatherMesh, ElementsLargerThanAskedAreSplitUntilTheyAreNot) {
  const Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 1;  // every face one element
  const SurfaceSet solved = discretise(scene, d);
  const float maxArea = 0.025f;
  size_t large = 0;
  for (const Element& e : solved.elements) large += e.area > maxArea;
  ASSERT_GT(large, 4u);
  ASSERT_LT(large, solved.elements.size());
  const GatherMesh mesh(scene, solved, 0, maxArea);
  ASSERT_TRUE(mesh.isSplit());
  const SurfaceSet& split = mesh.surfaces();
  std::vector<double> areaOf(solved.elements.size(), 0.0);
  std::vector<int> pieces(solved.elements.size(), 0);
  for (uint32_t e = 0; e < split.elements.size(); ++e) {
    EXPECT_LE(split.elements[e].area, maxArea * 1.0001f) << "element " << e;
    areaOf[mesh.parent(e)] += split.elements[e].area;
    ++pieces[mesh.parent(e)];
  }
  for (uint32_t p = 0; p < solved.elements.size(); ++p) {
    EXPECT_NEAR(areaOf[p], solved.elements[p].area, 1e-5 * solved.elements[p].area) << "element " << p;
    const bool wasLarge = solved.elements[p].area > maxArea;
    EXPECT_EQ(pieces[p] > 1, wasLarge) << "element " << p;
    // Each split takes a quarter: the fewest that bring it under maxArea.
    if (wasLarge) EXPECT_GT(solved.elements[p].area / float(pieces[p]) * 4.0f, maxArea) << "element " << p;
  }
  for (uint32_t e = 0; e < split.elements.size(); ++e)
    EXPECT_EQ(mesh.whole(e), pieces[mesh.parent(e)] == 1) << "element " << e;
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

// The Cornell box solved on 300 elements (progressive, its defaults), with the solution's
// indirect irradiance per element.
struct SolvedBox {
  SolvedBox() : scene(builtin::cornellBox()) {
    DiscretiseOptions d;
    d.elementBudget = 300;
    surfaces = discretise(scene, d);
    const Solution solution = solve(scene, surfaces, SolveOptions{});
    indirect.resize(solution.irradiance.size());
    for (size_t e = 0; e < indirect.size(); ++e)
      indirect[e] = glm::max(solution.irradiance[e] - solution.directIrradiance[e], Rgb(0.0f));
  }
  Scene scene;
  SurfaceSet surfaces;
  std::vector<Rgb> indirect;
};

// The vertex gather on a split mesh (VertexGather's `refined`): the solved elements' corners are
// gathered, and so is every vertex that one of its solved corners saw a surface near (creases,
// the blocks); the rest are the solved corners' values interpolated as a hit interpolates them.
// Against gathering every vertex with the same rays and seed: the gathered vertices are the same
// numbers, and the interpolated ones differ by the field's curvature over a solved element and the
// full gather's noise (measured: 5.7% rms a vertex, means 0.6% apart over the box).
TEST(GatherMesh, OnASplitMeshOnlyVerticesNearSurfacesAreGatheredBesideTheSolvedCorners) {
  const SolvedBox box;
  const Scene& scene = box.scene;
  const SurfaceSet& surfaces = box.surfaces;
  const std::vector<Rgb>& indirect = box.indirect;
  const GatherMesh mesh(scene, surfaces, 2);
  const SurfaceSet& shown = mesh.surfaces();
  const std::vector<Polygon> polygons = elementPolygonsTwinsApart(shown);
  const RayTracer tracer(polygons);
  const DirectLight direct(scene, surfaces, &shown);
  const std::vector<Rgb> corners = mesh.corners(elementCornerValues(surfaces, indirect));
  const FinalGather gather(shown, tracer, direct, corners);
  VertexGather adaptive(shown, gather, 256, 5, {}, &mesh);
  VertexGather full(shown, gather, 256, 5);
  const std::vector<Rgb> a = adaptive.all(), f = full.all();
  ASSERT_EQ(full.verticesTraced(), full.vertexCount());

  // The solved corners' values, from the split elements that have them (outside solids: a slot of
  // an element with a corner inside one is replaced by the mean of its others).
  const auto outside = [&](uint32_t e) {
    for (int c = 0; c < shown.elements[e].polygon.count; ++c)
      if (adaptive.cornerInside(e, c)) return false;
    return true;
  };
  std::map<std::pair<uint32_t, int>, Rgb> solvedCorner;
  for (uint32_t e = 0; e < shown.elements.size(); ++e)
    for (int c = 0; c < shown.elements[e].polygon.count; ++c) {
      const Vec2 st = mesh.local(e, c);
      const auto w = cornerWeights(surfaces.elements[mesh.parent(e)].polygon.count, st.x, st.y);
      const auto k = std::find(w.begin(), w.end(), 1.0f);
      if (k == w.end()) continue;
      EXPECT_TRUE(adaptive.cornerTraced(e, c)) << "element " << e << " corner " << c << " is a solved corner";
      if (outside(e)) solvedCorner[{mesh.parent(e), int(k - w.begin())}] = a[size_t(e) * 4 + size_t(c)];
    }

  size_t checked = 0, creaseCorners = 0;
  double adaptiveSum = 0.0, fullSum = 0.0;
  for (uint32_t e = 0; e < shown.elements.size(); ++e) {
    const Element& el = shown.elements[e];
    for (int c = 0; c < el.polygon.count; ++c) {
      const size_t slot = size_t(e) * 4 + size_t(c);
      // The floor's edge along the right wall (x = 0) is a crease: its vertices see the wall at once.
      if (el.normal.y > 0.99f && std::abs(el.polygon.v[size_t(c)].x) < 1e-6f) {
        ++creaseCorners;
        EXPECT_TRUE(adaptive.cornerTraced(e, c)) << "element " << e << " corner " << c << " on the floor's crease";
      }
      if (!outside(e)) continue;
      if (adaptive.cornerTraced(e, c)) {
        ASSERT_EQ(a[slot], f[slot]) << "element " << e << " corner " << c;
        continue;
      }
      const Vec2 st = mesh.local(e, c);
      const uint32_t parent = mesh.parent(e);
      const auto w = cornerWeights(surfaces.elements[parent].polygon.count, st.x, st.y);
      Rgb expected(0.0f);
      bool known = true;
      for (int k = 0; k < 4; ++k) {
        if (w[size_t(k)] <= 0.0f) continue;
        const auto it = solvedCorner.find({parent, k});
        if (it == solvedCorner.end()) known = false;
        else expected += w[size_t(k)] * it->second;
      }
      if (!known) continue;
      ++checked;
      ASSERT_NEAR(a[slot].g, expected.g, 1e-5f * std::max(1.0f, expected.g)) << "element " << e << " corner " << c;
      adaptiveSum += a[slot].g, fullSum += f[slot].g;
    }
  }
  EXPECT_GT(creaseCorners, 10u);
  EXPECT_GT(checked, shown.elements.size());  // measured: 1,792 of 3,795 vertices interpolated
  EXPECT_GT(adaptive.verticesTraced(), solvedCorner.size());
  EXPECT_NEAR(adaptiveSum / fullSum, 1.0, 0.01);
}

// A gather reading a coarse gather as it goes (FinalGather over a VertexGather) reads the same
// numbers as one reading that coarse gather done first: each vertex's gather is the same
// whenever it runs.
TEST(GatherMesh, ACoarseGatherReadAsItGoesIsTheOneGatheredFirst) {
  const SolvedBox box;
  const Scene& scene = box.scene;
  const SurfaceSet& surfaces = box.surfaces;
  const std::vector<Rgb>& indirect = box.indirect;
  const std::vector<Polygon> polygons = elementPolygonsTwinsApart(surfaces);
  const RayTracer tracer(polygons);
  const DirectLight direct(scene, surfaces, &surfaces);
  const std::vector<Rgb> corners = elementCornerValues(surfaces, indirect);
  const FinalGather fromSolution(surfaces, tracer, direct, corners, /*gatherNearHits=*/false);
  VertexGather first(surfaces, fromSolution, 16, 9);
  const std::vector<Rgb> coarse = first.all();
  const FinalGather fromCoarse(surfaces, tracer, direct, coarse, /*gatherNearHits=*/false);
  VertexGather asItGoes(surfaces, fromSolution, 16, 9);
  const FinalGather fromLazy(surfaces, tracer, direct, asItGoes);
  VertexGather a(surfaces, fromCoarse, 64, 4), b(surfaces, fromLazy, 64, 4);
  // Nothing is gathered below until a hit above needs it, and one element's corners need only the
  // vertices their rays met (in this box a full gather above meets every vertex).
  EXPECT_EQ(asItGoes.verticesGathered(), 0u);
  b.corners(0);
  EXPECT_GT(asItGoes.verticesGathered(), 0u);
  EXPECT_LT(asItGoes.verticesGathered(), asItGoes.vertexCount() / 2);
  const std::vector<Rgb> fromFirst = a.all(), fromAsItGoes = b.all();
  ASSERT_EQ(fromFirst.size(), fromAsItGoes.size());
  for (size_t i = 0; i < fromFirst.size(); ++i) ASSERT_EQ(fromFirst[i], fromAsItGoes[i]) << "slot " << i;
  EXPECT_GT(asItGoes.verticesGathered(), asItGoes.vertexCount() / 2);
}

}  // namespace
}  // namespace luxel
