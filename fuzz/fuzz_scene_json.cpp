// libFuzzer harness: luxel scene files (loadSceneJson, docs/scene-format.md) and the validation
// every loaded scene gets. Relative paths resolve in a folder that does not exist, so the mesh
// and texture files a scene names are missing, which must be a clean Error.
//
// A luxel::Error is the answer to a bad file; anything else escaping is a bug to fix.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "luxel/error.h"
#include "luxel/import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // Seed 002's rooms are built-in scenes of up to 10M faces: a valid way to spend minutes, not a bug.
  if (text.find("room-") != std::string_view::npos) return 0;
  try {
    const luxel::Scene scene = luxel::loadSceneJson(text, "/nonexistent/luxel-fuzz", "fuzz.json");
    scene.validate();
  } catch (const luxel::Error&) {
  }
  return 0;
}
