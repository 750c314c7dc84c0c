// luxel scene files (docs/scene-format.md): paths, transforms, materials, lights, cameras, errors.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/surface.h"
#include "scene/import/transform.h"
#include "error_message.h"

namespace fs = std::filesystem;
using luxel::Error;
using luxel::Light;
using luxel::Rgb;
using luxel::Scene;
using luxel::Vec3;

namespace {

using luxel::test::errorOf;

constexpr float kPi = 3.14159265358979f;

fs::path tmpDir(const std::string& name) {
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "scene-file" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
}

void expectVec(Vec3 got, Vec3 want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

// A unit quad in the xy plane facing +z, material `mat` (reflectance 0.5, emission 0).
void writeQuad(const fs::path& obj, const std::string& mat) {
  std::string mtl = obj.stem().string() + ".mtl";
  writeFile(obj, "mtllib " + mtl + "\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl " + mat +
                     "\nf 1 2 3 4\n");
  writeFile(obj.parent_path() / mtl, "newmtl " + mat + "\nKd 0.5 0.5 0.5\n");
}

Vec3 faceNormal(const luxel::Mesh& m, size_t f) {
  const auto& v = m.faces[f].v;
  return glm::normalize(
      glm::cross(m.positions[v[1]] - m.positions[v[0]], m.positions[v[2]] - m.positions[v[0]]));
}

// Writes `json` as scene.json in a fresh folder with a quad at models/quad.obj, and loads it.
Scene loadWithQuad(const std::string& test, const std::string& json) {
  fs::path dir = tmpDir(test);
  writeQuad(dir / "models" / "quad.obj", "paint");
  writeFile(dir / "scene.json", json);
  return luxel::loadSceneFile(dir / "scene.json");
}

// Expects loading `json` to fail with a message naming scene.json and containing each of `parts`.
void expectError(const std::string& test, const std::string& json,
                 std::initializer_list<std::string> parts) {
  fs::path dir = tmpDir(test);
  writeQuad(dir / "models" / "quad.obj", "paint");
  writeFile(dir / "scene.json", json);
  std::string msg = errorOf([&] { luxel::loadSceneFile(dir / "scene.json"); });
  EXPECT_NE(msg.find("scene.json"), std::string::npos) << msg;
  for (const std::string& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << msg;
}

}  // namespace

TEST(SceneFile, ResolvesMeshPathsRelativeToTheFile) {
  fs::path dir = tmpDir("relative");
  writeQuad(dir / "models" / "quad.obj", "paint");
  writeFile(dir / "scenes" / "scene.json", R"({ "meshes": [ { "file": "../models/quad.obj" } ] })");
  // The working directory is not the file's folder.
  Scene s = luxel::loadSceneFile(dir / "scenes" / "scene.json");
  EXPECT_EQ(s.name, "scene");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.faceCount(), 1u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "paint");
  expectVec(s.up, Vec3(0, 1, 0));
}

TEST(SceneFile, TransformsScaleThenRotateThenTranslate) {
  // Vertex (1, 0, 0) -> scale 2 -> (2, 0, 0) -> 90 degrees about +y -> (0, 0, -2) -> translate
  // (10, 0, 0) -> (10, 0, -2).
  Scene s = loadWithQuad("transform", R"({ "meshes": [ { "file": "models/quad.obj",
      "scale": 2, "rotate": { "axis": [0, 1, 0], "angle": 90 }, "translate": [10, 0, 0] } ] })");
  ASSERT_EQ(s.meshes.size(), 1u);
  expectVec(s.meshes[0].positions[0], Vec3(10, 0, 0));
  expectVec(s.meshes[0].positions[1], Vec3(10, 0, -2));
  expectVec(s.meshes[0].positions[2], Vec3(10, 2, -2));
  expectVec(faceNormal(s.meshes[0], 0), Vec3(1, 0, 0));  // +z turned to +x

  // Euler [90, 90, 0]: about x first ((1,0,0) stays, (0,1,0) -> (0,0,1)), then about y
  // ((1,0,0) -> (0,0,-1), (0,0,1) -> (1,0,0)).
  s = loadWithQuad("euler",
                   R"({ "meshes": [ { "file": "models/quad.obj", "rotate": [90, 90, 0] } ] })");
  expectVec(s.meshes[0].positions[1], Vec3(0, 0, -1));
  expectVec(s.meshes[0].positions[3], Vec3(1, 0, 0));

  // Non-uniform scale.
  s = loadWithQuad("scale3",
                   R"({ "meshes": [ { "file": "models/quad.obj", "scale": [2, 3, 4] } ] })");
  expectVec(s.meshes[0].positions[2], Vec3(2, 3, 0));
}

