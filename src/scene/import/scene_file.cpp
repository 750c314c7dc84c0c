// luxel scene files: JSON that places mesh files, overrides and adds materials, and adds lights
// and cameras. The format is documented in docs/scene-format.md; keep the two in step.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "luxel/error.h"
#include "luxel/import.h"
#include "io/input_file.h"
#include "scene/coincident_faces.h"
#include "scene/stray_geometry.h"
#include "scene/import/name_index.h"
#include "scene/import/strict_json.h"
#include "scene/import/transform.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;
// ordered_json keeps the file's key order, so added materials appear in the order written.
using Json = nlohmann::ordered_json;

constexpr float kPi = 3.14159265358979f;
constexpr float kMaxReflectance = 0.99f;  // as the mesh importer: every bounce must lose energy

float radians(float degrees) { return degrees * kPi / 180.0f; }

// JSON Pointer (RFC 6901) escaping for keys that become part of an error's path.
std::string escapeKey(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

std::string join(std::initializer_list<std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

// Reads typed values out of the document, naming the file and the JSON path of anything wrong.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& ptr, const std::string& what) const {
    throw Error(fmt::format("{}: {}: {}", file_, ptr.empty() ? "/" : ptr, what));
  }

  static std::string child(const std::string& ptr, std::string_view key) {
    return ptr + "/" + escapeKey(key);
  }
  static std::string child(const std::string& ptr, size_t index) {
    return ptr + "/" + std::to_string(index);
  }

  void expectType(const Json& j, const std::string& ptr, bool ok, std::string_view expected) const {
    if (!ok) fail(ptr, fmt::format("expected {}, got {}", expected, typeName(j)));
  }

  const Json& object(const Json& j, const std::string& ptr) const {
    expectType(j, ptr, j.is_object(), "an object");
    return j;
  }

  const Json& array(const Json& j, const std::string& ptr) const {
    expectType(j, ptr, j.is_array(), "an array");
    return j;
  }

  void keys(const Json& obj, const std::string& ptr,
            std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, value] : obj.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        fail(child(ptr, key), fmt::format("unknown key '{}' (expected {})", key, join(allowed)));
    }
  }

  float number(const Json& j, const std::string& ptr) const { return float(real(j, ptr)); }

  // A number kept in double, for times (seconds over a long animation).
  double real(const Json& j, const std::string& ptr) const {
    expectType(j, ptr, j.is_number(), "a number");
    double v = j.get<double>();
    if (!std::isfinite(v) || std::fabs(v) > 3.0e38) fail(ptr, "number out of range");
    return v;
  }

  float nonNegative(const Json& j, const std::string& ptr) const {
    float v = number(j, ptr);
    if (v < 0.0f) fail(ptr, fmt::format("must not be negative, got {}", v));
    return v;
  }

  bool boolean(const Json& j, const std::string& ptr) const {
    expectType(j, ptr, j.is_boolean(), "true or false");
    return j.get<bool>();
  }

  std::string string(const Json& j, const std::string& ptr) const {
    expectType(j, ptr, j.is_string(), "a string");
    return j.get<std::string>();
  }

  Vec3 vec3(const Json& j, const std::string& ptr) const {
    expectType(j, ptr, j.is_array() && j.size() == 3, "an array of 3 numbers");
    return Vec3(number(j[0], child(ptr, 0)), number(j[1], child(ptr, 1)),
                number(j[2], child(ptr, 2)));
  }

  Vec3 direction(const Json& j, const std::string& ptr) const {
    Vec3 d = vec3(j, ptr);
    if (!(glm::length(d) > 0.0f)) fail(ptr, "direction must not be zero");
    return glm::normalize(d);
  }

  // A colour is [r, g, b] or one number for grey; components must not be negative.
  Rgb color(const Json& j, const std::string& ptr) const {
    if (j.is_number()) return Rgb(nonNegative(j, ptr));
    expectType(j, ptr, j.is_array() && j.size() == 3, "a number or an array of 3 numbers");
    return Rgb(nonNegative(j[0], child(ptr, 0)), nonNegative(j[1], child(ptr, 1)),
               nonNegative(j[2], child(ptr, 2)));
  }

  const std::string& file() const { return file_; }

 private:
  static std::string typeName(const Json& j) {
    if (j.is_array()) return fmt::format("an array of {}", j.size());
    return j.type_name();
  }

  std::string file_;
};

class SceneFileLoader {
 public:
  // `file` names the scene in messages (its stem is the default scene name); relative paths
  // resolve against `folder`.
  SceneFileLoader(fs::path folder, std::string file)
      : name_(fs::path(file).stem().string()), folder_(std::move(folder)), in_(std::move(file)) {}

