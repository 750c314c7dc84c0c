// Mesh import through Assimp, textures and quad recovery.
//
// Scene facts used here come from the files themselves: CornellBox-Original.obj has 18 quads
// (36 triangles) using 8 materials of CornellBox-Original.mtl, whose light has Ke 17 12 4 and
// whose leftWall has Kd 0.63 0.065 0.05. Triangle counts of the other scenes were counted from
// their 'f' lines (a polygon of n vertices is n - 2 triangles).
#include <gtest/gtest.h>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "luxel/error.h"
#include "luxel/import.h"
#include "scene/import/quads.h"
#include "error_message.h"

namespace fs = std::filesystem;
using luxel::Error;
using luxel::Face;
using luxel::Rgb;
using luxel::Scene;
using luxel::Texture;
using luxel::Vec2;
using luxel::Vec3;

namespace {

using luxel::test::errorOf;

constexpr float kPi = 3.14159265358979f;

fs::path tmpDir(const std::string& name) {
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "import" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

fs::path cornellPath() {
  return fs::path(LUXEL_TEST_SCENES) / "mcguire-cornell-box" / "CornellBox-Original.obj";
}

// The OBJ the format round trips start from: McGuire's CornellBox-Original when the shared scenes
// are unzipped, else the built-in Cornell box written out as OBJ/MTL here, so that every format
// is still exercised on a machine without ../shared.
struct RoundTripSource {
  fs::path obj;
  size_t triangles;
  size_t materials;
  std::string red;  // the red wall's material name
};

RoundTripSource roundTripSource() {
  // 36 triangles in the file, but each box's last face repeats the corners of another of its
  // faces (the short box's "Bottom Face" is f -12 -11 -10 -9, its right face; the tall box's is
  // f -8 -7 -6 -5, its back face): coincident copies, which the importer removes
  // (scene/coincident_faces.h), so 32.
  if (fs::exists(cornellPath())) return {cornellPath(), 32, 8, "leftWall"};
  Scene cornell = luxel::builtinScene("cornell");
  fs::path dir = fs::path(LUXEL_TEST_TMP) / "import" / "builtin-cornell-obj";
  fs::create_directories(dir);
  std::ofstream mtl(dir / "cornell.mtl"), obj(dir / "cornell.obj");
  for (const luxel::Material& m : cornell.materials)
    mtl << "newmtl " << m.name << "\nKd " << m.reflectance.x << " " << m.reflectance.y << " "
        << m.reflectance.z << "\nKe " << m.emission.x << " " << m.emission.y << " " << m.emission.z
        << "\n";
  obj << "mtllib cornell.mtl\n";
  size_t base = 1;
  for (const luxel::Mesh& mesh : cornell.meshes) {
    obj << "o " << mesh.name << "\nusemtl " << cornell.materials[mesh.material].name << "\n";
    for (const Vec3& v : mesh.positions) obj << "v " << v.x << " " << v.y << " " << v.z << "\n";
    for (const luxel::Face& f : mesh.faces) {
      obj << "f";
      for (int i = 0; i < f.vertexCount(); ++i) obj << " " << base + f.v[size_t(i)];
      obj << "\n";
    }
    base += mesh.positions.size();
  }
  return {dir / "cornell.obj", cornell.triangleCount(), cornell.materials.size(), "red"};
}

#define SKIP_IF_MISSING(path) \
  if (!fs::exists(path))      \
  GTEST_SKIP() << (path).string() << " is missing: unzip ../shared/scenes/*.zip there"

void expectRgb(Rgb got, Rgb want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

void expectVec(Vec3 got, Vec3 want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

const luxel::Material& material(const Scene& s, const std::string& name) {
  int i = s.findMaterial(name);
  EXPECT_GE(i, 0) << "no material " << name;
  static const luxel::Material kNone;
  return i >= 0 ? s.materials[size_t(i)] : kNone;
}

// ---- tiny image writers, so that tests do not depend on an encoder -----------------------------

// Binary PPM (P6), top row first.
std::string ppm(int w, int h, const std::vector<std::array<uint8_t, 3>>& px) {
  std::string s = "P6\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n";
  for (const auto& p : px) s.append(reinterpret_cast<const char*>(p.data()), 3);
  return s;
}

uint32_t crc32(const std::string& data) {
  uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : data) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

std::string be32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

// An 8-bit RGB PNG with one stored (uncompressed) deflate block, top row first.
std::string png(int w, int h, const std::vector<std::array<uint8_t, 3>>& px) {
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw += '\0';  // filter: none
    for (int x = 0; x < w; ++x)
      raw.append(reinterpret_cast<const char*>(px[size_t(y * w + x)].data()), 3);
  }
  uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  std::string z = "\x78\x01";
  uint16_t len = uint16_t(raw.size());
  z += '\x01';
  z += char(len & 0xFF);
  z += char(len >> 8);
  z += char(~len & 0xFF);
  z += char((~len >> 8) & 0xFF);
  z += raw + be32((b << 16) | a);
  auto chunk = [](const std::string& type, const std::string& data) {
    return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
  };
  std::string ihdr = be32(uint32_t(w)) + be32(uint32_t(h)) + std::string("\x08\x02\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", z) +
         chunk("IEND", "");
}

std::string base64(const std::string& in) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8) | uint8_t(in[i + 2]);
    for (int k = 3; k >= 0; --k) out += kTable[(v >> (6 * k)) & 63];
  }
  if (i + 1 == in.size()) {
    uint32_t v = uint8_t(in[i]) << 16;
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    uint32_t v = (uint8_t(in[i]) << 16) | (uint8_t(in[i + 1]) << 8);
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += kTable[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

float srgb(uint8_t v) {
  float c = v / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

// ---- Texture ------------------------------------------------------------------------------------

// Bottom row (v = 0 side): t00 = black, t10 = red; top row: t01 = green, t11 = blue. Texel centres
// sit at (i + 0.5) / 2, so at (u, v) the weights are fx = 2u - 0.5, fy = 2v - 0.5 and the result is
// (1-fy)((1-fx) t00 + fx t10) + fy((1-fx) t01 + fx t11).
Texture twoByTwo() {
  Texture t;
  t.width = 2;
  t.height = 2;
  t.texels = {Rgb(0, 0, 0), Rgb(1, 0, 0), Rgb(0, 1, 0), Rgb(0, 0, 1)};
  return t;
}

TEST(Texture, BilinearMatchesClosedForm) {
  Texture t = twoByTwo();
  // (u, v) = (0.375, 0.625): fx = 0.25, fy = 0.75 -> r = 0.25 * 0.25, g = 0.75 * 0.75,
  // b = 0.75 * 0.25.
  expectRgb(t.sample(Vec2(0.375f, 0.625f)), Rgb(0.0625f, 0.5625f, 0.1875f));
  // Texel centres return the texel.
  expectRgb(t.sample(Vec2(0.25f, 0.25f)), Rgb(0, 0, 0));
  expectRgb(t.sample(Vec2(0.75f, 0.25f)), Rgb(1, 0, 0));
  expectRgb(t.sample(Vec2(0.25f, 0.75f)), Rgb(0, 1, 0));
  expectRgb(t.sample(Vec2(0.75f, 0.75f)), Rgb(0, 0, 1));
  // The centre is the mean of the four.
  expectRgb(t.sample(Vec2(0.5f, 0.5f)), Rgb(0.25f, 0.25f, 0.25f));
}

TEST(Texture, WrapsAround) {
  Texture t = twoByTwo();
  Rgb inside = t.sample(Vec2(0.375f, 0.625f));
  expectRgb(t.sample(Vec2(1.375f, -0.375f)), inside);
  expectRgb(t.sample(Vec2(-0.625f, 2.625f)), inside);
  expectRgb(t.sample(Vec2(7.375f, 3.625f)), inside);
  // At the corner the four texels are blended across both edges.
  expectRgb(t.sample(Vec2(0.0f, 0.0f)), Rgb(0.25f, 0.25f, 0.25f));
  // u = 0 between the two rows' centres at v = 0.25: half t00, half t10 (wrapped neighbour).
  expectRgb(t.sample(Vec2(0.0f, 0.25f)), Rgb(0.5f, 0.0f, 0.0f));
  // Non-finite coordinates do not crash.
  Rgb nan = t.sample(Vec2(std::nanf(""), INFINITY));
  EXPECT_TRUE(std::isfinite(nan.x));
}

TEST(Texture, Mean) { expectRgb(twoByTwo().mean(), Rgb(0.25f, 0.25f, 0.25f)); }

TEST(Texture, LoadsPpmFlippedAndDecodesSrgb) {
  fs::path dir = tmpDir("texture");
  // 1 x 2 image: top row (first in the file) red 255, bottom row grey 128.
  writeFile(dir / "t.ppm", ppm(1, 2, {{255, 0, 0}, {128, 128, 128}}));
  Texture srgbTex = luxel::loadTexture(dir / "t.ppm", true);
  ASSERT_EQ(srgbTex.width, 1);
  ASSERT_EQ(srgbTex.height, 2);
  float grey = srgb(128);  // 0.2158605
  EXPECT_NEAR(grey, 0.2158605f, 1e-6f);
  expectRgb(srgbTex.texels[0], Rgb(grey));  // bottom row first
  expectRgb(srgbTex.texels[1], Rgb(1, 0, 0));
  Texture linear = luxel::loadTexture(dir / "t.ppm", false);
  expectRgb(linear.texels[0], Rgb(128.0f / 255.0f));
}

TEST(Texture, LoadsPngAndHdr) {
  fs::path dir = tmpDir("texture-png-hdr");
  writeFile(dir / "t.png", png(2, 1, {{0, 0, 255}, {255, 255, 255}}));
  Texture t = luxel::loadTexture(dir / "t.png", true);
  ASSERT_EQ(t.width, 2);
  expectRgb(t.texels[0], Rgb(0, 0, 1));
  expectRgb(t.texels[1], Rgb(1, 1, 1));

  // Radiance RGBE: (128, 64, 32, e=129) is (1, 0.5, 0.25) * 2^(129-128-7)... stb_image computes
  // mantissa * 2^(e - 136): 128 * 2^-7 = 1, 64 * 2^-7 = 0.5, 32 * 2^-7 = 0.25. Linear: srgb is
  // ignored.
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n";
  hdr += std::string("\x80\x40\x20\x81", 4);
  writeFile(dir / "t.hdr", hdr);
  Texture h = luxel::loadTexture(dir / "t.hdr", true);
  ASSERT_EQ(h.width, 1);
  expectRgb(h.texels[0], Rgb(1.0f, 0.5f, 0.25f));
}

// 16-bit PNMs with one or two channels: stb_image, asked for RGB, wrote them through its 8-bit
// converter into half the buffer it then read as 16-bit (a heap overflow fuzz-texture found).
TEST(Texture, SixteenBitGreyPnmReadsItsOwnValues) {
  // 2 x 1 grey, maxval 65535, big-endian samples 0x0000 and 0xFFFF; then the same with alpha.
  const std::string grey = std::string("P5\n2 1\n65535\n") + std::string("\x00\x00\xff\xff", 4);
  Texture g = luxel::decodeTextureBytes(std::as_bytes(std::span<const char>(grey)), false, "grey.pgm");
  ASSERT_EQ(g.width, 2);
  ASSERT_EQ(g.height, 1);
  expectRgb(g.texels[0], Rgb(0, 0, 0));
  expectRgb(g.texels[1], Rgb(1, 1, 1));
  // The fuzzer's input itself: maxval 256 makes it 16-bit; it decodes or is refused, within bounds.
  const std::string found("\x50\x35\x0a\x32\x20\x31\x0a\x32\x35\x36\x0a\x32\x20\x31\x00\x23\x00\x00\x00\x00\x00\x3f\x52\x46\x0a\x32\x33\x31\x4f\xb6\x52\x4d\x41\x54\x3d\x33\x32\x2d\x62\x69\x00\x23\x3f\x52\x74\x5f\x72\x6c\x41\x44", 50);
  try {
    const Texture t = luxel::decodeTextureBytes(std::as_bytes(std::span<const char>(found)), true, "found.pnm");
    EXPECT_EQ(t.texels.size(), size_t(t.width) * size_t(t.height));
  } catch (const luxel::Error& e) {
    EXPECT_NE(std::string(e.what()).find("found.pnm"), std::string::npos) << e.what();
  }
}

TEST(Texture, BadFilesThrowNamingThePath) {
  fs::path dir = tmpDir("texture-bad");
  writeFile(dir / "garbage.png", "this is not an image at all");
  std::string msg = errorOf([&] { luxel::loadTexture(dir / "garbage.png", true); });
  EXPECT_NE(msg.find("garbage.png"), std::string::npos) << msg;
  msg = errorOf([&] { luxel::loadTexture(dir / "absent.png", true); });
  EXPECT_NE(msg.find("absent.png"), std::string::npos) << msg;
}

// ---- quad recovery ------------------------------------------------------------------------------

TEST(QuadRecovery, MergesPlanarConvexPairsOnly) {
  std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  // Assimp's split of (0,1,2,3).
  std::vector<Face> f = luxel::recoverQuads(p, {{{0, 1, 2}}, {{0, 2, 3}}});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].v, (std::array<uint32_t, 4>{0, 1, 2, 3}));

  // Not the (a,b,c),(a,c,d) pattern: two triangles.
  f = luxel::recoverQuads(p, {{{0, 1, 2}}, {{2, 3, 0}}});
  ASSERT_EQ(f.size(), 2u);
  EXPECT_TRUE(f[0].isTriangle());
  EXPECT_EQ(f[1].v, (std::array<uint32_t, 4>{2, 3, 0, 0}));

  // Non-planar: lift the fourth corner.
  std::vector<Vec3> bent = p;
  bent[3].z = 0.1f;
  EXPECT_EQ(luxel::recoverQuads(bent, {{{0, 1, 2}}, {{0, 2, 3}}}).size(), 2u);

  // Concave (a dart) with the reflex corner 0 first, as Assimp fans a concave quad from it:
  // quad (0,3,2,1) is counter-clockwise, both halves face +z, but corner 0 turns the wrong way.
  std::vector<Vec3> dart = {{0.5f, 0.4f, 0}, {0, 0, 0}, {0.5f, 1, 0}, {1, 0, 0}};
  std::vector<Face> d = luxel::recoverQuads(dart, {{{0, 3, 2}}, {{0, 2, 1}}});
  EXPECT_EQ(d.size(), 2u);
}

// ---- OBJ: the Cornell box -----------------------------------------------------------------------

TEST(ImportObj, CornellBoxOriginal) {
  fs::path path = cornellPath();
  SKIP_IF_MISSING(path);
  Scene s = luxel::importMeshFile(path);
  EXPECT_EQ(s.name, "CornellBox-Original");
  expectVec(s.up, Vec3(0, 1, 0));
  EXPECT_EQ(s.triangleCount(), 32u);
  // 18 quads in the file: 17 come back as quads; the left wall is not planar (its x are -1.01,
  // -0.99, -1.02, -1.02) and stays two triangles. Each box's last quad repeats another of its
  // faces, and those copies go (roundTripSource).
  EXPECT_EQ(s.faceCount(), 17u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("removed 2 faces"), std::string::npos) << s.warnings.back();
  EXPECT_EQ(s.materials.size(), 8u);  // the .mtl's 8, without Assimp's unused DefaultMaterial
  expectRgb(material(s, "light").emission, Rgb(17, 12, 4));
  EXPECT_TRUE(material(s, "light").isEmissive());
  expectRgb(material(s, "light").reflectance, Rgb(0.78f));
  expectRgb(material(s, "leftWall").reflectance, Rgb(0.63f, 0.065f, 0.05f));
  expectRgb(material(s, "rightWall").reflectance, Rgb(0.14f, 0.45f, 0.091f));
  expectRgb(material(s, "floor").emission, Rgb(0));
  EXPECT_TRUE(s.lights.empty());
  EXPECT_TRUE(s.cameras.empty());
  EXPECT_EQ(s.warnings.size(), 1u);  // only the coincident copies

  // The light (y = 1.98, planar) comes back as one quad facing down (it lights the room).
  bool foundLight = false;
  for (const luxel::Mesh& m : s.meshes) {
    if (s.materials[m.material].name != "light") continue;
    foundLight = true;
    ASSERT_EQ(m.faces.size(), 1u);
    ASSERT_FALSE(m.faces[0].isTriangle());
    const auto& v = m.faces[0].v;
    Vec3 n =
        glm::cross(m.positions[v[1]] - m.positions[v[0]], m.positions[v[2]] - m.positions[v[0]]);
    EXPECT_LT(n.y, 0.0f);
    for (uint32_t i : v) EXPECT_NEAR(m.positions[i].y, 1.98f, 1e-6f);
  }
  EXPECT_TRUE(foundLight);
}

// ---- the display-only highlight: Ks, Ns, illum and shading models -------------------------------

namespace {

// One triangle per material, each at its own depth (the same triangle twice would be removed as a
// coincident copy).
std::string trianglePerMaterial(const std::string& mtllib, const std::vector<std::string>& names) {
  std::string obj = "mtllib " + mtllib + "\n";
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string z = std::to_string(i);
    const std::string v = std::to_string(3 * i + 1);
    obj += "v 0 0 " + z + "\nv 1 0 " + z + "\nv 0 1 " + z + "\nusemtl " + names[i] + "\nf " + v + " " +
           std::to_string(3 * i + 2) + " " + std::to_string(3 * i + 3) + "\n";
  }
  return obj;
}

}  // namespace

TEST(ImportSpecular, KsAndNsGiveTheHighlightWhereIllumAsksForOne) {
  const fs::path dir = tmpDir("specular");
  writeFile(dir / "m.mtl",
            "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.5 0.4 0.3\nNs 96\nillum 2\n"
            // illum 4 (glass) and the other models from 3 up all have highlights, though Assimp's
            // shading model calls them Gouraud.
            "newmtl glass\nKd 0.5 0.5 0.5\nKs 0.1 0.1 0.1\nNs 256\nTf 0.4 0.4 0.4\nillum 4\n"
            // illum 1 is "colour on, ambient on": no highlight, whatever Ks and Ns say; 0 neither.
            "newmtl matte\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 10\nillum 1\n"
            "newmtl unlit\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 10\nillum 0\n"
            // No illum: Assimp's default, 1.
            "newmtl unsaid\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 10\n"
            // A colour but exponent 0: kept as written, but no highlight is drawn.
            "newmtl blunt\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 0\nillum 2\n"
            // Above the limits: clamped, with a warning each.
            "newmtl hot\nKd 0.5 0.5 0.5\nKs 1.5 0.5 0.25\nNs 20000\nillum 2\n"
            "newmtl plain\nKd 0.5 0.5 0.5\n");
  writeFile(dir / "m.obj",
            trianglePerMaterial("m.mtl", {"shiny", "glass", "matte", "unlit", "unsaid", "blunt", "hot", "plain"}));
  const Scene s = luxel::importMeshFile(dir / "m.obj");
  s.validate();

  expectRgb(material(s, "shiny").specular, Rgb(0.5f, 0.4f, 0.3f));
  EXPECT_EQ(material(s, "shiny").shininess, 96.0f);
  EXPECT_TRUE(material(s, "shiny").hasSpecular());
  expectRgb(material(s, "glass").specular, Rgb(0.1f));
  EXPECT_EQ(material(s, "glass").shininess, 256.0f);
  for (const char* none : {"matte", "unlit", "unsaid", "plain"}) {
    EXPECT_EQ(material(s, none).specular, Rgb(0.0f)) << none;
    EXPECT_EQ(material(s, none).shininess, 0.0f) << none;
    EXPECT_FALSE(material(s, none).hasSpecular()) << none;
  }
  expectRgb(material(s, "blunt").specular, Rgb(0.5f));
  EXPECT_EQ(material(s, "blunt").shininess, 0.0f);
  EXPECT_FALSE(material(s, "blunt").hasSpecular());
  // The diffuse part is untouched by any of it.
  for (const luxel::Material& m : s.materials) expectRgb(m.reflectance, Rgb(0.5f));

  expectRgb(material(s, "hot").specular, Rgb(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(material(s, "hot").shininess, luxel::kMaxShininess);
  const std::string where = (dir / "m.obj").string() + ": material 'hot': ";
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_EQ(s.warnings[0], where + "specular colour (1.5, 0.5, 0.25) clamped to [0, 1]");
  EXPECT_EQ(s.warnings[1], where + "shininess 20000 clamped to 10000");
  // illum 4 is glass: light would pass it (ImportTransmission).
  EXPECT_TRUE(material(s, "glass").transmits());
}

// Glass in a file: the lights' shadow rays pass it (trace/thin_glass.h) but light reflected by
// surfaces does not, and the import says which materials the file lets light through.
TEST(ImportTransmission, GlassIsNamedInOneWarning) {
  const fs::path dir = tmpDir("transmission");
  writeFile(dir / "m.mtl",
            "newmtl dissolved\nKd 0.5 0.5 0.5\nd 0.5\nillum 2\n"
            "newmtl clear\nKd 0 0 0\nTf 0.5 0.5 0.5\nillum 6\n"
            "newmtl stained\nKd 0 0 0\nTf 0.07 0.63 0.07\nillum 4\n"
            // A black filter lets nothing through, and illum 2 has no transparency whatever Tf says.
            "newmtl sealed\nKd 0 0 0\nTf 0 0 0\nillum 6\n"
            "newmtl stone\nKd 0.7 0.7 0.6\nTf 1 1 1\nd 1\nillum 2\n"
            "newmtl plain\nKd 0.5 0.5 0.5\n");
  writeFile(dir / "m.obj", trianglePerMaterial("m.mtl", {"dissolved", "clear", "stained", "sealed", "stone", "plain"}));
  const Scene s = luxel::loadScene((dir / "m.obj").string());
  for (const char* glass : {"dissolved", "clear", "stained"}) EXPECT_TRUE(material(s, glass).transmits()) << glass;
  for (const char* opaque : {"sealed", "stone", "plain"}) EXPECT_FALSE(material(s, opaque).transmits()) << opaque;
  // What passes: Tf with a transparent illum, else 1 - d.
  expectRgb(material(s, "dissolved").transmittance, Rgb(0.5f));
  expectRgb(material(s, "clear").transmittance, Rgb(0.5f));
  expectRgb(material(s, "stained").transmittance, Rgb(0.07f, 0.63f, 0.07f));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0].rfind("scene 'm': materials 'dissolved', 'clear', 'stained' let light through (glass", 0),
            0u)
      << s.warnings[0];
  // Of the file's reflectance.
  expectRgb(material(s, "clear").reflectance, Rgb(0.0f));
  expectRgb(material(s, "dissolved").reflectance, Rgb(0.5f));
}

// McGuire's glossy box: the sphere and the short box have highlights (illum 2, Ks 0.9 and 0.8,
// Ns 40); the walls give Ks 0 and Ns 10, which draws none.
TEST(ImportSpecular, McGuiresGlossyCornellBox) {
  const fs::path path = fs::path(LUXEL_TEST_SCENES) / "mcguire-cornell-box" / "CornellBox-Glossy.obj";
  SKIP_IF_MISSING(path);
  const Scene s = luxel::importMeshFile(path);
  expectRgb(material(s, "sphere").specular, Rgb(0.9f));
  EXPECT_EQ(material(s, "sphere").shininess, 40.0f);
  expectRgb(material(s, "shortBox").specular, Rgb(0.8f));
  EXPECT_EQ(material(s, "leftWall").specular, Rgb(0.0f));
  EXPECT_EQ(material(s, "leftWall").shininess, 10.0f);
  EXPECT_FALSE(material(s, "leftWall").hasSpecular());
}

// FBX and COLLADA carry the highlight as Phong materials; a COLLADA <lambert> has none, even with
// a <specular> in it. glTF has no Phong terms and gets none.
TEST(ImportSpecular, FbxAndColladaKeepItLambertAndGltfHaveNone) {
  const fs::path dir = tmpDir("specular-formats");
  writeFile(dir / "m.mtl", "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.5 0.4 0.3\nNs 96\nillum 2\n");
  writeFile(dir / "m.obj", trianglePerMaterial("m.mtl", {"shiny"}));
  Assimp::Importer importer;
  const aiScene* ai = importer.ReadFile((dir / "m.obj").string(), aiProcess_ValidateDataStructure);
  ASSERT_NE(ai, nullptr) << importer.GetErrorString();
  Assimp::Exporter exporter;
  for (const auto& [id, file] : {std::pair{"fbxa", "m.fbx"}, std::pair{"collada", "m.dae"}, std::pair{"gltf2", "m.gltf"}}) {
    const fs::path out = dir / file;
    ASSERT_EQ(exporter.Export(ai, id, out.string()), AI_SUCCESS) << exporter.GetErrorString();
    const Scene scene = luxel::importMeshFile(out);
    const luxel::Material& m = material(scene, "shiny");
    if (id == std::string("gltf2")) {
      EXPECT_FALSE(m.hasSpecular());
      EXPECT_EQ(m.specular, Rgb(0.0f));
      continue;
    }
    expectRgb(m.specular, Rgb(0.5f, 0.4f, 0.3f));
    EXPECT_EQ(m.shininess, 96.0f) << id;
  }
  std::ifstream in(dir / "m.dae", std::ios::binary);
  std::string dae((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(dae.find("<phong>"), std::string::npos);
  for (const auto& [from, to] : {std::pair{"<phong>", "<lambert>"}, std::pair{"</phong>", "</lambert>"}})
    for (size_t at; (at = dae.find(from)) != std::string::npos;) dae.replace(at, std::string(from).size(), to);
  writeFile(dir / "lambert.dae", dae);
  const Scene lambertScene = luxel::importMeshFile(dir / "lambert.dae");
  const luxel::Material& lambert = material(lambertScene, "shiny");
  EXPECT_FALSE(lambert.hasSpecular());
  EXPECT_EQ(lambert.specular, Rgb(0.0f));
}

// ---- every format through Assimp's exporters ----------------------------------------------------

class ImportFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(ImportFormat, CornellBoxRoundTrip) {
  const RoundTripSource source = roundTripSource();
  const fs::path src = source.obj;
  const std::string id = GetParam();
  Assimp::Exporter exporter;
  const aiExportFormatDesc* desc = nullptr;
  for (size_t i = 0; i < exporter.GetExportFormatCount(); ++i)
    if (id == exporter.GetExportFormatDescription(i)->id)
      desc = exporter.GetExportFormatDescription(i);
  if (!desc) GTEST_SKIP() << "this Assimp build has no '" << id << "' exporter";

  Assimp::Importer importer;
  const aiScene* ai = importer.ReadFile(src.string(), aiProcess_ValidateDataStructure);
  ASSERT_NE(ai, nullptr) << importer.GetErrorString();
  fs::path dir = tmpDir(std::string("format-") + id);
  fs::path out = dir / (std::string("cornell.") + desc->fileExtension);
  ASSERT_EQ(exporter.Export(ai, id, out.string()), AI_SUCCESS) << exporter.GetErrorString();
  // Assimp 5.2.5 cannot read back its own binary FBX ("FBX-Tokenize ... block offset is out of
  // range"); that is Assimp's limit, not ours, so skip rather than fail when it cannot.
  Assimp::Importer check;
  if (!check.ReadFile(out.string(), 0))
    GTEST_SKIP() << "Assimp cannot read back its own '" << id
                 << "' export: " << check.GetErrorString();

  Scene s = luxel::importMeshFile(out);
  EXPECT_EQ(s.triangleCount(), source.triangles) << out;
  if (id == std::string("ply")) {
    EXPECT_EQ(s.materials.size(), 1u);  // PLY has no materials: Assimp's default
  } else {
    EXPECT_EQ(s.materials.size(), source.materials) << out;
    int light = s.findMaterial("light");
    ASSERT_GE(light, 0);
    expectRgb(s.materials[size_t(light)].emission, Rgb(17, 12, 4), 1e-4f);
    expectRgb(material(s, source.red).reflectance, Rgb(0.63f, 0.065f, 0.05f), 1e-4f);
  }
}

INSTANTIATE_TEST_SUITE_P(Assimp, ImportFormat,
                         ::testing::Values("gltf2", "glb2", "fbx", "fbxa", "ply", "collada"),
                         [](const auto& info) { return std::string(info.param); });

// ---- glTF: KHR_materials_emissive_strength, lights, cameras, embedded textures ------------------

namespace {

// One unit quad (two triangles) in node "quadnode" at z = 5; a camera node at (1, 2, 3) turned
// 90 degrees about +y (so it looks down -x); a spot light at (0, 4, 0) turned -90 degrees about
// +x (so it points down -y). The material's base colour texture is a 2x2 PNG in a data URI: top
// row red, green; bottom row blue, white. The quad's glTF uvs equal its (x, y).
nlohmann::json gltfDoc(const std::string& bufferUri, size_t bufferBytes) {
  using nlohmann::json;
  const float s = std::sqrt(0.5f);
  std::string texture = "data:image/png;base64," +
                        base64(png(2, 2, {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}}));
  json g = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_lights_punctual", "KHR_materials_emissive_strength"}},
      {"extensions",
       {{"KHR_lights_punctual",
         {{"lights",
           {{{"type", "spot"},
             {"name", "spot1"},
             {"color", {1.0, 0.5, 0.25}},
             {"intensity", 40.0},
             {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}}}}}}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1, 2}}}}},
      {"nodes",
       {{{"mesh", 0}, {"name", "quadnode"}, {"translation", {0, 0, 5}}},
        {{"camera", 0}, {"name", "cam"}, {"translation", {1, 2, 3}}, {"rotation", {0, s, 0, s}}},
        {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
         {"name", "lamp"},
         {"translation", {0, 4, 0}},
         {"rotation", {-s, 0, 0, s}}}}},
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
         {"doubleSided", true},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 0.6, 0.7, 1.0}}, {"baseColorTexture", {{"index", 0}}}}},
         {"emissiveFactor", {1.0, 0.5, 0.25}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8.0}}}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", texture}}}},
      {"buffers", {{{"byteLength", bufferBytes}}}},
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
  return g;
}

