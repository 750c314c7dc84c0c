// The files `luxel bake --html` puts in its page, built into the binary (html_page_assets.cpp,
// CMakeLists.txt): the viewer's own page and script (apps/luxel/html_viewer/) and the three.js
// modules it imports, from the npm package tools/three-check/node_modules/three at build time.
#pragma once

#include <span>
#include <string_view>

namespace luxel::cli {

struct ThreeModule {
  std::string_view specifier;  // what the viewer and the other modules import it as: "three", ...
  std::string_view path;       // in the npm package: "build/three.module.js"
  std::string_view text;       // empty when the build found no such file
};

// three.js's modules, each one the viewer needs (directly or through another).
std::span<const ThreeModule> threeModules();
// Where the build looked for them: the package folder in the source tree.
std::string_view threePackageFolder();

// apps/luxel/html_viewer/page.html (the page, with {{NAME}} placeholders) and viewer.js.
std::string_view htmlViewerPage();
std::string_view htmlViewerScript();

}  // namespace luxel::cli
