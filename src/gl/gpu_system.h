// The radiosity system as the GPU solvers hold it (progressive_gl.cpp, gather_gl.cpp): the
// buffers both upload and the solution both read back, in one place.
#pragma once

#include <vector>

#include "gl/shared_layout.h"
#include "luxel/checkpoint.h"
#include "luxel/solve.h"
#include "solve/radiosity_system.h"

namespace luxel::gl {

// A shader storage buffer holding `bytes` of `data` (or uninitialised when data is null),
// updatable with glNamedBufferSubData. At least 16 bytes: zero-size storage is a GL error.
unsigned storageBuffer(const void* data, size_t bytes);

// Checkpoints: a storage buffer's whole contents into `out`, and back from `in` into a buffer of
// the same size (a different size is an Error from the reader).
void saveBuffer(unsigned buffer, StateWriter& out);
void restoreBuffer(unsigned buffer, StateReader& in);

// The patches: polygon, normal, area (the sum of its elements'), mean emission, and the range of
// its elements in `elements` (GpuPatch::ids.x, .y).
struct GpuPatches {
  std::vector<GpuPatch> patches;
  std::vector<uint32_t> elements;
};
GpuPatches gpuPatches(const RadiositySystem& system);

// B, H and direct H per element from the solvers' state buffer.
Solution solutionFromStates(const std::vector<GpuElementState>& states);

}  // namespace luxel::gl
