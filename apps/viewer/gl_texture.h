// A 2-D texture made and filled in one call, as the viewer's renderers make theirs (the scene's
// images, a baked glb's base colours and lightmaps).
#pragma once

namespace luxel::viewer {

struct TextureSpec {
  unsigned internalFormat;       // GL_SRGB8_ALPHA8, GL_RGBA8, GL_RGB16F, ...
  unsigned format, type;         // of `pixels`: GL_RGBA / GL_UNSIGNED_BYTE, GL_RGB / GL_FLOAT, ...
  bool mipmapped;                // a full chain, trilinear; else one level, bilinear
  unsigned wrap;                 // GL_REPEAT, GL_CLAMP_TO_EDGE
};

// Needs a current OpenGL 4.5 context; the caller deletes the texture.
unsigned makeTexture(const TextureSpec& spec, int width, int height, const void* pixels);

}  // namespace luxel::viewer
