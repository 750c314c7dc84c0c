#include "scene/scene_bytes.h"

#include <string>

#include "luxel/checkpoint.h"

namespace luxel {
namespace {

// Every field of every struct below is written. A field added to one of them must be added here
// too: these sizes (x86-64, libstdc++) make the build say so, unless the field fits in padding
// (a bool beside Material::twoSided would): tests/unit/test_child_process_import.cpp's round
// trip checks the fields one by one.
static_assert(sizeof(Texture) == 64, "Texture changed: update scene_bytes.cpp");
static_assert(sizeof(Material) == 104, "Material changed: update scene_bytes.cpp");
static_assert(sizeof(Object) == 168, "Object changed: update scene_bytes.cpp");
static_assert(sizeof(Mesh) == 192, "Mesh changed: update scene_bytes.cpp");
static_assert(sizeof(Light) == 96, "Light changed: update scene_bytes.cpp");
static_assert(sizeof(Camera) == 72, "Camera changed: update scene_bytes.cpp");
static_assert(sizeof(Motion) == 72, "Motion changed: update scene_bytes.cpp");
static_assert(sizeof(ObjectAnimation) == 144, "ObjectAnimation changed: update scene_bytes.cpp");
static_assert(sizeof(LightAnimation) == 120, "LightAnimation changed: update scene_bytes.cpp");
static_assert(sizeof(Scene) == 264, "Scene changed: update scene_bytes.cpp");

void put(StateWriter& out, const std::string& s) { out.array(std::span<const char>(s)); }
void get(StateReader& in, std::string& s) {
  s.resize(size_t(in.arrayLength(StateReader::kAnyLength, 1)));
  in.raw(s.data(), s.size());
}

// A keyframe is plain data (its optionals included), so a path is written as one array.
void put(StateWriter& out, const Motion& m) { out.value(m.spin), out.array(m.keyframes), out.value(m.loop); }
void get(StateReader& in, Motion& m) { in.value(m.spin), in.array(m.keyframes), in.value(m.loop); }

}  // namespace

std::vector<std::byte> sceneBytes(const Scene& scene) {
  StateWriter out;
  put(out, scene.name);
  out.value(uint64_t(scene.objects.size()));
  for (const Object& o : scene.objects) put(out, o.name), out.value(o.transform), out.value(o.dynamic), out.value(o.restTransform);
  out.value(uint64_t(scene.meshes.size()));
  for (const Mesh& m : scene.meshes) {
    put(out, m.name);
    out.value(m.object), out.value(m.material);
    out.array(m.positions), out.array(m.uvs), out.array(m.lightmapUvs), out.array(m.faces);
    out.array(m.elementGrids), out.array(m.restPositions);
  }
  out.value(uint64_t(scene.materials.size()));
  for (const Material& m : scene.materials) {
    put(out, m.name);
    out.value(m.reflectance), out.value(m.reflectanceTexture), out.value(m.emission), out.value(m.emissionTexture);
    out.value(m.normalTexture), out.value(m.normalScale);
    out.value(m.specular), out.value(m.shininess), out.value(m.twoSided), out.value(m.transmittance);
  }
  out.value(uint64_t(scene.textures.size()));
  for (const Texture& t : scene.textures) put(out, t.path), out.value(t.width), out.value(t.height), out.array(t.texels);
  out.value(uint64_t(scene.lights.size()));
  for (const Light& l : scene.lights) {
    put(out, l.name);
    out.value(l.type), out.value(l.color), out.value(l.intensity), out.value(l.position), out.value(l.direction);
    out.value(l.innerConeAngle), out.value(l.outerConeAngle), out.value(l.angularRadius);
  }
  out.value(uint64_t(scene.cameras.size()));
  for (const Camera& c : scene.cameras) put(out, c.name), out.value(c.eye), out.value(c.target), out.value(c.up), out.value(c.fovY);
  out.value(scene.up);
  out.value(uint64_t(scene.warnings.size()));
  for (const std::string& w : scene.warnings) put(out, w);
  out.value(uint64_t(scene.animation.objects.size()));
  for (const ObjectAnimation& a : scene.animation.objects) out.value(a.object), out.value(a.rest), put(out, a.motion);
  out.value(uint64_t(scene.animation.lights.size()));
  for (const LightAnimation& a : scene.animation.lights) {
    out.value(a.light), out.value(a.restPosition), out.value(a.restDirection), out.value(a.restColor);
    out.value(a.restIntensity), put(out, a.motion);
  }
  return out.bytes();
}

Scene sceneFromBytes(std::span<const std::byte> bytes) {
  StateReader in(bytes, "an imported scene");
  // A count is checked against the bytes left (each item takes at least one byte) before anything
  // is allocated for it.
  auto count = [&] { return size_t(in.arrayLength(StateReader::kAnyLength, 1)); };
  Scene scene;
  get(in, scene.name);
  scene.objects.resize(count());
  for (Object& o : scene.objects) get(in, o.name), in.value(o.transform), in.value(o.dynamic), in.value(o.restTransform);
  scene.meshes.resize(count());
  for (Mesh& m : scene.meshes) {
    get(in, m.name);
    in.value(m.object), in.value(m.material);
    in.array(m.positions), in.array(m.uvs), in.array(m.lightmapUvs), in.array(m.faces);
    in.array(m.elementGrids), in.array(m.restPositions);
  }
  scene.materials.resize(count());
  for (Material& m : scene.materials) {
    get(in, m.name);
    in.value(m.reflectance), in.value(m.reflectanceTexture), in.value(m.emission), in.value(m.emissionTexture);
    in.value(m.normalTexture), in.value(m.normalScale);
    in.value(m.specular), in.value(m.shininess), in.value(m.twoSided), in.value(m.transmittance);
  }
  scene.textures.resize(count());
  for (Texture& t : scene.textures) get(in, t.path), in.value(t.width), in.value(t.height), in.array(t.texels);
  scene.lights.resize(count());
  for (Light& l : scene.lights) {
    get(in, l.name);
    in.value(l.type), in.value(l.color), in.value(l.intensity), in.value(l.position), in.value(l.direction);
    in.value(l.innerConeAngle), in.value(l.outerConeAngle), in.value(l.angularRadius);
  }
  scene.cameras.resize(count());
  for (Camera& c : scene.cameras) get(in, c.name), in.value(c.eye), in.value(c.target), in.value(c.up), in.value(c.fovY);
  in.value(scene.up);
  scene.warnings.resize(count());
  for (std::string& w : scene.warnings) get(in, w);
  scene.animation.objects.resize(count());
  for (ObjectAnimation& a : scene.animation.objects) in.value(a.object), in.value(a.rest), get(in, a.motion);
  scene.animation.lights.resize(count());
  for (LightAnimation& a : scene.animation.lights) {
    in.value(a.light), in.value(a.restPosition), in.value(a.restDirection), in.value(a.restColor);
    in.value(a.restIntensity), get(in, a.motion);
  }
  in.end();
  return scene;
}

}  // namespace luxel
