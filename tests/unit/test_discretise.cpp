// Discretisation (src/mesh/discretise.cpp, src/mesh/orient_faces.cpp): elements tile their faces,
// budgets and sizes are honoured, patches partition the elements, non-planar quads are split,
// two-sided materials get twin faces, absurd options throw, and faces wound the wrong way round
// are repaired by the light they receive, but not turned round by the rounding residue of an
// emitter in their own plane.
//
// Scene values used:
// - builtin::cornellBox(): the measured Cornell box in metres (about 0.55 m a side), light
//   radiance (17, 12, 4) in the ceiling hole facing -y; mesh 0 is the floor (normal +y), mesh 3
//   the back wall at z = 0.5592 (normal -z, into the box).
// - Hand-made quads: a unit square in z = 0, a 2 x 1 parallelogram with a 0.5 shear, a non-planar
//   quad whose 4th corner is lifted 0.2 off the plane.
// - A closed 2 m box of reflectance 0.5 whose ceiling (y = 2) is a 20 x 20 grid of 0.1 m quad
//   faces with the central 4 x 4 cells left out, and an emitter (Le = 100, facing down) filling
//   that hole in the ceiling's plane: one quad, or 4 x 4 cells.
// - A closed 4 x 2 x 2 box of reflectance 0.5 with a 1 x 1 emitting panel (Le = 10) at x = 0.5
//   facing +x, and a 1.6 x 1.6 panel at x = 2 (reflectance 0.5) between the emitter and the far
//   wall.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/solve.h"
#include "luxel/surface.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/builtin/seed_geometry.h"

namespace luxel {
namespace {

Polygon facePolygon(const SurfaceFace& f) { return Polygon{f.corners, f.triangle ? 3 : 4}; }

// One mesh of one material (reflectance 0.5) holding the given quads.
Scene quadScene(const std::vector<std::array<Vec3, 4>>& quads, bool twoSided = false) {
  Scene s;
  s.name = "quads";
  s.materials.push_back(Material{.name = "grey", .reflectance = Rgb(0.5f), .twoSided = twoSided});
  Mesh m;
  m.name = "quads";
  for (const auto& q : quads) builtin::addQuad(m, q[0], q[1], q[2], q[3]);
  s.meshes.push_back(m);
  return s;
}

TEST(Discretise, ElementAreasOfEachFaceSumToTheFaceArea) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions o;
  o.elementBudget = 2000;
  SurfaceSet set = discretise(scene, o);
  // The measured left (red) wall is not planar: its 4th corner is 3.2 mm off the plane of the
  // other three, so it is cut into two triangles. Every other Cornell quad is planar.
  EXPECT_EQ(set.splitQuads, 1u);
  ASSERT_EQ(set.faces.size(), scene.faceCount() + set.splitQuads);
  std::vector<double> sums(set.faces.size(), 0.0);
  for (const Element& e : set.elements) sums[e.face] += e.area;
  double total = 0.0;
  for (size_t f = 0; f < set.faces.size(); ++f) {
    const double area = facePolygon(set.faces[f]).area();
    total += area;
    EXPECT_NEAR(sums[f], area, 1e-4 * area) << "face " << f;
  }
  EXPECT_NEAR(set.totalArea(), total, 1e-4 * total);
}

TEST(Discretise, ElementBudgetIsRoughlyHonoured) {
  Scene scene = builtin::cornellBox();
  for (size_t n : {size_t(1000), size_t(10000)}) {
    DiscretiseOptions o;
    o.elementBudget = n;
    SurfaceSet set = discretise(scene, o);
    EXPECT_GE(set.elements.size(), size_t(0.7 * double(n))) << "budget " << n;
    EXPECT_LE(set.elements.size(), size_t(1.5 * double(n))) << "budget " << n;
  }
}

TEST(Discretise, ElementSizeBoundsEveryEdge) {
  Scene scene = builtin::cornellBox();
  for (float size : {0.05f, 0.021f}) {
    DiscretiseOptions o;
    o.elementSize = size;
    SurfaceSet set = discretise(scene, o);
    EXPECT_FLOAT_EQ(set.elementSize, size);
    float longest = 0.0f;
    for (const Element& e : set.elements)
      for (int i = 0; i < e.polygon.count; ++i)
        longest = std::max(longest, glm::length(e.polygon.v[(i + 1) % e.polygon.count] - e.polygon.v[i]));
    EXPECT_LE(longest, 1.01f * size) << "size " << size;
    EXPECT_GT(longest, 0.5f * size) << "size " << size;  // and not absurdly finer
  }
}

TEST(Discretise, PatchesPartitionTheElements) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions o;
  o.elementBudget = 3000;
  SurfaceSet set = discretise(scene, o);
  ASSERT_FALSE(set.patches.empty());
  std::vector<int> seen(set.elements.size(), 0);
  for (uint32_t p = 0; p < set.patches.size(); ++p) {
    const Patch& patch = set.patches[p];
    ASSERT_FALSE(patch.elements.empty()) << "patch " << p;
    double area = 0.0;
    for (uint32_t e : patch.elements) {
      ASSERT_LT(e, set.elements.size());
      ++seen[e];
      EXPECT_EQ(set.elements[e].patch, p) << "element " << e;
      EXPECT_EQ(set.elements[e].face, patch.face) << "element " << e;
      area += set.elements[e].area;
    }
    EXPECT_NEAR(area, patch.area, 1e-4 * patch.area) << "patch " << p;
  }
  for (size_t e = 0; e < seen.size(); ++e) ASSERT_EQ(seen[e], 1) << "element " << e;
}

