// Malformed mesh files that Assimp 5.2 accepts with geometry dropped or values replaced (issue 18):
// each is an Error naming the file and what is wrong, or, where the file is usable as it stands, a
// warning naming the file and what was done. And unlucky-but-valid OBJ files (a missing mtllib, an
// undefined usemtl) whose light would vanish without a word get a warning.
//
// Fixtures are written here. The glTF buffers are base64 data URIs; a cube's 8 corners, (0|1)^3 in
// binary order, as 24 little-endian floats, are built by `cubeCorners`.
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/resources.h"
#include "error_message.h"

namespace luxel {
namespace {

using luxel::test::errorOf;
using luxel::test::bytesOf;

std::string base64(const std::string& bytes) {
  static const char* const kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
  }
  return out;
}

template <class T>
void append(std::string& out, T v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);  // little-endian, as glTF
}

std::string cubeCorners() {
  std::string b;
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis) append(b, float((i >> axis) & 1));
  return b;
}

// One mesh "m" of one primitive; `accessors`, `views` and `primitive` are JSON text, the buffer's
// bytes are `buffer`; `extra` is added to the top-level object.
std::string gltf(const std::string& accessors, const std::string& views, const std::string& buffer,
                 const std::string& primitive, const std::string& extra = "") {
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"name":"m","primitives":[)" + primitive + "]}],\"accessors\":[" + accessors +
         "],\"bufferViews\":[" + views + "],\"buffers\":[{\"byteLength\":" + std::to_string(buffer.size()) +
         ",\"uri\":\"data:application/octet-stream;base64," + base64(buffer) + "\"}]" + extra + "}";
}

const MemoryResourceReader kNone;

TEST(ImportMalformed, GltfIndexPastTheVerticesIsAnError) {
  // Two triangles over the cube's 8 corners; the second's last index is 60,000. Assimp drops that
  // face and imports the rest.
  std::string buffer = cubeCorners();
  for (uint16_t i : {0, 1, 2, 1, 3, 60000}) append(buffer, i);
  const std::string file = gltf(
      R"({"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[0,0,0],"max":[1,1,1]},)"
      R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"})",
      R"({"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":12})", buffer,
      R"({"attributes":{"POSITION":0},"indices":1})");
  const std::string message = errorOf([&] { importMesh(bytesOf(file), "gltf", kNone, "far.gltf"); });
  EXPECT_NE(message.find("far.gltf: mesh 'm', primitive 0: index 5 of accessor 1 is 60000, but POSITION has only 8 "
                         "vertices"),
            std::string::npos)
      << message;
}

TEST(ImportMalformed, GltfIndicesInTheGlbBinaryChunkAreChecked) {
  std::string bin = cubeCorners();
  for (uint16_t i : {0, 1, 2, 1, 3, 8}) append(bin, i);
  std::string json =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[0,0,0],"max":[1,1,1]},)"
      R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":12}],)"
      R"("buffers":[{"byteLength":108}]})";
  while (json.size() % 4) json += ' ';
  std::string glb = "glTF";
  append(glb, uint32_t(2));
  append(glb, uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  append(glb, uint32_t(json.size()));
  glb += "JSON" + json;
  append(glb, uint32_t(bin.size()));
  glb += std::string("BIN\0", 4) + bin;
  const std::string message = errorOf([&] { importMesh(bytesOf(glb), "glb", kNone, "off.glb"); });
  EXPECT_NE(message.find("off.glb: mesh 0, primitive 0: index 5 of accessor 1 is 8, but POSITION has only 8"),
            std::string::npos)
      << message;
}

TEST(ImportMalformed, GltfPositionsThatAreNotFloatAreAnError) {
  // UNSIGNED_BYTE positions, padded to a 4-byte stride: Assimp reads the bytes as floats.
  const std::string buffer("\0\0\0\0\1\0\0\0\0\1\0\0", 12);
  const std::string file =
      gltf(R"({"bufferView":0,"componentType":5121,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]})",
           R"({"buffer":0,"byteLength":12,"byteStride":4})", buffer, R"({"attributes":{"POSITION":0}})");
  const std::string message = errorOf([&] { importMesh(bytesOf(file), "gltf", kNone, "bytes.gltf"); });
  EXPECT_NE(message.find("bytes.gltf: mesh 'm', primitive 0: POSITION accessor 0 has componentType 5121, but "
                         "positions must be FLOAT (5126)"),
            std::string::npos)
      << message;
}