  Scene load(const Json& doc) {
    in_.object(doc, "");
    in_.keys(doc, "", {"name", "builtin", "base", "up", "meshes", "objects", "materials", "lights", "replaceLights", "cameras"});

    if (doc.contains("builtin") && doc.contains("base"))
      in_.fail("/base", "give 'builtin' or 'base', not both (a base may itself be a built-in name)");
    if (auto it = doc.find("builtin"); it != doc.end()) loadBuiltin(*it, "/builtin");
    if (auto it = doc.find("base"); it != doc.end()) loadBase(*it, "/base");
    scene_.name = name_;
    if (auto it = doc.find("name"); it != doc.end()) scene_.name = in_.string(*it, "/name");

    // "material" on a mesh entry is applied after /materials, which may define it.
    std::vector<MaterialAssignment> assignments;
    if (auto it = doc.find("meshes"); it != doc.end()) {
      const Json& meshes = in_.array(*it, "/meshes");
      for (size_t i = 0; i < meshes.size(); ++i) {
        size_t first = scene_.meshes.size();
        std::optional<MaterialAssignment> a = addMeshFile(meshes[i], Reader::child("/meshes", i));
        if (a) {
          a->firstMesh = first;
          a->endMesh = scene_.meshes.size();
          assignments.push_back(*a);
        }
      }
    }
    if (auto it = doc.find("objects"); it != doc.end()) {
      const Json& objects = in_.object(*it, "/objects");
      for (const auto& [name, spec] : objects.items()) applyObject(name, spec, Reader::child("/objects", name));
    }
    if (auto it = doc.find("materials"); it != doc.end()) {
      const Json& materials = in_.object(*it, "/materials");
      for (const auto& [name, spec] : materials.items())
        applyMaterial(name, spec, Reader::child("/materials", name));
    }
    for (const MaterialAssignment& a : assignments) {
      int index = scene_.findMaterial(a.material);
      if (index < 0)
        in_.fail(a.ptr, fmt::format("no material named '{}' (define it under /materials or use "
                                    "one from the mesh files)",
                                    a.material));
      for (size_t m = a.firstMesh; m < a.endMesh; ++m) scene_.meshes[m].material = uint32_t(index);
    }
    // Meshes of omitted materials go, whichever way they got them (a file's, or /meshes' material).
    std::erase_if(scene_.meshes, [&](const Mesh& m) { return omitted_.count(scene_.materials[m.material].name) > 0; });
    if (auto it = doc.find("replaceLights"); it != doc.end() && in_.boolean(*it, "/replaceLights")) {
      // The lights of the built-in scene, the base and the mesh files go; /lights replaces them.
      scene_.lights.clear();
      scene_.animation.lights.clear();
    }
    if (auto it = doc.find("lights"); it != doc.end()) {
      const Json& lights = in_.array(*it, "/lights");
      for (size_t i = 0; i < lights.size(); ++i) {
        const std::string ptr = Reader::child("/lights", i);
        scene_.lights.push_back(readLight(lights[i], ptr, i));
        if (auto a = lights[i].find("animation"); a != lights[i].end()) animateLight(*a, Reader::child(ptr, "animation"));
      }
    }
    if (auto it = doc.find("cameras"); it != doc.end()) {
      const Json& cameras = in_.array(*it, "/cameras");
      NameIndex<> byName;
      for (size_t c = 0; c < scene_.cameras.size(); ++c) byName.findOrAdd(scene_.cameras[c].name, c);
      for (size_t i = 0; i < cameras.size(); ++i) {
        Camera cam = readCamera(cameras[i], Reader::child("/cameras", i), i);
        const auto [at, added] = byName.findOrAdd(cam.name, scene_.cameras.size());
        if (added)
          scene_.cameras.push_back(std::move(cam));
        else
          scene_.cameras[at] = std::move(cam);  // a file's camera redefined by name
      }
    }
    if (auto it = doc.find("up"); it != doc.end()) scene_.up = in_.direction(*it, "/up");
    return std::move(scene_);
  }

 private:
  struct MaterialAssignment {
    std::string material;
    std::string ptr;  // where it was asked for, for the error when it does not exist
    size_t firstMesh = 0, endMesh = 0;
  };

  void loadBuiltin(const Json& j, const std::string& ptr) {
    std::string name = in_.string(j, ptr);
    if (!isBuiltinScene(name)) {
      std::string names;
      for (const std::string& n : builtinSceneNames()) names += (names.empty() ? "" : ", ") + n;
      in_.fail(ptr, fmt::format("unknown built-in scene '{}' (expected {})", name, names));
    }
    try {
      scene_ = builtinScene(name);
    } catch (const Error& e) {
      in_.fail(ptr, e.what());
    }
  }

  // /base: any scene luxel loads (a built-in name, a scene file, a mesh file), which this file
  // then edits: what the viewer's `save` writes. Bases may chain, up to kMaxBaseDepth deep.
  static constexpr int kMaxBaseDepth = 8;
  static int& baseDepth() {
    thread_local int depth = 0;
    return depth;
  }
  void loadBase(const Json& j, const std::string& ptr) {
    const std::string spec = in_.string(j, ptr);
    if (spec.empty()) in_.fail(ptr, "the base scene is empty (a built-in name, a scene file or a mesh file)");
    if (baseDepth() >= kMaxBaseDepth)
      in_.fail(ptr, fmt::format("bases nest more than {} deep (does a scene name itself as its base?)", kMaxBaseDepth));
    ++baseDepth();
    try {
      scene_ = loadScene(isBuiltinScene(spec) ? spec : resolve(spec).string());
      --baseDepth();
    } catch (const Error& e) {
      --baseDepth();
      in_.fail(ptr, e.what());
    }
  }

