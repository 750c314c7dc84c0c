#include <cstring>

#include <fmt/format.h>

#include "luxel/checkpoint.h"
#include "luxel/error.h"

namespace luxel {

uint64_t StateReader::arrayLength(uint64_t expected, size_t itemSize) {
  const uint64_t n = value<uint64_t>();
  if (expected != kAnyLength && n != expected)
    fail(fmt::format("an array of {} items where {} are expected", n, expected));
  if (itemSize && n > (bytes_.size() - at_) / itemSize) fail(fmt::format("an array of {} items runs past its end", n));
  return n;
}

void StateReader::raw(void* out, size_t size) {
  if (size > bytes_.size() - at_) fail("it ends early");
  if (size) std::memcpy(out, bytes_.data() + at_, size);
  at_ += size;
}

void StateReader::end() const {
  if (at_ != bytes_.size()) fail(fmt::format("{} bytes are left over", bytes_.size() - at_));
}

void StateReader::fail(const std::string& what) const {
  throw Error(fmt::format("{}: {}", where_, what));
}

}  // namespace luxel
