// A 64-bit hash of a stream of bytes, for the keys of caches on disk (the face-cluster hierarchy,
// the bench's reference solutions): XXH3 from xxHash (Debian's libxxhash), stable across runs and
// machines of one byte order, and fast enough (gigabytes a second) that hashing a scene of
// millions of faces costs little next to what its key saves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>

namespace luxel {

class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  void bytes(const void* data, size_t size);
  void text(std::string_view s) { bytes(s.data(), s.size()); }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  uint64_t digest() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace luxel
