// Constants shared by the C++ side and the GLSL side, defined once: the shaders get them as
// #defines from glslPreamble(), so a vertex attribute or binding cannot drift between the two.
#pragma once

#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "solve/radiosity_system.h"
#include <glm/glm.hpp>

namespace luxel::gl {

constexpr int kPositionLocation = 0;  // vec3 world position
constexpr int kItemLocation = 1;      // uint item id (polygon index + 1; 0 is "nothing")

// The hemicube integration pass (hemicube.cpp): shader storage bindings, the texture unit of the
// five-layer item texture, and the work-group edge.
constexpr int kDeltaBinding = 0;    // uint[]: fixed-point delta form factors, top then side table
constexpr int kItemSumBinding = 1;  // uint[]: per item, the fixed-point sum of its pixels' deltas
constexpr int kItemTextureUnit = 0;
constexpr int kIntegrateGroup = 8;  // 8 x 8 = 64 pixel rows per work group
// Fixed point of the sums: one unit is 2^-31. A hemicube's deltas sum to 1 = 2^31 units, so no
// item's sum can overflow a uint; each pixel's delta is rounded once, on the CPU (at most 2^-32
// off), so a sum over N pixels is within N 2^-32 of the float sum (2.9e-6 for all 12,288 pixels
// of a 64-pixel hemicube, 4.6e-5 at 256), and in practice far closer since the roundings cancel.
constexpr double kFixedPointScale = 2147483648.0;

// GPU progressive refinement (progressive_gl.cpp): shader storage bindings of its passes, the
// texture unit of the shooters' distance layers, and work-group sizes.
constexpr int kElementBinding = 0;         // GpuElement[], read only
constexpr int kPatchBinding = 1;           // GpuPatch[], read only
constexpr int kPatchElementBinding = 2;    // uint[]: each patch's elements, in GpuPatch::ids.x/.y
constexpr int kPatchStateBinding = 3;      // GpuPatchState[]: unshot power this pass, shot yet
constexpr int kShooterBinding = 4;         // GpuShooter[]: one per hemicube of the pass
constexpr int kSolverStateBinding = 5;     // GpuSolverState
constexpr int kElementStateBinding = 6;    // GpuElementState[]: the solution
constexpr int kPatchRadiosityBinding = 7;  // vec4[]: radiosity per patch, that gathering renders
// uint[]: per face f, [items[f], items[f + 1]) index the ids of the faces that share a corner
// with it (LayeredHemicubes::neighbourItems)
constexpr int kFaceNeighbourBinding = 8;
// Redistribution after a move or a light edit (progressive_gl.cpp, the incremental method): per
// patch the radiosity it has shot and the emission its first shot carried (two vec4s), and the
// list of patches a redistribution pass shoots again.
constexpr int kRedistributionAmountBinding = 9;
constexpr int kRedistributionListBinding = 10;
// vec4[4 or 9 per element]: the L1 or L2 SH of what the shots brought each element (rgb), when a directional
// bake asked for it (Solver::recordIncidentSh).
constexpr int kElementShBinding = 11;
// Cross-redistribution on the GPU (cross_redistribution_gl.h): per patch, whether it moved and its
// twin's patch (uvec2); the back hemicubes' centres (GpuShooter[]); the moved elements' gather
// hemicubes' delta form factors (float[], top then side table); the back hemicubes' layers.
constexpr int kCrossPatchBinding = 12;
constexpr int kBackShooterBinding = 13;
constexpr int kCrossDeltaBinding = 14;
constexpr int kCrossEmitterBinding = 15;  // uint[]: the static emitting patches sampled exactly
// vec4[2 x pass slots x patches]: what each static patch's centre sees behind each moved patch of
// the pass (shot radiosity, w = 1 where its rays saw any of it; first-shot emission).
constexpr int kCrossBehindBinding = 16;
constexpr int kBackItemTextureUnit = 2;
constexpr int kBackDistanceTextureUnit = 3;
constexpr int kDistanceTextureUnit = 1;    // R32F distances (or RGBA32F radiosity) of layered hemicubes
constexpr int kGatherGroup = 256;          // one work group integrates one element's hemicubes
// GPU gathering (gather_gl.cpp) reuses the numbers its passes leave free: deltas, per-element
// inputs, and the iteration's largest change.
constexpr int kGatherDeltaBinding = 0;     // float[]: delta form factors, top then side table
constexpr int kGatherElementBinding = 3;   // GpuGatherElement[]
constexpr int kGatherResidualBinding = 5;  // uint[2]: float bits of the largest change and radiosity
constexpr int kPowerGroup = 64;
constexpr int kSelectGroup = 256;          // one work group chooses the shooters
constexpr int kReconstructGroup = 64;
// kMaxShootersPerPass (solve/radiosity_system.h) sizes GpuSolverState::chosenPatch.

// Records shared by C++ (which writes them) and GLSL (which reads them), std430, vec4-aligned so
// that the two layouts are the same by construction; the GLSL declarations are in glslPreamble().
struct GpuElement {
  glm::vec4 corners[4];    // the polygon; corners[0].w = corner count (3 or 4)
  glm::vec4 normalArea;    // xyz unit normal, w area
  glm::vec4 reflectance;   // rgb
  glm::uvec4 ids;          // x item (canonical face + 1), y patch, z face
};
struct GpuPatch {
  glm::vec4 corners[4];    // the polygon; corners[0].w = corner count (3 or 4)
  glm::vec4 normalArea;    // xyz unit normal, w area (sum of its elements' areas)
  glm::vec4 emission;      // rgb area-weighted mean emitted exitance
  glm::uvec4 ids;          // x first index into the patch-element list, y count, z face
};
// Written on the GPU only, from here on.
struct GpuPatchState {
  float power;    // sum over its elements of A (r + g + b) of the unshot radiosity
  uint32_t shot;  // 1 once it has shot (its first shot carries its emission: direct light)
};
// One per hemicube of a pass (shooter slot x sample).
struct GpuShooter {
  glm::vec4 eye;       // xyz hemicube centre (a point on the patch, lifted by the offset)
  glm::vec4 normal;    // xyz the patch's normal, w the hemicube's turn about it (radians)
  glm::vec4 unshot;    // rgb the patch's mean unshot radiosity, shot this pass
  glm::vec4 emission;  // rgb the patch's emission when this is its first shot, else 0
  glm::uvec4 ids;      // x patch, y active (0: an empty slot, drawn off screen)
};
struct GpuSolverState {
  float unshotPower;   // before this pass's shots: sum over elements of A (r + g + b)
  uint32_t chosen;     // shooters this pass
  uint32_t shots;      // shooters so far
  uint32_t passes;
  uint32_t chosenPatch[kMaxShootersPerPass];
};
struct GpuElementState {
  glm::vec4 radiosity, unshot, irradiance, direct;
};
struct GpuGatherElement {
  glm::vec4 emissionArea;  // rgb emitted exitance, w area
  glm::vec4 reflectance;   // rgb
  glm::vec4 analytic;      // rgb irradiance from analytic lights
};
static_assert(sizeof(GpuElement) == 112 && sizeof(GpuPatch) == 112 && sizeof(GpuShooter) == 80 && sizeof(GpuPatchState) == 8);
static_assert(sizeof(GpuSolverState) == 16 + 4 * kMaxShootersPerPass && sizeof(GpuElementState) == 64);
static_assert(sizeof(GpuGatherElement) == 48);

inline std::string glslPreamble() {
  return fmt::format(
      "#version 450 core\n"
      "#define POSITION_LOCATION {}\n"
      "#define ITEM_LOCATION {}\n"
      "#define DELTA_BINDING {}\n"
      "#define ITEM_SUM_BINDING {}\n"
      "#define ITEM_TEXTURE_UNIT {}\n"
      "#define INTEGRATE_GROUP {}\n"
      "#define ELEMENT_BINDING {}\n"
      "#define PATCH_BINDING {}\n"
      "#define PATCH_ELEMENT_BINDING {}\n"
      "#define PATCH_STATE_BINDING {}\n"
      "#define SHOOTER_BINDING {}\n"
      "#define SOLVER_STATE_BINDING {}\n"
      "#define ELEMENT_STATE_BINDING {}\n"
      "#define PATCH_RADIOSITY_BINDING {}\n"
      "#define FACE_NEIGHBOUR_BINDING {}\n"
      "#define REDISTRIBUTION_AMOUNT_BINDING {}\n"
      "#define REDISTRIBUTION_LIST_BINDING {}\n"
      "#define ELEMENT_SH_BINDING {}\n"
      "#define CROSS_PATCH_BINDING {}\n"
      "#define BACK_SHOOTER_BINDING {}\n"
      "#define CROSS_DELTA_BINDING {}\n"
      "#define CROSS_EMITTER_BINDING {}\n"
      "#define CROSS_BEHIND_BINDING {}\n"
      "#define BACK_ITEM_TEXTURE_UNIT {}\n"
      "#define BACK_DISTANCE_TEXTURE_UNIT {}\n"
      "#define GATHER_GROUP {}\n"
      "#define GATHER_DELTA_BINDING {}\n"
      "#define GATHER_ELEMENT_BINDING {}\n"
      "#define GATHER_RESIDUAL_BINDING {}\n"
      "#define DISTANCE_TEXTURE_UNIT {}\n"
      "#define POWER_GROUP {}\n"
      "#define SELECT_GROUP {}\n"
      "#define RECONSTRUCT_GROUP {}\n"
      "#define MAX_SHOOTERS_PER_PASS {}\n"
      "struct GpuElement {{ vec4 corners[4]; vec4 normalArea; vec4 reflectance; uvec4 ids; }};\n"
      "struct GpuPatch {{ vec4 corners[4]; vec4 normalArea; vec4 emission; uvec4 ids; }};\n"
      "struct GpuPatchState {{ float power; uint shot; }};\n"
      "struct GpuShooter {{ vec4 eye; vec4 normal; vec4 unshot; vec4 emission; uvec4 ids; }};\n"
      "struct GpuElementState {{ vec4 radiosity; vec4 unshot; vec4 irradiance; vec4 direct; }};\n"
      "struct GpuGatherElement {{ vec4 emissionArea; vec4 reflectance; vec4 analytic; }};\n",
      kPositionLocation, kItemLocation, kDeltaBinding, kItemSumBinding, kItemTextureUnit, kIntegrateGroup,
      kElementBinding, kPatchBinding, kPatchElementBinding, kPatchStateBinding, kShooterBinding,
      kSolverStateBinding, kElementStateBinding, kPatchRadiosityBinding, kFaceNeighbourBinding, kRedistributionAmountBinding, kRedistributionListBinding, kElementShBinding, kCrossPatchBinding, kBackShooterBinding, kCrossDeltaBinding, kCrossEmitterBinding, kCrossBehindBinding,
      kBackItemTextureUnit, kBackDistanceTextureUnit, kGatherGroup, kGatherDeltaBinding,
      kGatherElementBinding, kGatherResidualBinding, kDistanceTextureUnit, kPowerGroup, kSelectGroup,
      kReconstructGroup, kMaxShootersPerPass);
}

}  // namespace luxel::gl