TEST(SceneFile, MirroringKeepsFacesFacingTheSameWayInTheMirror) {
  // A mirror in x keeps the +z normal; without reversing the winding it would flip to -z.
  Scene s = loadWithQuad("mirror",
                         R"({ "meshes": [ { "file": "models/quad.obj", "scale": [-1, 1, 1] } ] })");
  expectVec(faceNormal(s.meshes[0], 0), Vec3(0, 0, 1));
  expectVec(s.meshes[0].positions[1], Vec3(-1, 0, 0));
}

// A mirror reverses the winding by swapping corners 1 and 3, so a prescribed element grid
// (elements along corner 0 -> 1, then along 0 -> 3) must swap its counts too. A 3 x 5 quad with a
// 3 x 5 grid has unit square elements, and keeps them under any mirror; without the swap they
// would be 0.6 x 1.67.
TEST(SceneFile, MirroringSwapsElementGridsWithTheCorners) {
  auto gridQuad = [] {
    Scene s;
    s.name = "grid quad";
    s.materials.push_back(luxel::Material{.name = "grey", .reflectance = Rgb(0.5f)});
    luxel::Mesh m;
    m.name = "quad";
    m.positions = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 5, 0), Vec3(0, 5, 0)};
    m.faces.push_back(luxel::Face{{0, 1, 2, 3}});
    m.elementGrids.push_back({3, 5});
    s.meshes.push_back(m);
    return s;
  };
  struct Case {
    Vec3 scale;
    bool mirrors;
  };
  for (const Case& c : {Case{Vec3(-1, 1, 1), true}, Case{Vec3(-1, -1, -1), true},
                        Case{Vec3(-1, -1, 1), false}, Case{Vec3(2, 2, 2), false}}) {
    SCOPED_TRACE(::testing::Message() << c.scale.x << " " << c.scale.y << " " << c.scale.z);
    Scene s = gridQuad();
    luxel::transformMesh(s.meshes[0], glm::scale(glm::mat4(1.0f), c.scale));
    const std::array<uint16_t, 2> want =
        c.mirrors ? std::array<uint16_t, 2>{5, 3} : std::array<uint16_t, 2>{3, 5};
    ASSERT_EQ(s.meshes[0].elementGrids.size(), 1u);
    EXPECT_EQ(s.meshes[0].elementGrids[0], want);
    s.validate();
    luxel::SurfaceSet set = luxel::discretise(s, luxel::DiscretiseOptions{.orientByLight = false});
    ASSERT_EQ(set.elements.size(), 15u);
    const float side = std::abs(c.scale.x);  // the scales are uniform in size
    for (const luxel::Element& e : set.elements)
      for (int i = 0; i < e.polygon.count; ++i)
        EXPECT_NEAR(glm::length(e.polygon.v[(i + 1) % e.polygon.count] - e.polygon.v[i]), side,
                    1e-4f);
  }
}

TEST(SceneFile, OverridesAndAddsMaterialsByName) {
  fs::path dir = tmpDir("materials");
  writeQuad(dir / "a" / "quad.obj", "paint");
  writeQuad(dir / "b" / "quad.obj", "paint");
  writeFile(dir / "tex.ppm", "P6\n1 1\n255\n\xff\xff\xff");
  writeFile(dir / "scene.json", R"({
    // Comments are allowed.
    "meshes": [
      { "file": "a/quad.obj" },
      { "file": "b/quad.obj", "translate": [0, 0, 1] },
      { "file": "a/quad.obj", "translate": [0, 0, 2], "material": "lamp" }
    ],
    "materials": {
      "paint": { "reflectance": [0.2, 0.3, 0.4], "twoSided": true, "texture": "tex.ppm" },
      "lamp": { "emission": [1, 2, 3], "emissionStrength": 10, "reflectance": 0.0 }
    }
  })");
  Scene s = luxel::loadSceneFile(dir / "scene.json");
  ASSERT_EQ(s.meshes.size(), 3u);
  // Three files' "paint" stay separate materials; the override reaches all of them.
  ASSERT_EQ(s.materials.size(), 4u);
  int paintCount = 0;
  for (const luxel::Material& m : s.materials) {
    if (m.name != "paint") continue;
    ++paintCount;
    expectVec(m.reflectance, Vec3(0.2f, 0.3f, 0.4f));
    EXPECT_TRUE(m.twoSided);
    ASSERT_GE(m.reflectanceTexture, 0);
    EXPECT_EQ(s.textures[size_t(m.reflectanceTexture)].width, 1);
  }
  EXPECT_EQ(paintCount, 3);
  EXPECT_NE(s.meshes[0].material, s.meshes[1].material);
  EXPECT_EQ(s.textures.size(), 1u);  // loaded once
  const luxel::Material& lamp = s.materials[s.meshes[2].material];
  EXPECT_EQ(lamp.name, "lamp");
  expectVec(lamp.emission, Vec3(10, 20, 30));
  expectVec(lamp.reflectance, Vec3(0));
}