  // /objects/NAME/transform: the object's transform (object to world) as 4 rows of 4 numbers, a
  // move of the dynamic object from where it was loaded (a rotation, translation and uniform scale).
  glm::mat4 readMatrix(const Json& j, const std::string& ptr) const {
    in_.expectType(j, ptr, j.is_array() && j.size() == 4, "4 rows of 4 numbers");
    glm::mat4 m(1.0f);
    for (size_t r = 0; r < 4; ++r) {
      const std::string row = Reader::child(ptr, r);
      in_.expectType(j[r], row, j[r].is_array() && j[r].size() == 4, "a row of 4 numbers");
      for (size_t c = 0; c < 4; ++c) m[int(c)][int(r)] = in_.number(j[r][c], Reader::child(row, c));
    }
    return m;
  }

  fs::path resolve(const std::string& relative) const {
    fs::path p(relative);
    return p.is_absolute() ? p : (folder_ / p).lexically_normal();
  }

  // Returns the material to assign to all of the file's meshes, when the entry names one.
  std::optional<MaterialAssignment> addMeshFile(const Json& j, const std::string& ptr) {
    in_.object(j, ptr);
    in_.keys(j, ptr, {"file", "name", "dynamic", "translate", "rotate", "scale", "material", "animation"});
    if (!j.contains("file")) in_.fail(ptr, "missing key 'file'");
    fs::path file = resolve(in_.string(j["file"], Reader::child(ptr, "file")));
    Scene part;
    try {
      part = importMeshFile(file);
    } catch (const Error& e) {
      in_.fail(Reader::child(ptr, "file"), e.what());
    }
    glm::mat4 m = readTransform(j, ptr);
    for (Mesh& mesh : part.meshes) transformMesh(mesh, m);
    for (Light& light : part.lights) transformLight(light, m);
    for (Camera& cam : part.cameras) transformCamera(cam, m);
    // Named, dynamic or animated: the whole file is one object, placed by the entry's transform.
    // Otherwise the file's own objects (its nodes) stay, placed by the entry's transform times
    // their own.
    std::optional<ObjectAnimation> animation;
    if (j.contains("name") || j.contains("dynamic") || j.contains("animation")) {
      Object object{.name = file.stem().string(), .transform = m};
      if (auto it = j.find("name"); it != j.end()) object.name = in_.string(*it, Reader::child(ptr, "name"));
      if (auto it = j.find("dynamic"); it != j.end()) object.dynamic = in_.boolean(*it, Reader::child(ptr, "dynamic"));
      if (auto it = j.find("animation"); it != j.end()) {
        // Only a dynamic object moves; an animated one is dynamic unless the entry says otherwise.
        if (j.contains("dynamic") && !object.dynamic)
          in_.fail(Reader::child(ptr, "animation"), fmt::format("object '{}' is animated, so it must be dynamic "
                                                                "(its 'dynamic' is false)", object.name));
        object.dynamic = true;
        animation = ObjectAnimation{.object = uint32_t(scene_.objects.size()), .rest = m,
                                    .motion = readMotion(*it, Reader::child(ptr, "animation"), MotionOf::Object, Vec3(m[3]))};
      }
      if (object.dynamic && glm::determinant(glm::mat3(m)) < 0.0f)
        in_.fail(ptr, "a dynamic object must not be mirrored (its moves are rotations, translations and scales)");
      part.objects = {object};
      for (Mesh& mesh : part.meshes) mesh.object = 0;
    } else {
      for (Object& o : part.objects) o.transform = m * o.transform;
    }
    merge(std::move(part));
    if (animation) scene_.animation.objects.push_back(std::move(*animation));

    if (!j.contains("material")) return std::nullopt;
    MaterialAssignment a;
    a.ptr = Reader::child(ptr, "material");
    a.material = in_.string(j["material"], a.ptr);
    return a;
  }

