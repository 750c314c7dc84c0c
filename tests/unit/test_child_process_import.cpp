// Imports in a child process (issue 18): whatever the importer does, a crash, a hang, a memory
// bomb or an error, the caller gets an Error naming the file and carries on; and the scene comes
// back whole, every field of it.
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/resources.h"
#include "scene/import/child_process_import.h"
#include "scene/scene_bytes.h"
#include "error_message.h"

namespace luxel {
namespace {

using luxel::test::errorOf;

void expectIn(const std::string& text, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(text.find(p), std::string::npos) << "'" << p << "' not in: " << text;
}

// A scene with every field away from its default, so that a field lost on the way shows.
Scene everyField() {
  Scene s;
  s.name = "every field";
  s.objects.push_back(Object{.name = "lamp", .transform = glm::mat4(2.0f), .dynamic = true, .restTransform = glm::mat4(3.0f)});
  Mesh m;
  m.name = "floor";
  m.object = 0;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.lightmapUvs = {{0.1f, 0.1f}, {0.9f, 0.1f}, {0.9f, 0.9f}, {0.1f, 0.9f}};
  m.faces = {Face{{0, 1, 2, 3}}};
  m.material = 1;
  m.elementGrids = {{3, 4}};
  m.restPositions = {{5, 6, 7}};
  s.meshes.push_back(m);
  s.materials.push_back(Material{.name = "grey"});
  s.materials.push_back(Material{.name = "lit", .reflectance = Rgb(0.1f, 0.2f, 0.3f), .reflectanceTexture = 0,
                                 .emission = Rgb(4, 5, 6), .emissionTexture = 0, .specular = Rgb(0.4f, 0.5f, 0.6f),
                                 .shininess = 32, .twoSided = true, .transmittance = Rgb(0.5f, 0.25f, 0.125f)});
  s.textures.push_back(Texture{.path = "tex/a.png", .width = 2, .height = 1, .texels = {Rgb(0.25f), Rgb(0.5f)}});
  s.lights.push_back(Light{.type = Light::Type::Spot, .name = "spot", .color = Rgb(1, 0.5f, 0.25f), .intensity = 7,
                           .position = {1, 2, 3}, .direction = {0, 0, -1}, .innerConeAngle = 0.1f,
                           .outerConeAngle = 0.2f, .angularRadius = 0.3f});
  s.cameras.push_back(Camera{.name = "cam", .eye = {1, 1, 1}, .target = {0, 0.5f, 0}, .up = {0, 0, 1}, .fovY = 30});
  s.up = {0, 0, 1};
  s.warnings = {"one", "two"};
  s.animation.objects.push_back(ObjectAnimation{
      .object = 0, .rest = glm::mat4(4.0f), .motion = {.spin = Spin{.axis = {0, 0, 1}, .pivot = {1, 2, 3}, .degreesPerSecond = 45}}});
  s.animation.lights.push_back(LightAnimation{
      .light = 0, .restPosition = {1, 2, 3}, .restDirection = {0, 0, -1}, .restColor = {1, 0.5f, 0.25f}, .restIntensity = 7,
      .motion = {.keyframes = {Keyframe{.time = 1, .translate = {1, 0, 0}, .rotate = glm::quat(0, 1, 0, 0), .scale = 2,
                                        .color = Rgb(0.5f), .intensity = 3},
                               Keyframe{.time = 2}},
                 .loop = true}});
  return s;
}

void expectSame(const Scene& a, const Scene& b) {
  EXPECT_EQ(sceneBytes(a), sceneBytes(b));  // byte for byte, having written every field
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.objects.size(), 1u);
  EXPECT_EQ(b.objects[0].name, "lamp");
  EXPECT_TRUE(b.objects[0].dynamic);
  EXPECT_EQ(b.objects[0].restTransform, glm::mat4(3.0f));
  ASSERT_EQ(b.meshes.size(), 1u);
  EXPECT_EQ(b.meshes[0].lightmapUvs, a.meshes[0].lightmapUvs);
  EXPECT_EQ(b.meshes[0].elementGrids, a.meshes[0].elementGrids);
  EXPECT_EQ(b.meshes[0].restPositions, a.meshes[0].restPositions);
  EXPECT_EQ(b.materials[1].emission, Rgb(4, 5, 6));
  EXPECT_EQ(b.materials[1].specular, Rgb(0.4f, 0.5f, 0.6f));
  EXPECT_EQ(b.materials[1].shininess, 32.0f);
  EXPECT_TRUE(b.materials[1].twoSided);
  EXPECT_EQ(b.materials[1].transmittance, Rgb(0.5f, 0.25f, 0.125f));
  EXPECT_FALSE(b.materials[0].transmits());
  EXPECT_EQ(b.textures[0].texels, a.textures[0].texels);
  EXPECT_EQ(b.lights[0].type, Light::Type::Spot);
  EXPECT_EQ(b.lights[0].angularRadius, 0.3f);
  EXPECT_EQ(b.cameras[0].fovY, 30.0f);
  EXPECT_EQ(b.up, Vec3(0, 0, 1));
  EXPECT_EQ(b.warnings, a.warnings);
  ASSERT_EQ(b.animation.objects.size(), 1u);
  EXPECT_EQ(b.animation.objects[0].rest, glm::mat4(4.0f));
  ASSERT_TRUE(b.animation.objects[0].motion.spin);
  EXPECT_EQ(b.animation.objects[0].motion.spin->degreesPerSecond, 45.0);
  ASSERT_EQ(b.animation.lights.size(), 1u);
  EXPECT_EQ(b.animation.lights[0].restIntensity, 7.0f);
  ASSERT_EQ(b.animation.lights[0].motion.keyframes.size(), 2u);
  EXPECT_EQ(b.animation.lights[0].motion.keyframes[0].intensity, std::optional<float>(3.0f));
  EXPECT_FALSE(b.animation.lights[0].motion.keyframes[1].color);
  EXPECT_TRUE(b.animation.lights[0].motion.loop);
}

TEST(ChildProcessImport, TheSceneComesBackWhole) {
  const Scene sent = everyField();
  expectSame(sent, importInChildProcess("every.obj", 0, [&] { return sent; }));
  expectSame(sent, sceneFromBytes(sceneBytes(sent)));
  // Bytes cut short or run on are an Error, not garbage.
  std::vector<std::byte> bytes = sceneBytes(sent);
  EXPECT_FALSE(errorOf([&] { sceneFromBytes(std::span(bytes).first(bytes.size() - 3)); }).empty());
  bytes.push_back(std::byte{0});
  EXPECT_FALSE(errorOf([&] { sceneFromBytes(bytes); }).empty());
}

TEST(ChildProcessImport, AnImportersErrorComesBackAsIs) {
  const std::string e = errorOf([] { importInChildProcess("bad.obj", 0, []() -> Scene { throw Error("bad.obj: line 3: nonsense"); }); });
  EXPECT_EQ(e, "bad.obj: line 3: nonsense");
}

TEST(ChildProcessImport, ACrashIsAnErrorNamingTheFile) {
  const std::string e = errorOf([] {
    importInChildProcess("crash.dae", 0, []() -> Scene {
      raise(SIGSEGV);
      return {};
    });
  });
  expectIn(e, {"crash.dae", "crashed"});
#if !defined(__SANITIZE_ADDRESS__)  // AddressSanitizer takes the signal, reports it and exits 1
  expectIn(e, {"segmentation fault"});
#endif
}

TEST(ChildProcessImport, AHangIsStoppedAtTheTimeLimit) {
  const auto start = std::chrono::steady_clock::now();
  const std::string e = errorOf([] {
    importInChildProcess(
        "loop.ply", 0,
        []() -> Scene {
          while (true) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        },
        {.seconds = 0.5});
  });
  expectIn(e, {"loop.ply", "still reading it after 0.5 s"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(ChildProcessImport, AMemoryBombRunsOutOfItsOwnMemory) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's shadow memory rules out a limit on the child's address space";
#endif
  const std::string e = errorOf([] {
    importInChildProcess(
        "bomb.ply", 0,
        []() -> Scene {
          std::vector<char> huge(size_t(1) << 30);  // 1 GiB: fine for the machine, over the 256 MiB limit
          huge[12345] = 1;
          Scene s;
          s.name = std::to_string(huge[12345]);
          return s;
        },
        {.bytes = size_t(256) << 20});
  });
  expectIn(e, {"bomb.ply", "ran out of memory"});
}

// A crash inside Assimp itself, as a ResourceReader that Assimp calls for the .mtl brings about.
class CrashingReader final : public ResourceReader {
 public:
  std::optional<std::vector<std::byte>> read(std::string_view) const override {
    raise(SIGSEGV);
    return std::nullopt;
  }
  bool exists(std::string_view) const override { return true; }
};

TEST(ChildProcessImport, ACrashInsideAssimpLeavesTheCallerStanding) {
  const std::string obj = "mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const CrashingReader reader;
  const std::string e = errorOf([&] {
    importMesh(std::as_bytes(std::span<const char>(obj)), "obj", reader, "models/box.obj");
  });
  expectIn(e, {"models/box.obj", "crashed"});
  // And the next import works.
  MemoryResourceReader fine;
  EXPECT_EQ(importMesh(std::as_bytes(std::span<const char>(obj)), "obj", fine, "box.obj").triangleCount(), 1u);
}

// A real one: an 855-byte COLLADA file (fuzz-mesh-dae found it) on which Debian's Assimp 5.2
// dereferences a null pointer in its COLLADA reader; in-process, luxel died of SIGSEGV.
TEST(ChildProcessImport, AFileThatCrashesAssimpIsAnErrorNamingIt) {
  const std::filesystem::path file = std::filesystem::path(LUXEL_SOURCE_DIR) / "tests/data/assimp-crashes/collada-null-node.dae";
  const std::string e = errorOf([&] { importMeshFile(file); });
  expectIn(e, {"collada-null-node.dae", "crashed"});
}

TEST(ChildProcessImport, CtrlCInTheChildCancels) {
  EXPECT_THROW(importInChildProcess("slow.fbx", 0,
                                    []() -> Scene {
                                      raise(SIGINT);  // as the terminal sends it to the whole process group
                                      return {};
                                    }),
               Cancelled);
}

}  // namespace
}  // namespace luxel
