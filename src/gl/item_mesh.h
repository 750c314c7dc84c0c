// Polygons as GL triangles with a flat item id per vertex (POSITION_LOCATION, ITEM_LOCATION),
// uploaded once: what every hemicube of the GPU backend rasterises. Quads split along 0-2, as
// the ray tracer, discretisation and glTF export split them.
#pragma once

#include <span>

#include "luxel/surface.h"

namespace luxel::gl {

class ItemMesh {
 public:
  // `items[i]` is the id polygon i draws (ids start at 1; 0 means "nothing"). Needs a current
  // OpenGL 4.5 context.
  ItemMesh(std::span<const Polygon> polygons, std::span<const uint32_t> items);
  ~ItemMesh();
  ItemMesh(const ItemMesh&) = delete;
  ItemMesh& operator=(const ItemMesh&) = delete;

  void draw() const;  // binds its vertex array and draws every triangle
  void drawInstanced(int instances) const;  // the same, `instances` times (gl_InstanceID)

 private:
  unsigned vao_ = 0, positions_ = 0, items_ = 0;
  int vertexCount_ = 0;
};

}  // namespace luxel::gl
