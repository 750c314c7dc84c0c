// Normal and bump maps read from files: bump maps made into normal maps (scene/bump_map.h) against
// the closed form, glTF normalTexture with its scale (an image file beside a .gltf, and embedded
// in a .glb), OBJ norm, bump and map_Bump with -bm, and the scene file's normalTexture and
// normalScale keys. Their texels are data: 8-bit value k reads back as k / 255
// exactly (float rounding, 1e-6), where the sRGB decode would give another number (128: 0.2159
// instead of 0.5020). The shading normal of an imported quad checks glTF's convention end to end:
// green is the image's up.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "error_message.h"
#include "luxel/error.h"
#include "luxel/import.h"
#include "render/normal_map.h"
#include "scene/bump_map.h"
#include "scene/scene_bytes.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;
using luxel::test::errorOf;

fs::path tmpDir(const std::string& name) {
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "normal-map-import" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// An 8-bit RGB PNG, top row first (stb_image_write).
std::string png(int w, int h, const std::vector<std::array<uint8_t, 3>>& px) {
  std::string out;
  auto append = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size));
  };
  EXPECT_NE(stbi_write_png_to_func(append, &out, w, h, 3, px.data(), w * 3), 0);
  return out;
}

// Left texel (128, 128, 255), a flat normal; right (128, 255, 128), a normal along +y (green, the
// image's up).
std::string normalPng() { return png(2, 1, {{128, 128, 255}, {128, 255, 128}}); }

// A grey ramp 8 wide and 4 high: 32 x in column x, the same in every row.
std::string rampPng() {
  std::vector<std::array<uint8_t, 3>> px;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) px.push_back({uint8_t(32 * x), uint8_t(32 * x), uint8_t(32 * x)});
  return png(8, 4, px);
}

float srgbDecoded(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

void expectRgb(Rgb got, Rgb want, float tol = 1e-6f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

const Material& material(const Scene& s, const std::string& name) {
  const int i = s.findMaterial(name);
  if (i < 0) throw Error("no material " + name);
  return s.materials[size_t(i)];
}

const float k128 = 128.0f / 255.0f;

// normalPng() read as data, and the shading normal at its right texel (uv (0.75, 0.5)) on a quad
// in the xy plane facing +z with the image upright on it (u along +x, v along +y): the texel
// (128, 255, 128) is the tangent normal (a, 1, a), a = 2 * 128/255 - 1, scaled to (a s, s, a) and
// normalised, on t = +x, b = +y, n = +z.
void expectNormalMapOnUprightQuad(const Scene& s, const Material& m, float scale) {
  ASSERT_GE(m.normalTexture, 0);
  EXPECT_EQ(m.normalScale, scale);
  const Texture& t = s.textures[size_t(m.normalTexture)];
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 1);
  expectRgb(t.texels[0], Rgb(k128, k128, 1.0f));  // not sRGB-decoded: that would be 0.2159
  expectRgb(t.texels[1], Rgb(k128, 1.0f, k128));
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.meshes[0].faces.size(), 1u);
  const float a = 2.0f * k128 - 1.0f;
  const Vec3 want = glm::normalize(Vec3(a * scale, scale, a));
  const Vec3 got = shadingNormal(s, 0, 0, Vec2(0.75f, 0.5f), Vec3(0, 0, 1));
  EXPECT_NEAR(got.x, want.x, 1e-6f);
  EXPECT_NEAR(got.y, want.y, 1e-6f);  // + y: green is the image's up
  EXPECT_NEAR(got.z, want.z, 1e-6f);
}

// A quad (0,0,0)-(1,1,0) facing +z whose uvs put the image upright on it: glTF's v = 0 is the
// image's top, at y = 1. One material "bumpy" with `normalTexture` {index 0, scale 0.25} and the
// same image as its base colour texture.
nlohmann::json gltfDoc(const nlohmann::json& image, const nlohmann::json& buffer) {
  nlohmann::json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                          {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}},
                          {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 32}}};
  if (image.contains("bufferView"))
    views.push_back({{"buffer", 0}, {"byteOffset", 92}, {"byteLength", image["length"]}});
  nlohmann::json img = image;
  img.erase("length");
  return {{"asset", {{"version", "2.0"}}},
          {"scene", 0},
          {"scenes", {{{"nodes", {0}}}}},
          {"nodes", {{{"mesh", 0}, {"name", "quad"}}}},
          {"meshes",
           {{{"name", "quad"},
             {"primitives",
              {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}}},
                {"indices", 1},
                {"material", 0}}}}}}},
          {"materials",
           {{{"name", "bumpy"},
             {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
             {"normalTexture", {{"index", 0}, {"scale", 0.25}}}}}},
          {"textures", {{{"source", 0}}}},
          {"images", {img}},
          {"buffers", {buffer}},
          {"bufferViews", views},
          {"accessors",
           {{{"bufferView", 0},
             {"componentType", 5126},
             {"count", 4},
             {"type", "VEC3"},
             {"min", {0, 0, 0}},
             {"max", {1, 1, 0}}},
            {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
            {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}}}};
}

