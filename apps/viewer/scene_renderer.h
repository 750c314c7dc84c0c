// Draws a discretised scene and its radiosity solution with OpenGL 4.5: element fields
// interpolated per pixel as the ray-cast renderer does, plus direct light per pixel from point, spot
// and sun lights with shadow maps (the dynamic direct light of seed 004 over the radiosity's
// indirect light), and the debug views. Needs a current OpenGL 4.5 core context.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene.h"
#include "luxel/surface.h"

namespace luxel::gl {
class ShaderProgram;
}

namespace luxel::viewer {

// Baked: what a glb from `luxel bake` carries, drawn as an engine would (baked_renderer.h);
// Texels: the bake's texels and their faults (texel_renderer.h).
enum class ViewMode { Final, Indirect, Direct, Radiosity, Patches, Elements, Density, Unshot, Baked, Texels };
ViewMode parseViewMode(const std::string& name);  // throws luxel::Error listing the modes
const char* viewModeName(ViewMode mode);
inline constexpr int kViewModeCount = 10;

inline constexpr int kMaxPerPixelLights = 8;

// How per-pixel lights cast shadows: cube (and, for suns, orthographic) shadow maps drawn when a
// light changes, or 004's stencil shadow volumes drawn every frame (exact, one pass per light).
enum class ShadowMethod { Maps, Volumes };
ShadowMethod parseShadowMethod(const std::string& name);  // "maps" | "volumes"
const char* shadowMethodName(ShadowMethod method);

// Whether the viewer draws `light` per pixel (point, spot and sun lights); skies stay in the field.
bool drawnPerPixel(const Light& light);

class SceneRenderer {
 public:
  // `shaderDir`: a folder whose files replace built-in shaders (view_shaders.h), or empty.
  SceneRenderer(const Scene& scene, const SurfaceSet& surfaces, std::filesystem::path shaderDir = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // The elements' places, normals and materials again (after a move or a new cut); the scene's
  // textures were read once, by the constructor.
  void setGeometry(const Scene& scene, const SurfaceSet& surfaces);
  // Per element corner (4 per element, elementCornerValues' layout): the field drawn by
  // interpolation (all irradiance but the per-pixel lights'), its direct part, and the per-pixel
  // lights' part.
  void setFields(const std::vector<Rgb>& field, const std::vector<Rgb>& direct, const std::vector<Rgb>& perPixel);
  // Per element, where the solve has work left, in [0, 1] (the unshot view's heat: 0 nothing or a
  // millionth of the most, 1 the most); empty: nothing known (the view is black).
  void setUnshot(const std::vector<float>& heat);
  // Which lights are drawn per pixel (indices into scene.lights, at most kMaxPerPixelLights) and
  // their shadow maps, drawn again now.
  void setLights(const Scene& scene, const std::vector<uint32_t>& perPixel);
  // Changes how shadows are drawn (the maps are drawn again when chosen).
  void setShadowMethod(ShadowMethod method);
  ShadowMethod shadowMethod() const { return shadowMethod_; }
  // Per-pixel lights shaded at each element corner and interpolated (Gouraud; 004's per-vertex
  // option) instead of at each pixel.
  void setPerVertex(bool perVertex);
  bool perVertex() const { return perVertex_; }
  // Compiles the shaders again (from the shader folder when there is one). Throws luxel::Error
  // with the compiler's log and keeps the old programs when one does not compile.
  void reloadShaders();

  struct Frame {
    ViewMode mode = ViewMode::Final;
    glm::mat4 viewProjection{1.0f};
    Vec3 eye{0.0f};
    float texelSize = 0.1f;  // the density view's checker
    bool elementEdges = false, patchEdges = false;
    float outputScale = 1.0f;  // radiance is stored times this (HdrTarget: half floats near the exposure)
  };
  // Draws into the bound framebuffer (an HdrTarget's: radiance and element ids), which it clears.
  void draw(const Frame& frame);


 private:
  struct Gl;
  void buildPrograms();
  gl::ShaderProgram& sceneProgram(ViewMode mode, int lights, bool lightOnly, bool highlight);
  void drawSky(const Frame& frame);
  // The surfaces with `lights` per-pixel lights from index `first` (one light's additive pass when
  // `lightOnly`), shadowed by the maps when `withShadowMaps`.
  void drawSurfaces(const Frame& frame, int lights, bool lightOnly, int first, bool withShadowMaps);
  void drawVolumes(const Frame& frame, int light);
  void drawEdges(const Frame& frame);
  ShadowMethod shadowMethod_ = ShadowMethod::Maps;
  bool perVertex_ = false;
  void drawShadows();
  std::unique_ptr<Gl> gl_;
  std::filesystem::path shaderDir_;
  int shadowSize_ = 512;  // cube map faces: 512 on a CPU rasteriser, 2048 on a GPU (the constructor)
  int sunSize_ = 2048;     // the sun's map: 2048, or 4096 on a GPU
};

}  // namespace luxel::viewer
