// Loaders reading from memory (importMesh, loadSceneJson, decodeTextureBytes) and the resource
// readers behind them: the same bytes must give the same Scene as the file-path loaders, side
// files must come from the ResourceReader, and bad bytes must give an Error naming the `name`.
//
// Values asserted here come from the fixtures written below: an OBJ whose MTL gives the lamp
// Kd 0.2 0.3 0.4 and Ke 4 2 1 and the wood Kd 0.5 0.25 0.125 with a 2x2 PNG; a glTF quad whose
// material has emissiveFactor (1, 0.5, 0.25) and KHR_materials_emissive_strength 8. The shared
// Cornell box facts (36 triangles, 8 materials, light Ke 17 12 4) are those test_import.cpp uses.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/resources.h"
#include "error_message.h"

namespace fs = std::filesystem;
using luxel::Error;
using luxel::FileResourceReader;
using luxel::MemoryResourceReader;
using luxel::ResourceReader;
using luxel::Rgb;
using luxel::Scene;
using luxel::Texture;
using luxel::Vec3;

namespace {

using luxel::test::errorOf;

fs::path tmpDir(const std::string& name) {
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "memory-load" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::span<const std::byte> bytesOf(const std::string& s) {
  return std::as_bytes(std::span<const char>(s.data(), s.size()));
}

// Every file under `dir`, by its path relative to `dir`: a model folder held in memory.
MemoryResourceReader memoryCopyOf(const fs::path& dir) {
  MemoryResourceReader reader;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file())
      reader.add(e.path().lexically_relative(dir).generic_string(), readFile(e.path()));
  return reader;
}

// Imports run in a child process (scene/import/child_process_import.h), where a RecordingReader's
// record stays: the tests that read the record import in-process.
class ImportsInProcess {
 public:
  ImportsInProcess() { setenv("LUXEL_IMPORT_IN_PROCESS", "1", 1); }
  ~ImportsInProcess() { unsetenv("LUXEL_IMPORT_IN_PROCESS"); }
};

// Passes through to another reader and remembers what it was asked to read.
class RecordingReader final : public ResourceReader {
 public:
  explicit RecordingReader(const ResourceReader& inner) : inner_(inner) {}
  std::optional<std::vector<std::byte>> read(std::string_view path) const override {
    reads.insert(std::string(path));
    return inner_.read(path);
  }
  bool exists(std::string_view path) const override { return inner_.exists(path); }
  std::vector<std::string> list(std::string_view folder) const override {
    return inner_.list(folder);
  }
  mutable std::set<std::string> reads;

 private:
  const ResourceReader& inner_;
};

// Finds everything and fails to read it, as a folder without read permission would.
class UnreadableReader final : public ResourceReader {
 public:
  std::optional<std::vector<std::byte>> read(std::string_view path) const override {
    throw Error("'" + std::string(path) + "': permission denied");
  }
  bool exists(std::string_view) const override { return true; }
};

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

float srgb(uint8_t v) {
  float c = v / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// An 8-bit RGB PNG, top row first, through stb_image_write (a different library from the decoder
// under test only in part; the pixel values asserted are the ones written here).
std::string png(int w, int h, const std::vector<std::array<uint8_t, 3>>& px) {
  std::string out;
  auto append = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size));
  };
  EXPECT_NE(stbi_write_png_to_func(append, &out, w, h, 3, px.data(), w * 3), 0);
  return out;
}

// Top row red, green; bottom row blue, grey 128. Stored bottom row first.
std::string twoByTwoPng() {
  return png(2, 2, {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {128, 128, 128}});
}

void expectTwoByTwo(const Texture& t) {
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 2);
  ASSERT_EQ(t.texels.size(), 4u);
  EXPECT_EQ(t.texels[0], Rgb(0, 0, 1));
  EXPECT_EQ(t.texels[1], Rgb(srgb(128)));
  EXPECT_NEAR(t.texels[1].x, 0.2158605f, 1e-6f);
  EXPECT_EQ(t.texels[2], Rgb(1, 0, 0));
  EXPECT_EQ(t.texels[3], Rgb(0, 1, 0));
}

template <class T, class Eq>
void expectSameVector(const std::vector<T>& a, const std::vector<T>& b, const std::string& what,
                      Eq eq) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (size_t i = 0; i < a.size(); ++i)
    if (!eq(a[i], b[i])) {
      ADD_FAILURE() << what << " differs first at " << i;
      return;
    }
}

template <class T>
void expectSameVector(const std::vector<T>& a, const std::vector<T>& b, const std::string& what) {
  expectSameVector(a, b, what, [](const T& x, const T& y) { return x == y; });
}