// Omitted materials take their meshes with them: a file's own (both files' "paint") and those a
// mesh entry gives one ("lamp"); the rest stay, and the materials themselves are kept.
TEST(SceneFile, OmittedMaterialsLeaveTheirMeshesOut) {
  fs::path dir = tmpDir("omit");
  writeQuad(dir / "a" / "quad.obj", "paint");
  writeQuad(dir / "b" / "quad.obj", "glass");
  writeFile(dir / "scene.json", R"({
    "meshes": [
      { "file": "a/quad.obj" },
      { "file": "b/quad.obj", "translate": [0, 0, 1] },
      { "file": "b/quad.obj", "translate": [0, 0, 2], "material": "lamp" },
      { "file": "a/quad.obj", "translate": [0, 0, 3] }
    ],
    "materials": { "glass": { "omit": true }, "lamp": { "emission": 1, "omit": true }, "paint": { "omit": false } }
  })");
  const Scene s = luxel::loadSceneFile(dir / "scene.json");
  ASSERT_EQ(s.meshes.size(), 2u);
  for (const luxel::Mesh& m : s.meshes) EXPECT_EQ(s.materials[m.material].name, "paint");
  EXPECT_NEAR(s.meshes[1].positions[0].z, 3.0f, 1e-6f);
  EXPECT_GE(s.findMaterial("glass"), 0);
  // Glass a scene file leaves out is not warned about; glass it keeps is.
  writeFile(dir / "b" / "quad.mtl", "newmtl glass\nKd 0 0 0\nTf 0.5 0.5 0.5\nillum 6\n");
  const Scene kept = luxel::loadScene((dir / "b" / "quad.obj").string());
  ASSERT_EQ(kept.warnings.size(), 1u);
  EXPECT_NE(kept.warnings[0].find("material 'glass' lets light through"), std::string::npos) << kept.warnings[0];
  EXPECT_TRUE(luxel::loadScene((dir / "scene.json").string()).warnings.empty());
  expectError("omit-type", R"({ "materials": { "glass": { "omit": "yes" } } })", {"/materials/glass/omit"});
}

TEST(SceneFile, EmissionStrengthScalesAnImportedEmission) {
  fs::path dir = tmpDir("strength");
  writeFile(dir / "lamp.obj",
            "mtllib lamp.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl light\nf 1 2 3\n");
  writeFile(dir / "lamp.mtl", "newmtl light\nKd 0.5 0.5 0.5\nKe 17 12 4\n");
  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "lamp.obj" } ],
                                     "materials": { "light": { "emissionStrength": 0.5 } } })");
  Scene s = luxel::loadSceneFile(dir / "scene.json");
  expectVec(s.materials[0].emission, Vec3(8.5f, 6.0f, 2.0f));
}

