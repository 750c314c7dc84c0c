#include "html_page.h"

#include <cctype>
#include <fstream>
#include <iterator>
#include <map>
#include <span>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "html_page_assets.h"
#include "io/atomic_file.h"
#include "luxel/error.h"

namespace fs = std::filesystem;

namespace luxel::cli {
namespace {

std::string base64(std::string_view in) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= in.size(); i += 3) {
    const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 | uint8_t(in[i + 2]);
    out += kDigits[v >> 18];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  if (i < in.size()) {
    const bool two = i + 1 < in.size();
    const uint32_t v = uint32_t(uint8_t(in[i])) << 16 | (two ? uint32_t(uint8_t(in[i + 1])) << 8 : 0u);
    out += kDigits[v >> 18];
    out += kDigits[(v >> 12) & 63];
    out += two ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string escapeHtml(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// JSON that is safe inside a <script> element: '<', '>' and '&' only occur in its strings, where
// their \u escapes mean the same.
std::string scriptJson(const nlohmann::json& j) {
  std::string out;
  for (char c : j.dump()) {
    if (c == '<') out += "\\u003c";
    else if (c == '>') out += "\\u003e";
    else if (c == '&') out += "\\u0026";
    else out += c;
  }
  return out;
}

// A module's text with its relative imports ('./three.core.js', '../utils/X.js') turned into the
// specifiers the import map names them by: a module loaded from a data: URL has no base URL that
// relative specifiers could be resolved against. Only a quoted path right after `from` or
// `import` is rewritten; a path that leads to no embedded module is an error, not a page that
// fails in the browser.
std::string rewriteRelativeImports(const ThreeModule& m, std::span<const ThreeModule> all) {
  std::string out;
  std::string_view t = m.text;
  size_t copied = 0;
  for (size_t q = t.find_first_of("'\""); q != std::string_view::npos; q = t.find_first_of("'\"", q + 1)) {
    const std::string_view rest = t.substr(q + 1);
    if (!(rest.starts_with("./") || rest.starts_with("../"))) continue;
    size_t k = q;  // the keyword before the quote, past white space
    while (k > 0 && (t[k - 1] == ' ' || t[k - 1] == '\t' || t[k - 1] == '\n' || t[k - 1] == '\r')) --k;
    auto endsWith = [&](std::string_view word) {
      return k >= word.size() && t.substr(k - word.size(), word.size()) == word &&
             (k == word.size() || !(std::isalnum(uint8_t(t[k - word.size() - 1])) || t[k - word.size() - 1] == '_' ||
                                    t[k - word.size() - 1] == '$'));
    };
    if (!endsWith("from") && !endsWith("import")) continue;
    const size_t close = t.find(t[q], q + 1);
    if (close == std::string_view::npos) break;
    const std::string relative(t.substr(q + 1, close - q - 1));
    const std::string target = (fs::path(std::string(m.path)).parent_path() / relative).lexically_normal().generic_string();
    const ThreeModule* found = nullptr;
    for (const ThreeModule& o : all)
      if (o.path == target) found = &o;
    if (!found)
      throw Error(fmt::format("--html: three.js's {} imports '{}' ({}), which this luxel does not embed (update "
                              "apps/luxel/html_page_assets.cpp for this version of three.js)",
                              m.path, relative, target));
    out.append(t.substr(copied, q + 1 - copied));
    out.append(found->specifier);
    copied = close;
    q = close;
  }
  out.append(t.substr(copied));
  return out;
}

// The import map: every module as a data: URL (base64, so that no character of three.js's text
// can end the <script> element it sits in).
std::string importMap() {
  const std::span<const ThreeModule> modules = threeModules();
  nlohmann::json imports = nlohmann::json::object();
  for (const ThreeModule& m : modules)
    imports[std::string(m.specifier)] = "data:text/javascript;base64," + base64(rewriteRelativeImports(m, modules));
  return scriptJson({{"imports", imports}});
}

// Fills page.html's {{NAME}} placeholders in one pass (so that nothing substituted is read as a
// placeholder again); each must be used exactly once.
std::string fillTemplate(std::string_view page, const std::map<std::string, std::string>& values) {
  std::string out;
  std::map<std::string, int> used;
  size_t copied = 0;
  for (size_t open = page.find("{{"); open != std::string_view::npos; open = page.find("{{", copied)) {
    const size_t close = page.find("}}", open);
    if (close == std::string_view::npos) break;
    const std::string name(page.substr(open + 2, close - open - 2));
    const auto it = values.find(name);
    if (it == values.end()) throw Error(fmt::format("--html: the page template has an unknown placeholder {{{{{}}}}}", name));
    out.append(page.substr(copied, open - copied));
    out.append(it->second);
    ++used[name];
    copied = close + 2;
  }
  out.append(page.substr(copied));
  for (const auto& [name, value] : values)
    if (used[name] != 1) throw Error(fmt::format("--html: the page template uses {{{{{}}}}} {} times", name, used[name]));
  return out;
}

}  // namespace

fs::path htmlPagePath(const fs::path& glb) {
  fs::path html = glb;
  html.replace_extension(".html");
  return html;
}

void checkHtmlPageAssets() {
  for (const ThreeModule& m : threeModules())
    if (m.text.empty())
      throw Error(fmt::format("--html: this luxel was built without three.js: {}/{} was missing when it was built; "
                              "run scripts/install-deps.sh (npm ci in tools/three-check), then rebuild",
                              threePackageFolder(), m.path));
}

std::string htmlPage(std::string_view glb, const HtmlPageInfo& info) {
  checkHtmlPageAssets();
  const std::string_view script = htmlViewerScript();
  // The script is inline: nothing in it may close its element (the template's own text is checked
  // by tests/cli/test_bake_html.cpp too).
  for (std::string_view bad : {"</script", "</SCRIPT", "<!--"})
    if (script.find(bad) != std::string_view::npos)
      throw Error(fmt::format("--html: the viewer script contains '{}', which would end its <script> element", bad));
  const nlohmann::json about = {{"scene", info.scene}, {"glb", info.glb}, {"bake", info.bake}, {"luxel", LUXEL_VERSION}};
  return fillTemplate(htmlViewerPage(), {
                                            {"title", escapeHtml(fmt::format("{} - luxel", info.scene))},
                                            {"glb-name", escapeHtml(info.glb)},
                                            {"luxel-version", escapeHtml(LUXEL_VERSION)},
                                            {"import-map", importMap()},
                                            {"bake-json", scriptJson(about)},
                                            {"glb-base64", base64(glb)},
                                            {"viewer-script", std::string(script)},
                                        });
}

void writeHtmlPage(const fs::path& glb, const fs::path& html, const HtmlPageInfo& info) {
  std::ifstream in(glb, std::ios::binary);
  if (!in) throw Error(fmt::format("--html: cannot read back {}", glb.string()));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(fmt::format("--html: cannot read back {}", glb.string()));
  if (bytes.empty()) throw Error(fmt::format("--html: {} is empty", glb.string()));
  writeTextAtomically(html, htmlPage(bytes, info));
}

}  // namespace luxel::cli
