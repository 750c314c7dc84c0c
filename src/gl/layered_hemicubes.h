// The hemicubes of a pass of GPU progressive refinement (seed 001 section 4.3; seed 003's texel
// shooting): one per shooter sample, whose centre and normal the GPU itself wrote into the
// shooter buffer (GpuShooter), so the CPU never reads back who shoots. Each hemicube renders its
// five faces into two layered targets: the item id of the nearest face (001's ID hemicube) and
// its distance from the centre (003's depth hemicube). The reconstruction pass looks into either.
#pragma once

#include <memory>
#include <vector>

#include "luxel/surface.h"

namespace luxel::gl {

class ShooterHemicubes {
 public:
  // Items are the faces of `surfaces`, a two-sided face and its twin under one id (the smaller
  // index + 1; see itemOfFace), so that the two coincident sides cannot z-fight. Needs a current
  // OpenGL 4.5 context. `hemicubes` layers of five faces of `resolution` pixels a side.
  ShooterHemicubes(const SurfaceSet& surfaces, int resolution, int hemicubes, float nearPlane, float farPlane);
  ~ShooterHemicubes();
  ShooterHemicubes(const ShooterHemicubes&) = delete;
  ShooterHemicubes& operator=(const ShooterHemicubes&) = delete;

  // Renders hemicube h = 0..count-1 from GpuShooter h of `shooterBuffer` (inactive ones are
  // drawn off screen: the CPU does not know how many are active).
  void render(unsigned shooterBuffer, int count);
  // Binds the item layers to ITEM_TEXTURE_UNIT and the distances to DISTANCE_TEXTURE_UNIT.
  void bindTextures() const;

  int resolution() const { return resolution_; }
  int capacity() const { return hemicubes_; }
  float nearPlane() const { return near_; }
  float farPlane() const { return far_; }

  static uint32_t itemOfFace(const SurfaceSet& surfaces, uint32_t face);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int resolution_ = 0, hemicubes_ = 0;
  float near_ = 0.0f, far_ = 0.0f;
};

}  // namespace luxel::gl