TEST(Discretise, NonPlanarQuadIsSplitIntoTwoTriangles) {
  // Unit square in z = 0 with its 4th corner lifted to z = 0.2.
  Scene bent = quadScene({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0.2f)}});
  DiscretiseOptions o;
  o.elementBudget = 50;
  SurfaceSet set = discretise(bent, o);
  EXPECT_EQ(set.splitQuads, 1u);
  ASSERT_EQ(set.faces.size(), 2u);
  for (const SurfaceFace& f : set.faces) EXPECT_TRUE(f.triangle);
  // Triangles (0,1,2) and (0,2,3): areas 1/2 and |(1,1,0) x (0,1,0.2)| / 2 = |(0.2,-0.2,1)| / 2
  // = sqrt(1.08) / 2.
  EXPECT_NEAR(set.totalArea(), 0.5 + std::sqrt(1.08) / 2.0, 1e-5);
  for (const Element& e : set.elements) {  // every element is planar: it lies in its face's plane
    const SurfaceFace& f = set.faces[e.face];
    for (int i = 0; i < e.polygon.count; ++i)
      EXPECT_NEAR(glm::dot(e.polygon.v[i] - f.corners[0], f.normal), 0.0f, 1e-5f);
  }

  Scene flat = quadScene({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}});
  SurfaceSet flatSet = discretise(flat, o);
  EXPECT_EQ(flatSet.splitQuads, 0u);
  ASSERT_EQ(flatSet.faces.size(), 1u);
  EXPECT_FALSE(flatSet.faces[0].triangle);
  EXPECT_NEAR(flatSet.totalArea(), 1.0, 1e-5);
}

TEST(Discretise, TwoSidedMaterialsGetCrossLinkedTwinFaces) {
  Scene one = builtin::cornellBox();
  Scene two = one;
  for (Material& m : two.materials) m.twoSided = true;
  DiscretiseOptions o;
  o.elementBudget = 1000;
  SurfaceSet a = discretise(one, o), b = discretise(two, o);
  for (const SurfaceFace& f : a.faces) EXPECT_EQ(f.twin, -1);
  ASSERT_EQ(b.faces.size(), 2 * a.faces.size());
  for (size_t i = 0; i < b.faces.size(); ++i) {
    const SurfaceFace& f = b.faces[i];
    ASSERT_GE(f.twin, 0) << "face " << i;
    ASSERT_LT(size_t(f.twin), b.faces.size());
    const SurfaceFace& t = b.faces[size_t(f.twin)];
    EXPECT_EQ(t.twin, int32_t(i)) << "face " << i;
    EXPECT_NEAR(glm::dot(f.normal, t.normal), -1.0f, 1e-5f) << "face " << i;
    // The twin covers the same polygon, wound the other way.
    EXPECT_NEAR(facePolygon(f).area(), facePolygon(t).area(), 1e-6f);
    EXPECT_NEAR(glm::length(facePolygon(f).centroid() - facePolygon(t).centroid()), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(facePolygon(t).normal(), t.normal), 1.0f, 1e-5f);  // the winding agrees
  }
  EXPECT_NEAR(b.totalArea(), 2.0f * a.totalArea(), 1e-4f * a.totalArea());
}

