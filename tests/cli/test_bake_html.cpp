// `luxel bake ... --html`: the page beside the glb, self-contained (the glb and three.js in it,
// nothing fetched from the network), written atomically, and the combinations it refuses before
// any work. Whether the page shows the bake right is checked in a browser by CTest Web.HtmlViewer
// (tools/three-check/html_check.mjs).
#include <cstdint>
#include <regex>

#include "cli/cli_runner.h"

namespace {

std::string base64(const std::string& in) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  uint32_t v = 0;
  int bits = 0;
  for (unsigned char c : in) {
    v = v << 8 | c;
    bits += 8;
    while (bits >= 6) out += digits[(v >> (bits -= 6)) & 63];
  }
  if (bits > 0) out += digits[(v << (6 - bits)) & 63];
  while (out.size() % 4) out += '=';
  return out;
}

// The luxel under test was built without three.js (tools/three-check/node_modules missing then).
bool builtWithoutThree(const CliRun& r) { return r.code == 1 && r.err.find("built without three.js") != std::string::npos; }

void expectSelfContained(const fs::path& html, const fs::path& glb) {
  const std::string text = readFile(html);
  ASSERT_FALSE(text.empty()) << html;
  EXPECT_EQ(text.rfind("<!doctype html>", 0), 0u);
  EXPECT_EQ(text.substr(text.size() - 8), "</html>\n");  // complete
  // Nothing from the network: no URL at all (three.js's own comments are inside base64), no
  // attribute that loads something, every module of the import map a data: URL.
  EXPECT_EQ(text.find("http://"), std::string::npos);
  EXPECT_EQ(text.find("https://"), std::string::npos);
  EXPECT_FALSE(std::regex_search(text, std::regex(R"(\s(src|href)\s*=)", std::regex::icase)));
  EXPECT_EQ(text.find("<link"), std::string::npos);
  const size_t mapStart = text.find("<script type=\"importmap\">");
  ASSERT_NE(mapStart, std::string::npos);
  const std::string map = text.substr(mapStart, text.find("</script>", mapStart) - mapStart);
  const std::string dataUrl = "data:text/javascript;base64,";
  size_t modules = 0;
  for (size_t at = map.find("\":\""); at != std::string::npos; at = map.find("\":\"", at + 1), ++modules)
    EXPECT_EQ(map.compare(at + 3, dataUrl.size(), dataUrl), 0) << map.substr(at, 80);
  EXPECT_GE(modules, 5u);  // three, three.core, GLTFLoader (and its two utils), OrbitControls
  // The glb, whole.
  EXPECT_NE(text.find(">" + base64(readFile(glb)) + "</script>"), std::string::npos) << "the glb is not in the page";
  // Only the page and its glb (and, with lightmaps, its EXR pages): no temporary file.
  expectNoTemporaries(html.parent_path());
}

TEST(BakeHtml, PageBesideTheGlbHoldsEverything) {
  const fs::path dir = scratchDir();
  fs::create_directories(dir / "out");
  CliRun r = luxel(dir, {"bake", "cornell", "-o", "out/cornell.glb", "--lightmaps", "--elements", "2000", "--html"});
  if (builtWithoutThree(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote out/cornell.html"), std::string::npos) << r.out;
  EXPECT_EQ(listDir(dir / "out"), (std::vector<std::string>{"cornell.glb", "cornell.html", "cornell.lightmap0.exr"}));
  expectSelfContained(dir / "out" / "cornell.html", dir / "out" / "cornell.glb");
  // The page says what it shows.
  const std::string text = readFile(dir / "out" / "cornell.html");
  EXPECT_NE(text.find("<title>cornell - luxel</title>"), std::string::npos);
  EXPECT_NE(text.find("\"bake\":\"lightmaps (irradiance)\""), std::string::npos);

  CliRun vc = luxel(dir, {"bake", "cornell", "-o", "vc.glb", "--vertex-colors", "--elements", "200", "--html", "-q"});
  ASSERT_EQ(vc.code, 0) << vc.err;
  EXPECT_TRUE(vc.out.empty()) << vc.out;  // -q
  expectSelfContained(dir / "vc.html", dir / "vc.glb");
  EXPECT_NE(readFile(dir / "vc.html").find("\"bake\":\"vertex colours (radiance)\""), std::string::npos);
}

// Refused before the solve, with nothing written: --html needs a .glb output and baked light, and
// its page must be a file that can be written and that no other output names.
TEST(BakeHtml, BadCombinationsFailWithoutWritingAnything) {
  const fs::path dir = scratchDir();
  const std::vector<std::string> empty;
  expectFailure(luxel(dir, {"bake", "cornell", "-o", "c.gltf", "--lightmaps", "--html", "-q"}), dir, empty,
                {"--html", ".glb", "c.gltf"});
  CliRun unlit = luxel(dir, {"bake", "cornell", "-o", "c.glb", "--html", "-q"});
  expectFailure(unlit, dir, empty, {"--html", "--lightmaps", "--vertex-colors"});
  EXPECT_EQ(unlit.err.find("solv"), std::string::npos) << unlit.err;  // no solve ran
  expectFailure(luxel(dir, {"bake", "cornell", "-o", "c.glb", "--vertex-colors", "--html", "--progress-trace", "c.html", "-q"}),
                dir, empty, {"--html", "c.html", "--progress-trace", "the same file"});
  fs::create_directories(dir / "c.html");
  expectFailure(luxel(dir, {"bake", "cornell", "-o", "c.glb", "--lightmaps", "--html", "-q"}), dir, {"c.html"},
                {"--html", "c.html", "directory"});
  fs::remove(dir / "c.html");
  expectFailure(luxel(dir, {"bake", "cornell", "-o", "no-such-folder/c.glb", "--lightmaps", "--html", "-q"}), dir, empty,
                {"no-such-folder"});
  CliRun usage = luxel(dir, {"bake", "cornell", "--html", "c.glb"});  // -o missing: bad usage
  EXPECT_EQ(usage.code, 2) << usage.err;
  EXPECT_TRUE(fs::is_empty(dir)) << "now: " << joined(listDir(dir));
}

// The page is written to a temporary file and renamed: when it cannot be written whole (here a
// file size limit that the glb and its lightmap fit under and the page does not), no page is left,
// not even a partial one, and the error names it. The glb before it is complete and stays.
TEST(BakeHtml, AFailedPageLeavesNoPartialFile) {
  const fs::path dir = scratchDir();
  CliRun r = luxel(dir, {"bake", "cornell", "-o", "c.glb", "--lightmaps", "--elements", "2000", "--html", "-q"},
                   "trap '' XFSZ; ulimit -f 1024; ");
  if (builtWithoutThree(r)) GTEST_SKIP() << r.err;
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("c.html"), std::string::npos) << r.err;
  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"c.glb", "c.lightmap0.exr"}));
  expectNoTemporaries(dir);
}

// The viewer's script goes into the page inline: nothing in it may end its <script> element or
// open an HTML comment, and it fetches nothing.
TEST(BakeHtml, ViewerScriptIsSafeInline) {
  const std::string script = readFile(fs::path(LUXEL_SOURCE_DIR) / "apps/luxel/html_viewer/viewer.js");
  ASSERT_FALSE(script.empty());
  for (const char* bad : {"</script", "</SCRIPT", "<!--", "http://", "https://", "fetch(", "import("})
    EXPECT_EQ(script.find(bad), std::string::npos) << bad;
}

}  // namespace
