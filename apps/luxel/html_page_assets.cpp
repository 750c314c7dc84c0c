// Files built into the binary with the assembler's .incbin, which reads them when this file is
// compiled (CMakeLists.txt passes their folders and lists them as OBJECT_DEPENDS, so a change
// recompiles it). Each is followed by a zero byte, and bounded by a start and an end symbol.
#include "html_page_assets.h"

#include <array>

// Defines NAME and NAME_end around the bytes of FILE in a read-only section.
#define LUXEL_INCBIN(NAME, FILE)                                                  \
  __asm__(".pushsection .rodata.luxel_html,\"a\",@progbits\n"                     \
          ".balign 16\n"                                                          \
          ".globl " #NAME "\n.hidden " #NAME "\n" #NAME ":\n"                      \
          ".incbin \"" FILE "\"\n"                                                \
          ".globl " #NAME "_end\n.hidden " #NAME "_end\n" #NAME "_end:\n"         \
          ".byte 0\n"                                                             \
          ".popsection\n");                                                       \
  extern "C" const char NAME[];                                                   \
  extern "C" const char NAME##_end[];

LUXEL_INCBIN(luxel_html_page, LUXEL_HTML_VIEWER_SOURCE "/page.html")
LUXEL_INCBIN(luxel_html_viewer, LUXEL_HTML_VIEWER_SOURCE "/viewer.js")
// Keep in step with apps/luxel/html_viewer/stage_three.cmake, which stages them.
LUXEL_INCBIN(luxel_three_module, LUXEL_HTML_VIEWER_ASSETS "/three/build/three.module.js")
LUXEL_INCBIN(luxel_three_core, LUXEL_HTML_VIEWER_ASSETS "/three/build/three.core.js")
LUXEL_INCBIN(luxel_three_gltf_loader, LUXEL_HTML_VIEWER_ASSETS "/three/examples/jsm/loaders/GLTFLoader.js")
LUXEL_INCBIN(luxel_three_buffer_geometry_utils, LUXEL_HTML_VIEWER_ASSETS "/three/examples/jsm/utils/BufferGeometryUtils.js")
LUXEL_INCBIN(luxel_three_skeleton_utils, LUXEL_HTML_VIEWER_ASSETS "/three/examples/jsm/utils/SkeletonUtils.js")
LUXEL_INCBIN(luxel_three_orbit_controls, LUXEL_HTML_VIEWER_ASSETS "/three/examples/jsm/controls/OrbitControls.js")

namespace luxel::cli {
namespace {

std::string_view bytes(const char* begin, const char* end) { return {begin, size_t(end - begin)}; }

}  // namespace

std::span<const ThreeModule> threeModules() {
  static const std::array<ThreeModule, 6> modules{{
      {"three", "build/three.module.js", bytes(luxel_three_module, luxel_three_module_end)},
      {"three/build/three.core.js", "build/three.core.js", bytes(luxel_three_core, luxel_three_core_end)},
      {"three/addons/loaders/GLTFLoader.js", "examples/jsm/loaders/GLTFLoader.js",
       bytes(luxel_three_gltf_loader, luxel_three_gltf_loader_end)},
      {"three/addons/utils/BufferGeometryUtils.js", "examples/jsm/utils/BufferGeometryUtils.js",
       bytes(luxel_three_buffer_geometry_utils, luxel_three_buffer_geometry_utils_end)},
      {"three/addons/utils/SkeletonUtils.js", "examples/jsm/utils/SkeletonUtils.js",
       bytes(luxel_three_skeleton_utils, luxel_three_skeleton_utils_end)},
      {"three/addons/controls/OrbitControls.js", "examples/jsm/controls/OrbitControls.js",
       bytes(luxel_three_orbit_controls, luxel_three_orbit_controls_end)},
  }};
  return modules;
}

std::string_view threePackageFolder() { return LUXEL_THREE_PACKAGE; }

std::string_view htmlViewerPage() { return bytes(luxel_html_page, luxel_html_page_end); }
std::string_view htmlViewerScript() { return bytes(luxel_html_viewer, luxel_html_viewer_end); }

}  // namespace luxel::cli