// Bit-for-bit the same scene, except Texture::path, which names where each came from.
void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.up, b.up);
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const luxel::Mesh &x = a.meshes[i], &y = b.meshes[i];
    const std::string what = "mesh " + x.name;
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.material, y.material) << what;
    expectSameVector(x.positions, y.positions, what + " positions");
    expectSameVector(x.uvs, y.uvs, what + " uvs");
    expectSameVector(x.lightmapUvs, y.lightmapUvs, what + " lightmap uvs");
    expectSameVector(x.faces, y.faces, what + " faces",
                     [](const luxel::Face& f, const luxel::Face& g) { return f.v == g.v; });
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    const luxel::Material &x = a.materials[i], &y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.reflectance, y.reflectance) << x.name;
    EXPECT_EQ(x.emission, y.emission) << x.name;
    EXPECT_EQ(x.reflectanceTexture, y.reflectanceTexture) << x.name;
    EXPECT_EQ(x.emissionTexture, y.emissionTexture) << x.name;
    EXPECT_EQ(x.twoSided, y.twoSided) << x.name;
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t i = 0; i < a.textures.size(); ++i) {
    EXPECT_EQ(a.textures[i].width, b.textures[i].width) << a.textures[i].path;
    EXPECT_EQ(a.textures[i].height, b.textures[i].height) << a.textures[i].path;
    expectSameVector(a.textures[i].texels, b.textures[i].texels, "texels of " + a.textures[i].path);
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    const luxel::Light &x = a.lights[i], &y = b.lights[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type) << x.name;
    EXPECT_EQ(x.color, y.color) << x.name;
    EXPECT_EQ(x.intensity, y.intensity) << x.name;
    EXPECT_EQ(x.position, y.position) << x.name;
    EXPECT_EQ(x.direction, y.direction) << x.name;
    EXPECT_EQ(x.innerConeAngle, y.innerConeAngle) << x.name;
    EXPECT_EQ(x.outerConeAngle, y.outerConeAngle) << x.name;
  }
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    const luxel::Camera &x = a.cameras[i], &y = b.cameras[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.eye, y.eye) << x.name;
    EXPECT_EQ(x.target, y.target) << x.name;
    EXPECT_EQ(x.up, y.up) << x.name;
    EXPECT_EQ(x.fovY, y.fovY) << x.name;
  }
  EXPECT_EQ(a.warnings, b.warnings);
}

struct Bounds {
  Vec3 lo{std::numeric_limits<float>::max()};
  Vec3 hi{-std::numeric_limits<float>::max()};
};

Bounds boundsOf(const Scene& s) {
  Bounds b;
  for (const luxel::Mesh& m : s.meshes)
    for (const Vec3& p : m.positions) {
      b.lo = glm::min(b.lo, p);
      b.hi = glm::max(b.hi, p);
    }
  return b;
}

// ---- fixtures -----------------------------------------------------------------------------------

// box.obj: a quad "lamp" at y = 2 and a triangle "floor" with uvs; box.mtl: lamp (Kd 0.2 0.3 0.4,
// Ke 4 2 1) and wood (Kd 0.5 0.25 0.125, map_Kd tex/wood.png).
const std::string kObj =
    "mtllib box.mtl\n"
    "o lamp\nv 0 2 0\nv 1 2 0\nv 1 2 1\nv 0 2 1\nusemtl lamp\nf 1 4 3 2\n"
    "o floor\nv 0 0 0\nv 4 0 0\nv 0 0 4\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl wood\nf 5/1 7/3 6/2\n";
const std::string kMtl =
    "newmtl lamp\nKd 0.2 0.3 0.4\nKe 4 2 1\n"
    "newmtl wood\nKd 0.5 0.25 0.125\nmap_Kd tex/wood.png\n";

void writeObjFixture(const fs::path& dir) {
  writeFile(dir / "box.obj", kObj);
  writeFile(dir / "box.mtl", kMtl);
  writeFile(dir / "tex" / "wood.png", twoByTwoPng());
}

MemoryResourceReader objFixtureInMemory() {
  MemoryResourceReader r;
  r.add("box.mtl", kMtl);
  r.add("tex/wood.png", twoByTwoPng());
  return r;
}

// The glTF fixture: one quad at z = 5 (uvs = xy), material "glow" (baseColorFactor 0.5 0.6 0.7,
// emissiveFactor 1 0.5 0.25, emissive strength 8, base colour texture `image`), a perspective
// camera (yfov 0.8, aspect 1.5) in node "cam" at (1, 2, 3). `bufferUri` empty: the GLB's buffer.
std::string gltfBuffer() {
  const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  const float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  std::string b(reinterpret_cast<const char*>(pos), sizeof pos);
  b.append(reinterpret_cast<const char*>(idx), sizeof idx);
  b.append(reinterpret_cast<const char*>(uv), sizeof uv);
  return b;  // 92 bytes
}