TEST(Discretise, SplitElementQuartersAParallelogram) {
  // Parallelogram a, a + u, a + u + v, a + v with u = (2, 0, 0), v = (0.5, 1, 0): area 2.
  Scene scene = quadScene({{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2.5f, 1, 0), Vec3(0.5f, 1, 0)}});
  DiscretiseOptions o;
  o.elementBudget = 8;
  o.elementsPerPatchSide = 2;
  SurfaceSet set = discretise(scene, o);
  ASSERT_GE(set.elements.size(), 2u);
  const double before = set.totalArea();
  EXPECT_NEAR(before, 2.0, 1e-5);
  const size_t n = set.elements.size();
  const uint32_t target = 1;
  const Element parent = set.elements[target];
  set.splitElement(target, scene);
  ASSERT_EQ(set.elements.size(), n + 3);
  EXPECT_NEAR(set.totalArea(), before, 1e-5 * before);
  const std::vector<uint32_t> children = {target, uint32_t(n), uint32_t(n + 1), uint32_t(n + 2)};
  Vec3 centroid(0.0f);
  for (uint32_t c : children) {
    const Element& e = set.elements[c];
    EXPECT_NEAR(e.area, parent.area / 4.0f, 1e-5f * parent.area) << "child " << c;
    EXPECT_EQ(e.patch, parent.patch);
    EXPECT_EQ(e.face, parent.face);
    EXPECT_EQ(e.depth, parent.depth + 1);
    centroid += e.centroid / 4.0f;
    const auto& list = set.patches[parent.patch].elements;
    EXPECT_EQ(std::count(list.begin(), list.end(), c), 1) << "child " << c;
  }
  EXPECT_NEAR(glm::length(centroid - parent.centroid), 0.0f, 1e-5f);  // the children tile the parent
  // Still a partition.
  std::vector<int> seen(set.elements.size(), 0);
  for (const Patch& p : set.patches)
    for (uint32_t e : p.elements) ++seen[e];
  for (size_t e = 0; e < seen.size(); ++e) EXPECT_EQ(seen[e], 1) << "element " << e;
}

TEST(Discretise, SplitElementQuartersATriangle) {
  // The bent quad of NonPlanarQuadIsSplitIntoTwoTriangles: its elements are triangles, which
  // split at their edge midpoints into four congruent quarters.
  Scene scene = quadScene({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0.2f)}});
  DiscretiseOptions o;
  o.elementBudget = 20;
  SurfaceSet set = discretise(scene, o);
  const double before = set.totalArea();
  const size_t n = set.elements.size();
  const Element parent = set.elements[0];
  ASSERT_EQ(parent.polygon.count, 3);
  set.splitElement(0, scene);
  ASSERT_EQ(set.elements.size(), n + 3);
  EXPECT_NEAR(set.totalArea(), before, 1e-5 * before);
  for (uint32_t c : {uint32_t(0), uint32_t(n), uint32_t(n + 1), uint32_t(n + 2)}) {
    EXPECT_EQ(set.elements[c].polygon.count, 3);
    EXPECT_NEAR(set.elements[c].area, parent.area / 4.0f, 1e-5f * parent.area) << "child " << c;
    EXPECT_EQ(set.elements[c].patch, parent.patch);
  }
}

TEST(Discretise, AbsurdOptionsThrow) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions o;
  o.elementSize = -0.1f;
  EXPECT_THROW(discretise(scene, o), Error);
  o = DiscretiseOptions{};
  o.elementSize = std::nanf("");
  EXPECT_THROW(discretise(scene, o), Error);
  o = DiscretiseOptions{};
  o.elementBudget = 0;
  EXPECT_THROW(discretise(scene, o), Error);
  o.elementBudget = size_t(1e12);
  EXPECT_THROW(discretise(scene, o), Error);
  o = DiscretiseOptions{};
  o.elementSize = 1e-6f;  // about 10^12 elements
  EXPECT_THROW(discretise(scene, o), Error);
}

TEST(Discretise, SceneWithOnlyZeroAreaFacesThrows) {
  // A quad whose corners are collinear, and one whose corners coincide.
  Scene scene = quadScene({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)},
                           {Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}});
  EXPECT_THROW(discretise(scene, DiscretiseOptions{}), Error);
}