// The viewer's highlight (display only): a grey or a colour and an exponent, over an imported Ks/Ns.
TEST(SceneFile, SpecularAndShininessSetTheHighlight) {
  fs::path dir = tmpDir("specular");
  writeFile(dir / "quad.obj", "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl paint\nf 1 2 3\n"
                              "v 0 0 1\nv 1 0 1\nv 1 1 1\nusemtl gloss\nf 4 5 6\n");
  writeFile(dir / "quad.mtl", "newmtl paint\nKd 0.5 0.5 0.5\nKs 0.2 0.2 0.2\nNs 8\nillum 2\n"
                              "newmtl gloss\nKd 0.5 0.5 0.5\nKs 0.7 0.7 0.7\nNs 50\nillum 2\n");
  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "quad.obj" } ],
    "materials": { "paint": { "specular": [0.1, 0.2, 0.3], "shininess": 64 },
                   "gloss": { "specular": 0.25 },
                   "new": { "shininess": 0 } } })");
  Scene s = luxel::loadSceneFile(dir / "scene.json");
  const luxel::Material& paint = s.materials[size_t(s.findMaterial("paint"))];
  expectVec(paint.specular, Vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(paint.shininess, 64.0f);
  EXPECT_TRUE(paint.hasSpecular());
  const luxel::Material& gloss = s.materials[size_t(s.findMaterial("gloss"))];
  expectVec(gloss.specular, Vec3(0.25f));
  EXPECT_EQ(gloss.shininess, 50.0f);  // the file's Ns, not given here
  const luxel::Material& added = s.materials[size_t(s.findMaterial("new"))];
  EXPECT_EQ(added.specular, Vec3(0.0f));
  EXPECT_FALSE(added.hasSpecular());
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneFile, TransmittanceMakesGlass) {
  fs::path dir = tmpDir("transmittance");
  writeFile(dir / "quad.obj", "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl window\nf 1 2 3\n");
  writeFile(dir / "quad.mtl", "newmtl window\nKd 0.1 0.1 0.1\nillum 2\n");
  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "quad.obj" } ],
    "materials": { "window": { "transmittance": [0.8, 0.7, 0.6] } } })");
  Scene s = luxel::loadScene((dir / "scene.json").string());
  const luxel::Material& window = s.materials[size_t(s.findMaterial("window"))];
  expectVec(window.transmittance, Vec3(0.8f, 0.7f, 0.6f));
  EXPECT_TRUE(window.transmits());
  // The scene is told what passes the glass and what does not.
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("material 'window' lets light through"), std::string::npos) << s.warnings[0];
}

TEST(SceneFile, EveryLightType) {
  Scene s = loadWithQuad("lights", R"({
    "meshes": [ { "file": "models/quad.obj" } ],
    "lights": [
      { "type": "point", "name": "bulb", "position": [1, 2, 3], "color": [1, 0.5, 0.25],
        "intensity": 100 },
      { "type": "spot", "position": [0, 3, 0], "target": [0, 0, 0], "innerConeAngle": 20,
        "outerConeAngle": 30, "intensity": 50 },
      { "type": "spot", "position": [0, 3, 0], "direction": [1, 0, 0] },
      { "type": "directional", "name": "sun", "direction": [0, -2, 0], "intensity": 100000,
        "angularRadius": 0.2665 },
      { "type": "sky", "intensity": 5000, "color": 0.9 },
      { "type": "cie-overcast", "intensity": 8000 }
    ],
    "up": [0, 0, 2]
  })");
  ASSERT_EQ(s.lights.size(), 6u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, Light::Type::Point);
  EXPECT_EQ(point.name, "bulb");
  expectVec(point.position, Vec3(1, 2, 3));
  expectVec(point.color, Vec3(1, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(point.intensity, 100.0f);

  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, Light::Type::Spot);
  EXPECT_EQ(spot.name, "light1");
  expectVec(spot.direction, Vec3(0, -1, 0));
  EXPECT_NEAR(spot.innerConeAngle, 20.0f * kPi / 180.0f, 1e-6f);
  EXPECT_NEAR(spot.outerConeAngle, 30.0f * kPi / 180.0f, 1e-6f);
  expectVec(s.lights[2].direction, Vec3(1, 0, 0));
  EXPECT_NEAR(s.lights[2].outerConeAngle, kPi / 4.0f, 1e-6f);  // default 45 degrees

  const Light& sun = s.lights[3];
  EXPECT_EQ(sun.type, Light::Type::Directional);
  expectVec(sun.direction, Vec3(0, -1, 0));
  EXPECT_NEAR(sun.angularRadius, 0.00465f, 1e-5f);

  EXPECT_EQ(s.lights[4].type, Light::Type::Sky);
  expectVec(s.lights[4].color, Vec3(0.9f));
  EXPECT_EQ(s.lights[5].type, Light::Type::CieOvercastSky);
  EXPECT_FLOAT_EQ(s.lights[5].intensity, 8000.0f);
  expectVec(s.up, Vec3(0, 0, 1));
}

TEST(SceneFile, Cameras) {
  Scene s = loadWithQuad("cameras", R"({
    "meshes": [ { "file": "models/quad.obj" } ],
    "cameras": [
      { "name": "front", "eye": [278, 273, -800], "target": [278, 273, 0], "fov": 39.3077 },
      { "eye": [0, 0, 5], "target": [0, 0, 0], "up": [1, 0, 0] }
    ]
  })");
  ASSERT_EQ(s.cameras.size(), 2u);
  const luxel::Camera* front = s.findCamera("front");
  ASSERT_NE(front, nullptr);
  expectVec(front->eye, Vec3(278, 273, -800));
  expectVec(front->target, Vec3(278, 273, 0));
  EXPECT_FLOAT_EQ(front->fovY, 39.3077f);
  expectVec(front->up, Vec3(0, 1, 0));
  EXPECT_EQ(s.cameras[1].name, "camera1");
  expectVec(s.cameras[1].up, Vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(s.cameras[1].fovY, 45.0f);
}

