// Draws what `luxel bake` wrote into a glb (BakedGlb) as an engine would: per-vertex radiance as
// it is, per-vertex or lightmap irradiance times the base colour over pi, plus emission
// (docs/baking.md's recipes), backs culled unless a material is double-sided. Needs a current
// OpenGL 4.5 context; draws into the bound HdrTarget with the SceneRenderer's conventions
// (reversed depth, radiance times the output scale).
#pragma once

#include <filesystem>
#include <memory>

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

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
};

}  // namespace luxel::viewer