std::string gltfJson(const std::string& bufferUri, const std::string& image) {
  using nlohmann::json;
  json g = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_emissive_strength"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes",
       {{{"mesh", 0}, {"name", "quadnode"}, {"translation", {0, 0, 5}}},
        {{"camera", 0}, {"name", "cam"}, {"translation", {1, 2, 3}}}}},
      {"cameras",
       {{{"type", "perspective"},
         {"perspective", {{"yfov", 0.8}, {"aspectRatio", 1.5}, {"znear", 0.1}}}}}},
      {"meshes",
       {{{"name", "quad"},
         {"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}}},
            {"indices", 1},
            {"material", 0}}}}}}},
      {"materials",
       {{{"name", "glow"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 0.6, 0.7, 1.0}}, {"baseColorTexture", {{"index", 0}}}}},
         {"emissiveFactor", {1.0, 0.5, 0.25}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8.0}}}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", image}}}},
      {"buffers", {{{"byteLength", gltfBuffer().size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}},
        {{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 32}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}}}};
  if (!bufferUri.empty()) g["buffers"][0]["uri"] = bufferUri;
  return g.dump(1);
}

std::string le32(uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

std::string glb(const std::string& image) {
  std::string json = gltfJson("", image);
  while (json.size() % 4) json += ' ';
  std::string bin = gltfBuffer();
  while (bin.size() % 4) bin += '\0';
  return "glTF" + le32(2) + le32(uint32_t(12 + 8 + json.size() + 8 + bin.size())) +
         le32(uint32_t(json.size())) + "JSON" + json + le32(uint32_t(bin.size())) +
         std::string("BIN\0", 4) + bin;
}

void checkGltfValues(const Scene& s) {
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangleCount(), 2u);
  for (const Vec3& p : s.meshes[0].positions) EXPECT_EQ(p.z, 5.0f);
  ASSERT_EQ(s.materials.size(), 1u);
  const luxel::Material& m = s.materials[0];
  EXPECT_EQ(m.name, "glow");
  EXPECT_EQ(m.reflectance, Rgb(0.5f, 0.6f, 0.7f));
  // emissiveFactor * KHR_materials_emissive_strength: Assimp 5.2 drops the strength, so 8 here
  // proves gltf_extras read the JSON from the same bytes.
  EXPECT_EQ(m.emission, Rgb(8.0f, 4.0f, 2.0f));
  ASSERT_GE(m.reflectanceTexture, 0);
  expectTwoByTwo(s.textures[size_t(m.reflectanceTexture)]);
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, "cam");
  EXPECT_NEAR(s.cameras[0].fovY, 0.8f * 180.0f / 3.14159265f, 1e-4f);
  EXPECT_EQ(s.cameras[0].eye, Vec3(1, 2, 3));
}

}  // namespace

// ---- (e) textures -------------------------------------------------------------------------------

