// Loaders against hostile files (issue 18): deep nesting that once overflowed the stack, headers
// that declare far more than the file holds, and broken JSON, each an Error naming the file and
// what is wrong (or, for deep nesting, a correct import), never a crash or a memory bomb.
//
// Fixtures are written here. The glTF triangle's buffer is 9 little-endian floats, (0,0,0),
// (1,0,0), (0,1,0), in base64.
#include <cstdint>
#include <cstring>
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

const char* const kTriangleBuffer = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

// A glTF whose one triangle hangs at the end of a chain of `depth` nodes, each the only child of
// the one before.
std::string nodeChainGltf(int depth) {
  std::string nodes;
  for (int i = 0; i < depth - 1; ++i) nodes += "{\"children\":[" + std::to_string(i + 1) + "]},";
  nodes += "{\"mesh\":0}";
  return std::string(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)") + nodes +
         R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,"uri":")" +
         kTriangleBuffer + "\"}]}";
}

TEST(HostileLoaders, ADeepNodeChainImportsInsteadOfOverflowingTheStack) {
  const std::string gltf = nodeChainGltf(20000);
  const MemoryResourceReader none;
  const Scene scene = importMesh(bytesOf(gltf), "gltf", none, "chain.gltf");
  EXPECT_EQ(scene.faceCount(), 1u);
}

TEST(HostileLoaders, ADeepColladaNestingImports) {
  std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_geometries><geometry id="tri"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
<technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s">)";
  const int depth = 10000;
  for (int i = 0; i < depth; ++i) dae += "<node id=\"n" + std::to_string(i) + "\">";
  dae += "<instance_geometry url=\"#tri\"/>";
  for (int i = 0; i < depth; ++i) dae += "</node>";
  dae += "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#s\"/></scene></COLLADA>";
  const MemoryResourceReader none;
  EXPECT_EQ(importMesh(bytesOf(dae), "dae", none, "deep.dae").faceCount(), 1u);
}

TEST(HostileLoaders, APlyHeaderClaimingMoreThanTheFileHoldsIsRefusedAtOnce) {
  // 10^9 vertices of three floats in a file of a few hundred bytes.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  ply += std::string(64, '\0');
  const MemoryResourceReader none;
  const std::string message = errorOf([&] { importMesh(bytesOf(ply), "ply", none, "bomb.ply"); });
  EXPECT_NE(message.find("bomb.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("1000000000 vertex"), std::string::npos) << message;
  EXPECT_NE(message.find("at least 12000000001 bytes"), std::string::npos) << message;  // and the face's list count
  // The same header in ASCII needs at least two characters a value.
  std::string ascii = "ply\nformat ascii 1.0\nelement vertex 1000\nproperty float x\nproperty float y\nproperty float z\n"
                      "end_header\n0 0 0\n";
  EXPECT_NE(errorOf([&] { importMesh(bytesOf(ascii), "ply", none, "short.ply"); }).find("at least 6000 bytes"),
            std::string::npos);
}

// Inputs fuzz-mesh-ply and fuzz-mesh-glb found crashing or exhausting Assimp 5.2: a binary PLY whose
// header breaks off before end_header, and a GLB whose JSON chunk claims 1.7 GB.
TEST(HostileLoaders, FuzzFindingsAreErrorsBeforeAssimpSeesThem) {
  const MemoryResourceReader none;
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\npr";
  ply += std::string("\x80?\0\0\x80?\0\x80?\0\0\0\0\0\0\0\0\0\0\x80?\0\0\x80?\0\0\x01\0\0\0\x02\0\0\0", 36);
  EXPECT_NE(errorOf([&] { importMesh(bytesOf(ply), "ply", none, "cut.ply"); }).find("no end_header"), std::string::npos);
  std::string glb("glTF\x02\0\0\0", 8);
  const auto u32 = [&](uint32_t v) {
    for (int s = 0; s < 32; s += 8) glb += char((v >> s) & 0xFF);
  };
  u32(40);
  u32(0x6500217C);  // the JSON chunk's claimed length
  glb += "JSON{\"asset\":{\"version\":\"2.0\"}}";
  const std::string message = errorOf([&] { importMesh(bytesOf(glb), "glb", none, "claims.glb"); });
  EXPECT_NE(message.find("claims.glb: a GLB chunk at byte 12 claims 1694507388 bytes"), std::string::npos) << message;
}

TEST(HostileLoaders, GltfThatIsNotJsonSaysWhereItBreaks) {
  const std::string broken = R"({"asset": {"version": "2.0"}, "nodes": [ {"mesh": 0}, ])";
  const MemoryResourceReader none;
  const std::string message = errorOf([&] { importMesh(bytesOf(broken), "gltf", none, "broken.gltf"); });
  EXPECT_NE(message.find("broken.gltf: invalid JSON at byte"), std::string::npos) << message;
}

// A PNG header (signature, then IHDR) that declares 16000 x 16000: the decoder must refuse it from
// the header, before it allocates 6 GiB for the pixels.
TEST(HostileLoaders, ATextureThatDeclaresTooManyPixelsIsRefusedFromItsHeader) {
  std::string png = "\x89PNG\r\n\x1a\n";
  const auto u32 = [&](uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) png += char((v >> s) & 0xFF);
  };
  u32(13);
  png += "IHDR";
  u32(16000);
  u32(16000);
  png += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter, no interlace
  u32(0);                                          // CRC (not checked before the size)
  png += std::string(1000, '\0');
  const std::string message = errorOf([&] { decodeTextureBytes(bytesOf(png), true, "huge.png"); });
  EXPECT_NE(message.find("huge.png"), std::string::npos) << message;
  EXPECT_NE(message.find("16000 x 16000"), std::string::npos) << message;
  EXPECT_NE(message.find("over the limit"), std::string::npos) << message;
}

}  // namespace
}  // namespace luxel
