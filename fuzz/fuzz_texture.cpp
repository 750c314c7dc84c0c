// libFuzzer harness: textures from memory (decodeTextureBytes: PNG, JPEG, TGA, BMP, PSD, GIF, HDR,
// PIC, PNM through stb_image), decoded as sRGB or linear by the first byte.
//
// A luxel::Error is the answer to a bad image; anything else escaping is a bug to fix.
#include <cstddef>
#include <cstdint>
#include <span>

#include "luxel/error.h"
#include "luxel/import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  try {
    const luxel::Texture t = luxel::decodeTextureBytes(std::as_bytes(std::span(data + 1, size - 1)), data[0] & 1, "fuzz");
    (void)t.mean();
  } catch (const luxel::Error&) {
  }
  return 0;
}
