// The emitting surfaces as polygons, for whatever samples them directly (the renderer's and the
// path tracer's direct light, the face-cluster solver's per-element direct light): a face whose
// elements all carry one exitance is one polygon, its own; otherwise (an emission texture) each
// of its emitting elements is, so that the texture's variation is kept. Pieces of one lamp (one
// exitance, one plane, sharing corners) that tile a convex polygon of at most four corners are
// that polygon: a quad lamp split into triangles, or a panel made of cells, is sampled as one.
#pragma once

#include <vector>

#include "luxel/surface.h"

namespace luxel {

struct EmittingPolygon {
  Polygon polygon;
  Vec3 normal{0.0f};
  Rgb exitance{0.0f};  // pi Le, W/m^2
};

std::vector<EmittingPolygon> emittingPolygons(const SurfaceSet& surfaces);

// `pieces` with the pieces of each lamp that tile a convex polygon of at most four corners joined
// into it (the rule above), for a caller that has faces rather than surfaces.
std::vector<EmittingPolygon> joinLampPieces(std::vector<EmittingPolygon> pieces);

}  // namespace luxel
