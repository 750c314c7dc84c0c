// A mesh far from everything else: one stray triangle 10^7 m from a 1 m room. Discretisation,
// corner grouping and ray offsets are sized from the scene's extent, so the room gets a handful of
// elements and offsets as long as it is wide: it renders black with exit 0.
#pragma once

#include <string>

#include "luxel/scene.h"

namespace luxel {

// When the scene's bounding box is over 10^4 times as wide as it is without one mesh, adds a
// warning to scene.warnings starting "`where`: " that names the mesh and both extents and says
// what to do, unless scene.warnings already says so of that mesh. Returns whether the scene has
// such a mesh.
bool warnAboutStrayMesh(Scene& scene, const std::string& where);

}  // namespace luxel
