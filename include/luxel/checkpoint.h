// Checkpoints: a solve's state on disk, so that a long solve or bake that is killed part way
// continues where it stopped instead of starting again (`--checkpoint FILE`, `--resume FILE`).
// A resumed solve ends with the same solution, bit for bit, as one that was never interrupted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace luxel {

struct CheckpointOptions {
  // Write the solve's state here every `intervalSeconds` of solving and when it ends ("": never).
  std::filesystem::path path;
  // Continue from this checkpoint ("": start afresh). It must have been written for the same
  // surfaces, lights, solver, backend, options and luxel version; anything else is an Error.
  std::filesystem::path resume;
  double intervalSeconds = 60.0;
};

// A solver's state as bytes, written field by field in an order its restore reads back.
class StateWriter {
 public:
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void value(const T& v) {
    raw(&v, sizeof v);
  }
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void array(std::span<const T> items) {
    value(uint64_t(items.size()));
    raw(items.data(), items.size_bytes());
  }
  template <class T>
  void array(const std::vector<T>& items) {
    array(std::span<const T>(items));
  }
  void raw(const void* data, size_t size) {
    const auto* p = static_cast<const std::byte*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  const std::vector<std::byte>& bytes() const { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
};

// Reads what a StateWriter wrote. A read past the end, or an array whose length is not the one the
// reader expects, throws Error beginning with `where` (what is being read): a checkpoint is
// checked before a solver sees it, so this is a defence against a reader and writer disagreeing.
class StateReader {
 public:
  StateReader(std::span<const std::byte> bytes, std::string where) : bytes_(bytes), where_(std::move(where)) {}

  template <class T>
    requires std::is_trivially_copyable_v<T>
  T value() {
    T v;
    raw(&v, sizeof v);
    return v;
  }
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void value(T& v) {
    raw(&v, sizeof v);
  }
  // Reads an array into `items`; `expected` (when not kAnyLength) is the length it must have.
  static constexpr uint64_t kAnyLength = ~uint64_t(0);
  template <class T>
    requires std::is_trivially_copyable_v<T>
  void array(std::vector<T>& items, uint64_t expected = kAnyLength) {
    const uint64_t n = arrayLength(expected, sizeof(T));
    items.resize(size_t(n));
    raw(items.data(), size_t(n) * sizeof(T));
  }
  // The length of the next array, checked against `expected` and against the bytes left.
  uint64_t arrayLength(uint64_t expected, size_t itemSize);
  void raw(void* out, size_t size);
  // Throws unless every byte was read.
  void end() const;

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::span<const std::byte> bytes_;
  size_t at_ = 0;
  std::string where_;
};

}  // namespace luxel
