// Cross-redistribution on the GPU: after objects move, only the moved patches render hemicubes
// (M. van de Hoef, "Real-Time Dynamic Radiosity for High Quality Global Illumination", Utrecht
// 2013, Sec. 3.3 and 4.5; shared/seeds/notes/001-dynamic-radiosity.md, sections 2.9, 2.11 and 3.7).
// The incremental method (progressive_gl.cpp) has every patch shoot again from the old and the
// new geometry; this one splits the change of H = sum_p F[e <- p] S_p by who is moved (M) and who
// stays (C):
//  - M -> everything: each moved patch j shoots -S_j from where it was and +S_j from where it is
//    (its front hemicubes, as a progressive shot);
//  - C -> M, R_g(C, M): each moved element gathers the shot radiosity of C through a hemicube at
//    its centre (2 x 2 hemicubes, the reconstruction's rule, for elements wide beside their
//    distance to a light), where it was (subtracted) and where it is (added); the static
//    emitters not from their pixels but as their shots reached it (below);
//  - C -> C, the cross projection R_x(C, C) (001 Eq. 3.3.1): light from C to a static receiver i
//    changes only where it passes through a moved patch j, at one of its places. j's appearance
//    takes away F'[i <- j] P(C, j', i) and its departure gives back F[i <- j] P(C, j, i), where
//    P is the mean shot radiosity of C that i would see through j: rays from i through a g x g
//    grid on j, marched through a hemicube on j's back side (the seed's "back hemicube") that
//    holds only the patches that stay. F comes from j's front hemicubes in the same pass as its
//    shot, so it costs no hemicube more.
// Choices the seed leaves open or that differ from it, each deliberate and measured
// (docs/algorithms.md, "Dynamic radiosity"):
//  - static emitters are not left to the back hemicube's rays: the light a moved patch hides of
//    each is its exact unoccluded factor times the share of the points the emitter's own shots
//    came from whose segment to i crosses j. 001's known weakness, small bright lights
//    undersampled by the rays (notes 3.7), was most of the error. The moved elements' gathers
//    take them the same way, with the gather hemicube for the visibility of each point;
//  - P is cast from each receiver patch's centre and shared by its elements, each of whose 2 x 2
//    points weighs it by its share of F (settings.behindPerPatch; or cast from every point): P is
//    the light reflected by what lies behind the mover, smooth over a receiver patch, and per
//    point it was half a frame's GPU time;
//  - rays are marched through the back hemicube (the seed's single reprojection step, depth along
//    the parallel ray from j's centre, is kept as the first try);
//  - the moved elements' part from C is a difference of two gathers (where it was, where it is)
//    instead of 001's overwrite by one: the solution keeps luxel's invariant H = H0 + sum F S, so
//    a gather's mismatch with the shooting factors stays the same from frame to frame instead of
//    entering B;
//  - the back hemicubes hold item ids and distances, not colours: the shot radiosity and the
//    first-shot emission (the direct light shown apart) are both looked up by patch;
//  - P weights the g x g rays by the point kernel cos cos / r^2 (the form factor's own weight)
//    where 001 took their plain mean;
//  - the back hemicubes leave out every moved patch, not only j: a closed mover's far faces would
//    otherwise hide the static surfaces behind it from its near faces' back hemicubes.
// What remains an estimate (the rays into the back hemicube for non-emitting surfaces, the gather
// against the shots) does not accumulate over frames while the shot radiosity stays: each move's
// passes at the old place cancel the last move's at the same place.
#pragma once

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gl/cross_redistribution_settings.h"
#include "solve/radiosity_system.h"

namespace luxel::gl {

class GpuTimeline;
class LayeredHemicubes;
class ShaderProgram;

// GLSL for the reconstruction pass: crossProjected(k, x, n, P, shot, emitted), the mean shot
// radiosity and first-shot emission of the static patches (but the sampled emitters) that point x
// (normal n) sees through the k-th moved patch P of the pass, from back hemicube k; and
// emittersHidden(x, n, P, shot, emitted), the sampled emitters' irradiance P hides;
// crossPatches[p] = (moved | sampled emitter << 1, twin patch). Needs kHemicubeGlsl,
// kFormFactorGlsl, the preamble's structs and a `patches` buffer.
std::string crossProjectionGlsl();

// The GPU objects of the passes above that progressive shooting does not already have. Needs a
// current OpenGL 4.5 context; the solver owns one per solve.
class CrossRedistribution {
 public:
  // `objectOfPatch`: each patch's scene object. `backCapacity`: back hemicubes per shooting pass.
  CrossRedistribution(const RadiositySystem& system, std::vector<uint32_t> objectOfPatch,
                      const CrossRedistributionSettings& settings, int backCapacity,
                      float nearPlane, float farPlane, float offset, const std::string& preamble);
  ~CrossRedistribution();
  CrossRedistribution(const CrossRedistribution&) = delete;
  CrossRedistribution& operator=(const CrossRedistribution&) = delete;

