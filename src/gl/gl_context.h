// A headless OpenGL 4.5 core context through EGL, for the GPU backend (seeds 000, 001, 003 render
// hemicubes; any 4.5 driver will do: NVIDIA, AMD, Intel, or Mesa's llvmpipe on machines without
// a GPU). No window and no X server: EGL's device platform first, then Mesa's surfaceless one.
// Entry points come from libepoxy.
#pragma once

#include <functional>
#include <string>

namespace luxel::gl {

// Whether a GL_RENDERER string names a rasteriser that runs on the CPU (Mesa's llvmpipe or
// softpipe, SwiftShader).
bool isSoftwareRasteriser(const std::string& renderer);

class Context {
 public:
  // Where driver messages (KHR_debug) go; empty: dropped. The library never prints.
  using MessageSink = std::function<void(const std::string&)>;

  // Makes the context current on the calling thread. Throws luxel::Error saying why no 4.5 core
  // context could be made, platform by platform.
  explicit Context(MessageSink sink = {});
  // Borrows the caller's context (a viewer's window), which must be current on the calling
  // thread and stay alive and current while this is used; nothing is made or destroyed. Throws
  // luxel::Error when it is older than OpenGL 4.5.
  struct BorrowCurrent {};
  explicit Context(BorrowCurrent);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Makes this context current on the calling thread, where another (a second session's) may be;
  // a borrowed context is left to its owner. Throws luxel::Error when EGL refuses.
  void makeCurrent();

  std::string renderer() const;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  // Whether the renderer rasterises on the CPU (Mesa's llvmpipe or softpipe, SwiftShader).
  bool softwareRasteriser() const;
  std::string version() const;   // e.g. "4.5 (Core Profile) Mesa 22.3.6"
  std::string platform() const { return platform_; }  // "device", "surfaceless" or "borrowed"

  // Throws luxel::Error naming `what` when glGetError reports an error.
  static void check(const char* what);

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string platform_;
  MessageSink sink_;
};

}  // namespace luxel::gl
