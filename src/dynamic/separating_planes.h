// The planes that separate a polygon from a box: through an edge of one and a corner of the other,
// with the polygon on one side and the box on the other. With the polygon as a light they bound
// the box's shadow, umbra and penumbra (Nishita and Nakamae, "Half-tone representation of 3-D
// objects illuminated by area sources or polyhedron sources", COMPSAC 1983), and like the planes
// of Haines and Wallace's shafts they prove a pair of surfaces clear without a ray: every segment
// from a receiver wholly on the polygon's side of one of them to the polygon stays on that side,
// away from the box.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/surface.h"

namespace luxel {

class SeparatingPlanes {
 public:
  // The planes between the prism of `source` lifted by 0 to `lift` (rays leave a surface a small
  // offset along its normal) and the box with these 8 corners, corner i sharing an edge with
  // corners i ^ 1, i ^ 2 and i ^ 4. `tolerance` is the rounding allowed in each plane's defining
  // points; the box must be larger than what it bounds by more than that.
  SeparatingPlanes(const Polygon& source, Vec3 lift, const std::array<Vec3, 8>& box, float tolerance);

  // Whether the prism of `receiver` lifted by 0 to `lift` lies on the source's side of one of the
  // planes, so that no segment between it and the source's prism meets the box.
  bool separates(const Polygon& receiver, Vec3 lift) const;

  size_t size() const { return planes_.size(); }

 private:
  std::vector<glm::vec4> planes_;  // normal n, offset w: the source's side is n.x <= w + tolerance
  float tolerance_;
};

}  // namespace luxel