  // Before a move's passes: marks the patches of `objects` as moved and lists the static emitters
  // to sample; when the moved set changed, makes the back hemicubes draw the rest and picks each
  // moved element's gather.
  void begin(std::span<const uint32_t> objects);
  // After the surfaces' new geometry is in the solver's buffers (or any change of it the
  // solver made): the gather hemicubes draw it, and none kept from before is used again.
  void geometryMoved();

  // The back hemicubes of a shooting pass: their centres are written by the pass's shooter
  // setup into backShooters() (one per patch shot, on its back side); render draws them and
  // binds their layers and the patch table for the reconstruction.
  GLuint backShooters() const { return backShooters_; }
  void renderBackHemicubes(int count);
  void bindForReconstruction() const;
  // What each static patch's centre sees behind each of the pass's `count` moved patches
  // (`samples` shooters each in the pass's shooter buffer), which the reconstruction shares
  // among the patch's elements. After bindForReconstruction, with the pass's buffers bound.
  // Nothing where that table would be too large: each element point then casts its own rays.
  void projectBehind(int count, int samples);
  // The reconstruction program's fixed uniforms; `emitterSide`: k_e, the emitters' hemicubes a
  // side (their shots' points, which emittersHidden and the moved elements' gather sample again).
  void setReconstructionUniforms(GLuint program, int emitterSide);

  // R_g(C, M): every moved element gathers the shot radiosity (`amounts`, two vec4 a patch, as
  // the redistribution's amounts pass writes them) of the patches that stay, at the geometry now
  // in `elements` and `patches`, and adds `sign` times it to its state (irradiance, radiosity,
  // unshot and direct light). Leaves the bindings it used changed: the caller binds its own again.
  // Its phases are marked on `timeline`. A negative gather after a positive one with nothing moved
  // between (geometryMoved not called) reads the positive one's hemicubes, where they were kept.
  void gatherMoved(float sign, GLuint elements, GLuint patches, GLuint states, GLuint amounts,
                   GpuTimeline& timeline);

  bool moved(uint32_t patch) const { return moved_[patch] != 0; }
  // Whether the moved set, as begin() last saw it, shows no one-sided face's back outside (every
  // edge of such a face shared within the set): a closed object, or two-sided sheets. The cross
  // projection follows light past the moved patches' fronts only, so an open one-sided mover (a
  // lamp panel) needs the incremental redistribution instead.
  bool closedToOutside() const { return closed_; }

 private:
  void uploadPatchTable();

  const RadiositySystem& sys_;
  const std::vector<uint32_t> objectOfPatch_;
  const CrossRedistributionSettings s_;
  const int backCapacity_;
  const float offset_;
  std::vector<uint32_t> twinPatch_;  // each patch's twin on a two-sided face's other side, or ~0u
  std::vector<uint32_t> movedObjects_;
  std::vector<uint8_t> moved_;           // per patch
  std::vector<uint8_t> sampledEmitter_;  // per patch: sampled exactly (emittersHidden)
  GLuint reconstruction_ = 0, emitterList_ = 0;
  std::unique_ptr<ShaderProgram> behindProgram_;  // null where the table would be too large
  GLuint behind_ = 0;
  bool closed_ = true;
  // The moved elements that gather with one hemicube at their centre, and those near a light
  // that gather with 2 x 2 (the .cpp's kNearLight): their list and their passes.
  struct GatherRule {
    int samples = 1;
    std::vector<uint32_t> elements;
    GLuint list = 0;
    std::unique_ptr<ShaderProgram> eyes, integrate;
  };
  GatherRule rules_[2] = {{.samples = 1}, {.samples = 4}};
  size_t perBatch(const GatherRule& rule) const { return size_t(std::max(gatherCapacity_ / rule.samples, 1)); }
  int gatherCapacity_ = 0;  // hemicubes a gather batch
  std::unique_ptr<LayeredHemicubes> back_;
  // The gather batches' hemicubes, one set a batch where they fit kMostGatherBytes (else one for
  // all): a move's gather where the movers were is the last move's gather where they went, the
  // same pixels, so those are kept and not drawn again while imagesKept_.
  std::vector<std::unique_ptr<LayeredHemicubes>> gathers_;
  // What they draw: every patch, where the solver's buffers last said (before a move's upload,
  // where the movers were; the surfaces already say where they went).
  std::vector<Polygon> gatherPolygons_;
  std::vector<uint32_t> gatherItems_;
  bool keepGathers_ = false, imagesKept_ = false;
  GLuint patchTable_ = 0, backShooters_ = 0, gatherEyes_ = 0, deltas_ = 0;
};

}  // namespace luxel::gl