TEST(MemoryLoad, TextureFromBytesEqualsLoadTexture) {
  fs::path dir = tmpDir("texture");
  const std::string bytes = twoByTwoPng();
  writeFile(dir / "t.png", bytes);
  for (bool srgbDecode : {true, false}) {
    Texture fromFile = luxel::loadTexture(dir / "t.png", srgbDecode);
    Texture fromBytes = luxel::decodeTextureBytes(bytesOf(bytes), srgbDecode, "t.png");
    EXPECT_EQ(fromBytes.path, "t.png");
    EXPECT_EQ(fromBytes.width, fromFile.width);
    EXPECT_EQ(fromBytes.height, fromFile.height);
    expectSameVector(fromBytes.texels, fromFile.texels, "texels");
    if (srgbDecode) {
      expectTwoByTwo(fromBytes);
    } else {
      EXPECT_EQ(fromBytes.texels[1], Rgb(128.0f / 255.0f));
    }
  }
  // Radiance RGBE (128, 64, 32, e = 129): stb_image gives mantissa * 2^(e - 136), (1, 0.5, 0.25),
  // linear whatever `srgb` says.
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n";
  hdr += std::string("\x80\x40\x20\x81", 4);
  writeFile(dir / "t.hdr", hdr);
  Texture h = luxel::decodeTextureBytes(bytesOf(hdr), true, "sky");
  ASSERT_EQ(h.texels.size(), 1u);
  EXPECT_EQ(h.texels[0], Rgb(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(h.texels, luxel::loadTexture(dir / "t.hdr", true).texels);
}

TEST(MemoryLoad, BadTextureBytesNameTheName) {
  const std::string full = twoByTwoPng();
  for (const std::string& bad : {std::string(), std::string("not an image"),
                                 full.substr(0, full.size() / 2), full.substr(0, 8)}) {
    std::string msg = errorOf([&] { luxel::decodeTextureBytes(bytesOf(bad), true, "skin#3"); });
    EXPECT_TRUE(startsWith(msg, "texture 'skin#3': ")) << bad.size() << " bytes: " << msg;
  }
  EXPECT_EQ(errorOf([] { luxel::decodeTextureBytes({}, true, "none"); }),
            "texture 'none': file is empty");
}

// ---- resource readers ---------------------------------------------------------------------------

TEST(MemoryLoad, MemoryReaderNormalisesPaths) {
  MemoryResourceReader r;
  r.add("tex\\Wood.png", std::string("abc"));
  r.add("./top.mtl", std::string("d"));
  r.add("a/b/../c.bin", std::string(""));
  for (const char* p :
       {"tex/Wood.png", "tex\\Wood.png", "./tex/Wood.png", "tex//Wood.png", "x/../tex/Wood.png"}) {
    ASSERT_TRUE(r.exists(p)) << p;
    auto bytes = r.read(p);
    ASSERT_TRUE(bytes.has_value()) << p;
    EXPECT_EQ(bytes->size(), 3u) << p;
  }
  EXPECT_FALSE(r.exists("tex/wood.png"));  // exact case: the importer does the case fallback
  EXPECT_FALSE(r.read("Wood.png").has_value());
  EXPECT_TRUE(r.read("top.mtl").has_value());
  ASSERT_TRUE(r.read("a/c.bin").has_value());
  EXPECT_TRUE(r.read("a/c.bin")->empty());
  EXPECT_EQ(r.list(""), std::vector<std::string>{"top.mtl"});
  EXPECT_EQ(r.list("tex"), std::vector<std::string>{"Wood.png"});
  EXPECT_EQ(r.list("./a/"), std::vector<std::string>{"c.bin"});
  EXPECT_TRUE(r.list("nowhere").empty());
  EXPECT_EQ(r.describe("tex/Wood.png"), "tex/Wood.png");
}

TEST(MemoryLoad, FileReaderReadsUnderItsRoot) {
  fs::path dir = tmpDir("file-reader");
  writeFile(dir / "models" / "m.obj", "v 0 0 0\n");
  writeFile(dir / "shared" / "Wood.PNG", "xyz");
  FileResourceReader r(dir / "models");
  ASSERT_TRUE(r.read("m.obj").has_value());
  EXPECT_EQ(r.read("m.obj")->size(), 8u);
  EXPECT_TRUE(r.exists("../shared/Wood.PNG"));  // not a sandbox: as the path loaders resolved
  EXPECT_FALSE(r.exists("../shared/wood.png"));
  EXPECT_FALSE(r.read("absent.mtl").has_value());
  EXPECT_FALSE(r.read("").has_value());  // the root is a folder, not a file
  EXPECT_EQ(r.list("../shared"), std::vector<std::string>{"Wood.PNG"});
  EXPECT_EQ(r.describe("../shared/Wood.PNG"), (dir / "shared" / "Wood.PNG").string());
  // Absolute paths are read as they are.
  EXPECT_TRUE(r.exists((dir / "shared" / "Wood.PNG").string()));
}

// ---- (a) OBJ + MTL + texture --------------------------------------------------------------------

TEST(MemoryLoad, ObjMtlAndTextureFromMemoryMatchTheFile) {
  const ImportsInProcess inProcess;
  fs::path dir = tmpDir("obj");
  writeObjFixture(dir);
  const Scene fromFile = luxel::importMeshFile(dir / "box.obj");

  MemoryResourceReader memory = objFixtureInMemory();
  RecordingReader recorder(memory);
  // The same name as the file, so that every name and message matches too.
  const Scene fromMemory =
      luxel::importMesh(bytesOf(kObj), "obj", recorder, (dir / "box.obj").string());
  expectSameScene(fromMemory, fromFile);
  // The side files came from the reader, by paths relative to the main file.
  EXPECT_EQ(recorder.reads, (std::set<std::string>{"box.mtl", "tex/wood.png"}));

  // And the values are the fixture's, not just equal to each other.
  const Scene& s = fromMemory;
  EXPECT_EQ(s.name, "box");
  EXPECT_EQ(s.triangleCount(), 3u);
  EXPECT_EQ(s.faceCount(), 2u);
  ASSERT_EQ(s.materials.size(), 2u);
  const luxel::Material& lamp = s.materials[size_t(s.findMaterial("lamp"))];
  EXPECT_EQ(lamp.reflectance, Rgb(0.2f, 0.3f, 0.4f));
  EXPECT_EQ(lamp.emission, Rgb(4, 2, 1));
  EXPECT_EQ(lamp.reflectanceTexture, -1);
  const luxel::Material& wood = s.materials[size_t(s.findMaterial("wood"))];
  EXPECT_EQ(wood.reflectance, Rgb(0.5f, 0.25f, 0.125f));
  EXPECT_EQ(wood.emission, Rgb(0));
  ASSERT_EQ(wood.reflectanceTexture, 0);
  ASSERT_EQ(s.textures.size(), 1u);
  expectTwoByTwo(s.textures[0]);
  EXPECT_EQ(s.textures[0].path, "tex/wood.png");  // what the memory reader calls it
  EXPECT_EQ(fromFile.textures[0].path, (dir / "tex" / "wood.png").string());
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "lamp");
  EXPECT_EQ(s.meshes[0].positions, (std::vector<Vec3>{{0, 2, 0}, {0, 2, 1}, {1, 2, 1}, {1, 2, 0}}));
  ASSERT_EQ(s.meshes[0].faces.size(), 1u);
  EXPECT_EQ(s.meshes[0].faces[0].v, (std::array<uint32_t, 4>{0, 1, 2, 3}));
  EXPECT_EQ(s.meshes[1].name, "floor");
  EXPECT_EQ(s.meshes[1].positions, (std::vector<Vec3>{{0, 0, 0}, {0, 0, 4}, {4, 0, 0}}));
  EXPECT_EQ(s.meshes[1].uvs, (std::vector<luxel::Vec2>{{0, 0}, {0, 1}, {1, 0}}));
}

TEST(MemoryLoad, NameAndHintAreIndependentOfWhereBytesLive) {
  MemoryResourceReader memory = objFixtureInMemory();
  // No extension on the name: the hint picks the importer (leading dot and case ignored). The
  // name's folder part only names things; side files still come from the reader's root.
  for (const char* hint : {"obj", ".OBJ"}) {
    Scene s = luxel::importMesh(bytesOf(kObj), hint, memory, "uploads/7f3a");
    EXPECT_EQ(s.name, "7f3a") << hint;
    EXPECT_EQ(s.materials.size(), 2u) << hint;
    EXPECT_EQ(s.textures.size(), 1u) << hint;
  }
  std::string msg =
      errorOf([&] { luxel::importMesh(bytesOf(kObj), "obj/../x", memory, "upload"); });
  EXPECT_EQ(msg, "upload: format hint 'obj/../x' is not a file extension");
}

TEST(MemoryLoad, TextureLookupMatchesTheFileLoader) {
  // Backslashes and the wrong letter case (as Sponza's MTL has them), a percent-encoded name and
  // "./": all found the same way in memory as on disk.
  const std::string obj =
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
      "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\nusemtl c\nf 3/3 2/2 1/1\n";
  const std::string mtl =
      "newmtl a\nKd 1 1 1\nmap_Kd maps\\WOOD.png\n"
      "newmtl b\nKd 1 1 1\nmap_Kd ./maps/wood.png\n"
      "newmtl c\nKd 1 1 1\nmap_Kd maps/my%20stone.png\n";
  fs::path dir = tmpDir("texture-lookup");
  writeFile(dir / "m.obj", obj);
  writeFile(dir / "m.mtl", mtl);
  writeFile(dir / "maps" / "wood.png", twoByTwoPng());
  writeFile(dir / "maps" / "my stone.png", png(1, 1, {{255, 255, 255}}));
  const Scene fromFile = luxel::importMeshFile(dir / "m.obj");
  MemoryResourceReader memory = memoryCopyOf(dir);
  const Scene fromMemory = luxel::importMesh(bytesOf(obj), "obj", memory, (dir / "m.obj").string());
  expectSameScene(fromMemory, fromFile);
  // a and b share one decoded texture; c has its own.
  ASSERT_EQ(fromMemory.textures.size(), 2u);
  EXPECT_EQ(fromMemory.textures[0].path, "maps/wood.png");
  EXPECT_EQ(fromMemory.textures[1].path, "maps/my stone.png");
  EXPECT_EQ(fromMemory.materials[0].reflectanceTexture, 0);
  EXPECT_EQ(fromMemory.materials[1].reflectanceTexture, 0);
  EXPECT_EQ(fromMemory.materials[2].reflectanceTexture, 1);
}

// ---- (b) glTF with an external buffer, and GLB --------------------------------------------------

TEST(MemoryLoad, GltfWithExternalBufferFromMemoryMatchesTheFile) {
  const ImportsInProcess inProcess;
  fs::path dir = tmpDir("gltf");
  const std::string json = gltfJson("buffers/quad.bin", "tex/my%20tex.png");
  writeFile(dir / "scene.gltf", json);
  writeFile(dir / "buffers" / "quad.bin", gltfBuffer());
  writeFile(dir / "tex" / "my tex.png", twoByTwoPng());
  const Scene fromFile = luxel::importMeshFile(dir / "scene.gltf");
  checkGltfValues(fromFile);

  MemoryResourceReader memory;
  memory.add("buffers/quad.bin", gltfBuffer());
  memory.add("tex/my tex.png", twoByTwoPng());
  RecordingReader recorder(memory);
  const Scene fromMemory =
      luxel::importMesh(bytesOf(json), "gltf", recorder, (dir / "scene.gltf").string());
  expectSameScene(fromMemory, fromFile);
  checkGltfValues(fromMemory);
  EXPECT_EQ(recorder.reads, (std::set<std::string>{"buffers/quad.bin", "tex/my tex.png"}));

  // A bare name with a folder: the buffer is still looked up relative to the main file.
  Scene named = luxel::importMesh(bytesOf(json), "gltf", memory, "in/flight");
  EXPECT_EQ(named.name, "flight");
  checkGltfValues(named);
}

TEST(MemoryLoad, GlbFromMemoryMatchesTheFile) {
  const ImportsInProcess inProcess;
  fs::path dir = tmpDir("glb");
  const std::string bytes = glb("tex/t.png");
  writeFile(dir / "scene.glb", bytes);
  writeFile(dir / "tex" / "t.png", twoByTwoPng());
  const Scene fromFile = luxel::importMeshFile(dir / "scene.glb");
  checkGltfValues(fromFile);

  MemoryResourceReader memory;
  memory.add("tex/t.png", twoByTwoPng());
  RecordingReader recorder(memory);
  const Scene fromMemory =
      luxel::importMesh(bytesOf(bytes), "glb", recorder, (dir / "scene.glb").string());
  expectSameScene(fromMemory, fromFile);
  checkGltfValues(fromMemory);
  EXPECT_EQ(recorder.reads, (std::set<std::string>{"tex/t.png"}));
}

// ---- (b) the shared scenes, read into memory ----------------------------------------------------

#define SKIP_IF_MISSING(path) \
  if (!fs::exists(path))      \
  GTEST_SKIP() << (path).string() << " is missing: unzip ../shared/scenes/*.zip there"

TEST(MemoryLoad, CornellBoxFromMemoryMatchesTheFile) {
  const fs::path dir = fs::path(LUXEL_TEST_SCENES) / "mcguire-cornell-box";
  const fs::path path = dir / "CornellBox-Original.obj";
  SKIP_IF_MISSING(path);
  const Scene fromFile = luxel::importMeshFile(path);
  MemoryResourceReader memory;
  memory.add("CornellBox-Original.mtl", readFile(dir / "CornellBox-Original.mtl"));
  const std::string obj = readFile(path);
  const Scene fromMemory =
      luxel::importMesh(bytesOf(obj), "obj", memory, "CornellBox-Original.obj");
  EXPECT_EQ(fromMemory.triangleCount(), 32u);  // 36 in the file, less two coincident quads (test_import.cpp)
  EXPECT_EQ(fromFile.triangleCount(), 32u);
  EXPECT_EQ(fromMemory.faceCount(), fromFile.faceCount());
  EXPECT_EQ(fromMemory.materials.size(), 8u);
  EXPECT_EQ(fromMemory.materials[size_t(fromMemory.findMaterial("light"))].emission,
            Rgb(17, 12, 4));
  Bounds a = boundsOf(fromMemory), b = boundsOf(fromFile);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  expectSameScene(fromMemory, fromFile);
}

TEST(MemoryLoad, SponzaFromMemoryMatchesTheFile) {
  // Sponza's MTL gets the case of its JPEG names wrong: the memory reader's list() must give the
  // importer the same fallback as the folder on disk.
  const fs::path dir = fs::path(LUXEL_TEST_SCENES) / "dabrovic-sponza";
  const fs::path path = dir / "sponza.obj";
  SKIP_IF_MISSING(path);
  const Scene fromFile = luxel::importMeshFile(path);
  MemoryResourceReader memory = memoryCopyOf(dir);
  const std::string obj = readFile(path);
  const Scene fromMemory = luxel::importMesh(bytesOf(obj), "obj", memory, path.string());
  EXPECT_EQ(fromMemory.triangleCount(), 66446u);  // 66,450 in the file, less 4 coincident copies (test_import.cpp)
  EXPECT_GT(fromMemory.textures.size(), 0u);
  Bounds a = boundsOf(fromMemory), b = boundsOf(fromFile);
  EXPECT_EQ(a.lo, b.lo);
  EXPECT_EQ(a.hi, b.hi);
  expectSameScene(fromMemory, fromFile);
}

// ---- (c) scene JSON -----------------------------------------------------------------------------

TEST(MemoryLoad, SceneJsonWithBaseFolderMatchesTheFile) {
  fs::path dir = tmpDir("scene-json");
  writeObjFixture(dir / "models");
  writeFile(dir / "maps" / "w.png", png(1, 1, {{255, 255, 255}}));
  const std::string text = R"({
    // comments are allowed, as in files
    "meshes": [ { "file": "models/box.obj", "translate": [10, 0, 0], "scale": 2 } ],
    "materials": { "lamp": { "emissionStrength": 3 },
                   "paint": { "reflectance": 0.5, "texture": "maps/w.png" } },
    "lights": [ { "type": "point", "position": [1, 2, 3], "intensity": 5 } ],
    "cameras": [ { "name": "main", "eye": [0, 1, 5], "target": [0, 1, 0], "fov": 40 } ]
  })";
  writeFile(dir / "scene.json", text);
  const Scene fromFile = luxel::loadSceneFile(dir / "scene.json");
  const Scene fromText = luxel::loadSceneJson(text, dir, (dir / "scene.json").string());
  expectSameScene(fromText, fromFile);

  // The values: the box scaled by 2 and moved by +10 in x; the lamp's Ke 4 2 1 times 3.
  const Scene& s = fromText;
  EXPECT_EQ(s.name, "scene");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].positions[2], Vec3(12, 4, 2));
  EXPECT_EQ(s.materials[size_t(s.findMaterial("lamp"))].emission, Rgb(12, 6, 3));
  const luxel::Material& paint = s.materials[size_t(s.findMaterial("paint"))];
  EXPECT_EQ(paint.reflectance, Rgb(0.5f));
  ASSERT_GE(paint.reflectanceTexture, 0);
  EXPECT_EQ(s.textures[size_t(paint.reflectanceTexture)].texels, std::vector<Rgb>{Rgb(1.0f)});
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].position, Vec3(1, 2, 3));
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].fovY, 40.0f);

  // Another name: the scene is named after its stem, and the base folder alone decides where
  // relative paths point (the working directory is not `dir`).
  Scene other = luxel::loadSceneJson(text, dir, "inline.json");
  EXPECT_EQ(other.name, "inline");
  EXPECT_EQ(other.triangleCount(), s.triangleCount());
  std::string msg = errorOf([&] { luxel::loadSceneJson(text, dir / "elsewhere", "inline.json"); });
  EXPECT_TRUE(startsWith(msg, "inline.json: /meshes/0/file: ")) << msg;
  EXPECT_NE(msg.find("box.obj: no such file"), std::string::npos) << msg;
}

