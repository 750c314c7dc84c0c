#include "scene/import/obj_references.h"

#include <charconv>
#include <set>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "luxel/error.h"
#include "scene/import/resource_path.h"

namespace luxel {
namespace {

std::string_view trim(std::string_view s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// Each line of `text` without its comment, trimmed, with its 1-based number.
template <class F>
void forEachLine(std::string_view text, F&& f) {
  size_t line = 0;
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(at, end - at);
    l = trim(l.substr(0, l.find('#')));
    f(l, ++line);
    at = end + 1;
  }
}

// The keyword and the rest of the line.
std::pair<std::string_view, std::string_view> split(std::string_view line) {
  const size_t space = line.find_first_of(" \t");
  if (space == std::string_view::npos) return {line, {}};
  return {line.substr(0, space), trim(line.substr(space))};
}

std::set<std::string> definedMaterials(std::string_view mtl) {
  std::set<std::string> names;
  forEachLine(mtl, [&](std::string_view line, size_t) {
    auto [key, rest] = split(line);
    if (key == "newmtl") names.emplace(rest);
  });
  return names;
}

}  // namespace

std::vector<std::string> checkObjReferences(std::span<const std::byte> bytes,
                                            const ResourceReader& resources, const std::string& file) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::vector<std::string> warnings;
  // Counts of v, vt and vn defined so far: a face may only use those (relative indices count back).
  size_t counts[3] = {0, 0, 0};
  const char* const kinds[3] = {"vertex", "texture coordinate", "normal"};
  std::set<std::string> materials, undefined;
  std::vector<std::pair<std::string, size_t>> used;  // usemtl names and their lines
  bool libraryMissing = false, anyLibrary = false;
  forEachLine(text, [&](std::string_view line, size_t number) {
    auto [key, rest] = split(line);
    if (key == "v") ++counts[0];
    else if (key == "vt") ++counts[1];
    else if (key == "vn") ++counts[2];
    else if (key == "usemtl") used.emplace_back(rest, number);
    else if (key == "mtllib") {
      anyLibrary = true;
      const std::string path = normalizeResourcePath(std::string(rest));
      if (std::optional<std::vector<std::byte>> mtl = resources.read(path)) {
        materials.merge(definedMaterials({reinterpret_cast<const char*>(mtl->data()), mtl->size()}));
      } else {
        libraryMissing = true;
        warnings.push_back(fmt::format("{}: line {}: material library '{}' not found (looked for '{}'): its "
                                       "materials are missing, so faces get a default grey and nothing emits",
                                       file, number, rest, resources.describe(path)));
      }
    } else if (key == "f" || key == "l" || key == "p") {
      std::istringstream corners{std::string(rest)};
      for (std::string corner; corners >> corner;) {
        size_t slot = 0;
        for (size_t at = 0; at <= corner.size() && slot < 3; ++slot) {
          size_t end = corner.find('/', at);
          if (end == std::string::npos) end = corner.size();
          const std::string_view field(corner.data() + at, end - at);
          at = end + 1;
          if (field.empty()) continue;  // "1//3": no texture coordinate
          long long index = 0;
          const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), index);
          const long long count = (long long)counts[slot];
          if (ec != std::errc() || ptr != field.data() + field.size() || index == 0 || index > count ||
              index < -count)
            throw Error(fmt::format("{}: line {}: face corner '{}' refers to {} {}, but {} {} defined before it",
                                    file, number, corner, kinds[slot], field, count,
                                    count == 1 ? "is" : "are"));
          if (end == corner.size()) break;
        }
      }
    }
  });
  if (!libraryMissing)
    for (const auto& [name, number] : used)
      if (!materials.contains(name) && undefined.insert(name).second)
        warnings.push_back(fmt::format("{}: line {}: material '{}' is not defined in {}: faces that use it get a "
                                       "default grey and do not emit",
                                       file, number, name, !anyLibrary ? "any material library (the file names no mtllib)" : "the file's material libraries"));
  return warnings;
}

}  // namespace luxel