// A quad 10^30 across: its area overflows float to infinity, so no face passes as having one. The
// cause is the coordinates, past the 10^9 limit Scene::validate names; saying "no face has a
// positive area" sent users looking for degenerate faces.
TEST(Discretise, CoordinatesPastTheLimitAreNamedRatherThanTheAreasTheyOverflow) {
  const float big = 1e30f;
  Scene scene = quadScene({{Vec3(0, 0, 0), Vec3(big, 0, 0), Vec3(big, big, 0), Vec3(0, big, 0)}});
  std::string message;
  try {
    discretise(scene, DiscretiseOptions{});
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("mesh 'quads': vertex 1 at (1e+30, 0, 0) is beyond 1e+09 scene units"), std::string::npos)
      << message;
}

// The Cornell box with the back wall (mesh 3) and the floor (mesh 0) wound the wrong way round:
// face vertices 1 and 3 swapped.
Scene cornellWithTwoWallsReversed() {
  Scene scene = builtin::cornellBox();
  for (size_t m : {size_t(0), size_t(3)})
    for (Face& f : scene.meshes[m].faces) std::swap(f.v[1], f.v[3]);
  return scene;
}

TEST(Orientation, FacesLitFromBehindAreTurnedRound) {
  Scene original = builtin::cornellBox();
  Scene reversed = cornellWithTwoWallsReversed();
  DiscretiseOptions o;
  o.elementBudget = 1000;
  SurfaceSet ref = discretise(original, o);
  EXPECT_EQ(ref.flippedFaces, 0u);  // the measured box is wound consistently

  SurfaceSet repaired = discretise(reversed, o);
  EXPECT_EQ(repaired.flippedFaces, 2u);
  ASSERT_EQ(repaired.faces.size(), ref.faces.size());
  for (size_t f = 0; f < ref.faces.size(); ++f) {
    const bool wasReversed = ref.faces[f].mesh == 0 || ref.faces[f].mesh == 3;
    EXPECT_EQ(repaired.faces[f].flipped, wasReversed) << "face " << f;
    EXPECT_NEAR(glm::dot(repaired.faces[f].normal, ref.faces[f].normal), 1.0f, 1e-5f) << "face " << f;
  }
  // Floor normal +y, back wall normal -z: into the box.
  for (const SurfaceFace& f : repaired.faces) {
    if (f.mesh == 0) {
      EXPECT_NEAR(f.normal.y, 1.0f, 1e-5f);
    }
    if (f.mesh == 3) {
      EXPECT_NEAR(f.normal.z, -1.0f, 1e-5f);
    }
  }

  o.orientByLight = false;
  SurfaceSet kept = discretise(reversed, o);
  EXPECT_EQ(kept.flippedFaces, 0u);
  for (const SurfaceFace& f : kept.faces) {
    if (f.mesh == 0) {
      EXPECT_NEAR(f.normal.y, -1.0f, 1e-5f);
    }
    if (f.mesh == 3) {
      EXPECT_NEAR(f.normal.z, 1.0f, 1e-5f);
    }
  }
}

TEST(Orientation, RepairedSceneSolvesLikeTheOriginal) {
  auto backWallMean = [](const Scene& scene) {
    DiscretiseOptions d;
    d.elementBudget = 1000;
    SurfaceSet set = discretise(scene, d);
    Solution sol = solve(scene, set, SolveOptions{});
    double sum = 0.0, area = 0.0;
    for (size_t e = 0; e < set.elements.size(); ++e) {
      if (set.faces[set.elements[e].face].mesh != 3) continue;
      const Rgb b = sol.radiosity[e];
      sum += set.elements[e].area * (b.r + b.g + b.b);
      area += set.elements[e].area;
    }
    EXPECT_GT(area, 0.0);
    return sum / area;
  };
  const double original = backWallMean(builtin::cornellBox());
  const double repaired = backWallMean(cornellWithTwoWallsReversed());
  ASSERT_GT(original, 0.0);
  EXPECT_NEAR(repaired, original, 0.02 * original);
}