// ---- (d) bad bytes: an Error naming the name, never a crash -------------------------------------

TEST(MemoryLoad, EmptyBytesNameTheName) {
  MemoryResourceReader none;
  for (const char* hint : {"obj", "gltf", "glb", "ply", "fbx", "dae", "stl", ""}) {
    std::string msg = errorOf([&] { luxel::importMesh({}, hint, none, "nothing"); });
    EXPECT_TRUE(startsWith(msg, "nothing: ")) << hint << ": " << msg;
  }
  std::string msg = errorOf([] { luxel::loadSceneJson("", ".", "blank.json"); });
  EXPECT_TRUE(startsWith(msg, "blank.json: invalid JSON at byte 1: ")) << msg;
}

TEST(MemoryLoad, TruncatedGlbNamesTheName) {
  const std::string full = glb("tex/t.png");
  MemoryResourceReader memory;
  memory.add("tex/t.png", twoByTwoPng());
  ASSERT_EQ(luxel::importMesh(bytesOf(full), "glb", memory, "ok.glb").triangleCount(), 2u);
  for (size_t keep : {full.size() - 1, full.size() - 40, full.size() / 2, size_t(30), size_t(20),
                      size_t(12), size_t(5)}) {
    const std::string cut = full.substr(0, keep);
    std::string msg = errorOf([&] { luxel::importMesh(bytesOf(cut), "glb", memory, "cut.glb"); });
    EXPECT_TRUE(startsWith(msg, "cut.glb: ")) << keep << " bytes: " << msg;
  }
}

