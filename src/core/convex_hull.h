// The convex hull of points in a plane (Andrew's monotone chain, 1979).
#pragma once

#include <vector>

#include <glm/vec2.hpp>

namespace luxel {

// Counter-clockwise, without repeated points or collinear ones on an edge; fewer than three
// distinct points come back as they are (sorted, without repeats).
std::vector<glm::dvec2> convexHull2d(std::vector<glm::dvec2> points);

// The area a closed 2-D polygon encloses, positive when counter-clockwise (the shoelace formula).
double signedArea2d(const std::vector<glm::dvec2>& polygon);

}  // namespace luxel