std::string quadBuffer() {
  const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  const float uv[8] = {0, 1, 1, 1, 1, 0, 0, 0};  // glTF: v = 0 at the image's top
  std::string b(reinterpret_cast<const char*>(pos), sizeof pos);
  b.append(reinterpret_cast<const char*>(idx), sizeof idx);
  b.append(reinterpret_cast<const char*>(uv), sizeof uv);
  return b;  // 92 bytes
}

std::string le32(uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

void checkGltf(const Scene& s) {
  const Material& m = material(s, "bumpy");
  expectNormalMapOnUprightQuad(s, m, 0.25f);
  // The same image as base colour is a second texture, decoded from sRGB.
  ASSERT_GE(m.reflectanceTexture, 0);
  ASSERT_NE(m.reflectanceTexture, m.normalTexture);
  expectRgb(s.textures[size_t(m.reflectanceTexture)].texels[0],
            Rgb(srgbDecoded(k128), srgbDecoded(k128), 1.0f));
}

// h = x / 16 + y / 8 at texel (x, y) (row 0 at v = 0), stored as (h + 0.1, h - 0.1, h) so that only
// the channels' mean is h. Away from the wrap-around, central differences are exact: dh/du = 1/16
// and dh/dv = 1/8 per texel, so with multiplier 2 the normal is normalize(-1/8, -1/4, 1).
TEST(BumpMap, HeightRampGivesTheClosedFormNormal) {
  Texture h{.path = "h.png", .width = 8, .height = 4};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const float v = float(x) / 16.0f + float(y) / 8.0f;
      h.texels.push_back(Rgb(v + 0.1f, v - 0.1f, v));
    }
  const Texture n = normalMapFromHeight(h, 2.0f);
  ASSERT_EQ(n.width, 8);
  ASSERT_EQ(n.height, 4);
  EXPECT_EQ(n.path, "h.png");
  const Vec3 want = glm::normalize(Vec3(-0.125f, -0.25f, 1.0f));
  for (int y = 1; y < 3; ++y)
    for (int x = 1; x < 7; ++x) expectRgb(2.0f * n.texels[size_t(y * 8 + x)] - 1.0f, want);
  // Multiplier 0: flat, (0.5, 0.5, 1).
  expectRgb(normalMapFromHeight(h, 0.0f).texels[10], Vec3(0.5f, 0.5f, 1.0f));
}

TEST(BumpMap, NormalMapsAreToldFromHeightMaps) {
  Texture grey{.path = "g", .width = 2, .height = 1, .texels = {Rgb(0.2f), Rgb(0.9f)}};
  EXPECT_FALSE(looksLikeNormalMap(grey));
  EXPECT_TRUE(
      looksLikeNormalMap(normalMapFromHeight(grey, 1.0f)));  // (0.5, 0.5, 1)-ish: coloured, blue
  Texture brick{.path = "b", .width = 1, .height = 1, .texels = {Rgb(0.6f, 0.2f, 0.1f)}};
  EXPECT_FALSE(looksLikeNormalMap(brick));  // coloured, not blue
}

TEST(NormalMapImport, GltfNormalTextureAndScaleFromAnImageFile) {
  const fs::path dir = tmpDir("gltf");
  writeFile(dir / "quad.bin", quadBuffer());
  writeFile(dir / "n.png", normalPng());
  writeFile(dir / "quad.gltf",
            gltfDoc({{"uri", "n.png"}}, {{"uri", "quad.bin"}, {"byteLength", 92}}).dump(1));
  checkGltf(importMeshFile(dir / "quad.gltf"));
}

