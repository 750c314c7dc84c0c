// Draws the texels view: the scene's faces with the lightmap atlas `luxel bake` would make for them,
// each texel coloured by what the bake would make of it (luxel/texel_diagnostics.h): a checker per
// chart, so that texel sizes and chart borders show; red where a texel lies inside geometry
// (invalid), magenta where two faces' UVs claim it (overlap), yellow where bilinear filtering
// reads another chart's texel (no gutter). Needs a current OpenGL 4.5 context; draws into the
// bound HdrTarget with the SceneRenderer's conventions (reversed depth, colours times the output
// scale, element ids for picking: each face writes its first element in the solve's surfaces).
#pragma once

#include <filesystem>
#include <memory>

#include <glm/glm.hpp>

#include "luxel/lightmap.h"
#include "luxel/scene.h"
#include "luxel/surface.h"
#include "luxel/texel_diagnostics.h"

namespace luxel::viewer {

class TexelRenderer {
 public:
  TexelRenderer(const Scene& scene, const SurfaceSet& surfaces, const LightmapAtlas& atlas,
                const TexelDiagnostics& diagnostics, const std::filesystem::path& shaderDir);
  ~TexelRenderer();
  TexelRenderer(const TexelRenderer&) = delete;
  TexelRenderer& operator=(const TexelRenderer&) = delete;

  void draw(const glm::mat4& viewProjection, float outputScale);

 private:
  struct Gl;
  std::unique_ptr<Gl> gl_;
};

}  // namespace luxel::viewer
