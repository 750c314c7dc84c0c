// Finding an earlier item by name while a file's list is read (a scene file's cameras, which
// replace earlier ones of the same name). A search of the list per item was quadratic in the
// number of items (docs/hostile-inputs.md has the timings); a hash map is linear.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <unordered_map>
#include <utility>

namespace luxel {

// `Equal` compares names; a test passes a counting one to check the cost stays linear.
template <class Equal = std::equal_to<std::string>>
class NameIndex {
 public:
  explicit NameIndex(Equal equal = {}) : positions_(0, std::hash<std::string>(), std::move(equal)) {}

  // The position recorded for `name`, and false; or, when the name is new, `next` (now recorded
  // for it) and true.
  std::pair<size_t, bool> findOrAdd(const std::string& name, size_t next) {
    const auto [it, added] = positions_.emplace(name, next);
    return {it->second, added};
  }

 private:
  std::unordered_map<std::string, size_t, std::hash<std::string>, Equal> positions_;
};

}  // namespace luxel