TEST(ImportMalformed, GltfIllegalByteStrideIsAnError) {
  std::string triangle;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(triangle, v);
  const std::string accessor =
      R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]})";
  const std::string prim = R"({"attributes":{"POSITION":0}})";
  // 6 is not a multiple of 4: Assimp reads overlapping, misaligned floats.
  const std::string six = gltf(accessor, R"({"buffer":0,"byteLength":36,"byteStride":6})", triangle, prim);
  EXPECT_NE(errorOf([&] { importMesh(bytesOf(six), "gltf", kNone, "six.gltf"); })
                .find("six.gltf: bufferView 0 has byteStride 6; glTF requires a multiple of 4 from 4 to 252"),
            std::string::npos);
  // 8 is legal, but shorter than a 12-byte VEC3 of floats.
  const std::string eight = gltf(accessor, R"({"buffer":0,"byteLength":36,"byteStride":8})", triangle, prim);
  EXPECT_NE(errorOf([&] { importMesh(bytesOf(eight), "gltf", kNone, "eight.gltf"); })
                .find("eight.gltf: accessor 0 has 12-byte elements, but its bufferView 0 has byteStride 8"),
            std::string::npos);
  // 12, the element size, is what a tightly packed view says explicitly: it imports.
  const std::string twelve = gltf(accessor, R"({"buffer":0,"byteLength":36,"byteStride":12})", triangle, prim);
  EXPECT_EQ(importMesh(bytesOf(twelve), "gltf", kNone, "twelve.gltf").faceCount(), 1u);
}

TEST(ImportMalformed, SpotConeOutOfRangeIsAWarningNamingTheLightAndTheAnglesUsed) {
  std::string triangle;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(triangle, v);
  std::string file = gltf(
      R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]})",
      R"({"buffer":0,"byteLength":36})", triangle, R"({"attributes":{"POSITION":0}})",
      R"(,"extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[)"
      R"({"type":"spot","intensity":10,"spot":{"innerConeAngle":1.2,"outerConeAngle":2.0}}]}})");
  // The light hangs under a named node (Assimp names glTF lights after their node).
  file.replace(file.find(R"("nodes":[{"mesh":0}])"), 20,
               R"("nodes":[{"mesh":0,"children":[1]},{"name":"wide","extensions":{"KHR_lights_punctual":{"light":0}}}])");
  const Scene scene = importMesh(bytesOf(file), "gltf", kNone, "cone.gltf");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_FLOAT_EQ(scene.lights[0].outerConeAngle, 0.25f * 3.14159265f);
  EXPECT_FLOAT_EQ(scene.lights[0].innerConeAngle, 0.25f * 3.14159265f);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("cone.gltf: light 'wide': spot cone angles inner 1.2 and outer 2 rad are outside"),
            std::string::npos)
      << scene.warnings[0];
  EXPECT_NE(scene.warnings[0].find("using inner 0.785398 and outer 0.785398 rad"), std::string::npos)
      << scene.warnings[0];
}

TEST(ImportMalformed, NegativeColladaIndexIsAnError) {
  const std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="12">0 0 0 1 0 0 0 1 0 1 1 0</float_array>
<technique_common><accessor source="#pa" count="4" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="2"><input semantic="VERTEX" source="#v" offset="0"/>
<p>0 1 2 1 3 -1</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>)";
  const std::string message = errorOf([&] { importMesh(bytesOf(dae), "dae", kNone, "neg.dae"); });
  EXPECT_NE(message.find("neg.dae: line 8: index '-1' in a <p> index list is not a non-negative integer"),
            std::string::npos)
      << message;
}

TEST(ImportMalformed, ObjTextureCoordinatePastTheEndIsAnError) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/99 2/99 3/99\n";
  const std::string message = errorOf([&] { importMesh(bytesOf(obj), "obj", kNone, "uv.obj"); });
  EXPECT_NE(message.find("uv.obj: line 7: face corner '1/99' refers to texture coordinate 99, but 3 are defined "
                         "before it"),
            std::string::npos)
      << message;
  // Relative (negative) indices count back from the last defined; -4 of 3 is past the start.
  const std::string relative = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n";
  EXPECT_NE(errorOf([&] { importMesh(bytesOf(relative), "obj", kNone, "rel.obj"); })
                .find("rel.obj: line 4: face corner '-4' refers to vertex -4, but 3 are defined before it"),
            std::string::npos);
  // In range, both ways, with and without texture coordinates: imports.
  const std::string good = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2//1 -1/-1/-1\n";
  EXPECT_EQ(importMesh(bytesOf(good), "obj", kNone, "good.obj").faceCount(), 1u);
}

TEST(ImportMalformed, MissingMtllibIsAWarningNamingTheLibrary) {
  const std::string obj = "mtllib lamp.mtl\nusemtl light\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const Scene scene = importMesh(bytesOf(obj), "obj", kNone, "room.obj");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("room.obj: line 1: material library 'lamp.mtl' not found (looked for "
                                   "'lamp.mtl'): its materials are missing, so faces get a default grey and "
                                   "nothing emits"),
            std::string::npos)
      << scene.warnings[0];
}

