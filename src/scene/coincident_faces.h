// Faces that lie on top of each other, facing the same way: a mesh listed twice in a scene file,
// a glTF mesh placed twice at the same spot, an exporter's doubled geometry.
#pragma once

#include <cstddef>

#include "luxel/scene.h"

namespace luxel {

// Removes every face that repeats an earlier one (the same corners in the same winding, each
// within 1e-6 of the scene's extent), and adds one warning to scene.warnings naming how many went
// and from which meshes. Returns the number removed.
//
// Why: coincident copies cannot shadow each other, so each one receives all the light arriving at
// the spot and reflects it again. Every bounce multiplies the energy: with a whole room doubled,
// the effective reflectance is twice the real one and the solve diverges.
//
// Kept: the first copy, unless a later one emits and it does not (the light stays). Opposite
// facing pairs (both sides of a thin wall) are not copies. Meshes of dynamic objects are left
// alone (they are only coincident in some poses). A mesh left without faces is removed.
size_t removeCoincidentFaces(Scene& scene);

}  // namespace luxel