  // translate * rotate * scale: scale first, about the file's origin.
  glm::mat4 readTransform(const Json& j, const std::string& ptr) const {
    glm::mat4 m(1.0f);
    if (auto it = j.find("translate"); it != j.end())
      m = glm::translate(m, in_.vec3(*it, Reader::child(ptr, "translate")));
    if (auto it = j.find("rotate"); it != j.end())
      m = m * readRotation(*it, Reader::child(ptr, "rotate"));
    if (auto it = j.find("scale"); it != j.end()) {
      std::string p = Reader::child(ptr, "scale");
      Vec3 s = it->is_number() ? Vec3(in_.number(*it, p)) : in_.vec3(*it, p);
      if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) in_.fail(p, "scale must not be zero");
      m = glm::scale(m, s);
    }
    return m;
  }

  // [x, y, z] Euler angles in degrees, applied about X, then Y, then Z (fixed axes); or
  // {"axis": [x, y, z], "angle": degrees}, counter-clockwise looking down the axis; or
  // {"quaternion": [x, y, z, w]} (glTF's order), normalised.
  glm::mat4 readRotation(const Json& j, const std::string& ptr) const {
    if (j.is_array()) {
      Vec3 e = in_.vec3(j, ptr);
      glm::mat4 r(1.0f);
      r = glm::rotate(r, radians(e.z), Vec3(0.0f, 0.0f, 1.0f));
      r = glm::rotate(r, radians(e.y), Vec3(0.0f, 1.0f, 0.0f));
      r = glm::rotate(r, radians(e.x), Vec3(1.0f, 0.0f, 0.0f));
      return r;
    }
    in_.expectType(j, ptr, j.is_object(),
                   "[x, y, z] degrees, {\"axis\": [x, y, z], \"angle\": degrees} or {\"quaternion\": [x, y, z, w]}");
    in_.keys(j, ptr, {"axis", "angle", "quaternion"});
    if (auto it = j.find("quaternion"); it != j.end()) {
      const std::string p = Reader::child(ptr, "quaternion");
      if (j.size() != 1) in_.fail(ptr, "give either 'quaternion' or 'axis' and 'angle'");
      in_.expectType(*it, p, it->is_array() && it->size() == 4, "an array of 4 numbers [x, y, z, w]");
      glm::dvec4 xyzw;
      for (int c = 0; c < 4; ++c) xyzw[c] = in_.real((*it)[c], Reader::child(p, c));
      const double length = glm::length(xyzw);  // in double: float squares of 3e38 overflow
      if (!(length > 1e-12)) in_.fail(p, "quaternion must not be zero");
      xyzw /= length;
      return glm::mat4_cast(glm::quat(float(xyzw.w), float(xyzw.x), float(xyzw.y), float(xyzw.z)));
    }
    if (!j.contains("axis") || !j.contains("angle")) in_.fail(ptr, "needs both 'axis' and 'angle'");
    Vec3 axis = in_.direction(j["axis"], Reader::child(ptr, "axis"));
    float angle = in_.number(j["angle"], Reader::child(ptr, "angle"));
    return glm::rotate(glm::mat4(1.0f), radians(angle), axis);
  }

  // What a motion moves, for the keys it may use: an object has a size to scale and no colour; a
  // light has a colour and intensity, a position unless it is directional or a sky, and a
  // direction to turn unless it is a sky.
  enum class MotionOf { Object, PositionedLight, DirectionalLight, Sky };

  // {"spin": {...}} or {"keyframes": [...], "loop": bool}; see docs/scene-format.md. `origin` is
  // where the thing stands at rest: a spin's default pivot.
  Motion readMotion(const Json& j, const std::string& ptr, MotionOf what, Vec3 origin) const {
    in_.object(j, ptr);
    in_.keys(j, ptr, {"spin", "keyframes", "loop"});
    const bool spin = j.contains("spin"), keys = j.contains("keyframes");
    if (spin == keys) in_.fail(ptr, "needs exactly one of 'spin' and 'keyframes'");
    Motion m;
    if (spin) {
      if (j.contains("loop")) in_.fail(Reader::child(ptr, "loop"), "'loop' belongs to 'keyframes' (a spin never ends)");
      const std::string p = Reader::child(ptr, "spin");
      if (what == MotionOf::Sky) in_.fail(p, "a sky has no position or direction to turn");
      const Json& sj = in_.object(j["spin"], p);
      in_.keys(sj, p, {"axis", "degreesPerSecond", "pivot"});
      for (const char* key : {"axis", "degreesPerSecond"})
        if (!sj.contains(key)) in_.fail(p, fmt::format("a spin needs '{}'", key));
      Spin s{.axis = in_.direction(sj["axis"], Reader::child(p, "axis")),
             .pivot = origin,
             .degreesPerSecond = in_.real(sj["degreesPerSecond"], Reader::child(p, "degreesPerSecond"))};
      if (auto it = sj.find("pivot"); it != sj.end()) s.pivot = in_.vec3(*it, Reader::child(p, "pivot"));
      m.spin = s;
      return m;
    }
    const std::string p = Reader::child(ptr, "keyframes");
    const Json& keyframes = in_.array(j["keyframes"], p);
    if (keyframes.empty()) in_.fail(p, "needs at least one keyframe");
    for (size_t i = 0; i < keyframes.size(); ++i) m.keyframes.push_back(readKeyframe(keyframes[i], Reader::child(p, i), what));
    for (size_t i = 1; i < m.keyframes.size(); ++i)
      if (!(m.keyframes[i].time > m.keyframes[i - 1].time))
        in_.fail(Reader::child(Reader::child(p, i), "time"),
                 fmt::format("time {:g} is not after the previous keyframe's ({:g}): times must increase",
                             m.keyframes[i].time, m.keyframes[i - 1].time));
    if (auto it = j.find("loop"); it != j.end()) m.loop = in_.boolean(*it, Reader::child(ptr, "loop"));
    return m;
  }

  Keyframe readKeyframe(const Json& j, const std::string& ptr, MotionOf what) const {
    in_.object(j, ptr);
    in_.keys(j, ptr, {"time", "translate", "rotate", "scale", "color", "intensity"});
    if (!j.contains("time")) in_.fail(ptr, "a keyframe needs 'time' (seconds)");
    Keyframe k{.time = in_.real(j["time"], Reader::child(ptr, "time"))};
    const bool light = what != MotionOf::Object;
    auto refuse = [&](const char* key, bool refused, const char* why) {
      if (refused && j.contains(key)) in_.fail(Reader::child(ptr, key), why);
    };
    refuse("translate", what == MotionOf::DirectionalLight || what == MotionOf::Sky,
           "a directional light or a sky has no position to move");
    refuse("rotate", what == MotionOf::Sky, "a sky has no direction to turn");
    refuse("scale", light, "a light has no size to scale");
    refuse("color", !light, "only a light's keyframes have a colour (an object's colour is its material's)");
    refuse("intensity", !light, "only a light's keyframes have an intensity");
    if (auto it = j.find("translate"); it != j.end()) k.translate = in_.vec3(*it, Reader::child(ptr, "translate"));
    if (auto it = j.find("rotate"); it != j.end())
      k.rotate = glm::normalize(glm::quat_cast(glm::mat3(readRotation(*it, Reader::child(ptr, "rotate")))));
    if (auto it = j.find("scale"); it != j.end()) {
      const std::string p = Reader::child(ptr, "scale");
      k.scale = in_.number(*it, p);  // one number: a move keeps the object's shape
      if (!(k.scale > 0.0f)) in_.fail(p, fmt::format("scale must be positive, got {:g}", k.scale));
    }
    if (auto it = j.find("color"); it != j.end()) k.color = in_.color(*it, Reader::child(ptr, "color"));
    if (auto it = j.find("intensity"); it != j.end()) k.intensity = in_.nonNegative(*it, Reader::child(ptr, "intensity"));
    return k;
  }

  // /objects/NAME: settings for the objects of that name already in the scene (from the built-in
  // scene or the mesh files): "dynamic", and "animation" (null removes one).
  void applyObject(const std::string& name, const Json& spec, const std::string& ptr) {
    in_.object(spec, ptr);
    in_.keys(spec, ptr, {"dynamic", "animation", "transform"});
    std::vector<uint32_t> targets;
    for (uint32_t o = 0; o < scene_.objects.size(); ++o)
      if (scene_.objects[o].name == name) targets.push_back(o);
    if (targets.empty()) {
      std::string names;
      for (const Object& o : scene_.objects) names += (names.empty() ? "'" : ", '") + o.name + "'";
      in_.fail(ptr, fmt::format("no object named '{}' (the scene's objects: {})", name, names.empty() ? "none" : names));
    }
    for (uint32_t o : targets) {
      Object& object = scene_.objects[o];
      if (auto it = spec.find("dynamic"); it != spec.end()) object.dynamic = in_.boolean(*it, Reader::child(ptr, "dynamic"));
      auto& animations = scene_.animation.objects;
      if (auto it = spec.find("animation"); it != spec.end()) {
        std::erase_if(animations, [o](const ObjectAnimation& a) { return a.object == o; });
        if (it->is_null()) continue;
        const std::string p = Reader::child(ptr, "animation");
        if (spec.contains("dynamic") && !object.dynamic)
          in_.fail(p, fmt::format("object '{}' is animated, so it must be dynamic (its 'dynamic' is false)", name));
        if (glm::determinant(glm::mat3(object.transform)) < 0.0f)
          in_.fail(p, fmt::format("object '{}' is mirrored, and a moving object must not be (its moves are rotations, "
                                  "translations and scales)",
                                  name));
        object.dynamic = true;
        animations.push_back(ObjectAnimation{
            .object = o, .rest = object.transform,
            .motion = readMotion(*it, p, MotionOf::Object, Vec3(object.transform[3]))});
      }
      if (auto it = spec.find("transform"); it != spec.end()) {
        const std::string p = Reader::child(ptr, "transform");
        if (!object.dynamic)
          in_.fail(p, fmt::format("object '{}' is not dynamic, and only a dynamic object moves from where it was loaded "
                                  "(add \"dynamic\": true)",
                                  name));
        try {
          scene_.placeObject(o, readMatrix(*it, p));
        } catch (const Error& e) {
          in_.fail(p, e.what());
        }
      }
      const bool animated = std::any_of(animations.begin(), animations.end(), [o](const ObjectAnimation& a) { return a.object == o; });
      if (animated && !object.dynamic)
        in_.fail(Reader::child(ptr, "dynamic"), fmt::format("object '{}' is animated, so it must be dynamic (give "
                                                            "\"animation\": null to stop it)",
                                                            name));
    }
  }

  // The animation of the light just added.
  void animateLight(const Json& j, const std::string& ptr) {
    const Light& light = scene_.lights.back();
    MotionOf what = MotionOf::PositionedLight;
    if (light.type == Light::Type::Directional) what = MotionOf::DirectionalLight;
    if (light.type == Light::Type::Sky || light.type == Light::Type::CieOvercastSky) what = MotionOf::Sky;
    scene_.animation.lights.push_back(LightAnimation{.light = uint32_t(scene_.lights.size() - 1),
                                                     .restPosition = light.position,
                                                     .restDirection = light.direction,
                                                     .restColor = light.color,
                                                     .restIntensity = light.intensity,
                                                     .motion = readMotion(j, ptr, what, light.position)});
  }

  // Appends another scene's contents. Materials keep their names even when another file has a
  // material of the same name: both stay, and a /materials override applies to both.
  void merge(Scene part) {
    uint32_t materialBase = uint32_t(scene_.materials.size());
    int textureBase = int(scene_.textures.size());
    for (Material& m : part.materials) {
      if (m.reflectanceTexture >= 0) m.reflectanceTexture += textureBase;
      if (m.emissionTexture >= 0) m.emissionTexture += textureBase;
      if (m.normalTexture >= 0) m.normalTexture += textureBase;
      scene_.materials.push_back(std::move(m));
    }
    for (Texture& t : part.textures) scene_.textures.push_back(std::move(t));
    const uint32_t objectBase = uint32_t(scene_.objects.size());
    for (Object& o : part.objects) scene_.objects.push_back(std::move(o));
    for (Mesh& mesh : part.meshes) {
      mesh.material += materialBase;
      if (mesh.object != kNoObject) mesh.object += objectBase;
      scene_.meshes.push_back(std::move(mesh));
    }
    for (Light& l : part.lights) scene_.lights.push_back(std::move(l));
    for (Camera& c : part.cameras) scene_.cameras.push_back(std::move(c));
    for (std::string& w : part.warnings) scene_.warnings.push_back(std::move(w));
  }

  void applyMaterial(const std::string& name, const Json& spec, const std::string& ptr) {
    in_.object(spec, ptr);
    in_.keys(
        spec, ptr,
        {"reflectance", "emission", "emissionStrength", "twoSided", "texture", "emissionTexture", "specular",
         "shininess", "normalTexture", "normalScale", "transmittance", "omit"});
    if (auto it = spec.find("omit"); it != spec.end() && in_.boolean(*it, Reader::child(ptr, "omit")))
      omitted_.insert(name);
    std::vector<size_t> targets;
    for (size_t i = 0; i < scene_.materials.size(); ++i)
      if (scene_.materials[i].name == name) targets.push_back(i);
    if (targets.empty()) {
      Material added;
      added.name = name;
      targets.push_back(scene_.materials.size());
      scene_.materials.push_back(added);
    }

    std::optional<Rgb> reflectance, emission, specular, transmittance;
    std::optional<float> strength, shininess, normalScale;
    std::optional<bool> twoSided;
    std::optional<int> texture, emissionTexture, normalTexture;  // -1 removes
    if (auto it = spec.find("reflectance"); it != spec.end()) {
      std::string p = Reader::child(ptr, "reflectance");
      Rgb r = in_.color(*it, p);
      if (r.x > 1.0f || r.y > 1.0f || r.z > 1.0f)
        in_.fail(p, fmt::format("reflectance ({}, {}, {}) is above 1", r.x, r.y, r.z));
      Rgb clamped = glm::min(r, Rgb(kMaxReflectance));
      if (clamped != r)
        scene_.warnings.push_back(
            fmt::format("{}: {}: reflectance clamped to {}", in_.file(), p, kMaxReflectance));
      reflectance = clamped;
    }
    if (auto it = spec.find("emission"); it != spec.end())
      emission = in_.color(*it, Reader::child(ptr, "emission"));
    if (auto it = spec.find("emissionStrength"); it != spec.end())
      strength = in_.nonNegative(*it, Reader::child(ptr, "emissionStrength"));
    if (auto it = spec.find("twoSided"); it != spec.end())
      twoSided = in_.boolean(*it, Reader::child(ptr, "twoSided"));
    // The viewer's highlight (display only, scene.h): unlike an imported file's, values out of
    // range are an error here, where the user typed them.
    specular = fraction(spec, ptr, "specular");
    if (auto it = spec.find("shininess"); it != spec.end()) {
      std::string p = Reader::child(ptr, "shininess");
      float v = in_.nonNegative(*it, p);
      if (v > kMaxShininess) in_.fail(p, fmt::format("shininess {} is above {:g}", v, kMaxShininess));
      shininess = v;
    }
    // Thin glass (scene.h): what passes straight through.
    transmittance = fraction(spec, ptr, "transmittance");
    if (auto it = spec.find("texture"); it != spec.end())
      texture = readTexture(*it, Reader::child(ptr, "texture"));
    if (auto it = spec.find("emissionTexture"); it != spec.end())
      emissionTexture = readTexture(*it, Reader::child(ptr, "emissionTexture"));
    // A tangent-space normal map: data, read without the sRGB curve (render/normal_map.h).
    if (auto it = spec.find("normalTexture"); it != spec.end())
      normalTexture = readTexture(*it, Reader::child(ptr, "normalTexture"), false);
    if (auto it = spec.find("normalScale"); it != spec.end())
      normalScale = in_.number(*it, Reader::child(ptr, "normalScale"));

    for (size_t i : targets) {
      Material& m = scene_.materials[i];
      if (reflectance) m.reflectance = *reflectance;
      if (emission) m.emission = *emission;
      if (strength) m.emission *= *strength;
      if (twoSided) m.twoSided = *twoSided;
      if (specular) m.specular = *specular;
      if (shininess) m.shininess = *shininess;
      if (texture) m.reflectanceTexture = *texture;
      if (emissionTexture) m.emissionTexture = *emissionTexture;
      if (normalTexture) m.normalTexture = *normalTexture;
      if (normalScale) m.normalScale = *normalScale;
      if (transmittance) m.transmittance = *transmittance;
      // Passing and reflecting more than arrives would make light. Said where the user typed it;
      // a file's glass is lowered with a warning at import instead.
      if ((transmittance || reflectance) && m.transmits())
        for (int c = 0; c < 3; ++c)
          if (m.reflectance[c] + m.transmittance[c] > 1.0f)
            in_.fail(Reader::child(ptr, transmittance ? "transmittance" : "reflectance"),
                     fmt::format("reflectance ({}, {}, {}) plus transmittance ({}, {}, {}) is above 1", m.reflectance.r,
                                 m.reflectance.g, m.reflectance.b, m.transmittance.r, m.transmittance.g,
                                 m.transmittance.b));
    }
  }

  // A material's colour `key` that is a share of the light (the highlight's, the glass's): each
  // channel in [0, 1], an error above, where the user typed it.
  std::optional<Rgb> fraction(const Json& spec, const std::string& ptr, const char* key) const {
    auto it = spec.find(key);
    if (it == spec.end()) return std::nullopt;
    std::string p = Reader::child(ptr, key);
    Rgb c = in_.color(*it, p);
    if (c.x > 1.0f || c.y > 1.0f || c.z > 1.0f) in_.fail(p, fmt::format("{} ({}, {}, {}) is above 1", key, c.x, c.y, c.z));
    return c;
  }

  // A path relative to the scene file, decoded from sRGB (colour) or read as stored (data, when
  // not `srgb`); null removes the texture.
  int readTexture(const Json& j, const std::string& ptr, bool srgb = true) {
    if (j.is_null()) return -1;
    fs::path file = resolve(in_.string(j, ptr));
    std::string key = (srgb ? "colour " : "data ") + file.string();
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    Texture tex;
    try {
      tex = loadTexture(file, srgb);
    } catch (const Error& e) {
      in_.fail(ptr, e.what());
    }
    int index = int(scene_.textures.size());
    scene_.textures.push_back(std::move(tex));
    textures_[key] = index;
    return index;
  }

  Light readLight(const Json& j, const std::string& ptr, size_t index) const {
    in_.object(j, ptr);
    if (!j.contains("type")) in_.fail(ptr, "missing key 'type'");
    std::string typePtr = Reader::child(ptr, "type");
    std::string type = in_.string(j["type"], typePtr);
    Light light;
    if (type == "point") {
      light.type = Light::Type::Point;
      in_.keys(j, ptr, {"type", "name", "color", "intensity", "position", "animation"});
    } else if (type == "spot") {
      light.type = Light::Type::Spot;
      in_.keys(j, ptr,
               {"type", "name", "color", "intensity", "position", "direction", "target",
                "innerConeAngle", "outerConeAngle", "animation"});
    } else if (type == "directional") {
      light.type = Light::Type::Directional;
      in_.keys(j, ptr, {"type", "name", "color", "intensity", "direction", "angularRadius", "animation"});
    } else if (type == "sky") {
      light.type = Light::Type::Sky;
      in_.keys(j, ptr, {"type", "name", "color", "intensity", "animation"});
    } else if (type == "cie-overcast") {
      light.type = Light::Type::CieOvercastSky;
      in_.keys(j, ptr, {"type", "name", "color", "intensity", "animation"});
    } else {
      in_.fail(typePtr, fmt::format("unknown light type '{}' (expected point, spot, directional, "
                                    "sky, cie-overcast)",
                                    type));
    }

    light.name = fmt::format("light{}", index);
    if (auto it = j.find("name"); it != j.end())
      light.name = in_.string(*it, Reader::child(ptr, "name"));
    if (auto it = j.find("color"); it != j.end())
      light.color = in_.color(*it, Reader::child(ptr, "color"));
    if (auto it = j.find("intensity"); it != j.end())
      light.intensity = in_.nonNegative(*it, Reader::child(ptr, "intensity"));

    auto require = [&](const char* key) -> const Json& {
      if (!j.contains(key)) in_.fail(ptr, fmt::format("a {} light needs '{}'", type, key));
      return j[key];
    };
    if (light.type == Light::Type::Point || light.type == Light::Type::Spot)
      light.position = in_.vec3(require("position"), Reader::child(ptr, "position"));
    if (light.type == Light::Type::Directional)
      light.direction = in_.direction(require("direction"), Reader::child(ptr, "direction"));
    if (light.type == Light::Type::Spot) {
      bool hasDir = j.contains("direction"), hasTarget = j.contains("target");
      if (hasDir == hasTarget)
        in_.fail(ptr, "a spot light needs exactly one of 'direction' and 'target'");
      if (hasDir) {
        light.direction = in_.direction(j["direction"], Reader::child(ptr, "direction"));
      } else {
        std::string p = Reader::child(ptr, "target");
        Vec3 d = in_.vec3(j["target"], p) - light.position;
        if (!(glm::length(d) > 0.0f)) in_.fail(p, "target is at the light's position");
        light.direction = glm::normalize(d);
      }
      float inner = 0.0f, outer = 45.0f;  // degrees, from the axis to the cone's edge
      if (auto it = j.find("innerConeAngle"); it != j.end())
        inner = in_.nonNegative(*it, Reader::child(ptr, "innerConeAngle"));
      if (auto it = j.find("outerConeAngle"); it != j.end())
        outer = in_.nonNegative(*it, Reader::child(ptr, "outerConeAngle"));
      if (!(outer > 0.0f) || outer > 90.0f)
        in_.fail(Reader::child(ptr, "outerConeAngle"),
                 fmt::format("must be in (0, 90] degrees, got {}", outer));
      if (inner > outer)
        in_.fail(Reader::child(ptr, "innerConeAngle"),
                 fmt::format("{} degrees is wider than outerConeAngle ({})", inner, outer));
      light.innerConeAngle = radians(inner);
      light.outerConeAngle = radians(outer);
    }
    if (light.type == Light::Type::Directional) {
      if (auto it = j.find("angularRadius"); it != j.end()) {
        std::string p = Reader::child(ptr, "angularRadius");
        float r = in_.nonNegative(*it, p);
        if (r >= 90.0f) in_.fail(p, fmt::format("must be below 90 degrees, got {}", r));
        light.angularRadius = radians(r);
      }
    }
    return light;
  }

  Camera readCamera(const Json& j, const std::string& ptr, size_t index) const {
    in_.object(j, ptr);
    in_.keys(j, ptr, {"name", "eye", "target", "up", "fov"});
    Camera cam;
    cam.name = fmt::format("camera{}", index);
    if (auto it = j.find("name"); it != j.end())
      cam.name = in_.string(*it, Reader::child(ptr, "name"));
    for (const char* key : {"eye", "target"})
      if (!j.contains(key)) in_.fail(ptr, fmt::format("a camera needs '{}'", key));
    cam.eye = in_.vec3(j["eye"], Reader::child(ptr, "eye"));
    cam.target = in_.vec3(j["target"], Reader::child(ptr, "target"));
    if (!(glm::length(cam.target - cam.eye) > 0.0f))
      in_.fail(Reader::child(ptr, "target"), "target is at the eye");
    if (auto it = j.find("up"); it != j.end())
      cam.up = in_.direction(*it, Reader::child(ptr, "up"));
    if (glm::length(glm::cross(glm::normalize(cam.target - cam.eye), cam.up)) < 1e-6f)
      in_.fail(Reader::child(ptr, "up"), "up is parallel to the viewing direction");
    if (auto it = j.find("fov"); it != j.end()) {
      std::string p = Reader::child(ptr, "fov");
      cam.fovY = in_.number(*it, p);
      if (!(cam.fovY > 0.0f) || !(cam.fovY < 180.0f))
        in_.fail(
            p, fmt::format("vertical field of view must be in (0, 180) degrees, got {}", cam.fovY));
    }
    return cam;
  }

  std::string name_;
  fs::path folder_;
  Reader in_;
  Scene scene_;
  std::map<std::string, int> textures_;  // textures this file loaded, by decoding and path
  std::set<std::string> omitted_;         // materials whose meshes are left out (/materials/NAME/omit)
};

}  // namespace

