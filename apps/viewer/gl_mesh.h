// An indexed triangle mesh's buffers and vertex array, made and filled in one call, as the
// viewer's renderers of other geometry than the solve's elements make theirs (a baked glb, the
// texels view).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace luxel::viewer {

struct VertexAttribute {
  unsigned index;         // the shader's location
  int size;               // components
  size_t offset;          // bytes into a vertex
  bool unsignedInt = false;  // 32-bit unsigned integers (a `uint` input), not floats
};

struct IndexedMesh {
  unsigned vao = 0, vbo = 0, ibo = 0;
};

// Interleaved vertices of `stride` bytes (vertexCount of them) and 32-bit indices. Needs a current
// OpenGL 4.5 context; the caller deletes the three objects.
IndexedMesh makeIndexedMesh(const void* vertices, size_t vertexCount, size_t stride, const std::vector<uint32_t>& indices,
                            const std::vector<VertexAttribute>& attributes);

}  // namespace luxel::viewer
