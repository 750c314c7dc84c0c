// Shadow rays through thin glass (Material::transmittance): a ray that meets only glass on its way
// to a light carries the product of the panes' transmittances instead of being blocked. Embree's
// occlusion test stops at the first surface, so the rays it finds blocked are traced again with
// closest hits, pane after pane, until one is opaque or none is left; scenes without glass pay
// nothing. (An occlusion filter function would do it in one pass, but Embree may call it more than
// once for the same pane, which would count a pane twice.)
#pragma once

#include <span>
#include <vector>

#include "luxel/scene.h"
#include "luxel/surface.h"
#include "trace/ray_tracer.h"

namespace luxel {

// RTCRay::id of a shadow ray that glass blocks (light from a surface, which the solvers do not pass
// through glass); 0, makeRay's, for the lights' rays, which pass it.
inline constexpr unsigned kOpaqueToGlass = 1;

class ThinGlass {
 public:
  // The transmittance of each primitive of a ray tracer, in its order (zero: opaque); `offset`
  // is how far past a pane the next search starts (rayOffsetFor the scene).
  ThinGlass(std::vector<Rgb> perPrimitive, float offset);
  // Over SurfaceSet::faces (the transport's tracer) or over the elements (the renderers'). The two
  // sides of a two-sided glass face are one pane: a ray filtered by one is not by the other.
  static ThinGlass overFaces(const Scene& scene, const SurfaceSet& surfaces);
  static ThinGlass overElements(const Scene& scene, const SurfaceSet& surfaces);

  // Whether any primitive transmits (RayTracer::transmitted asks this glass only then).
  bool any() const { return any_; }
  Rgb of(uint32_t primitive) const {
    return primitive < transmittance_.size() ? transmittance_[primitive] : Rgb(0.0f);
  }

  // Occlusion with glass (for a tracer over the same primitives): `through[i]` is what ray i carries, 1 where nothing is in the way, the
  // product of the panes' transmittances where only glass is, 0 where something opaque is (or
  // anything, for a ray marked kOpaqueToGlass); rays that carry nothing are marked occluded
  // (tfar = -inf) and the others are not.
  void occluded(const RayTracer& tracer, std::span<RTCRay> rays, std::vector<Rgb>& through, bool coherent = false) const;

 private:
  std::vector<Rgb> transmittance_;
  float offset_ = 0.0f;
  bool any_ = false;
};

}  // namespace luxel
