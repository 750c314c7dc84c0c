// libFuzzer harness: one mesh format through luxel's import path (Assimp, then luxel's own
// conversion, coincident-face removal and validation). The format is fixed at compile time
// (LUXEL_FUZZ_FORMAT: obj, gltf, glb, ply, dae, fbx), so each harness's corpus is plain files of
// that format. Side files (an OBJ's .mtl, a glTF's buffers) are absent: the importer must cope.
//
// A luxel::Error is the answer to a bad file; anything else escaping (a crash, a sanitizer report,
// std::bad_alloc from a size taken on trust, any other exception) is a bug to fix.
#include <cstddef>
#include <cstdint>
#include <span>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/resources.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const luxel::MemoryResourceReader noSideFiles;
  try {
    const luxel::Scene scene = luxel::importMesh(std::as_bytes(std::span(data, size)), LUXEL_FUZZ_FORMAT, noSideFiles,
                                                 "fuzz." LUXEL_FUZZ_FORMAT);
    scene.validate();
  } catch (const luxel::Error&) {
  }
  return 0;
}
