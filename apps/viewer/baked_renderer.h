// Draws what `luxel bake` wrote into a glb (BakedGlb) as an engine would: per-vertex radiance as
// it is, per-vertex or lightmap irradiance times the base colour over pi, plus emission
// (docs/baking.md's recipes), transfer lightmaps relit by a light that can change between frames,
// backs culled unless a material is double-sided. Needs a current
// OpenGL 4.5 context; draws into the bound HdrTarget with the SceneRenderer's conventions
// (reversed depth, radiance times the output scale).
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "baked_glb.h"

namespace luxel::viewer {

class BakedRenderer {
 public:
  BakedRenderer(const BakedGlb& glb, const std::filesystem::path& shaderDir);
  ~BakedRenderer();
  BakedRenderer(const BakedRenderer&) = delete;
  BakedRenderer& operator=(const BakedRenderer&) = delete;

  void draw(const glm::mat4& viewProjection, float outputScale);
  // The light that relights LUXEL_lightmap_transfer materials: the glb's bands^2 RGB coefficients
  // of radiance SH (transferLightSh). Throws luxel::Error when the count is not the glb's.
  void setTransferLight(const std::vector<Rgb>& sh);

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
};

}  // namespace luxel::viewer