TEST(SceneFile, BuiltinBase) {
  if (!luxel::isBuiltinScene("cornell")) GTEST_SKIP() << "no built-in scene 'cornell'";
  Scene base = luxel::builtinScene("cornell");
  Scene s = loadWithQuad("builtin", R"({ "builtin": "cornell",
      "meshes": [ { "file": "models/quad.obj", "translate": [0, 0, 3] } ] })");
  EXPECT_EQ(s.meshes.size(), base.meshes.size() + 1);
  EXPECT_EQ(s.materials.size(), base.materials.size() + 1);
  EXPECT_EQ(s.meshes.back().material, base.materials.size());  // remapped past the built-in's
  EXPECT_EQ(s.lights.size(), base.lights.size());

  expectError("builtin-bad", R"({ "builtin": "cornel" })", {"/builtin", "cornel", "cornell"});
}

TEST(SceneFile, LoadSceneDispatchesJson) {
  fs::path dir = tmpDir("load-scene");
  writeQuad(dir / "quad.obj", "paint");
  writeFile(dir / "s.JSON", R"({ "meshes": [ { "file": "quad.obj" } ] })");
  EXPECT_EQ(luxel::loadScene((dir / "s.JSON").string()).faceCount(), 1u);
}

// ---- errors name the file and the JSON path ----------------------------------------------------

TEST(SceneFileErrors, UnknownLightType) {
  expectError("light-type", R"({ "lights": [ {"type": "point", "position": [0,0,0]},
      {"type": "sky"}, {"type": "spto"} ] })",
              {"/lights/2/type", "unknown light type 'spto'",
               "point, spot, directional, sky, cie-overcast"});
}

TEST(SceneFileErrors, UnknownKeys) {
  expectError("key-top", R"({ "mesh": [] })", {"/mesh", "unknown key 'mesh'"});
  expectError("key-camera",
              R"({ "cameras": [ { "eye": [0,0,1], "target": [0,0,0], "fob": 40 } ] })",
              {"/cameras/0/fob", "unknown key 'fob'"});
  // A key that belongs to another light type.
  expectError("key-light", R"({ "lights": [ { "type": "directional", "direction": [0,-1,0],
      "position": [0,0,0] } ] })",
              {"/lights/0/position", "unknown key"});
  expectError("key-material", R"({ "materials": { "a/b": { "colour": [1,1,1] } } })",
              {"/materials/a~1b/colour", "unknown key 'colour'"});
}

TEST(SceneFileErrors, WrongTypes) {
  expectError("type-intensity", R"({ "lights": [ { "type": "sky", "intensity": "bright" } ] })",
              {"/lights/0/intensity", "expected a number, got string"});
  expectError("type-vec", R"({ "cameras": [ { "eye": [0, 0], "target": [0,0,0] } ] })",
              {"/cameras/0/eye", "expected an array of 3 numbers"});
  expectError("type-lights", R"({ "lights": { "type": "sky" } })",
              {"/lights", "expected an array"});
  expectError("type-root", R"([1, 2])", {"/:", "expected an object"});
  expectError("type-bool", R"({ "materials": { "m": { "twoSided": 1 } } })",
              {"/materials/m/twoSided", "expected true or false"});
  expectError("type-component", R"({ "up": [0, "1", 0] })", {"/up/1", "expected a number"});
}

