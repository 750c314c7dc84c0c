// `luxel bake ... --html`: a page beside the glb (OUT.html) that shows the bake in a browser, with
// three.js and docs/baking.md's display recipes, walk and orbit navigation and an exposure control.
// It is self-contained, so that it opens from disk with no network and no server: the glb is in
// it (base64), three.js's modules are data: URLs in its import map, and the viewer's script is
// inline (docs/baking.md, "Viewing a bake in the browser").
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace luxel::cli {

// The page's path for a glb: OUT.glb -> OUT.html, in the same folder.
std::filesystem::path htmlPagePath(const std::filesystem::path& glb);

// Throws Error when this luxel was built without three.js's modules (tools/three-check/
// node_modules was not installed when it was built), naming the first missing file and
// scripts/install-deps.sh. Reads no file: the modules are in the binary.
void checkHtmlPageAssets();

struct HtmlPageInfo {
  std::string scene;  // the scene's name, for the title
  std::string glb;    // the glb's file name, as the page says where it came from
  std::string bake;   // what it holds, in words: "lightmaps", "vertex colours (radiance)", ...
};

// The page's text for a glb's bytes.
std::string htmlPage(std::string_view glb, const HtmlPageInfo& info);

// Reads the glb that was just written and writes its page atomically (a temporary file beside it,
// renamed: a failure leaves no partial page).
void writeHtmlPage(const std::filesystem::path& glb, const std::filesystem::path& html, const HtmlPageInfo& info);

}  // namespace luxel::cli
