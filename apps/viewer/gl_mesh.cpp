#include "gl_mesh.h"

#include <epoxy/gl.h>

#include <algorithm>

namespace luxel::viewer {

IndexedMesh makeIndexedMesh(const void* vertices, size_t vertexCount, size_t stride, const std::vector<uint32_t>& indices,
                            const std::vector<VertexAttribute>& attributes) {
  IndexedMesh m;
  // Empty buffers get a few bytes: GL refuses storage of size zero.
  glCreateBuffers(1, &m.vbo);
  glNamedBufferStorage(m.vbo, GLsizeiptr(std::max<size_t>(16, vertexCount * stride)), vertexCount ? vertices : nullptr, 0);
  glCreateBuffers(1, &m.ibo);
  glNamedBufferStorage(m.ibo, GLsizeiptr(std::max<size_t>(16, indices.size() * sizeof(uint32_t))),
                       indices.empty() ? nullptr : indices.data(), 0);
  glCreateVertexArrays(1, &m.vao);
  glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, GLsizei(stride));
  glVertexArrayElementBuffer(m.vao, m.ibo);
  for (const VertexAttribute& a : attributes) {
    glEnableVertexArrayAttrib(m.vao, a.index);
    if (a.unsignedInt) glVertexArrayAttribIFormat(m.vao, a.index, a.size, GL_UNSIGNED_INT, GLuint(a.offset));
    else glVertexArrayAttribFormat(m.vao, a.index, a.size, GL_FLOAT, GL_FALSE, GLuint(a.offset));
    glVertexArrayAttribBinding(m.vao, a.index, 0);
  }
  return m;
}

}  // namespace luxel::viewer
