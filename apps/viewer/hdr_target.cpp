#include "hdr_target.h"

#include <epoxy/gl.h>

#include <algorithm>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "gl/shader_program.h"
#include "luxel/error.h"

namespace luxel::viewer {

HdrTarget::HdrTarget(int width, int height, bool fullFloat) : fullFloat_(fullFloat) { resize(width, height); }

HdrTarget::~HdrTarget() { release(); }

void HdrTarget::release() {
  GLuint textures[] = {radiance_, ids_, depth_, meterTexture_};
  glDeleteTextures(4, textures);
  GLuint fbos[] = {fbo_, meterFbo_};
  glDeleteFramebuffers(2, fbos);
  fbo_ = radiance_ = ids_ = depth_ = meterFbo_ = meterTexture_ = 0;
  meterW_ = meterH_ = 0;
}

void HdrTarget::resize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error(fmt::format("viewer: a {}x{} picture (each side 1 to 16384)", width, height));
  if (width == width_ && height == height_ && fbo_) return;
  release();
  width_ = width;
  height_ = height;
  glCreateTextures(GL_TEXTURE_2D, 1, &radiance_);
  glTextureStorage2D(radiance_, 1, fullFloat_ ? GL_RGBA32F : GL_RGBA16F, width, height);
  glTextureParameteri(radiance_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(radiance_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(radiance_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(radiance_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glCreateTextures(GL_TEXTURE_2D, 1, &ids_);
  glTextureStorage2D(ids_, 1, GL_R32UI, width, height);
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
  // With a stencil, for the shadow-volume path.
  glTextureStorage2D(depth_, 1, GL_DEPTH32F_STENCIL8, width, height);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, radiance_, 0);
  glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT1, ids_, 0);
  glNamedFramebufferTexture(fbo_, GL_DEPTH_STENCIL_ATTACHMENT, depth_, 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo_, 2, buffers);
  const GLenum status = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw Error(fmt::format("viewer: the {}x{} picture's framebuffer is incomplete (0x{:x})", width, height, status));
  gl::Context::check("viewer: picture");
}

void HdrTarget::bind() {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glDisable(GL_SCISSOR_TEST);
}

Image HdrTarget::readRadiance() const {
  std::vector<float> rgba(size_t(width_) * size_t(height_) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(radiance_, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
  gl::Context::check("viewer: reading the picture");
  Image image(width_, height_);
  image.coverage.resize(image.pixels.size());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const float* p = &rgba[(size_t(height_ - 1 - y) * size_t(width_) + size_t(x)) * 4];  // GL rows go up
      image.at(x, y) = Rgb(p[0], p[1], p[2]);
      image.coverage[size_t(y) * size_t(width_) + size_t(x)] = p[3];
    }
  return image;
}

int64_t HdrTarget::elementAt(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
  GLuint id = 0;
  glGetTextureSubImage(ids_, 0, x, height_ - 1 - y, 0, 1, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, sizeof id, &id);
  return int64_t(id) - 1;
}

double HdrTarget::meterExposure(int meterWidth) {
  const int w = std::max(1, std::min(width_, meterWidth));
  const int h = std::max(1, int(int64_t(height_) * w / width_));
  if (w != meterW_ || h != meterH_) {
    glDeleteTextures(1, &meterTexture_);
    glDeleteFramebuffers(1, &meterFbo_);
    glCreateTextures(GL_TEXTURE_2D, 1, &meterTexture_);
    glTextureStorage2D(meterTexture_, 1, GL_RGBA32F, w, h);
    glCreateFramebuffers(1, &meterFbo_);
    glNamedFramebufferTexture(meterFbo_, GL_COLOR_ATTACHMENT0, meterTexture_, 0);
    meterW_ = w;
    meterH_ = h;
  }
  glNamedFramebufferReadBuffer(fbo_, GL_COLOR_ATTACHMENT0);
  glBlitNamedFramebuffer(fbo_, meterFbo_, 0, 0, width_, height_, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
  std::vector<float> rgba(size_t(w) * size_t(h) * 4);
  glGetTextureImage(meterTexture_, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
  Image image(w, h);
  image.coverage.resize(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = Rgb(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]);
    image.coverage[i] = rgba[i * 4 + 3];
  }
  return autoExposureScale(image);
}

ToneMapPass::ToneMapPass(const std::string& vertex, const std::string& fragment)
    : program_(std::make_unique<gl::ShaderProgram>("viewer tone map", vertex, fragment)) {
  glCreateVertexArrays(1, &vao_);
}

ToneMapPass::~ToneMapPass() { glDeleteVertexArrays(1, &vao_); }

void ToneMapPass::draw(unsigned radianceTexture, int width, int height, float scale, ToneMap::Curve curve) {
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  program_->use();
  glUniform1f(glGetUniformLocation(program_->id(), "uScale"), scale);
  glUniform1i(glGetUniformLocation(program_->id(), "uCurve"),
              curve == ToneMap::Curve::Filmic ? 0 : curve == ToneMap::Curve::Reinhard ? 1 : 2);
  glBindTextureUnit(0, radianceTexture);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

void beginOpaquePass() {
  const float clearRadiance[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint clearId[4] = {0, 0, 0, 0};
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glClearBufferfv(GL_COLOR, 0, clearRadiance);
  glClearBufferuiv(GL_COLOR, 1, clearId);
  glClearBufferfi(GL_DEPTH_STENCIL, 0, 0.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

}  // namespace luxel::viewer
