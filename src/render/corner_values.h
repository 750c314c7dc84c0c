// Nodal averaging with the corner groups given, for callers that average several fields over the
// same surfaces (the viewer: three fields each time the solution changes) and build the groups once.
#pragma once

#include <vector>

#include "luxel/surface.h"
#include "mesh/corner_groups.h"

namespace luxel {

// elementCornerValues (luxel/render.h) over `groups`, built from the same surfaces.
std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const CornerGroups& groups, const std::vector<Rgb>& perElement);

}  // namespace luxel
