#include "scene/import/ply_header.h"

#include <cstdint>
#include <map>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {
namespace {

// Bytes of a PLY scalar type (both the old and the sized names), 0 when unknown.
size_t scalarBytes(const std::string& type) {
  static const std::map<std::string, size_t> sizes = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},    {"short", 2},  {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},     {"int32", 4},  {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto found = sizes.find(type);
  return found == sizes.end() ? 0 : found->second;
}

}  // namespace

void checkPlyCounts(std::span<const std::byte> bytes, const std::string& file) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (text.substr(0, 4) != "ply\n" && text.substr(0, 5) != "ply\r\n") return;
  const size_t end = text.find("end_header");
  // Assimp 5.2's PLY reader crashes on some malformed headers (found by fuzz-mesh-ply): anything
  // this check cannot read is refused here rather than handed to it.
  if (end == std::string_view::npos) throw Error(fmt::format("{}: the PLY header has no end_header", file));
  const size_t bodyStart = text.find('\n', end);
  const uint64_t body = bodyStart == std::string_view::npos ? 0 : uint64_t(text.size() - bodyStart - 1);

  std::istringstream header{std::string(text.substr(0, end))};
  std::string line;
  bool ascii = false;
  // The running total of the least bytes the declared elements need, and the element being read.
  long double least = 0.0L;
  std::string element;
  uint64_t count = 0;
  uint64_t perItem = 0;
  std::string biggest;
  long double biggestBytes = 0.0L;
  const auto closeElement = [&] {
    const long double need = (long double)count * (long double)perItem;
    least += need;
    if (need > biggestBytes) biggestBytes = need, biggest = fmt::format("{} {}", count, element);
    element.clear(), count = 0, perItem = 0;
  };
  size_t lineNumber = 0;
  bool formatSeen = false;
  const auto malformed = [&](const std::string& why) {
    return Error(fmt::format("{}: PLY header line {}: {}", file, lineNumber, why));
  };
  while (std::getline(header, line)) {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (lineNumber == 1 || keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string format;
      words >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        throw malformed(fmt::format("unknown format '{}'", format));
      ascii = format == "ascii";
      formatSeen = true;
    } else if (keyword == "element") {
      if (!element.empty()) closeElement();
      words >> element >> count;
      if (!words) throw malformed("expected 'element NAME COUNT'");
    } else if (keyword == "property") {
      if (element.empty()) throw malformed("a property before any element");
      std::string type;
      words >> type;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        if (scalarBytes(countType) == 0 || scalarBytes(itemType) == 0)
          throw malformed(fmt::format("unknown list types '{}' '{}'", countType, itemType));
        perItem += ascii ? 2 : scalarBytes(countType);  // an empty list is just its count
      } else {
        if (scalarBytes(type) == 0) throw malformed(fmt::format("unknown property type '{}'", type));
        perItem += ascii ? 2 : scalarBytes(type);
      }
    } else {
      throw malformed(fmt::format("unknown keyword '{}'", keyword.substr(0, 40)));
    }
  }
  if (!formatSeen) throw Error(fmt::format("{}: the PLY header has no format line", file));
  if (!element.empty()) closeElement();
  if (least > (long double)body)
    throw Error(fmt::format("{}: the PLY header declares {} (at least {:.0f} bytes), but only {} bytes follow the header",
                            file, biggest, double(least), body));
}

}  // namespace luxel