TEST(SceneFileErrors, BadValues) {
  expectError("negative", R"({ "lights": [ { "type": "sky", "intensity": -1 } ] })",
              {"/lights/0/intensity", "negative"});
  expectError("missing", R"({ "lights": [ { "type": "point" } ] })",
              {"/lights/0", "needs 'position'"});
  expectError("cone", R"({ "lights": [ { "type": "spot", "position": [0,1,0], "direction": [0,-1,0],
      "innerConeAngle": 50, "outerConeAngle": 40 } ] })",
              {"/lights/0/innerConeAngle"});
  expectError("fov", R"({ "cameras": [ { "eye": [0,0,1], "target": [0,0,0], "fov": 180 } ] })",
              {"/cameras/0/fov"});
  expectError("zero-dir", R"({ "up": [0, 0, 0] })", {"/up", "zero"});
  expectError("reflectance", R"({ "materials": { "m": { "reflectance": [1.5, 0, 0] } } })",
              {"/materials/m/reflectance", "above 1"});
  expectError("assign", R"({ "meshes": [ { "file": "models/quad.obj", "material": "nope" } ] })",
              {"/meshes/0/material", "'nope'"});
  expectError("scale", R"({ "meshes": [ { "file": "models/quad.obj", "scale": [1, 0, 1] } ] })",
              {"/meshes/0/scale"});
  expectError("rotate",
              R"({ "meshes": [ { "file": "models/quad.obj", "rotate": { "axis": [0,1,0] } } ] })",
              {"/meshes/0/rotate", "angle"});
}

TEST(SceneFileErrors, SpecularAndShininess) {
  expectError("specular-above", R"({ "materials": { "m": { "specular": [1.5, 0, 0] } } })",
              {"/materials/m/specular", "specular (1.5, 0, 0) is above 1"});
  expectError("specular-negative", R"({ "materials": { "m": { "specular": -0.5 } } })",
              {"/materials/m/specular", "must not be negative, got -0.5"});
  expectError("specular-component", R"({ "materials": { "m": { "specular": [0.5, -1, 0] } } })",
              {"/materials/m/specular/1", "must not be negative"});
  expectError("specular-type", R"({ "materials": { "m": { "specular": "white" } } })",
              {"/materials/m/specular", "expected a number or an array of 3 numbers, got string"});
  expectError("shininess-negative", R"({ "materials": { "m": { "shininess": -1 } } })",
              {"/materials/m/shininess", "must not be negative, got -1"});
  expectError("shininess-above", R"({ "materials": { "m": { "shininess": 20000 } } })",
              {"/materials/m/shininess", "shininess 20000 is above 10000"});
  expectError("shininess-type", R"({ "materials": { "m": { "shininess": [32] } } })",
              {"/materials/m/shininess", "expected a number, got an array of 1"});
  expectError("shininess-huge", R"({ "materials": { "m": { "shininess": 1e300 } } })",
              {"/materials/m/shininess", "number out of range"});
}

// Thin glass: at most 1 a channel, and with the reflectance at most what arrives.
TEST(SceneFileErrors, Transmittance) {
  expectError("transmittance-above", R"({ "materials": { "m": { "transmittance": [1.5, 0, 0] } } })",
              {"/materials/m/transmittance", "transmittance (1.5, 0, 0) is above 1"});
  expectError("transmittance-negative", R"({ "materials": { "m": { "transmittance": -0.5 } } })",
              {"/materials/m/transmittance", "must not be negative, got -0.5"});
  expectError("transmittance-with-reflectance",
              R"({ "materials": { "m": { "reflectance": 0.5, "transmittance": [0.2, 0.6, 0.2] } } })",
              {"/materials/m/transmittance", "reflectance (0.5, 0.5, 0.5) plus transmittance (0.2, 0.6, 0.2) is above 1"});
}

TEST(SceneFileErrors, MissingFilesNameBoth) {
  expectError("mesh-missing", R"({ "meshes": [ { "file": "models/absent.obj" } ] })",
              {"/meshes/0/file", "absent.obj", "no such file"});
  expectError("texture-missing", R"({ "materials": { "m": { "texture": "img/absent.png" } } })",
              {"/materials/m/texture", "absent.png"});
  std::string msg = errorOf([] { luxel::loadSceneFile("/no/such/place/scene.json"); });
  EXPECT_NE(msg.find("scene.json"), std::string::npos) << msg;
}

TEST(SceneFileErrors, BadJsonGivesBytePosition) {
  // The stray comma is the 24th byte (nlohmann counts from 1).
  expectError("json", "{ \"lights\": [ {\"type\": , \"sky\"} ] }",
              {"invalid JSON at byte 24", "line 1, column 24"});
  expectError("json-empty", "", {"invalid JSON"});
}

// ---- animation (luxel/animation.h) -------------------------------------------------------------

namespace {
Vec3 at(const glm::mat4& m, Vec3 p) { return Vec3(m * glm::vec4(p, 1.0f)); }
}  // namespace

