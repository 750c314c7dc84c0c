// JSON parsing that refuses an object with the same key twice. RFC 8259 leaves duplicates to the
// parser, and nlohmann::json keeps the last: a scene file with two "materials" objects would lose
// the first without a word.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace luxel {

// Parses `text` (comments allowed) as nlohmann::ordered_json::parse does, throwing its exceptions
// for malformed JSON, and Error("<file>: line L, column C: key 'k' appears twice in one object
// ...") for a duplicate key, the position being the second one's.
nlohmann::ordered_json parseJsonWithoutDuplicateKeys(std::string_view text, const std::string& file);

}  // namespace luxel
