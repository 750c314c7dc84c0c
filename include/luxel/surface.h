// The discretised scene: faces cut into elements (which receive and are displayed) grouped into
// patches (which shoot), after Cohen, Greenberg, Immel and Brock, "An Efficient Radiosity
// Approach for Realistic Image Synthesis", IEEE CG&A 6(3), 1986 (substructuring).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

// A planar convex polygon with 3 or 4 corners, counter-clockwise seen from its front.
struct Polygon {
  std::array<Vec3, 4> v{};
  int count = 0;

  Vec3 centroid() const;
  Vec3 normal() const;  // unit, from the winding
  float area() const;
  // Whether the area is above rounding noise for the polygon's own size (1e-14 of its longest
  // edge squared). Relative to the face, not the scene: a small face (a lamp) in a scene whose
  // extent is huge is still a face.
  bool hasArea() const;
};

// A scene face after import, kept so elements can be re-cut from its parameter space.
// Quads map (s,t) in [0,1]^2 bilinearly; triangles map barycentric (s,t) with s+t <= 1.
struct SurfaceFace {
  std::array<Vec3, 4> corners{};
  std::array<Vec2, 4> uvs{};
  bool triangle = false;
  uint32_t mesh = 0;
  uint32_t meshFace = 0;  // index into Scene::meshes[mesh].faces: the face this was cut from
  uint32_t material = 0;
  Vec3 normal{0.0f};
  int32_t twin = -1;     // the other side of a two-sided face, or -1
  bool flipped = false;  // turned round because its back received more direct light

  Vec3 position(Vec2 st) const;
  Vec2 uv(Vec2 st) const;
};

// Element::patch of a set without patches (SurfaceSet::dropPatches).
inline constexpr uint32_t kNoPatch = 0xffffffffu;

struct Element {
  Polygon polygon;                   // in world space
  std::array<Vec2, 4> param{};       // corners in the face's parameter space
  Vec3 centroid{0.0f};
  Vec3 normal{0.0f};
  float area = 0.0f;
  uint32_t face = 0;                 // index into SurfaceSet::faces
  uint32_t patch = 0;                // index into SurfaceSet::patches, or kNoPatch
  uint32_t material = 0;
  Rgb reflectance{0.0f};             // albedo averaged over the element (texture included)
  Rgb exitance{0.0f};                // emitted exitance, pi * Le averaged over the element
  uint8_t depth = 0;                 // adaptive refinement level, 0 for the initial cut
};

struct Patch {
  Polygon polygon;
  Vec3 centroid{0.0f};
  Vec3 normal{0.0f};
  float area = 0.0f;
  uint32_t face = 0;
  std::vector<uint32_t> elements;  // indices into SurfaceSet::elements
};

struct DiscretiseOptions {
  // Target element edge length in scene units. When 0, derived from elementBudget.
  float elementSize = 0.0f;
  // Approximate total number of elements wanted (used when elementSize is 0).
  size_t elementBudget = 10000;
  // A patch is about this many elements along each side.
  int elementsPerPatchSide = 8;
  // Turn faces round whose back receives more direct light than their front (models with
  // inconsistent winding).
  bool orientByLight = true;
};

struct SurfaceSet {
  std::vector<SurfaceFace> faces;
  std::vector<Patch> patches;
  std::vector<Element> elements;
  float elementSize = 0.0f;  // the target size that was used
  float sceneExtent = 0.0f;  // bounding-box diagonal
  size_t flippedFaces = 0;   // faces turned round by orientByLight
  size_t splitQuads = 0;     // non-planar quads cut into two triangles

  // Each scene object's transform when these surfaces were cut (Scene::objects, same order).
  std::vector<glm::mat4> objectTransforms;
  // Where a dynamic object's faces, patches and elements were cut, recorded at its first move, so
  // that every pose is computed from them (no rounding builds up over many moves).
  struct RestPose {
    uint32_t object = 0;
    std::vector<uint32_t> faces, patches, elements;
    std::vector<SurfaceFace> faceRest;
    std::vector<Patch> patchRest;
    std::vector<Element> elementRest;
  };
  std::vector<RestPose> restPoses;

  float totalArea() const;
  // Patches are the flat solvers' shooters. A set cut for a solver that does not shoot from them
  // (the face-cluster hierarchy) can drop them: at one element a face they are a third of the
  // set's memory. Afterwards every element's patch is kNoPatch.
  bool hasPatches() const { return !patches.empty(); }
  void dropPatches();
  // Moves the faces, patches and elements of scene.objects[object] to where its current transform
  // puts them (after Scene::placeObject). Throws Error when the move is not a similarity, or the
  // object's elements were refined after its first move.
  void placeObject(const Scene& scene, uint32_t object);
  // Reads every element's reflectance and exitance again from its face's material (after the
  // scene's materials were edited); geometry is untouched.
  void refreshMaterials(const Scene& scene);
  // Splits element `e` into four (quads at parameter midpoints, triangles at edge midpoints).
  // The first child reuses index `e`; the other three are appended. Patches are updated.
  void splitElement(uint32_t e, const Scene& scene);
};

// Cuts every face of `scene` into patches and elements. Throws Error when the scene has no
// face with positive area or the options are absurd (negative sizes, a budget over 50 million).
SurfaceSet discretise(const Scene& scene, const DiscretiseOptions& options);

}  // namespace luxel