// A closed 2 m box (reflectance 0.5), its corner at the origin, whose ceiling at y = 2 is k x k
// quad faces round a hole of the central fifth each way, filled by an emitter (Le = 100) in the
// same plane, facing down: one quad (`lampCells` false) or cells of the ceiling's grid.
// `floorReversed` winds the floor the wrong way round (facing down, out of the box).
Scene coplanarLampBox(int k, bool lampCells, bool floorReversed = false) {
  Scene s;
  s.name = "coplanar lamp box";
  s.materials = {Material{.name = "wall", .reflectance = Rgb(0.5f)},
                 Material{.name = "lamp", .reflectance = Rgb(0.5f), .emission = Rgb(100.0f)}};
  const float e = 2.0f;
  const Vec3 o(0.0f), X(e, 0, 0), Y(0, e, 0), Z(0, 0, e);
  Mesh walls;
  walls.name = "walls";
  // Floor (z cross x = +y; reversed x cross z = -y), back (+z), front (-z), left (+x), right (-x).
  if (floorReversed)
    builtin::addQuad(walls, o, X, X + Z, Z);
  else
    builtin::addQuad(walls, o, Z, Z + X, X);
  builtin::addQuad(walls, o, X, X + Y, Y);
  builtin::addQuad(walls, Z, Z + Y, Z + Y + X, Z + X);
  builtin::addQuad(walls, o, Y, Y + Z, Z);
  builtin::addQuad(walls, X, X + Z, X + Z + Y, X + Y);
  const int l0 = 2 * k / 5, l1 = 3 * k / 5;
  Mesh ceiling;
  ceiling.name = "ceiling";
  // Origin Y, u = x, v = z: x cross z = -y, facing down into the box.
  builtin::addCellGrid(ceiling, Y, X, Z, k, k,
                       [=](int i, int j) { return i >= l0 && i < l1 && j >= l0 && j < l1; });
  Mesh lamp;
  lamp.name = "lamp";
  lamp.material = 1;
  const float f0 = float(l0) / float(k), fl = float(l1 - l0) / float(k);
  const Vec3 corner = Y + f0 * X + f0 * Z;
  if (lampCells)
    builtin::addCellGrid(lamp, corner, fl * X, fl * Z, l1 - l0, l1 - l0);
  else
    builtin::addQuad(lamp, corner, corner + fl * X, corner + fl * X + fl * Z, corner + fl * Z);
  s.meshes = {walls, ceiling, lamp};
  return s;
}

// An emitter in a receiver's plane is seen edge-on from both of the receiver's sides: the front
// gets an exact 0 and rounding can leave the back a tiny positive value. That must not turn the
// ceiling's faces round (it turned 2 of them with the one-quad lamp, 12 with the cells).
TEST(Orientation, CeilingCoplanarWithItsLampIsNotTurnedRound) {
  for (bool lampCells : {false, true}) {
    SCOPED_TRACE(lampCells ? "lamp of cells" : "lamp of one quad");
    const Scene scene = coplanarLampBox(20, lampCells);
    SurfaceSet set = discretise(scene, DiscretiseOptions{});
    EXPECT_EQ(set.flippedFaces, 0u);
    for (const SurfaceFace& f : set.faces)
      if (f.mesh == 1) EXPECT_NEAR(f.normal.y, -1.0f, 1e-5f);
  }
  // The absolute threshold still lets a face wound the wrong way round (the floor) be repaired.
  SurfaceSet set =
      discretise(coplanarLampBox(20, false, /*floorReversed=*/true), DiscretiseOptions{});
  EXPECT_EQ(set.flippedFaces, 1u);
  EXPECT_TRUE(set.faces[0].flipped);
  EXPECT_NEAR(set.faces[0].normal.y, 1.0f, 1e-5f);
}

// A closed 4 x 2 x 2 box (reflectance 0.5) with an emitting 1 x 1 panel at x = 0.5 facing +x,
// and a 1.6 x 1.6 panel at x = 2 spanning y, z in [0.2, 1.8]. `panelFacesLight`: the panel's
// winding faces -x (towards the emitter) or +x (away from it).
Scene panelBox(bool twoSided, bool panelFacesLight) {
  Scene s;
  s.name = "panel box";
  s.materials = {Material{.name = "wall", .reflectance = Rgb(0.5f)},
                 Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(10.0f)},
                 Material{.name = "panel", .reflectance = Rgb(0.5f), .twoSided = twoSided}};
  Mesh box;
  box.name = "box";
  builtin::addInwardBox(box, Vec3(0.0f), Vec3(4.0f, 2.0f, 2.0f));
  Mesh lamp;
  lamp.name = "lamp";
  lamp.material = 1;
  // Normal (b - a) x (d - a) with a = (0.5,0.5,0.5): (0,1,0) x (0,0,1) = +x.
  builtin::addQuad(lamp, Vec3(0.5f, 0.5f, 0.5f), Vec3(0.5f, 1.5f, 0.5f), Vec3(0.5f, 1.5f, 1.5f),
                   Vec3(0.5f, 0.5f, 1.5f));
  Mesh panel;
  panel.name = "panel";
  panel.material = 2;
  const Vec3 a(2, 0.2f, 0.2f), b(2, 1.8f, 0.2f), c(2, 1.8f, 1.8f), d(2, 0.2f, 1.8f);
  if (panelFacesLight)
    builtin::addQuad(panel, a, d, c, b);  // (0,0,1) x (0,1,0) = -x
  else
    builtin::addQuad(panel, a, b, c, d);  // +x
  s.meshes = {box, lamp, panel};
  return s;
}

