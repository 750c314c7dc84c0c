// Objects on import: a file's nodes become objects with their global transforms, and a scene
// file entry with a name or "dynamic" becomes one object placed by the entry's transform, which a
// session can then move.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/session.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

fs::path tmpDir(const std::string& name) {
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "scene-objects" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A glTF whose one quad mesh is placed by two nodes: a parent translated by (0, 0, 3) with a child
// translated by (2, 0, 0), each holding the mesh.
const char* kTwoNodes = R"({
  "asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [
    {"name": "parent", "mesh": 0, "translation": [0, 0, 3], "children": [1]},
    {"name": "child", "mesh": 0, "translation": [2, 0, 0]}
  ],
  "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAACAPwAAAAAAAIA/AAAAAAAAAAAAAIA/AAABAAIAAAACAAMA"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 0, 1]},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ]
})";

TEST(SceneObjects, NodesBecomeObjectsWithTheirGlobalTransforms) {
  const fs::path dir = tmpDir("nodes");
  writeFile(dir / "two.gltf", kTwoNodes);
  const Scene scene = importMeshFile(dir / "two.gltf");
  ASSERT_EQ(scene.objects.size(), 2u);
  ASSERT_EQ(scene.meshes.size(), 2u);
  const int parent = scene.findObject("parent"), child = scene.findObject("child");
  ASSERT_GE(parent, 0);
  ASSERT_GE(child, 0);
  EXPECT_EQ(Vec3(scene.objects[size_t(parent)].transform[3]), Vec3(0, 0, 3));
  EXPECT_EQ(Vec3(scene.objects[size_t(child)].transform[3]), Vec3(2, 0, 3));  // parent then child
  for (const Mesh& m : scene.meshes) {
    ASSERT_NE(m.object, kNoObject);
    const Vec3 offset(scene.objects[m.object].transform[3]);
    // World positions are the mesh's own, placed by its object.
    EXPECT_EQ(m.positions[0], offset);
    EXPECT_EQ(m.positions[2], offset + Vec3(1, 0, 1));
    EXPECT_FALSE(scene.objects[m.object].dynamic);
  }
}

TEST(SceneObjects, SceneFileEntriesPlaceTheirObjects) {
  const fs::path dir = tmpDir("entries");
  writeFile(dir / "two.gltf", kTwoNodes);
  writeFile(dir / "scene.json", R"({
    "meshes": [
      {"file": "two.gltf", "translate": [10, 0, 0]},
      {"file": "two.gltf", "name": "mover", "dynamic": true, "translate": [0, 5, 0], "rotate": [0, 90, 0]}
    ]
  })");
  const Scene scene = loadSceneFile(dir / "scene.json");
  // The first entry keeps the file's two objects, moved by the entry; the second is one object.
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(Vec3(scene.objects[1].transform[3]), Vec3(12, 0, 3));
  const int mover = scene.findObject("mover");
  ASSERT_EQ(mover, 2);
  EXPECT_TRUE(scene.objects[2].dynamic);
  EXPECT_EQ(scene.dynamicObjects(), std::vector<uint32_t>{2u});
  EXPECT_EQ(Vec3(scene.objects[2].transform[3]), Vec3(0, 5, 0));
  size_t onMover = 0;
  for (const Mesh& m : scene.meshes) onMover += m.object == 2u ? 1 : 0;
  EXPECT_EQ(onMover, 2u);

  writeFile(dir / "mirror.json", R"({"meshes": [{"file": "two.gltf", "dynamic": true, "scale": [-1, 1, 1]}]})");
  try {
    loadSceneFile(dir / "mirror.json");
    FAIL() << "a mirrored dynamic object loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/meshes/0"), std::string::npos) << e.what();
  }
  writeFile(dir / "bad.json", R"({"meshes": [{"file": "two.gltf", "dynamic": "yes"}]})");
  EXPECT_THROW(loadSceneFile(dir / "bad.json"), Error);
}

// A dynamic object from a scene file moves in a session: the light it blocks follows it.
TEST(SceneObjects, ADynamicObjectFromASceneFileMovesInASession) {
  const fs::path dir = tmpDir("session");
  // A floor, a blocker above it and an emitter above both: the blocker's shadow on the floor.
  writeFile(dir / "floor.obj", "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 4 3 2\n");
  writeFile(dir / "blocker.obj", "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0 0.5\nv -0.5 0 0.5\nf 1 2 3 4\nf 1 4 3 2\n");
  writeFile(dir / "light.obj", "mtllib light.mtl\nusemtl lamp\nv -0.5 2 -0.5\nv 0.5 2 -0.5\nv 0.5 2 0.5\nv -0.5 2 0.5\nf 1 2 3 4\n");
  writeFile(dir / "light.mtl", "newmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
  writeFile(dir / "scene.json", R"({
    "meshes": [{"file": "floor.obj"}, {"file": "light.obj"},
               {"file": "blocker.obj", "name": "blocker", "dynamic": true, "translate": [0, 1, 0]}]
  })");
  Session session(loadSceneFile(dir / "scene.json"), DiscretiseOptions{.elementBudget = 800}, {});
  const uint32_t blocker = uint32_t(session.scene().findObject("blocker"));
  auto floorUnder = [&](const Solution& s, float x) {  // irradiance on the floor element nearest (x, 0, 0)
    size_t best = 0;
    float bestDistance = 1e30f;
    for (size_t e = 0; e < session.surfaces().elements.size(); ++e) {
      const Element& el = session.surfaces().elements[e];
      if (el.normal.y < 0.9f || std::abs(el.centroid.y) > 1e-4f) continue;
      const float d = glm::length(el.centroid - Vec3(x, 0, 0));
      if (d < bestDistance) bestDistance = d, best = e;
    }
    return double(s.irradiance[best].g);
  };
  const Solution before = session.solve();
  session.placeObject(blocker, glm::translate(glm::mat4(1.0f), Vec3(1.5f, 1.0f, 0.0f)));
  const Solution after = session.solve();
  // Under the lamp the shadow has gone; where the blocker went, the floor is darker than before.
  EXPECT_GT(floorUnder(after, 0.0f), 1.5 * floorUnder(before, 0.0f));
  EXPECT_LT(floorUnder(after, 1.6f), floorUnder(before, 1.6f));
}

}  // namespace
}  // namespace luxel
