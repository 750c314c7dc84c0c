// Placing imported geometry, lights and cameras in the scene with an affine transform: shared by
// the Assimp importer (node transforms) and scene files (per-mesh transforms).
#pragma once

#include <glm/glm.hpp>

#include "luxel/scene.h"

namespace luxel {

// Transforms positions. A transform that mirrors (negative determinant) would turn every face
// inside out, so the winding is reversed to keep front faces (and emitters) facing the same way;
// per-face element grids are swapped with the corners, so they keep covering the same places.
void transformMesh(Mesh& mesh, const glm::mat4& m);

// Moves a light's position and turns its direction (renormalised). Intensities are unchanged:
// scaling a scene does not change the lamps in it.
void transformLight(Light& light, const glm::mat4& m);

// Moves the eye and target and turns the up vector.
void transformCamera(Camera& camera, const glm::mat4& m);

}  // namespace luxel
