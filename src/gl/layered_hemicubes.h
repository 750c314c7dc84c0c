// Hemicubes rendered many at a time into layered targets, each centred where a buffer on the GPU
// says (GpuShooter records: centre and normal), so the CPU never reads back who renders. Two
// kinds of content:
//  - ItemsAndDistances: per pixel, the item id of the nearest polygon (seed 001's ID hemicube)
//    and its distance from the centre (seed 003's depth hemicube), for progressive shooting;
//  - Radiosity: per pixel, the radiosity of the nearest polygon from a buffer indexed by item
//    (black from behind: a one-sided surface radiates only in front), for gathering (seed 000
//    and 001 section 4.2).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "gl/hemicube_layering.h"
#include "luxel/surface.h"

namespace luxel::gl {

class LayeredHemicubes {
 public:
  enum class Content { ItemsAndDistances, Radiosity };
  using Layering = HemicubeLayering;

  // `items[i]` (>= 1) is the id polygon i draws. Needs a current OpenGL 4.5 context. Room for
  // `capacity` hemicubes of five faces, `resolution` pixels a side.
  // Throws Error when `layering` asks for the vertex shader and the driver lacks the extension.
  LayeredHemicubes(std::span<const Polygon> polygons, std::span<const uint32_t> items, Content content,
                   int resolution, int capacity, float nearPlane, float farPlane,
                   Layering layering = Layering::Auto);
  ~LayeredHemicubes();
  LayeredHemicubes(const LayeredHemicubes&) = delete;
  LayeredHemicubes& operator=(const LayeredHemicubes&) = delete;

  // Renders hemicubes 0..count-1 from GpuShooter records first..first+count-1 of the buffer bound
  // at SHOOTER_BINDING (records marked inactive are drawn off screen). Radiosity reads the
  // per-item colours (vec4, index item - 1) bound at PATCH_RADIOSITY_BINDING.
  void render(int first, int count);
  // Replaces the polygons drawn (after objects moved), keeping the targets.
  void setPolygons(std::span<const Polygon> polygons, std::span<const uint32_t> items);
  // Binds the item layers to ITEM_TEXTURE_UNIT and the distance or radiosity layers to
  // DISTANCE_TEXTURE_UNIT, or to the units given (a pass that reads two sets of hemicubes).
  void bindTextures() const;
  void bindTextures(int itemUnit, int distanceUnit) const;

  int resolution() const { return resolution_; }
  Layering layering() const { return layering_; }  // GeometryShader or VertexShader, as chosen
  int capacity() const { return capacity_; }
  float nearPlane() const { return near_; }
  float farPlane() const { return far_; }

  // The faces of `surfaces` as items: a two-sided face and its twin drawn once, under one id
  // (the smaller index + 1), so that the two coincident sides cannot z-fight.
  static uint32_t itemOfFace(const SurfaceSet& surfaces, uint32_t face);
  static void faceItems(const SurfaceSet& surfaces, std::vector<Polygon>& polygons, std::vector<uint32_t>& items);
  // For each face, the ids of the faces that share a corner position with it (its twin's
  // neighbours included; at most kMaxNeighbours each), as a flat table: entries [t[f], t[f + 1])
  // of t are face f's. A point beside a convex edge is seen in a hemicube's pixel as the face
  // round the edge, one of these; a face beyond a thin wall is not.
  static std::vector<uint32_t> neighbourItems(const SurfaceSet& surfaces);
  static constexpr size_t kMaxNeighbours = 16;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Content content_;
  Layering layering_ = Layering::GeometryShader;
  int resolution_ = 0, capacity_ = 0;
  float near_ = 0.0f, far_ = 0.0f;
};

}  // namespace luxel::gl
