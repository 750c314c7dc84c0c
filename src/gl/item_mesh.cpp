#include "gl/item_mesh.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

#include "gl/shared_layout.h"
#include "luxel/error.h"

namespace luxel::gl {

ItemMesh::ItemMesh(std::span<const Polygon> polygons, std::span<const uint32_t> polygonItems) {
  if (polygons.size() != polygonItems.size()) throw Error("hemicube polygons and items differ in number");
  std::vector<Vec3> positions;
  std::vector<uint32_t> items;
  for (size_t i = 0; i < polygons.size(); ++i) {
    const Polygon& p = polygons[i];
    for (int t = 0; t + 2 < p.count; ++t)
      for (int k : {0, t + 1, t + 2}) positions.push_back(p.v[size_t(k)]), items.push_back(polygonItems[i]);
  }
  vertexCount_ = int(positions.size());
  glCreateVertexArrays(1, &vao_);
  glCreateBuffers(1, &positions_);
  glCreateBuffers(1, &items_);
  // Zero-size storage is an error in GL: an empty scene keeps one unused element.
  glNamedBufferStorage(positions_, GLsizeiptr(std::max<size_t>(positions.size(), 1) * sizeof(Vec3)), positions.data(), 0);
  glNamedBufferStorage(items_, GLsizeiptr(std::max<size_t>(items.size(), 1) * sizeof(uint32_t)), items.data(), 0);
  glVertexArrayVertexBuffer(vao_, 0, positions_, 0, sizeof(Vec3));
  glVertexArrayVertexBuffer(vao_, 1, items_, 0, sizeof(uint32_t));
  glEnableVertexArrayAttrib(vao_, kPositionLocation);
  glEnableVertexArrayAttrib(vao_, kItemLocation);
  glVertexArrayAttribFormat(vao_, kPositionLocation, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(vao_, kItemLocation, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao_, kPositionLocation, 0);
  glVertexArrayAttribBinding(vao_, kItemLocation, 1);
}

ItemMesh::~ItemMesh() {
  glDeleteBuffers(1, &positions_);
  glDeleteBuffers(1, &items_);
  glDeleteVertexArrays(1, &vao_);
}

void ItemMesh::draw() const {
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, vertexCount_);
}

void ItemMesh::drawInstanced(int instances) const {
  glBindVertexArray(vao_);
  glDrawArraysInstanced(GL_TRIANGLES, 0, vertexCount_, instances);
}

}  // namespace luxel::gl