std::string gltfBuffer() {
  const float pos[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
  const float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  std::string b(reinterpret_cast<const char*>(pos), sizeof pos);
  b.append(reinterpret_cast<const char*>(idx), sizeof idx);
  b.append(reinterpret_cast<const char*>(uv), sizeof uv);
  return b;  // 92 bytes
}

std::string le32(uint32_t v) { return {char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; }

void checkGltfScene(const Scene& s) {
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangleCount(), 2u);
  ASSERT_EQ(s.faceCount(), 1u);  // the two triangles were one quad
  for (const Vec3& p : s.meshes[0].positions) EXPECT_NEAR(p.z, 5.0f, 1e-6f);
  ASSERT_EQ(s.meshes[0].uvs.size(), 4u);
  // glTF puts uv (0, 0) at the image's top-left, luxel (like OBJ) at the bottom-left: Assimp flips
  // v, and the texture is stored bottom row first, so the same texel comes back.
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(s.meshes[0].uvs[i].x, s.meshes[0].positions[i].x, 1e-6f);
    EXPECT_NEAR(s.meshes[0].uvs[i].y, 1.0f - s.meshes[0].positions[i].y, 1e-6f);
  }

  ASSERT_EQ(s.materials.size(), 1u);
  const luxel::Material& m = s.materials[0];
  EXPECT_EQ(m.name, "glow");
  expectRgb(m.reflectance, Rgb(0.5f, 0.6f, 0.7f));
  expectRgb(m.emission, Rgb(8.0f, 4.0f, 2.0f));  // emissiveFactor * emissiveStrength
  EXPECT_TRUE(m.twoSided);
  ASSERT_GE(m.reflectanceTexture, 0);
  const Texture& t = s.textures[size_t(m.reflectanceTexture)];
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 2);
  expectRgb(t.texels[0], Rgb(0, 0, 1));  // bottom-left
  expectRgb(t.texels[2], Rgb(1, 0, 0));  // top-left
  // glTF uv (0.25, 0.25) is the image's top-left texel (red); in luxel's convention (0.25, 0.75).
  expectRgb(t.sample(Vec2(0.25f, 0.75f)), Rgb(1, 0, 0));
  expectRgb(t.sample(Vec2(0.75f, 0.25f)), Rgb(1, 1, 1));

  ASSERT_EQ(s.lights.size(), 1u);
  const luxel::Light& l = s.lights[0];
  EXPECT_EQ(l.type, luxel::Light::Type::Spot);
  EXPECT_EQ(l.name, "lamp");
  expectRgb(l.color, Rgb(1.0f, 0.5f, 0.25f));
  EXPECT_NEAR(l.intensity, 40.0f, 1e-4f);
  expectRgb(l.power(), Rgb(40.0f, 20.0f, 10.0f), 1e-4f);
  expectVec(l.position, Vec3(0, 4, 0));
  expectVec(l.direction, Vec3(0, -1, 0));
  EXPECT_NEAR(l.innerConeAngle, 0.2f, 1e-6f);
  EXPECT_NEAR(l.outerConeAngle, 0.6f, 1e-6f);

  ASSERT_EQ(s.cameras.size(), 1u);
  const luxel::Camera& c = s.cameras[0];
  EXPECT_EQ(c.name, "cam");
  expectVec(c.eye, Vec3(1, 2, 3));  // not (2, 4, 6): the translation counts once
  expectVec(glm::normalize(c.target - c.eye), Vec3(-1, 0, 0));
  expectVec(c.up, Vec3(0, 1, 0));
  EXPECT_NEAR(c.fovY, 0.8f * 180.0f / kPi, 1e-4f);  // glTF yfov is the full vertical angle
}

}  // namespace

