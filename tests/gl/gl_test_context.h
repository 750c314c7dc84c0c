// An OpenGL 4.5 context for a GL test, or the reason there is none (the test then skips with it).
#pragma once

#include <memory>
#include <string>

#include "gl/gl_context.h"
#include "luxel/error.h"

namespace luxel::test {

inline std::unique_ptr<gl::Context> glContextOr(std::string& why) {
  try {
    return std::make_unique<gl::Context>();
  } catch (const Error& e) {
    why = e.what();
    return nullptr;
  }
}

}  // namespace luxel::test