TEST(MemoryLoad, GarbageNamesTheName) {
  MemoryResourceReader none;
  uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (size_t size : {size_t(1), size_t(64), size_t(4096)}) {
    std::string garbage;
    for (size_t i = 0; i < size; ++i) garbage += char(next() >> 24);
    for (const char* hint : {"obj", "gltf", "glb", "ply", "fbx", "dae", ""}) {
      std::string msg = errorOf([&] { luxel::importMesh(bytesOf(garbage), hint, none, "noise"); });
      EXPECT_TRUE(startsWith(msg, "noise: ")) << hint << ", " << size << " bytes: " << msg;
    }
  }
  // Text that starts like each format and then goes wrong.
  for (auto [hint, text] : std::vector<std::pair<const char*, std::string>>{
           {"gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {"},
           {"gltf", "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"byteLength\": 1e30}]}"},
           {"glb", std::string("glTF\x02\0\0\0garbage garbage garbage garbage", 39)},
           {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1\n"},
           {"obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n"},
           {"dae", "<?xml version=\"1.0\"?><COLLADA version=\"1.4.1\"><library_geometries>"}}) {
    std::string msg = errorOf([&] { luxel::importMesh(bytesOf(text), hint, none, "partial"); });
    EXPECT_TRUE(startsWith(msg, "partial: ")) << hint << ": " << msg;
  }
}

TEST(MemoryLoad, JsonSyntaxErrorNamesTheName) {
  std::string msg = errorOf([] { luxel::loadSceneJson("{ \"meshes\": [ }", ".", "typo.json"); });
  EXPECT_TRUE(startsWith(msg, "typo.json: invalid JSON at byte 15: ")) << msg;
  EXPECT_NE(msg.find("line 1, column 15"), std::string::npos) << msg;
  msg = errorOf([] { luxel::loadSceneJson(R"({ "lights": [ { "type": "spto" } ] })", ".", "t"); });
  EXPECT_EQ(msg,
            "t: /lights/0/type: unknown light type 'spto' (expected point, spot, directional, sky, "
            "cie-overcast)");
}

TEST(MemoryLoad, MissingSideFilesNameTheNameAndTheFile) {
  MemoryResourceReader empty;
  // A glTF buffer.
  const std::string json = gltfJson("buffers/quad.bin", "tex/t.png");
  std::string msg = errorOf([&] { luxel::importMesh(bytesOf(json), "gltf", empty, "q.gltf"); });
  EXPECT_TRUE(startsWith(msg, "q.gltf: ")) << msg;
  EXPECT_NE(msg.find("buffers/quad.bin"), std::string::npos) << msg;
  // A texture, from a .glb and from an OBJ's MTL.
  msg = errorOf([&] { luxel::importMesh(bytesOf(glb("tex/t.png")), "glb", empty, "q.glb"); });
  EXPECT_EQ(msg, "q.glb: material 'glow': texture 'tex/t.png' not found (looked for 'tex/t.png')");
  MemoryResourceReader mtlOnly;
  mtlOnly.add("box.mtl", kMtl);
  msg = errorOf([&] { luxel::importMesh(bytesOf(kObj), "obj", mtlOnly, "box.obj"); });
  EXPECT_EQ(msg,
            "box.obj: material 'wood': texture 'tex/wood.png' not found (looked for "
            "'tex/wood.png')");
  // A texture that the reader finds but cannot read: its reason, after the same prefix.
  msg = errorOf(
      [&] { luxel::importMesh(bytesOf(glb("tex/t.png")), "glb", UnreadableReader(), "u.glb"); });
  EXPECT_EQ(msg, "u.glb: material 'glow': texture 'tex/t.png': permission denied");
  // A texture whose bytes are not an image.
  MemoryResourceReader broken;
  broken.add("tex/t.png", std::string("not a png"));
  msg = errorOf([&] { luxel::importMesh(bytesOf(glb("tex/t.png")), "glb", broken, "b.glb"); });
  EXPECT_TRUE(startsWith(msg, "b.glb: material 'glow': texture 'tex/t.png': ")) << msg;
  // A missing .mtl is not an error, from a file or from memory: Assimp imports the geometry with
  // its default material.
  Scene noMtl = luxel::importMesh(bytesOf(kObj), "obj", empty, "box.obj");
  EXPECT_EQ(noMtl.triangleCount(), 3u);
  EXPECT_TRUE(noMtl.textures.empty());
}