struct PanelSides {
  double towardsLight = 0.0, away = 0.0;  // area-weighted mean irradiance (green channel)
  size_t flipped = 0;
  int facesTowards = 0, facesAway = 0;
};

PanelSides solvePanelBox(const Scene& scene) {
  DiscretiseOptions d;
  d.elementBudget = 3000;
  SurfaceSet set = discretise(scene, d);
  Solution sol = solve(scene, set, SolveOptions{});
  PanelSides r;
  r.flipped = set.flippedFaces;
  for (const SurfaceFace& f : set.faces)
    if (f.mesh == 2) (f.normal.x < 0.0f ? r.facesTowards : r.facesAway)++;
  double areaT = 0.0, areaA = 0.0;
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const Element& el = set.elements[e];
    const SurfaceFace& f = set.faces[el.face];
    if (f.mesh != 2) continue;
    if (f.normal.x < -0.99f) {
      r.towardsLight += el.area * sol.irradiance[e].g;
      areaT += el.area;
    } else if (f.normal.x > 0.99f) {
      r.away += el.area * sol.irradiance[e].g;
      areaA += el.area;
    } else {
      ADD_FAILURE() << "panel element with normal (" << f.normal.x << ", " << f.normal.y << ", " << f.normal.z << ")";
    }
  }
  if (areaT > 0.0) r.towardsLight /= areaT;
  if (areaA > 0.0) r.away /= areaA;
  return r;
}

TEST(TwoSided, LightDoesNotLeakThroughATwoSidedPanel) {
  PanelSides s = solvePanelBox(panelBox(/*twoSided=*/true, /*panelFacesLight=*/true));
  EXPECT_EQ(s.flipped, 0u);
  EXPECT_EQ(s.facesTowards, 1);
  EXPECT_EQ(s.facesAway, 1);
  ASSERT_GT(s.towardsLight, 0.0);
  // The lit side sees the emitter directly (form factor of a 1 x 1 square at 1.5 m, about 0.1,
  // times pi * 10); the back only gets light that went round the panel via the walls. (Measured
  // at the time of writing: front 4.05, back 0.24 W/m^2.) Light leaking through the panel would
  // give the back about what the front gets.
  EXPECT_GT(s.away, 0.0);
  EXPECT_LT(s.away, 0.3 * s.towardsLight) << "front " << s.towardsLight << " back " << s.away;
  // Winding the two-sided panel the other way round changes nothing: both sides take part.
  PanelSides r = solvePanelBox(panelBox(true, false));
  EXPECT_EQ(r.flipped, 0u);
  EXPECT_NEAR(r.towardsLight, s.towardsLight, 0.02 * s.towardsLight);
  EXPECT_NEAR(r.away, s.away, 0.05 * s.away + 1e-3 * s.towardsLight);
}

TEST(TwoSided, BackwardsOneSidedPanelIsRepaired) {
  PanelSides good = solvePanelBox(panelBox(/*twoSided=*/false, /*panelFacesLight=*/true));
  EXPECT_EQ(good.flipped, 0u);
  EXPECT_EQ(good.facesTowards, 1);
  EXPECT_EQ(good.facesAway, 0);
  PanelSides bad = solvePanelBox(panelBox(false, false));
  EXPECT_EQ(bad.flipped, 1u);
  EXPECT_EQ(bad.facesTowards, 1);
  EXPECT_EQ(bad.facesAway, 0);
  ASSERT_GT(good.towardsLight, 0.0);
  EXPECT_NEAR(bad.towardsLight, good.towardsLight, 0.02 * good.towardsLight);
}

}  // namespace
}  // namespace luxel
