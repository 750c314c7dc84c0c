// Decoding image bytes into a Texture: behind decodeTextureBytes (and so loadTexture) and the
// Assimp importer's embedded textures (glTF/GLB and FBX files).
#pragma once

#include <cstddef>
#include <string>

#include "luxel/scene.h"

namespace luxel {

// Decodes PNG, JPEG, TGA, BMP, HDR, ... bytes (whatever stb_image reads) into a linear-RGB
// texture stored bottom row first. 8- and 16-bit images are decoded from sRGB when `srgb`; HDR
// images are linear already. `path` names the image in the texture and in errors. Throws
// Error("texture '<path>': <reason>") when the bytes cannot be decoded, the header declares more
// than kMaxTexturePixels texels, or an HDR texel is not finite or over kMaxRadiance.
Texture decodeTexture(const unsigned char* data, size_t size, bool srgb, const std::string& path);

// Most texels a texture may have: 8192 x 8192, 768 MiB as linear float RGB. Radiosity averages a
// texture over each element, so a bigger one only costs memory; scale it down.
inline constexpr long long kMaxTexturePixels = 8192LL * 8192LL;
// Throws Error naming the texture, its size and the limit when width x height is over it.
void checkTextureSize(const std::string& path, long long width, long long height);

// The sRGB transfer function inverted (IEC 61966-2-1), for one 8-bit channel value / 255.
float srgbToLinear(float encoded);
// The sRGB transfer function (IEC 61966-2-1), `linear` clamped to [0, 1] first: what PNG output,
// glTF's colour textures and the viewer's 8-bit textures store.
float linearToSrgb(float linear);

}  // namespace luxel
