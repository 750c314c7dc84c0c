// Inputs that are valid, or nearly, but would lose what the user meant without a word (issue 18):
// a scene file with a key twice, a scene path that is a folder or a FIFO, a mesh far from the
// rest that makes the scene's extent; and what must stay quiet: an emissive glTF, 100,000 cameras
// (the camera list was quadratic in their number).
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/resources.h"
#include "luxel/surface.h"
#include "scene/import/name_index.h"
#include "error_message.h"

namespace luxel {
namespace {

using luxel::test::errorOf;
using luxel::test::bytesOf;

namespace fs = std::filesystem;

fs::path tmpDir(const std::string& name) {
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "import-unlucky" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(ImportUnlucky, SceneJsonWithADuplicateKeyIsAnErrorNamingTheKeyAndWhere) {
  const std::string json = "{\n  \"name\": \"a\",\n  \"up\": [0, 1, 0],\n  \"name\": \"b\"\n}\n";
  const std::string message = errorOf([&] { loadSceneJson(json, ".", "dup.json"); });
  EXPECT_NE(message.find("dup.json: line 4, column 3: key 'name' appears twice in one object"), std::string::npos)
      << message;
  // The same key in two different objects is not a duplicate.
  const std::string nested = R"({"builtin": "cornell", "cameras": [{"name": "a", "eye": [0,0,1], "target": [0,0,0]},
                                 {"name": "b", "eye": [0,0,2], "target": [0,0,0]}]})";
  const Scene scene = loadSceneJson(nested, ".", "ok.json");
  EXPECT_TRUE(scene.findCamera("a") && scene.findCamera("b"));
}

// The name lookup behind a scene file's cameras costs a bounded number of name comparisons per
// name: a search of the list per camera, as before, made 5 * 10^9 for 100,000 cameras.
TEST(ImportUnlucky, CamerasByNameCostLinearlyManyComparisons) {
  size_t comparisons = 0;
  const auto counting = [&](const std::string& a, const std::string& b) {
    ++comparisons;
    return a == b;
  };
  NameIndex<std::function<bool(const std::string&, const std::string&)>> index(counting);
  const size_t n = 100000;
  for (size_t i = 0; i < n; ++i) EXPECT_TRUE(index.findOrAdd("camera" + std::to_string(i), i).second);
  const auto [at, added] = index.findOrAdd("camera123", n);
  EXPECT_FALSE(added);
  EXPECT_EQ(at, 123u);
  EXPECT_LE(comparisons, 2 * n) << "name lookups are no longer constant time";
}

TEST(ImportUnlucky, AFolderOrAFifoAsTheSceneSaysWhatItIs) {
  const fs::path dir = tmpDir("paths");
  fs::create_directories(dir / "scene.json");
  fs::create_directories(dir / "room.obj");
  EXPECT_NE(errorOf([&] { loadScene((dir / "scene.json").string()); }).find("scene.json: is a directory"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadScene((dir / "room.obj").string()); }).find("room.obj: is a directory"),
            std::string::npos);
  // A FIFO with no writer: opening it would wait forever.
  ASSERT_EQ(mkfifo((dir / "pipe.json").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo((dir / "pipe.obj").c_str(), 0600), 0);
  EXPECT_NE(errorOf([&] { loadScene((dir / "pipe.json").string()); })
                .find("pipe.json: is not a regular file (a FIFO, socket or device)"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadScene((dir / "pipe.obj").string()); })
                .find("pipe.obj: is not a regular file (a FIFO, socket or device)"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { loadTexture(dir / "pipe.obj", true); }).find("is not a regular file"), std::string::npos);
}

// A 1 m room (one grey square, one emitting square above it) and one triangle 10^7 m away, its own object.
const char* const kStrayObj =
    "mtllib room.mtl\no room\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl grey\nf 1 2 3 4\n"
    "o lamp\nv 0.45 0.45 0.5\nv 0.45 0.55 0.5\nv 0.55 0.55 0.5\nv 0.55 0.45 0.5\nusemtl lamp\nf 5 6 7 8\n"
    "o stray\nv 1e7 0 0\nv 1.0000001e7 0 0\nv 1e7 1 0\nusemtl grey\nf 9 10 11\n";
const char* const kStrayMtl = "newmtl grey\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 10 10 10\n";

TEST(ImportUnlucky, AMeshFarFromTheRestIsAWarningNamingItAndTheExtents) {
  MemoryResourceReader side;
  side.add("room.mtl", kStrayMtl);
  const Scene scene = importMesh(bytesOf(kStrayObj), "obj", side, "stray.obj");
  // First; then coincident faces, whose tolerance (10^-6 of the extent, 10 m) the stray mesh makes
  // wide enough to take the room for a copy of the lamp: the consequence the warning explains.
  ASSERT_FALSE(scene.warnings.empty());
  EXPECT_NE(scene.warnings[0].find("stray.obj: mesh 'stray' lies far from the rest of the scene: with it the scene is "
                                   "1e+07 units across, without it 1.5."),
            std::string::npos)
      << scene.warnings[0];
  // Without the stray triangle: no warning.
  std::string room = kStrayObj;
  room.erase(room.find("o stray"));
  EXPECT_TRUE(importMesh(bytesOf(room), "obj", side, "room.obj").warnings.empty());
}

// The lamp (0.01 m^2) is far below 10^-14 of the squared extent (10^14 m^2, so 1 m^2), which
// discretisation used to call degenerate: the light vanished and the image was black.
TEST(ImportUnlucky, ASmallEmitterInAHugeSceneKeepsItsElements) {
  MemoryResourceReader side;
  side.add("room.mtl", kStrayMtl);
  const Scene scene = importMesh(bytesOf(kStrayObj), "obj", side, "stray.obj");
  DiscretiseOptions options;
  options.elementBudget = 1000;
  const SurfaceSet set = discretise(scene, options);
  double emittingArea = 0.0;
  for (const Element& e : set.elements)
    if (scene.materials[set.faces[e.face].material].isEmissive()) emittingArea += e.area;
  EXPECT_NEAR(emittingArea, 0.01, 1e-6);  // the lamp's area, to float rounding at 0.5 m
}

// A glTF emitter with the default base colour (1, glTF's default) is a valid file: luxel caps
// reflectance below 1 so that the solvers converge, and that is not the file's fault.
TEST(ImportUnlucky, AnEmissiveGltfWithTheDefaultBaseColourGivesNoWarning) {
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("materials":[{"name":"lamp","emissiveFactor":[1,1,1]}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":"data:application/)"
      R"(octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
  const MemoryResourceReader none;
  const Scene scene = importMesh(bytesOf(gltf), "gltf", none, "lamp.gltf");
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_TRUE(scene.materials[0].isEmissive());
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings[0];
  // Reflectance above 1 is the file's error, and still said.
  std::string bright = gltf;
  bright.replace(bright.find(R"("emissiveFactor")"), 16, R"("pbrMetallicRoughness":{"baseColorFactor":[2,1,1,1]},"emissiveFactor")");
  const Scene clamped = importMesh(bytesOf(bright), "gltf", none, "bright.gltf");
  ASSERT_EQ(clamped.warnings.size(), 1u);
  EXPECT_NE(clamped.warnings[0].find("bright.gltf: material 'lamp': reflectance (2, 1, 1)"), std::string::npos)
      << clamped.warnings[0];
}

}  // namespace
}  // namespace luxel
