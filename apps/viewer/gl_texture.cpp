#include "gl_texture.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

namespace luxel::viewer {

unsigned makeTexture(const TextureSpec& spec, int width, int height, const void* pixels) {
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  const int levels = spec.mipmapped ? 1 + int(std::floor(std::log2(double(std::max(width, height))))) : 1;
  glTextureStorage2D(tex, levels, spec.internalFormat, width, height);
  glTextureSubImage2D(tex, 0, 0, 0, width, height, spec.format, spec.type, pixels);
  if (spec.mipmapped) glGenerateTextureMipmap(tex);
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, spec.mipmapped ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GLint(spec.wrap));
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GLint(spec.wrap));
  return tex;
}

}  // namespace luxel::viewer