TEST(ImportMalformed, UndefinedUsemtlIsAWarningNamingTheMaterial) {
  MemoryResourceReader side;
  side.add("room.mtl", "newmtl wall\nKd 0.5 0.5 0.5\n");
  const std::string obj =
      "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nusemtl wall\nf 1 2 3\nusemtl lamp\nf 2 4 3\n";
  const Scene scene = importMesh(bytesOf(obj), "obj", side, "room.obj");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("room.obj: line 8: material 'lamp' is not defined in the file's material "
                                   "libraries: faces that use it get a default grey and do not emit"),
            std::string::npos)
      << scene.warnings[0];
  // Every material defined: no warning.
  side.add("room.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKe 1 1 1\n");
  EXPECT_TRUE(importMesh(bytesOf(obj), "obj", side, "room.obj").warnings.empty());
}

// A specular colour or exponent that is negative or NaN (Assimp reads "nan" as NaN) is a broken
// file: an Error naming the file and the material. Above range is clamped with a warning
// (ImportSpecular.KsAndNsGiveTheHighlightWhereIllumAsksForOne).
TEST(ImportMalformed, NegativeOrNanSpecularIsAnErrorNamingTheMaterial) {
  const std::string obj = "mtllib s.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl chrome\nf 1 2 3\n";
  auto error = [&](const std::string& mtl) {
    MemoryResourceReader side;
    side.add("s.mtl", "newmtl chrome\nKd 0.5 0.5 0.5\nillum 2\n" + mtl);
    return errorOf([&] { importMesh(bytesOf(obj), "obj", side, "shiny.obj"); });
  };
  EXPECT_EQ(error("Ks 0.5 -0.25 0.5\nNs 32\n"),
            "shiny.obj: material 'chrome': specular colour (0.5, -0.25, 0.5) is negative or not a number");
  EXPECT_EQ(error("Ks nan 0.5 0.5\nNs 32\n"),
            "shiny.obj: material 'chrome': specular colour (nan, 0.5, 0.5) is negative or not a number");
  EXPECT_EQ(error("Ks 0.5 0.5 0.5\nNs -4\n"), "shiny.obj: material 'chrome': shininess -4 is negative or not a number");
  EXPECT_EQ(error("Ks 0.5 0.5 0.5\nNs nan\n"), "shiny.obj: material 'chrome': shininess nan is negative or not a number");
  // Where illum asks for no highlight, Ks and Ns are not read, so not judged either.
  MemoryResourceReader side;
  side.add("s.mtl", "newmtl chrome\nKd 0.5 0.5 0.5\nillum 1\nKs -1 -1 -1\nNs nan\n");
  const Scene matte = importMesh(bytesOf(obj), "obj", side, "shiny.obj");
  EXPECT_FALSE(matte.materials.at(0).hasSpecular());
  EXPECT_EQ(matte.materials.at(0).shininess, 0.0f);
}

// Assimp's own words name its parser's stages and tokens, or say nothing about the file.
TEST(ImportMalformed, AssimpMessagesAreTranslatedKeepingTheFileName) {
  const std::string fbx = "; FBX 7.4.0 project file\n\"foo\": {{\n";
  const std::string message = errorOf([&] { importMesh(bytesOf(fbx), "fbx", kNone, "broken.fbx"); });
  EXPECT_EQ(message, "broken.fbx: not a valid FBX file: its syntax breaks at line 2, column 6");
  const std::string text = "hello world, this is not a model\n";
  EXPECT_EQ(errorOf([&] { importMesh(bytesOf(text), "xyz", kNone, "note.xyz"); }),
            "note.xyz: not a valid .xyz file, nor any other format luxel can import");
}

// stb_image's reasons are its shorthand ("first not IHDR", "unknown image type").
TEST(ImportMalformed, TextureDecoderMessagesSayWhatIsWrongWithTheFile) {
  const std::string png = std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDX", 16) + std::string(17, '\0');
  EXPECT_EQ(errorOf([&] { decodeTextureBytes(bytesOf(png), true, "cut.png"); }),
            "texture 'cut.png': the image is damaged or truncated and cannot be decoded");
  EXPECT_EQ(errorOf([&] { decodeTextureBytes(bytesOf(std::string("plain text")), true, "notes.txt"); }),
            "texture 'notes.txt': not an image luxel reads (PNG, JPEG, TGA, BMP, PSD, GIF, HDR, PIC or PNM)");
}

}  // namespace
}  // namespace luxel
