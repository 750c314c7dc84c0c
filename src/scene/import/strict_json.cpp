#include "scene/import/strict_json.h"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <set>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"

namespace luxel {
namespace {

using Json = nlohmann::ordered_json;

// A char iterator that records how far the parser has read, so that a callback (which nlohmann
// gives no position) can say where a key is: at a key's callback the lexer has just read its
// closing quote.
struct TrackingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  const char* at = nullptr;
  const char** reached = nullptr;

  reference operator*() const { return *at; }
  TrackingIterator& operator++() {
    *reached = std::max(*reached, ++at);
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const TrackingIterator& o) const { return at == o.at; }
  bool operator!=(const TrackingIterator& o) const { return at != o.at; }
};

// nlohmann's DOM builder, with the keys of each open object remembered. Not a parser callback:
// nlohmann's callback builder searches the whole parent at every object's end, which is quadratic
// in a long list of objects (docs/hostile-inputs.md).
class DuplicateKeySax {
 public:
  DuplicateKeySax(Json& result, std::string_view text, const char* const& reached, const std::string& file)
      : dom_(result, /*allow_exceptions=*/true), text_(text), reached_(reached), file_(file) {}

  bool null() { return dom_.null(); }
  bool boolean(bool v) { return dom_.boolean(v); }
  bool number_integer(Json::number_integer_t v) { return dom_.number_integer(v); }
  bool number_unsigned(Json::number_unsigned_t v) { return dom_.number_unsigned(v); }
  bool number_float(Json::number_float_t v, const Json::string_t& s) { return dom_.number_float(v, s); }
  bool string(Json::string_t& v) { return dom_.string(v); }
  bool binary(Json::binary_t& v) { return dom_.binary(v); }
  bool start_object(std::size_t n) {
    objects_.emplace_back();
    return dom_.start_object(n);
  }
  bool key(Json::string_t& k) {
    if (!objects_.back().insert(k).second) duplicate(k);
    return dom_.key(k);
  }
  bool end_object() {
    objects_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) { return dom_.start_array(n); }
  bool end_array() { return dom_.end_array(); }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
    return dom_.parse_error(position, token, e);
  }

 private:
  [[noreturn]] void duplicate(const std::string& key) const {
    // The key's opening quote: the last quote before the closing one the lexer stopped at.
    const size_t close = size_t(reached_ - text_.data()) - 1;
    const size_t open = close > 0 ? text_.rfind('"', close - 1) : 0;
    const size_t start = open == std::string_view::npos ? close : open;
    const size_t line = 1 + size_t(std::count(text_.begin(), text_.begin() + long(start), '\n'));
    const size_t lineStart = start == 0 ? std::string_view::npos : text_.rfind('\n', start - 1);
    const size_t column = start - (lineStart == std::string_view::npos ? 0 : lineStart + 1) + 1;
    throw Error(fmt::format("{}: line {}, column {}: key '{}' appears twice in one object (only one "
                            "would be used: remove or rename the other)",
                            file_, line, column, key));
  }

  nlohmann::detail::json_sax_dom_parser<Json> dom_;
  std::vector<std::set<std::string>> objects_;  // the keys seen in each object being parsed
  std::string_view text_;
  const char* const& reached_;
  const std::string& file_;
};

}  // namespace

Json parseJsonWithoutDuplicateKeys(std::string_view text, const std::string& file) {
  const char* reached = text.data();
  Json result;
  DuplicateKeySax sax(result, text, reached, file);
  const TrackingIterator first{text.data(), &reached}, last{text.data() + text.size(), &reached};
  Json::sax_parse(first, last, &sax, nlohmann::detail::input_format_t::json, /*strict=*/true,
                  /*ignore_comments=*/true);
  return result;
}

}  // namespace luxel