TEST(ImportGltf, EmissiveStrengthLightsCamerasAndEmbeddedTexture) {
  fs::path dir = tmpDir("gltf");
  std::string buffer = gltfBuffer();
  nlohmann::json doc =
      gltfDoc("data:application/octet-stream;base64," + base64(buffer), buffer.size());
  writeFile(dir / "scene.gltf", doc.dump(1));
  Scene s = luxel::importMeshFile(dir / "scene.gltf");
  EXPECT_EQ(s.name, "scene");
  checkGltfScene(s);
}

// glTF glass: KHR_materials_transmission, or alpha blending below full opacity (an opaque
// material's base colour alpha means nothing and is not glass).
TEST(ImportGltf, TransmissionAndBlendingAreNamedAsGlass) {
  const fs::path dir = tmpDir("gltf-glass");
  const std::string buffer = gltfBuffer();
  const std::string uri = "data:application/octet-stream;base64," + base64(buffer);
  const auto glow = [](nlohmann::json& doc) -> nlohmann::json& { return doc["materials"][0]; };
  nlohmann::json transmitted = gltfDoc(uri, buffer.size());
  glow(transmitted)["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 0.9}};
  transmitted["extensionsUsed"].push_back("KHR_materials_transmission");
  nlohmann::json blended = gltfDoc(uri, buffer.size());
  glow(blended)["alphaMode"] = "BLEND";
  glow(blended)["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.6, 0.7, 0.4};
  nlohmann::json opaque = gltfDoc(uri, buffer.size());
  glow(opaque)["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.6, 0.7, 0.4};
  for (const auto& [name, doc, glass] : {std::tuple{"transmitted", transmitted, true},
                                         std::tuple{"blended", blended, true}, std::tuple{"opaque", opaque, false}}) {
    writeFile(dir / (std::string(name) + ".gltf"), doc.dump(1));
    const Scene s = luxel::loadScene((dir / (std::string(name) + ".gltf")).string());
    size_t named = 0;
    for (const std::string& w : s.warnings) named += w.find("material 'glow' lets light through") != std::string::npos;
    EXPECT_EQ(named, glass ? 1u : 0u) << name;
  }
}

TEST(ImportGltf, BinaryGlb) {
  fs::path dir = tmpDir("glb");
  std::string bin = gltfBuffer();
  while (bin.size() % 4) bin += '\0';
  std::string json = gltfDoc("", gltfBuffer().size()).dump();
  while (json.size() % 4) json += ' ';
  std::string glb = "glTF" + le32(2) + le32(uint32_t(12 + 8 + json.size() + 8 + bin.size())) +
                    le32(uint32_t(json.size())) + "JSON" + json + le32(uint32_t(bin.size())) +
                    std::string("BIN\0", 4) + bin;
  writeFile(dir / "scene.glb", glb);
  checkGltfScene(luxel::importMeshFile(dir / "scene.glb"));
}

// ---- COLLADA camera: xfov is the full horizontal angle ------------------------------------------

TEST(ImportCollada, CameraFieldOfView) {
  fs::path dir = tmpDir("collada");
  // One triangle, and a camera with xfov 60 degrees and aspect 1.5 at (1, 2, 3). The vertical
  // angle is 2 atan(tan(30 deg) / 1.5) = 42.1034 degrees.
  const std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_cameras>
    <camera id="cam-lib" name="cam">
      <optics><technique_common><perspective>
        <xfov>60</xfov><aspect_ratio>1.5</aspect_ratio><znear>0.1</znear><zfar>100</zfar>
      </perspective></technique_common></optics>
    </camera>
  </library_cameras>
  <library_geometries>
    <geometry id="tri" name="tri"><mesh>
      <source id="tri-pos"><float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
        <technique_common><accessor source="#tri-pos-array" count="3" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#tri-vtx" offset="0"/>
        <p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">
      <node id="tri-node" name="tri-node"><instance_geometry url="#tri"/></node>
      <node id="cam-node" name="cam-node"><translate>1 2 3</translate>
        <instance_camera url="#cam-lib"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
  writeFile(dir / "camera.dae", dae);
  Scene s = luxel::importMeshFile(dir / "camera.dae");
  EXPECT_EQ(s.triangleCount(), 1u);
  ASSERT_EQ(s.cameras.size(), 1u);
  float want = 2.0f * std::atan(std::tan(30.0f * kPi / 180.0f) / 1.5f) * 180.0f / kPi;
  EXPECT_NEAR(want, 42.1034f, 1e-3f);
  EXPECT_NEAR(s.cameras[0].fovY, want, 1e-3f);
  expectVec(s.cameras[0].eye, Vec3(1, 2, 3));
  expectVec(glm::normalize(s.cameras[0].target - s.cameras[0].eye), Vec3(0, 0, -1));
}

// ---- materials ----------------------------------------------------------------------------------

TEST(ImportObj, ClampsReflectanceWithWarningAndLoadsTextures) {
  fs::path dir = tmpDir("obj-material");
  writeFile(dir / "quad.obj",
            "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl bright\nf 1/1 2/2 3/3 4/4\n");
  // Kd above 1; the texture file name differs in case from the reference, as in Sponza.
  writeFile(dir / "quad.mtl", "newmtl bright\nKd 1.2 0.5 -0.1\nmap_Kd Tex.PPM\n");
  writeFile(dir / "tex.ppm", ppm(1, 1, {{255, 255, 255}}));
  Scene s = luxel::importMeshFile(dir / "quad.obj");
  ASSERT_EQ(s.materials.size(), 1u);
  expectRgb(s.materials[0].reflectance, Rgb(0.99f, 0.5f, 0.0f));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("bright"), std::string::npos) << s.warnings[0];
  ASSERT_GE(s.materials[0].reflectanceTexture, 0);
  expectRgb(s.textures[size_t(s.materials[0].reflectanceTexture)].texels[0], Rgb(1.0f));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].uvs.size(), s.meshes[0].positions.size());
  EXPECT_EQ(s.faceCount(), 1u);
}

