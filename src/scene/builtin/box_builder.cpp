#include "scene/builtin/builtin_scenes.h"

namespace luxel::builtin {

void addQuad(Mesh& mesh, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  auto base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), {a, b, c, d});
  // Built-in quads get a unit uv square each, so that textures can be attached to them.
  mesh.uvs.insert(mesh.uvs.end(), {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
  mesh.faces.push_back(Face{{base, base + 1, base + 2, base + 3}});
}

void addInwardBox(Mesh& mesh, Vec3 lo, Vec3 hi) {
  Vec3 p000{lo.x, lo.y, lo.z}, p100{hi.x, lo.y, lo.z}, p010{lo.x, hi.y, lo.z},
      p110{hi.x, hi.y, lo.z}, p001{lo.x, lo.y, hi.z}, p101{hi.x, lo.y, hi.z},
      p011{lo.x, hi.y, hi.z}, p111{hi.x, hi.y, hi.z};
  addQuad(mesh, p000, p001, p101, p100);  // floor, normal +y
  addQuad(mesh, p010, p110, p111, p011);  // ceiling, normal -y
  addQuad(mesh, p000, p100, p110, p010);  // z = lo, normal +z
  addQuad(mesh, p001, p011, p111, p101);  // z = hi, normal -z
  addQuad(mesh, p000, p010, p011, p001);  // x = lo, normal +x
  addQuad(mesh, p100, p101, p111, p110);  // x = hi, normal -x
}

}  // namespace luxel::builtin
