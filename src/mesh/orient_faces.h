// Repairing inconsistent winding: a face whose back receives more direct light than its front is
// turned round, so that a wall modelled "inside out" is lit, not black. Only direct light decides
// (emitting faces and analytic lights, with shadow rays); faces that receive none keep their
// winding, and so do faces whose difference is rounding noise (an emitter in the face's own
// plane): the back must beat the front by a ratio and by an absolute floor. Two-sided materials are left alone: both their sides take part anyway.
#pragma once

#include <vector>

#include "luxel/scene.h"
#include "luxel/surface.h"

namespace luxel {

// Returns the number of faces turned round.
// `sceneExtent` is the bounding-box diagonal, for ray offsets.
size_t orientFacesByLight(const Scene& scene, std::vector<SurfaceFace>& faces, float sceneExtent);

}  // namespace luxel