TEST(NormalMapImport, GlbWithTheImageEmbedded) {
  const fs::path dir = tmpDir("glb");
  const std::string image = normalPng();
  std::string bin = quadBuffer() + image;
  while (bin.size() % 4) bin += '\0';
  std::string json =
      gltfDoc({{"bufferView", 3}, {"mimeType", "image/png"}, {"length", image.size()}},
              {{"byteLength", bin.size()}})
          .dump();
  while (json.size() % 4) json += ' ';
  writeFile(dir / "quad.glb", "glTF" + le32(2) +
                                  le32(uint32_t(12 + 8 + json.size() + 8 + bin.size())) +
                                  le32(uint32_t(json.size())) + "JSON" + json +
                                  le32(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin);
  checkGltf(importMeshFile(dir / "quad.glb"));
}

// A quad facing +z with uvs (x, y) (OBJ's v is up, as luxel's), one material per `usemtl`.
std::string objQuads(const std::vector<std::string>& materials) {
  std::string obj = "mtllib m.mtl\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  for (size_t i = 0; i < materials.size(); ++i) {
    const std::string z = std::to_string(i);
    obj += "v 0 0 " + z + "\nv 1 0 " + z + "\nv 1 1 " + z + "\nv 0 1 " + z + "\nusemtl " +
           materials[i] + "\n";
    const size_t b = 4 * i + 1;
    obj += "f " + std::to_string(b) + "/1 " + std::to_string(b + 1) + "/2 " +
           std::to_string(b + 2) + "/3 " + std::to_string(b + 3) + "/4\n";
  }
  return obj;
}