TEST(SceneFile, AnimatesMeshesAndLights) {
  Scene s = loadWithQuad("animation", R"({
    "meshes": [
      { "file": "models/quad.obj", "name": "spinner", "translate": [1, 0, 0],
        "animation": { "spin": { "axis": [0, 2, 0], "degreesPerSecond": 45 } } },
      { "file": "models/quad.obj", "name": "mover",
        "animation": { "keyframes": [ { "time": 0 },
          { "time": 2, "translate": [2, 0, 0], "rotate": { "quaternion": [0, 0, 1, 1] }, "scale": 3 } ],
          "loop": true } } ],
    "lights": [
      { "type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0],
        "animation": { "keyframes": [ { "time": 0, "intensity": 1 },
                                      { "time": 1, "intensity": 3, "color": [1, 0, 0] } ] } },
      { "type": "directional", "direction": [0, -1, 0],
        "animation": { "spin": { "axis": [1, 0, 0], "degreesPerSecond": 90 } } } ] })");
  s.validate();
  ASSERT_EQ(s.objects.size(), 2u);
  // Animated objects are dynamic without saying so.
  EXPECT_TRUE(s.objects[0].dynamic);
  EXPECT_TRUE(s.objects[1].dynamic);
  ASSERT_EQ(s.animation.objects.size(), 2u);
  // The spin's pivot defaults to the object's origin, (1, 0, 0): after 2 s (90 degrees) it stays,
  // and (2, 0, 0) turns to (1, 0, -1).
  const glm::mat4 spun = luxel::objectTransformAt(s, 0, 2.0) * glm::inverse(s.objects[0].transform);
  expectVec(at(spun, Vec3(1, 0, 0)), Vec3(1, 0, 0));
  expectVec(at(spun, Vec3(2, 0, 0)), Vec3(1, 0, -1));
  // The path, half way (t = 1, and t = 3 a period later): moved (1, 0, 0), scaled 2, turned 45
  // degrees about z (the quaternion is 90 degrees about z, normalised).
  const float r = std::sqrt(2.0f);
  for (double t : {1.0, 3.0}) expectVec(at(luxel::objectTransformAt(s, 1, t), Vec3(1, 0, 0)), Vec3(1 + r, r, 0));
  // The spot's intensity and colour half way through its keys.
  const Light spot = luxel::lightAt(s, 0, 0.5);
  EXPECT_FLOAT_EQ(spot.intensity, 2.0f);
  expectVec(spot.color, Rgb(1, 0.5f, 0.5f));
  // The sun turns 90 degrees about x in a second: from straight down to along -z.
  expectVec(luxel::lightAt(s, 1, 1.0).direction, Vec3(0, 0, -1));
}

TEST(SceneFile, ObjectsOverrideABuiltinsAnimation) {
  if (!luxel::isBuiltinScene("cornell-low")) GTEST_SKIP() << "no built-in scene 'cornell-low'";
  Scene s = loadWithQuad("animation-builtin", R"({ "builtin": "cornell-low",
      "objects": { "box": { "animation": { "spin": { "axis": [1, 0, 0], "degreesPerSecond": 10 } } } } })");
  ASSERT_EQ(s.animation.objects.size(), 1u);
  ASSERT_TRUE(s.animation.objects[0].motion.spin);
  expectVec(s.animation.objects[0].motion.spin->axis, Vec3(1, 0, 0));
  expectVec(s.animation.objects[0].motion.spin->pivot, Vec3(0.275f));  // the box's centre
  Scene still = loadWithQuad("animation-null", R"({ "builtin": "cornell-low", "objects": { "box": { "animation": null } } })");
  EXPECT_TRUE(still.animation.empty());
  EXPECT_TRUE(still.objects[0].dynamic);
}