// ---- bad input: an Error naming the file, never a crash -----------------------------------------

TEST(ImportErrors, NonexistentPath) {
  std::string msg = errorOf([] { luxel::importMeshFile("/no/such/dir/missing-model.obj"); });
  EXPECT_NE(msg.find("missing-model.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(ImportErrors, GarbageObj) {
  fs::path dir = tmpDir("garbage-obj");
  std::string bytes;
  for (int i = 0; i < 4096; ++i) bytes += char((i * 7919 + 13) % 256);
  writeFile(dir / "garbage.obj", bytes);
  std::string msg = errorOf([&] { luxel::importMeshFile(dir / "garbage.obj"); });
  EXPECT_NE(msg.find("garbage.obj"), std::string::npos) << msg;
}

TEST(ImportErrors, TruncatedAndGarbageGlb) {
  const fs::path src = roundTripSource().obj;
  Assimp::Importer importer;
  const aiScene* ai = importer.ReadFile(src.string(), 0);
  ASSERT_NE(ai, nullptr);
  fs::path dir = tmpDir("truncated-glb");
  Assimp::Exporter exporter;
  if (exporter.Export(ai, "glb2", (dir / "full.glb").string()) != AI_SUCCESS)
    GTEST_SKIP() << "no glb2 exporter: " << exporter.GetErrorString();
  std::ifstream in(dir / "full.glb", std::ios::binary);
  std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (size_t keep : {full.size() / 2, size_t(30), size_t(12), size_t(5)}) {
    writeFile(dir / "truncated.glb", full.substr(0, keep));
    std::string msg = errorOf([&] { luxel::importMeshFile(dir / "truncated.glb"); });
    EXPECT_NE(msg.find("truncated.glb"), std::string::npos) << keep << " bytes: " << msg;
  }
  writeFile(dir / "garbage.glb", "glTF\x02\0\0\0garbage garbage garbage garbage");
  std::string msg = errorOf([&] { luxel::importMeshFile(dir / "garbage.glb"); });
  EXPECT_NE(msg.find("garbage.glb"), std::string::npos) << msg;
}

TEST(ImportErrors, MissingTextureNamesTextureAndMaterial) {
  fs::path dir = tmpDir("missing-texture");
  writeFile(dir / "box.obj", "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl paint\nf 1 2 3\n");
  writeFile(dir / "box.mtl", "newmtl paint\nKd 0.5 0.5 0.5\nmap_Kd nowhere/wood.png\n");
  std::string msg = errorOf([&] { luxel::importMeshFile(dir / "box.obj"); });
  EXPECT_NE(msg.find("box.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("wood.png"), std::string::npos) << msg;
  EXPECT_NE(msg.find("paint"), std::string::npos) << msg;
}

TEST(ImportErrors, ObjWithoutFaces) {
  fs::path dir = tmpDir("empty-obj");
  writeFile(dir / "empty.obj", "# only vertices\nv 0 0 0\nv 1 0 0\nv 1 1 0\n");
  std::string msg = errorOf([&] { luxel::importMeshFile(dir / "empty.obj"); });
  EXPECT_NE(msg.find("empty.obj: contains no triangles"), std::string::npos) << msg;
  // Only a line: dropped, so nothing is left.
  writeFile(dir / "line.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  msg = errorOf([&] { luxel::importMeshFile(dir / "line.obj"); });
  EXPECT_NE(msg.find("line.obj: contains no triangles"), std::string::npos) << msg;
  writeFile(dir / "zero.obj", "");
  msg = errorOf([&] { luxel::importMeshFile(dir / "zero.obj"); });
  EXPECT_NE(msg.find("zero.obj"), std::string::npos) << msg;
}

TEST(ImportErrors, NonFiniteVertexNamesMesh) {
  fs::path dir = tmpDir("nan-obj");
  writeFile(dir / "nan.obj", "o broken\nv 0 0 0\nv 1e999 0 0\nv 1 1 0\nf 1 2 3\n");
  std::string msg = errorOf([&] { luxel::importMeshFile(dir / "nan.obj"); });
  EXPECT_NE(msg.find("nan.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mesh 'broken'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("vertex 1"), std::string::npos) << msg;
}

TEST(LoadScene, DispatchesOnSpec) {
  const RoundTripSource source = roundTripSource();
  EXPECT_EQ(luxel::loadScene(source.obj.string()).triangleCount(), source.triangles);
  std::string msg = errorOf([] { luxel::loadScene("no-such-scene.json"); });
  EXPECT_NE(msg.find("no-such-scene.json"), std::string::npos) << msg;
  for (const std::string& name : luxel::builtinSceneNames()) {
    // Seed 002's rooms are made from a shared scene, up to 10M faces:
    // test_face_cluster_room.cpp loads the small ones.
    if (name.starts_with("room-")) continue;
    EXPECT_GT(luxel::loadScene(name).faceCount(), 0u) << name;
  }
}

// ---- the shared test scenes ---------------------------------------------------------------------

struct SharedScene {
  const char* path;
  size_t triangles;   // in the file
  size_t coincident;  // of those, copies of another face in the same place, facing the same way
};

void PrintTo(const SharedScene& s, std::ostream* os) { *os << s.path << " (" << s.triangles << ")"; }

class ImportShared : public ::testing::TestWithParam<SharedScene> {};

TEST_P(ImportShared, TriangleCount) {
  fs::path path = fs::path(LUXEL_TEST_SCENES) / GetParam().path;
  SKIP_IF_MISSING(path);
  Scene s = luxel::importMeshFile(path);
  EXPECT_EQ(s.triangleCount(), GetParam().triangles - GetParam().coincident) << path;
  bool warned = GetParam().coincident == 0;
  for (const std::string& w : s.warnings) warned = warned || w.find("repeat another face") != std::string::npos;
  EXPECT_TRUE(warned) << "the removed copies are not reported";
  EXPECT_LE(s.faceCount(), s.triangleCount());
  for (const luxel::Material& m : s.materials) {
    if (m.reflectanceTexture >= 0) {
      const Texture& t = s.textures[size_t(m.reflectanceTexture)];
      EXPECT_GT(t.width * t.height, 0) << t.path;
    }
  }
}

// Counted from the files' 'f' lines. Sibenik: 75,165 faces (75,046 triangles, 119 quads), so
// 75,284 triangles (the scenes README's 75,165 counts faces). Sponza: 40,211 faces (13,972
// triangles, 26,239 quads), 66,450 triangles. Bunny: 144,046 triangles. Conference room: 330,837
// faces (330,495 triangles, 342 quads), 331,179 triangles. Coincident copies, counted by the
// importer when it removes them (the warning lists the meshes): Sibenik 213, Sponza 4 (in the
// ceiling), the conference room 29,708.
INSTANTIATE_TEST_SUITE_P(Scenes, ImportShared,
                         ::testing::Values(SharedScene{"sibenik-cathedral/sibenik.obj", 75284, 213},
                                           SharedScene{"dabrovic-sponza/sponza.obj", 66450, 4},
                                           SharedScene{"stanford-bunny/bunny.obj", 144046, 0},
                                           SharedScene{"conference-room/conference.obj", 331179, 29708}),
                         [](const auto& info) {
                           std::string n = fs::path(info.param.path).stem().string();
                           return n;
                         });
