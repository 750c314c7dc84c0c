// The scene: meshes, materials, textures, lights and cameras, in the units the user gave.
//
// Units are physical and consistent: emission is radiance (W m^-2 sr^-1, or cd/m^2 when the
// user works photometrically); a surface with emission Le has exitance pi * Le. Lengths are in
// scene units (metres for the built-in scenes). Nothing in here is discretised yet: that is
// SurfaceSet's job (surface.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/animation.h"

namespace luxel {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Rgb = glm::vec3;  // linear RGB

// A linear-RGB texture. Texels are stored bottom row first (v = 0 at row 0), as glTF and OBJ
// texture coordinates expect after the loader's flip.
struct Texture {
  std::string path;  // where it came from, for error messages
  int width = 0;
  int height = 0;
  std::vector<Rgb> texels;  // width * height, linear

  // Bilinear lookup with wrap-around (repeat) addressing.
  Rgb sample(Vec2 uv) const;
  // Mean over the whole image.
  Rgb mean() const;
};

struct Material {
  std::string name;
  Rgb reflectance{0.8f};       // diffuse albedo in [0,1); multiplies the texture when there is one
  int reflectanceTexture = -1;  // index into Scene::textures, -1 for none
  Rgb emission{0.0f};          // emitted radiance; multiplies the emission texture
  int emissionTexture = -1;
  // A tangent-space normal map (glTF 2.0 normalTexture): index into Scene::textures, -1 for none.
  // Its texels are data, stored undecoded in [0,1] (no sRGB curve): the normal is 2 * texel - 1,
  // x along +u, y along +v (green up, OpenGL's convention), z out of the surface. normalScale
  // multiplies x and y (glTF's normalTexture.scale; 0 leaves the surface flat). Only shading
  // reads it (render/normal_map.h, docs/scene-format.md "Normal maps"); the solve does not.
  int normalTexture = -1;
  float normalScale = 1.0f;
  // A Blinn-Phong highlight, for display only: the viewer draws it for the lights it shades per
  // pixel (point, spot and directional; seed 004 section 3.1). The radiosity solve, `luxel render`
  // and the bakes are purely diffuse and never read these two fields.
  //  - specular: the highlight's reflectance colour, linear, each in [0,1] (OBJ Ks).
  //  - shininess: the Blinn-Phong exponent s (OBJ Ns), in [0, 10000]; 0 draws no highlight.
  // The exponent is used as written, unnormalised, as in 004's Listing 1 and the fixed-function
  // model the files' Ks and Ns were tuned for: a light of irradiance E (its N.L included) adds
  //   radiance = specular / pi * pow(max(N.H, 0), shininess) * E,   H = normalize(toLight + toEye),
  // beside the diffuse reflectance / pi * E, so Ks and Kd keep the proportion their author saw. No
  // (s+8)/(8 pi) normalisation: that would make Ns 96 highlights 13 times brighter than authored.
  // Unnormalised, the lobe reflects at most `specular` of the light (pow(...) <= 1), so
  // reflectance + specular <= 1 never creates energy. See hasSpecular().
  Rgb specular{0.0f};
  float shininess = 0.0f;
  // Surfaces take part in light transport through their front face only (counter-clockwise
  // winding, geometric normal): they emit, receive and reflect there. A two-sided material gets a
  // back face as well, with its own radiosity, so light never passes through a zero-thickness
  // wall. Faces whose back receives more direct light than their front are turned round at
  // discretisation (docs/algorithms.md, "Sides and winding").
  bool twoSided = false;
  // Thin glass: the share of light that passes straight through the surface, per channel (OBJ Tf
  // with a transparent illum, or 1 - d; glTF KHR_materials_transmission times the base colour);
  // zero for an opaque surface. The shadow rays of the lights (lamps, suns, skies) pass it,
  // filtered by it; light from surfaces (emitting or reflecting) does not: docs/algorithms.md,
  // "Thin glass". At most 1 - reflectance per channel.
  Rgb transmittance{0.0f};
  bool transmits() const { return transmittance.r > 0.0f || transmittance.g > 0.0f || transmittance.b > 0.0f; }

