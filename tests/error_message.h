// What a test of an error message needs: the message of the luxel::Error a call throws, and a
// string's bytes as the in-memory loaders take them.
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include <gtest/gtest.h>

#include "luxel/error.h"

namespace luxel::test {

// Runs `f`, expects it to throw luxel::Error, and returns its message. Throwing nothing, or
// anything else, fails the test and returns "".
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-luxel exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "did not throw";
  return {};
}

inline std::span<const std::byte> bytesOf(const std::string& s) { return std::as_bytes(std::span<const char>(s)); }

}  // namespace luxel::test