TEST(NormalMapImport, ObjNormWithBumpMultiplier) {
  const fs::path dir = tmpDir("obj-norm");
  writeFile(dir / "n.png", normalPng());
  writeFile(dir / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnorm -bm 0.5 n.png\n");
  writeFile(dir / "m.obj", objQuads({"a"}));
  const Scene s = importMeshFile(dir / "m.obj");
  expectNormalMapOnUprightQuad(s, material(s, "a"), 0.5f);
}

// bump and map_Bump (Assimp's HEIGHT) become normal maps: the ramp's slope is 32/255 per texel
// along u, times -bm (2 for "b", the default 1 for "c"), so away from the wrap-around the normal
// is normalize(-slope, 0, 1). Read with the sRGB curve the slopes would differ column by column.
TEST(NormalMapImport, ObjBumpBecomesANormalMapScaledByBm) {
  const fs::path dir = tmpDir("obj-bump");
  writeFile(dir / "h.png", rampPng());
  writeFile(dir / "m.mtl",
            "newmtl b\nKd 0.5 0.5 0.5\nbump -bm 2 h.png\n"
            "newmtl c\nKd 0.5 0.5 0.5\nmap_Bump h.png\n"
            "newmtl d\nKd 0.5 0.5 0.5\nmap_Kd h.png\n");
  writeFile(dir / "m.obj", objQuads({"b", "c", "d"}));
  const Scene s = importMeshFile(dir / "m.obj");
  for (const auto& [name, bm] : {std::pair{"b", 2.0f}, std::pair{"c", 1.0f}}) {
    SCOPED_TRACE(name);
    const Material& m = material(s, name);
    ASSERT_GE(m.normalTexture, 0);
    EXPECT_EQ(m.normalScale, 1.0f);  // the multiplier is in the texels
    const Texture& t = s.textures[size_t(m.normalTexture)];
    ASSERT_EQ(t.width, 8);
    ASSERT_EQ(t.height, 4);
    const Vec3 want = 0.5f * glm::normalize(Vec3(-bm * 32.0f / 255.0f, 0.0f, 1.0f)) + 0.5f;
    for (int y = 0; y < 4; ++y)
      for (int x = 1; x < 7; ++x) expectRgb(t.texels[size_t(y * 8 + x)], want);
  }
  EXPECT_NE(material(s, "b").normalTexture, material(s, "c").normalTexture);
  // The same image as a colour texture: its own, decoded from sRGB.
  const Material& d = material(s, "d");
  EXPECT_EQ(d.normalTexture, -1);
  ASSERT_GE(d.reflectanceTexture, 0);
  expectRgb(s.textures[size_t(d.reflectanceTexture)].texels[3], Rgb(srgbDecoded(96.0f / 255.0f)));
  EXPECT_EQ(s.textures.size(), 3u);
}

TEST(NormalMapImport, BluishImageInABumpSlotIsReadAsANormalMap) {
  // Blender's OBJ exporter writes a normal map as map_Bump, with its strength as -bm.
  const fs::path dir = tmpDir("obj-bump-normal");
  writeFile(dir / "n.png", normalPng());
  writeFile(dir / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nmap_Bump -bm 0.8 n.png\n");
  writeFile(dir / "m.obj", objQuads({"a"}));
  const Scene s = importMeshFile(dir / "m.obj");
  expectNormalMapOnUprightQuad(s, material(s, "a"), 0.8f);
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned |= w.find("'a'") != std::string::npos && w.find("read as one") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(NormalMapImport, MissingOrBrokenMapIsAnErrorNamingFileAndMaterial) {
  const fs::path dir = tmpDir("obj-missing");
  writeFile(dir / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nnorm nowhere/n.png\n");
  writeFile(dir / "m.obj", objQuads({"a"}));
  std::string msg = errorOf([&] { importMeshFile(dir / "m.obj"); });
  EXPECT_NE(msg.find("m.obj: material 'a': texture 'nowhere/n.png' not found"), std::string::npos)
      << msg;

  writeFile(dir / "h.png", "not an image");
  writeFile(dir / "m.mtl", "newmtl a\nKd 0.5 0.5 0.5\nbump h.png\n");
  msg = errorOf([&] { importMeshFile(dir / "m.obj"); });
  EXPECT_NE(msg.find("m.obj: material 'a': texture '"), std::string::npos) << msg;
  EXPECT_NE(msg.find("h.png': not an image luxel reads"), std::string::npos) << msg;
}

// The scene file's keys: normalTexture read as data (beside the same file as a colour texture,
// decoded), normalScale, and null to remove; errors name the key.
TEST(NormalMapImport, SceneFileKeys) {
  const fs::path dir = tmpDir("scene-file");
  writeFile(dir / "img" / "n.png", normalPng());
  writeFile(dir / "m.mtl", "newmtl paint\nKd 0.5 0.5 0.5\n");
  writeFile(dir / "m.obj", objQuads({"paint"}));
  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "m.obj" } ],
    "materials": { "paint": { "texture": "img/n.png", "normalTexture": "img/n.png", "normalScale": 0.5 } } })");
  const Scene s = loadSceneFile(dir / "scene.json");
  const Material& m = material(s, "paint");
  expectNormalMapOnUprightQuad(s, m, 0.5f);
  ASSERT_GE(m.reflectanceTexture, 0);
  expectRgb(s.textures[size_t(m.reflectanceTexture)].texels[0],
            Rgb(srgbDecoded(k128), srgbDecoded(k128), 1.0f));

  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "m.obj" } ],
    "materials": { "paint": { "normalTexture": null, "normalScale": 0 } } })");
  const Scene none = loadSceneFile(dir / "scene.json");
  EXPECT_EQ(material(none, "paint").normalTexture, -1);
  EXPECT_EQ(material(none, "paint").normalScale, 0.0f);

  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "m.obj" } ],
    "materials": { "paint": { "normalTexture": "img/absent.png" } } })");
  std::string msg = errorOf([&] { loadSceneFile(dir / "scene.json"); });
  EXPECT_NE(msg.find("scene.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/materials/paint/normalTexture"), std::string::npos) << msg;
  EXPECT_NE(msg.find("absent.png"), std::string::npos) << msg;

  writeFile(dir / "scene.json", R"({ "meshes": [ { "file": "m.obj" } ],
    "materials": { "paint": { "normalScale": "strong" } } })");
  msg = errorOf([&] { loadSceneFile(dir / "scene.json"); });
  EXPECT_NE(msg.find("/materials/paint/normalScale"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a number"), std::string::npos) << msg;
}

TEST(NormalMapImport, ValidationAndSceneBytesKeepTheFields) {
  Scene s = builtinScene("cornell");
  s.textures.push_back(
      Texture{.path = "n", .width = 1, .height = 1, .texels = {Rgb(0.5f, 0.5f, 1.0f)}});
  s.materials[1].normalTexture = int(s.textures.size()) - 1;
  s.materials[1].normalScale =
      -0.75f;  // glTF puts no bound on the scale; negative turns bumps into dents
  s.validate();
  const Scene back = sceneFromBytes(sceneBytes(s));
  EXPECT_EQ(back.materials[1].normalTexture, s.materials[1].normalTexture);
  EXPECT_EQ(back.materials[1].normalScale, -0.75f);

  const std::string where = "scene '" + s.name + "': material '" + s.materials[1].name + "': ";
  Scene bad = s;
  bad.materials[1].normalTexture = int(s.textures.size());
  EXPECT_EQ(errorOf([&] { bad.validateMaterials(); }),
            where + "texture index " + std::to_string(s.textures.size()) + " out of range");
  bad = s;
  bad.materials[1].normalScale = std::nanf("");
  EXPECT_EQ(errorOf([&] { bad.validateMaterials(); }), where + "normal scale nan is not finite");
}

}  // namespace
}  // namespace luxel
