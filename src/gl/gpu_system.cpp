#include "gl/gpu_system.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstddef>

#include "gl/gl_context.h"

namespace luxel::gl {

unsigned storageBuffer(const void* data, size_t bytes) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferStorage(b, GLsizeiptr(std::max<size_t>(bytes, 16)), nullptr, GL_DYNAMIC_STORAGE_BIT);
  if (data && bytes) glNamedBufferSubData(b, 0, GLsizeiptr(bytes), data);
  return b;
}

namespace {
size_t bufferBytes(unsigned buffer) {
  GLint64 bytes = 0;
  glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &bytes);
  return size_t(bytes);
}
}  // namespace

void saveBuffer(unsigned buffer, StateWriter& out) {
  std::vector<std::byte> bytes(bufferBytes(buffer));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(buffer, 0, GLsizeiptr(bytes.size()), bytes.data());
  Context::check("reading back a GPU buffer for a checkpoint");
  out.array(bytes);
}

void restoreBuffer(unsigned buffer, StateReader& in) {
  std::vector<std::byte> bytes;
  in.array(bytes, bufferBytes(buffer));
  glNamedBufferSubData(buffer, 0, GLsizeiptr(bytes.size()), bytes.data());
  Context::check("writing a checkpoint's state to a GPU buffer");
}

GpuPatches gpuPatches(const RadiositySystem& sys) {
  const std::vector<Rgb> emission = sys.patchMeans(sys.emission);
  GpuPatches out;
  out.patches.resize(sys.patchCount());
  for (size_t p = 0; p < sys.patchCount(); ++p) {
    const Patch& patch = sys.surfaces.patches[p];
    GpuPatch& g = out.patches[p];
    for (int c = 0; c < 4; ++c) g.corners[c] = glm::vec4(patch.polygon.v[size_t(c)], 0.0f);
    g.corners[0].w = float(patch.polygon.count);
    g.normalArea = glm::vec4(patch.normal, sys.patchArea[p]);
    g.emission = glm::vec4(emission[p], 0.0f);
    g.ids = glm::uvec4(uint32_t(out.elements.size()), uint32_t(patch.elements.size()), patch.face, 0u);
    out.elements.insert(out.elements.end(), patch.elements.begin(), patch.elements.end());
  }
  return out;
}

Solution solutionFromStates(const std::vector<GpuElementState>& states) {
  Solution sol;
  sol.radiosity.reserve(states.size());
  sol.irradiance.reserve(states.size());
  sol.directIrradiance.reserve(states.size());
  for (const GpuElementState& s : states) {
    sol.radiosity.push_back(Rgb(s.radiosity));
    sol.irradiance.push_back(Rgb(s.irradiance));
    sol.directIrradiance.push_back(Rgb(s.direct));
  }
  return sol;
}

}  // namespace luxel::gl
