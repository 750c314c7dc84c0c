#include "scene/import/collada_indices.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {

void checkColladaIndices(std::span<const std::byte> bytes, const std::string& file) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  for (size_t at = text.find("<p"); at != std::string_view::npos; at = text.find("<p", at + 2)) {
    // "<p>" or "<p attr...>", not "<param", "<polylist", ...
    const char next = at + 2 < text.size() ? text[at + 2] : '\0';
    if (next != '>' && !std::isspace((unsigned char)next)) continue;
    const size_t open = text.find('>', at);
    if (open == std::string_view::npos || text[open - 1] == '/') continue;
    const size_t close = text.find('<', open);
    const std::string_view list = text.substr(open + 1, close == std::string_view::npos ? close : close - open - 1);
    for (size_t i = 0; i < list.size(); ++i) {
      if (std::isdigit((unsigned char)list[i]) || std::isspace((unsigned char)list[i])) continue;
      size_t end = i;
      while (end < list.size() && !std::isspace((unsigned char)list[end])) ++end;
      const size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(open + 1 + i), '\n'));
      throw Error(fmt::format("{}: line {}: index '{}' in a <p> index list is not a non-negative integer",
                              file, line, list.substr(i, end - i)));
    }
  }
}

}  // namespace luxel
