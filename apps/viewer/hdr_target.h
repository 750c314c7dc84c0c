// The viewer's offscreen picture: linear radiance (alpha = 1 where a surface is seen), element ids
// for picking (R32UI), and depth. The scene is drawn here and the tone pass puts it on the screen.
// On screen the radiance is kept in half floats, scaled near the exposure (a quarter less to move
// per pixel made llvmpipe's frame 20% faster); screenshots draw the frame again into a full-float
// one, so an EXR screenshot holds what `luxel render` would write.
#pragma once

#include <cstdint>
#include <memory>

#include "luxel/image.h"

namespace luxel::gl {
class ShaderProgram;
}

namespace luxel::viewer {

class HdrTarget {
 public:
  // `fullFloat`: RGBA32F radiance (screenshots); else RGBA16F (the screen).
  HdrTarget(int width, int height, bool fullFloat);
  ~HdrTarget();
  HdrTarget(const HdrTarget&) = delete;
  HdrTarget& operator=(const HdrTarget&) = delete;

  void resize(int width, int height);  // no-op when unchanged
  int width() const { return width_; }
  int height() const { return height_; }
  void bind();  // as the draw framebuffer, with its viewport
  unsigned radianceTexture() const { return radiance_; }

  // The radiance, row 0 at the top, with coverage from alpha (Image::coverage).
  Image readRadiance() const;
  // The element drawn at pixel (x, y) (y down), or -1 for the background.
  int64_t elementAt(int x, int y) const;
  // The automatic exposure's multiplier (autoExposureScale) metered on a copy reduced to at most
  // `meterWidth` pixels across: cheap enough to do every few frames.
  double meterExposure(int meterWidth = 256);

 private:
  void release();
  bool fullFloat_ = false;
  int width_ = 0, height_ = 0;
  unsigned fbo_ = 0, radiance_ = 0, ids_ = 0, depth_ = 0;
  unsigned meterFbo_ = 0, meterTexture_ = 0;
  int meterW_ = 0, meterH_ = 0;
};

// Draws a radiance texture to the bound framebuffer with exposure, a tone curve and the sRGB
// transfer (the same operator as PNG files, src/io/tonemap.cpp).
// Clears the bound HdrTarget (radiance, element ids, depth) and sets an opaque pass's state as
// SceneRenderer draws: reversed depth (cleared to 0, GL_GREATER), no blending or stencil, filled
// polygons. Culling is the caller's.
void beginOpaquePass();

class ToneMapPass {
 public:
  explicit ToneMapPass(const std::string& vertex, const std::string& fragment);
  ~ToneMapPass();
  void draw(unsigned radianceTexture, int width, int height, float scale, ToneMap::Curve curve);

 private:
  std::unique_ptr<gl::ShaderProgram> program_;
  unsigned vao_ = 0;
};

}  // namespace luxel::viewer
