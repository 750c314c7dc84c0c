#include "gl/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <map>
#include <mutex>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel::gl {
namespace {

std::string eglErrorName(EGLint e) {
  switch (e) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return fmt::format("EGL error 0x{:x}", e);
  }
}

void GLAPIENTRY onDebugMessage(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                               const void* user) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  // NVIDIA's driver reports each read-back of a storage buffer as a medium "performance warning"
  // (the buffer moved from video to host memory): the solvers read back by design, and on an
  // H200 a cross-redistribution move filled its warnings with 23 of them. Only severe ones stay.
  if (type == GL_DEBUG_TYPE_PERFORMANCE && severity != GL_DEBUG_SEVERITY_HIGH) return;
  const auto* sink = static_cast<const Context::MessageSink*>(user);
  if (*sink) (*sink)(fmt::format("GL debug (type 0x{:x}, id {}): {}", type, id, message));
}

// A display on `platform`, initialised, or nullptr with the reason appended to `why`.
EGLDisplay openDisplay(EGLenum platform, void* native, const char* name, std::string& why) {
  EGLDisplay d = eglGetPlatformDisplayEXT(platform, native, nullptr);
  if (d == EGL_NO_DISPLAY) {
    why += fmt::format("; {}: no display ({})", name, eglErrorName(eglGetError()));
    return nullptr;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(d, &major, &minor)) {
    why += fmt::format("; {}: eglInitialize failed ({})", name, eglErrorName(eglGetError()));
    return nullptr;
  }
  return d;
}

// How many live Contexts use each display. EGL displays are per device, shared by every context
// on it, and eglTerminate is not counted: terminating one session's display would destroy the
// contexts of every other session of the process.
std::mutex displayMutex;
std::map<void*, int>& displayUsers() {
  static std::map<void*, int> users;
  return users;
}

}  // namespace

Context::Context(MessageSink sink) : sink_(std::move(sink)) {
  const std::lock_guard lock(displayMutex);
  std::string why;
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
    throw Error("OpenGL: EGL has no EGL_EXT_platform_base, so no headless display can be opened");
  std::vector<std::pair<EGLDisplay, std::string>> candidates;
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count) && count > 0) {
      for (EGLint i = 0; i < count; ++i)
        if (EGLDisplay d = openDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], "device", why))
          candidates.emplace_back(d, "device");
    } else {
      why += "; device: no EGL devices";
    }
  } else {
    why += "; device: EGL_EXT_platform_device missing";
  }
  if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    if (EGLDisplay d = openDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, "surfaceless", why))
      candidates.emplace_back(d, "surfaceless");
  } else {
    why += "; surfaceless: EGL_MESA_platform_surfaceless missing";
  }

  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE, EGL_NONE};
  for (auto& [display, name] : candidates) {
    if (!context_) {
      if (!eglBindAPI(EGL_OPENGL_API)) {
        why += fmt::format("; {}: no desktop OpenGL API", name);
      } else if (EGLContext c = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes)) {
        if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
          display_ = display, context_ = c, platform_ = name;
          continue;
        }
        why += fmt::format("; {}: eglMakeCurrent failed ({})", name, eglErrorName(eglGetError()));
        eglDestroyContext(display, c);
      } else {
        why += fmt::format("; {}: no OpenGL 4.5 core context ({})", name, eglErrorName(eglGetError()));
      }
    }
    if (display != display_ && displayUsers()[display] == 0) eglTerminate(display);
  }
  if (!context_) throw Error("OpenGL: no headless 4.5 core context could be made" + why);
  ++displayUsers()[display_];
  if (epoxy_has_gl_extension("GL_KHR_debug") || epoxy_gl_version() >= 43) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onDebugMessage, &sink_);
  }
}

Context::Context(BorrowCurrent) : platform_("borrowed") {
  const int version = epoxy_gl_version();
  if (version < 45)
    throw Error(fmt::format("OpenGL: the borrowed context is version {}.{}; the GL backend needs 4.5", version / 10,
                            version % 10));
}

Context::~Context() {
  auto display = static_cast<EGLDisplay>(display_);
  if (!display) return;
  const std::lock_guard lock(displayMutex);
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display, static_cast<EGLContext>(context_));
  if (--displayUsers()[display_] == 0) eglTerminate(display);
}

void Context::makeCurrent() {
  if (!display_) return;  // borrowed: the caller keeps it current
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_)) return;
  if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_)))
    throw Error(fmt::format("OpenGL: the session's context could not be made current ({})", eglErrorName(eglGetError())));
}

std::string Context::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }

bool isSoftwareRasteriser(const std::string& renderer) {
  for (const char* name : {"llvmpipe", "softpipe", "SwiftShader"})
    if (renderer.find(name) != std::string::npos) return true;
  return false;
}

bool Context::softwareRasteriser() const { return isSoftwareRasteriser(renderer()); }
std::string Context::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

void Context::check(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw Error(fmt::format("OpenGL: {} failed (error 0x{:x})", what, e));
}

}  // namespace luxel::gl
