// Geometry for the seed papers' test scenes (docs/seed-scenes.md): quads whose element grids are
// prescribed (Mesh::elementGrids), so that the scenes have the papers' exact element counts.
// Every helper appends positions, unit-square uvs, faces and grids together, so a mesh built only
// with them always has one uv per position and one grid per face.
#pragma once

#include <functional>
#include <string>

#include "luxel/scene.h"

namespace luxel::builtin {

// The parallelogram origin, origin + u, origin + u + v, origin + v as one face, front side
// u x v, cut into nu elements along u and nv along v.
void addGridQuad(Mesh& mesh, Vec3 origin, Vec3 u, Vec3 v, int nu, int nv);

// The same parallelogram as nu x nv quad faces of one element each, sharing vertices: the
// tessellated models of seed 000, whose triangle count is 2 nu nv. Cells (i, j) with `skip(i, j)`
// true are left out (a hole for a light panel).
void addCellGrid(Mesh& mesh, Vec3 origin, Vec3 u, Vec3 v, int nu, int nv,
                 const std::function<bool(int i, int j)>& skip = {});

// A box of `size` (x, y, z) centred on `centre`, turned by `yawDegrees` about the vertical axis
// through its centre, as six outward faces: nx x ny x nz elements along its edges, so
// 2 (nx ny + ny nz + nz nx) elements in all.
void addOutwardBox(Mesh& mesh, Vec3 centre, Vec3 size, float yawDegrees, int nx, int ny, int nz);

// Makes `mesh` (already in `scene`) the one mesh of a new dynamic object named `name`, whose
// origin is `centre` (so that turning the object turns the mesh about it): seed 001's moving box.
void makeDynamicObject(Scene& scene, Mesh& mesh, const std::string& name, Vec3 centre);

// Gives dynamic object `object` a spin about the vertical line through its origin, from the pose it
// has now: seed 001's rotating box.
void spinAboutVertical(Scene& scene, uint32_t object, double degreesPerSecond);

}  // namespace luxel::builtin