  bool isEmissive() const { return emission.r > 0.0f || emission.g > 0.0f || emission.b > 0.0f; }
  // Whether the viewer draws a highlight: a positive exponent and a specular colour that is not black.
  bool hasSpecular() const {
    return shininess > 0.0f && (specular.r > 0.0f || specular.g > 0.0f || specular.b > 0.0f);
  }
};

// The largest Blinn-Phong exponent (Material::shininess) a scene may give. MTL's Ns goes to 1000;
// pow(N.H, 10000) halves within 0.7 degrees of the half vector, a highlight near a mirror's, and
// larger exponents only risk underflow in a shader's pow.
inline constexpr float kMaxShininess = 10000.0f;

// Faces are quads or triangles. A triangle repeats its last vertex (v[3] == v[2]), which is the
// layout Embree's quad geometry accepts directly.
struct Face {
  std::array<uint32_t, 4> v{};
  bool isTriangle() const { return v[3] == v[2]; }
  int vertexCount() const { return isTriangle() ? 3 : 4; }
};

// An object: meshes placed together by one transform, from a glTF, FBX or COLLADA node or a
// named object of a scene file. A dynamic object moves after loading (Scene::placeObject): the
// ray tracer keeps it as an instance, so a move is a transform and a commit, not a rebuild.
struct Object {
  std::string name;
  glm::mat4 transform{1.0f};  // object space to world space
  bool dynamic = false;
  // The transform under which its meshes' restPositions were recorded (its first move).
  glm::mat4 restTransform{1.0f};
};
inline constexpr uint32_t kNoObject = 0xFFFFFFFFu;

struct Mesh {
  std::string name;
  // The object that places this mesh (index into Scene::objects), or kNoObject for geometry given
  // in world space. `positions` are always in world space, the object's transform applied.
  uint32_t object = kNoObject;
  std::vector<Vec3> positions;
  std::vector<Vec2> uvs;  // empty, or one per position
  // Empty, or one per position: a second UV set (glTF TEXCOORD_1) laying the mesh out in a
  // lightmap, in [0,1] without overlaps (checked by buildLightmapAtlas, lightmap.h).
  std::vector<Vec2> lightmapUvs;
  std::vector<Face> faces;
  uint32_t material = 0;  // index into Scene::materials
  // Optional element grids, for scenes whose element counts are prescribed (the seed papers' test
  // scenes): empty, or one per face, {elements along s, elements along t}; {0, 0} leaves the face
  // to the automatic cut (DiscretiseOptions' size or budget). A quad with {nu, nv} is cut into
  // exactly nu x nv elements, uniform in its parameter space (s from v[0] to v[1], t from v[0] to
  // v[3]), grouped into patches of about elementsPerPatchSide x elementsPerPatchSide elements. A
  // triangle needs nu == nv = n and gets n^2 elements. Hinted elements count as fixed: the budget
  // search sizes only the other faces, with what the hinted ones leave of the budget. A quad that
  // discretisation has to cut in two (non-planar or non-convex) falls back to the automatic cut;
  // the back face of a two-sided material keeps the grid.
  std::vector<std::array<uint16_t, 2>> elementGrids;
  // World positions where the mesh stood when its object was first moved (Scene::placeObject):
  // every later pose is computed from these, so that many moves do not accumulate rounding.
  std::vector<Vec3> restPositions;
};

struct Light {
  enum class Type { Point, Spot, Directional, Sky, CieOvercastSky };
  Type type = Type::Point;
  std::string name;
  Rgb color{1.0f};
  // Point and spot: radiant intensity (W/sr, or cd). Directional: irradiance on a surface facing
  // the light (W/m^2, or lux). Sky: radiance (uniform) or zenith radiance (CIE overcast).
  float intensity = 1.0f;
  Vec3 position{0.0f};
  Vec3 direction{0.0f, -1.0f, 0.0f};  // the direction light travels (spot, directional)
  float innerConeAngle = 0.0f;        // radians, spot: full intensity inside
  float outerConeAngle = 0.7853982f;  // radians, spot: zero outside, smooth in between
  float angularRadius = 0.0f;         // radians, directional: the sun's disc (0.00465 for the sun)

  Rgb power() const { return color * intensity; }
};

struct Camera {
  std::string name;
  Vec3 eye{0.0f, 0.0f, 1.0f};
  Vec3 target{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = 45.0f;  // vertical field of view, degrees
};

// Limits every scene value obeys (Scene::validate), so that what is computed from them stays finite
// in float: a face's area is a squared length, form factors divide by squared distances, and
// energies are sums over millions of elements.
//  - Coordinates (vertices, lights, cameras): |x| <= 1e9 scene units, a million km in metres. A
//    cross product of two edges is then at most ~1e18 and its squared length ~1e37 < FLT_MAX.
//    (Embree also rejects ray origins beyond ~1.8e18.)
//  - Emitted radiance and light intensity times colour: at most 1e15 per channel, about a million
//    times the sun's luminance (1.6e9 cd/m^2), so a million elements' summed power stays ~1e30.
inline constexpr float kMaxCoordinate = 1e9f;
inline constexpr float kMaxRadiance = 1e15f;

struct Scene {
  std::string name;
  std::vector<Object> objects;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  Vec3 up{0.0f, 1.0f, 0.0f};  // the zenith, for skies
  Animation animation;        // what moves with time (luxel/animation.h); empty: a still scene
  std::vector<std::string> warnings;  // what loading repaired (clamped albedo, ...), for the caller to show

  size_t faceCount() const;
  size_t triangleCount() const;  // quads count as two
  // Throws luxel::Error naming the mesh and face when indices, materials or values are invalid
  // (out of range, NaN, negative emission, reflectance or specular outside [0,1], shininess
  // outside [0, kMaxShininess], empty scene).
  void validate() const;
  // The parts of validate() for materials and lights alone (an edit of either checks only these).
  void validateMaterials() const;
  void validateLights() const;
  // The part of validate() for the animation: every animated object exists and is dynamic, every
  // animated light exists, and every motion is finite with unit axes and rotations, positive
  // scales and strictly increasing key times.
  void validateAnimation() const;
  const Camera* findCamera(const std::string& name) const;
  int findMaterial(const std::string& name) const;  // -1 when absent
  int findObject(const std::string& name) const;    // -1 when absent
  // Whether anything gives light: a light of positive intensity, or an emissive material that a
  // face uses. A scene without light solves to black.
  bool hasLight() const;
  std::vector<uint32_t> dynamicObjects() const;     // indices of the objects marked dynamic

  // Moves a dynamic object to `transform` (object to world): its meshes' positions follow.
  // Throws Error when the object is not dynamic, or the transform is not finite or not a
  // similarity (rotation, translation and uniform scale: a mirror or a shear would change the
  // faces' areas unevenly and turn fronts round).
  void placeObject(uint32_t object, const glm::mat4& transform);
  // What placeObject checks, without moving anything.
  void checkPlacement(uint32_t object, const glm::mat4& transform) const;
};

// The transform that takes geometry from where it stood under `from` to where it stands under
// `to` (to * inverse(from)), checked to be a similarity with positive scale; `scale` receives its
// uniform scale. Throws Error naming `what` otherwise.
glm::mat4 similarityBetween(const glm::mat4& from, const glm::mat4& to, const std::string& what, float* scale = nullptr);

}  // namespace luxel
