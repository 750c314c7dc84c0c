// Coincident faces (scene/coincident_faces.h): copies of a face in the same place and facing the
// same way are removed at load, and a solve that meets them anyway stops with an error instead of
// multiplying the light for ever (session/solver_host.cpp, checkHealth).
//
// Facts used: the furnace (builtin::furnace) is a closed unit cube of 6 quads, one material; with
// every wall doubled, each copy receives all the light the other reflects, so the effective
// reflectance is twice the real one, and with rho 0.7 it is 1.4: the light grows at every bounce.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/session.h"
#include "scene/builtin/builtin_scenes.h"
#include "scene/coincident_faces.h"
#include "solve/step_control.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

Scene doubled(Scene scene) {
  const size_t n = scene.meshes.size();
  for (size_t m = 0; m < n; ++m) scene.meshes.push_back(scene.meshes[m]);
  return scene;
}

Mesh quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t material, const std::string& name) {
  Mesh m;
  m.name = name;
  m.positions = {a, b, c, d};
  m.faces = {Face{{0, 1, 2, 3}}};
  m.material = material;
  return m;
}

TEST(CoincidentFaces, ADoubledSceneLosesExactlyItsCopies) {
  Scene scene = doubled(builtin::furnace(0.5f, 1.0f));
  ASSERT_EQ(scene.faceCount(), 12u);
  EXPECT_EQ(removeCoincidentFaces(scene), 6u);
  EXPECT_EQ(scene.faceCount(), 6u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("removed 6 faces"), std::string::npos) << scene.warnings[0];
  // Nothing left to remove: the survivors are all distinct.
  EXPECT_EQ(removeCoincidentFaces(scene), 0u);
  scene.validate();
}

TEST(CoincidentFaces, AnUndoubledSceneIsLeftAlone) {
  Scene scene = builtinScene("cornell");
  const size_t faces = scene.faceCount();
  EXPECT_EQ(removeCoincidentFaces(scene), 0u);
  EXPECT_EQ(scene.faceCount(), faces);
  EXPECT_TRUE(scene.warnings.empty());
}

// A scene of one white unit square, a b c d, in the plane z = 0 (its first mesh, `first`).
const Vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
Scene wall(const std::string& first) {
  Scene scene;
  scene.name = "wall";
  scene.materials.push_back(Material{.name = "white"});
  scene.meshes.push_back(quad(a, b, c, d, 0, first));
  return scene;
}

TEST(CoincidentFaces, OppositeFacingPairsAndNearbyFacesStay) {
  Scene scene = wall("front");
  scene.meshes.push_back(quad(a, d, c, b, 0, "back"));  // the other side of a thin wall
  const Vec3 off(0, 0, 1e-3f);  // a millimetre in front: a separate face (1e-3 of the extent)
  scene.meshes.push_back(quad(a + off, b + off, c + off, d + off, 0, "offset"));
  EXPECT_EQ(removeCoincidentFaces(scene), 0u);
  EXPECT_EQ(scene.faceCount(), 3u);
}

TEST(CoincidentFaces, NearlyCoincidentCopiesInAnyStartingCornerGo) {
  Scene scene = wall("first");
  const Vec3 e(2e-7f, -1e-7f, 1e-7f);  // float rounding of a copy placed by another transform
  scene.meshes.push_back(quad(c + e, d + e, a + e, b + e, 0, "copy"));  // same winding, other first corner
  EXPECT_EQ(removeCoincidentFaces(scene), 1u);
  ASSERT_EQ(scene.meshes.size(), 1u);  // the emptied mesh goes
  EXPECT_EQ(scene.meshes[0].name, "first");
}

TEST(CoincidentFaces, TheEmittingCopyStays) {
  Scene scene;
  scene.name = "lamp";
  scene.materials.push_back(Material{.name = "ceiling"});
  scene.materials.push_back(Material{.name = "light", .reflectance = Rgb(0.0f), .emission = Rgb(10.0f)});
  const Vec3 p0(0, 1, 0), p1(0, 1, 1), p2(1, 1, 1), p3(1, 1, 0);
  scene.meshes.push_back(quad(p0, p1, p2, p3, 0, "ceiling"));
  scene.meshes.push_back(quad(p1, p2, p3, p0, 1, "light"));
  EXPECT_EQ(removeCoincidentFaces(scene), 1u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].name, "light");
  EXPECT_TRUE(scene.hasLight());
}

TEST(CoincidentFaces, DynamicObjectsAreLeftAlone) {
  Scene scene = doubled(builtin::furnace(0.5f, 1.0f));
  scene.objects.push_back(Object{.name = "mover", .dynamic = true});
  for (size_t m = scene.meshes.size() / 2; m < scene.meshes.size(); ++m) scene.meshes[m].object = 0;
  EXPECT_EQ(removeCoincidentFaces(scene), 0u);
}

// The importers remove them: an OBJ room with 100 copies of one triangle, and a scene file that
// lists one mesh file twice.
TEST(CoincidentFaces, TheLoadersRemoveThem) {
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "coincident";
  fs::create_directories(dir);
  {
    std::ofstream obj(dir / "tri.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    for (int i = 0; i < 100; ++i) obj << "f 1 2 3\n";
    obj << "f 1 3 2\nf 1 2 4\n";  // the back of the triangle, and another triangle: both stay
  }
  const Scene obj = importMeshFile(dir / "tri.obj");
  EXPECT_EQ(obj.faceCount(), 3u);
  std::ofstream(dir / "twice.json") << R"({"meshes": [{"file": "tri.obj"}, {"file": "tri.obj"}]})";
  const Scene twice = loadSceneFile(dir / "twice.json");
  EXPECT_EQ(twice.faceCount(), 3u);
  bool warned = false;
  for (const std::string& w : twice.warnings) warned = warned || w.find("removed 3 faces") != std::string::npos;
  EXPECT_TRUE(warned);
  // Moved by a transform, the second copy is a separate object and stays.
  std::ofstream(dir / "beside.json")
      << R"({"meshes": [{"file": "tri.obj"}, {"file": "tri.obj", "translate": [2, 0, 0]}]})";
  EXPECT_EQ(loadSceneFile(dir / "beside.json").faceCount(), 6u);
}

// A scene built in code (no loader to clean it) whose light grows at every bounce: each solver
// stops with an error naming the likely causes, instead of looping or writing garbage.
class DivergingSolve : public ::testing::TestWithParam<const char*> {};

TEST_P(DivergingSolve, StopsWithAnErrorNamingTheCause) {
  Scene scene = builtin::furnace(0.7f, 1.0f);
  scene = doubled(scene);
  DiscretiseOptions d;
  d.elementBudget = 600;
  SessionOptions o;
  o.solve.method = GetParam();
  try {
    Session session(std::move(scene), d, o);
    session.solve();
    FAIL() << "a diverging solve ended without an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("coincident faces"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, DivergingSolve, ::testing::Values("progressive", "gather", "hierarchical"));

TEST(ProgressThrottle, ReportsWhenTheFractionStallsAfterATenthOfASecond) {
  ProgressThrottle throttle;
  EXPECT_TRUE(throttle.due(0.0));
  EXPECT_FALSE(throttle.due(0.001));  // too soon, too little
  EXPECT_TRUE(throttle.due(0.02));    // 1% further
  const Stopwatch watch;
  while (watch.seconds() < 0.11) {
  }
  EXPECT_TRUE(throttle.due(0.0));  // the fraction fell, but a tenth of a second passed: report (and read Ctrl-C)
}

}  // namespace
}  // namespace luxel
