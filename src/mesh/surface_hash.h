// The content of a SurfaceSet as a hash, for the keys of what is saved for it on disk (the
// face-cluster hierarchy, checkpoints): every element's polygon, face parameters, centroid,
// normal, area, reflectance and exitance, and every face's corners.
#pragma once

#include "core/content_hash.h"
#include "luxel/surface.h"

namespace luxel {

void hashSurfaces(ContentHash& h, const SurfaceSet& surfaces);

}  // namespace luxel