TEST(SceneFileErrors, Animations) {
  const std::string quad = R"("file": "models/quad.obj", "name": "q")";
  auto mesh = [&](const std::string& animation) { return R"({ "meshes": [ { )" + quad + R"(, "animation": )" + animation + " } ] }"; };
  const std::string spin = R"({ "spin": { "axis": [0, 1, 0], "degreesPerSecond": 30 } })";
  expectError("anim-key", mesh(R"({ "spinn": {} })"), {"/meshes/0/animation/spinn", "unknown key 'spinn'"});
  expectError("anim-spin-key", mesh(R"({ "spin": { "axis": [0, 1, 0], "rate": 3 } })"),
              {"/meshes/0/animation/spin/rate", "unknown key 'rate'", "degreesPerSecond"});
  expectError("anim-both", mesh(R"({ "spin": {}, "keyframes": [] })"), {"/meshes/0/animation", "exactly one of"});
  expectError("anim-neither", mesh("{}"), {"/meshes/0/animation", "exactly one of"});
  expectError("anim-rate", mesh(R"({ "spin": { "axis": [0, 1, 0] } })"), {"/meshes/0/animation/spin", "needs 'degreesPerSecond'"});
  expectError("anim-axis", mesh(R"({ "spin": { "axis": [0, 0, 0], "degreesPerSecond": 1 } })"),
              {"/meshes/0/animation/spin/axis", "must not be zero"});
  expectError("anim-spin-loop", mesh(R"({ "spin": { "axis": [0, 1, 0], "degreesPerSecond": 1 }, "loop": true })"),
              {"/meshes/0/animation/loop", "keyframes"});
  expectError("anim-empty", mesh(R"({ "keyframes": [] })"), {"/meshes/0/animation/keyframes", "at least one"});
  expectError("anim-time", mesh(R"({ "keyframes": [ { "translate": [0, 0, 0] } ] })"),
              {"/meshes/0/animation/keyframes/0", "needs 'time'"});
  expectError("anim-order", mesh(R"({ "keyframes": [ { "time": 0 }, { "time": 2 }, { "time": 2 } ] })"),
              {"/meshes/0/animation/keyframes/2/time", "not after the previous keyframe's (2)"});
  expectError("anim-scale", mesh(R"({ "keyframes": [ { "time": 0, "scale": -2 } ] })"),
              {"/meshes/0/animation/keyframes/0/scale", "must be positive"});
  expectError("anim-scale-vec", mesh(R"({ "keyframes": [ { "time": 0, "scale": [1, 2, 1] } ] })"),
              {"/meshes/0/animation/keyframes/0/scale", "expected a number"});
  expectError("anim-huge", mesh(R"({ "keyframes": [ { "time": 1e300 } ] })"),
              {"/meshes/0/animation/keyframes/0/time", "out of range"});
  // JSON has no NaN: the parser stops at it.
  expectError("anim-nan", mesh(R"({ "spin": { "axis": [0, 1, 0], "degreesPerSecond": NaN } })"), {"invalid JSON at byte"});
  expectError("anim-quaternion", mesh(R"({ "keyframes": [ { "time": 0, "rotate": { "quaternion": [0, 0, 0, 0] } } ] })"),
              {"/meshes/0/animation/keyframes/0/rotate/quaternion", "must not be zero"});
  expectError("anim-colour", mesh(R"({ "keyframes": [ { "time": 0, "color": 1 } ] })"),
              {"/meshes/0/animation/keyframes/0/color", "only a light"});
  expectError("anim-static",
              R"({ "meshes": [ { )" + quad + R"(, "dynamic": false, "animation": )" + spin + " } ] }",
              {"/meshes/0/animation", "object 'q' is animated, so it must be dynamic"});
  // Lights: what a light of the type cannot do.
  expectError("anim-sky", R"({ "lights": [ { "type": "sky", "animation": )" + spin + " } ] }",
              {"/lights/0/animation/spin", "a sky has no position or direction"});
  expectError("anim-sun-move", R"({ "lights": [ { "type": "directional", "direction": [0, -1, 0],
      "animation": { "keyframes": [ { "time": 0, "translate": [1, 0, 0] } ] } } ] })",
              {"/lights/0/animation/keyframes/0/translate", "no position"});
  expectError("anim-light-scale", R"({ "lights": [ { "type": "point", "position": [0, 1, 0],
      "animation": { "keyframes": [ { "time": 0, "scale": 2 } ] } } ] })",
              {"/lights/0/animation/keyframes/0/scale", "no size"});
  expectError("anim-light-intensity", R"({ "lights": [ { "type": "point", "position": [0, 1, 0],
      "animation": { "keyframes": [ { "time": 0, "intensity": -1 } ] } } ] })",
              {"/lights/0/animation/keyframes/0/intensity", "negative"});
  // /objects: names that exist, and an animated object stays dynamic.
  expectError("objects-name", R"({ "meshes": [ { )" + quad + R"( } ], "objects": { "crate": { "dynamic": true } } })",
              {"/objects/crate", "no object named 'crate'", "'q'"});
  expectError("objects-key", R"({ "meshes": [ { )" + quad + R"( } ], "objects": { "q": { "spin": {} } } })",
              {"/objects/q/spin", "unknown key 'spin'"});
  if (luxel::isBuiltinScene("cornell-low"))
    expectError("objects-static", R"({ "builtin": "cornell-low", "objects": { "box": { "dynamic": false } } })",
                {"/objects/box/dynamic", "object 'box' is animated", "\"animation\": null"});
}
