// Tangent-space normal maps (Material::normalTexture): the tangent frame of a face and the
// perturbed shading normal at a point of it.
//
// Convention: the glTF 2.0 specification's normalTexture ("Additional Textures"): a texel t
// encodes the unit normal 2 t - 1 in the tangent frame, x along +u, y along +v (green up,
// OpenGL's convention, in luxel's texture coordinates, where v = 0 is the image's bottom row), z
// out of the front; normalScale multiplies x and y before normalising. glTF asks for MikkTSpace
// tangents (Mikkelsen 2008, "Simulation of Wrinkled Surfaces Revisited"). luxel's faces are flat,
// with no vertex normals, and on a flat face MikkTSpace's tangent is the face's dp/du
// orthonormalised against its normal, with the bitangent's sign from the orientation of its uvs:
// exactly the per-face frame below. A glTF file's own TANGENT attribute is not read. (glTF puts
// v = 0 at the image's top; the importer flips v, so +y is the image's up in both conventions.)
#pragma once

#include <cstdint>

#include "luxel/scene.h"

namespace luxel {

// A right- or left-handed orthonormal frame: b = sign * cross(n, t), with sign -1 where the uvs
// are mirrored, so that b points along +v either way.
struct TangentFrame {
  Vec3 t{0.0f};        // along +u, unit, orthogonal to n
  Vec3 b{0.0f};        // along +v, unit
  Vec3 n{0.0f};        // the normal the frame was built on
  bool valid = false;  // false: the face's uvs (or positions) are degenerate; no perturbation
};

// The frame of mesh.faces[face] on the unit normal `n` (normally the face's own): dp/du and dp/dv
// from its positions and uvs (a triangle's two edges, a quad's two diagonals, exact for a planar
// quad with affine uvs), t = dp/du orthonormalised against n. Invalid when the mesh has no uvs or
// the uvs span no area (collinear or repeated: sin of the angle between the uv edges under 1e-6).
TangentFrame faceTangentFrame(const Mesh& mesh, uint32_t face, Vec3 n);

// A texel of a normal map, decoded: normalize((2 t - 1) * (scale, scale, 1)); (0, 0, 1) for the
// texel (0.5, 0.5, 0.5), which encodes no direction.
Vec3 tangentSpaceNormal(Rgb texel, float scale);

// The unit shading normal at texture coordinate `uv` of scene.meshes[mesh].faces[face], for the
// side of it whose unit geometric normal is `geometricNormal`: that normal itself when the face's
// material has no normal map, the mesh has no uvs or the face's uvs are degenerate. A side whose
// normal opposes the face's winding is either the back of a two-sided face, shaded with the front's
// perturbed normal reversed (glTF 2.0: "the back-face MUST have its normals reversed"), or a
// one-sided face that discretisation turned round (its winding was wrong: SurfaceFace::flipped),
// whose visible side gets the frame built on it. Called per pixel: no allocation, one texture
// lookup.
Vec3 shadingNormal(const Scene& scene, uint32_t mesh, uint32_t face, Vec2 uv, Vec3 geometricNormal);

}  // namespace luxel