Scene loadSceneJson(std::string_view text, const fs::path& baseFolder, std::string_view name) {
  const std::string file(name);
  Json doc;
  try {
    doc = parseJsonWithoutDuplicateKeys(text, file);
  } catch (const Json::parse_error& e) {
    // what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: ...".
    std::string what = e.what();
    if (size_t close = what.find("] ");
        what.rfind("[json.exception", 0) == 0 && close != std::string::npos)
      what = what.substr(close + 2);
    throw Error(fmt::format("{}: invalid JSON at byte {}: {}", file, e.byte, what));
  } catch (const Json::exception& e) {
    // Anything else the parser rejects, e.g. a number that overflows a double (1e999).
    std::string what = e.what();
    if (size_t close = what.find("] "); close != std::string::npos) what = what.substr(close + 2);
    throw Error(fmt::format("{}: invalid JSON: {}", file, what));
  }
  Scene scene = SceneFileLoader(baseFolder, file).load(doc);
  warnAboutStrayMesh(scene, file);  // first: what follows is measured against the extent
  removeCoincidentFaces(scene);  // across files: each file's own copies went at its import
  return scene;
}

Scene loadSceneFile(const fs::path& path) {
  const std::string file = path.string();
  if (const std::optional<std::string> why = whyNotARegularFile(path)) throw Error(fmt::format("{}: {}", file, *why));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: cannot open file", file));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(fmt::format("{}: read error", file));
  return loadSceneJson(text, path.parent_path(), file);
}

}  // namespace luxel
