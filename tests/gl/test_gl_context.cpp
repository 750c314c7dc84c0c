// The headless context's driver messages (gl/gl_context.h): what reaches a solve's warnings.
// Skips, saying why, without an OpenGL 4.5 context.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "gl/gl_context.h"
#include "luxel/error.h"

namespace {

// NVIDIA's driver reports every read-back of a storage buffer as a medium-severity performance
// message; the solvers read back by design, so those stay out of the warnings, and errors do not.
TEST(GlContextMessages, ReadBackPerformanceNotesAreDroppedAndErrorsKept) {
  std::vector<std::string> messages;
  std::unique_ptr<luxel::gl::Context> context;
  try {
    context = std::make_unique<luxel::gl::Context>([&](const std::string& m) { messages.push_back(m); });
  } catch (const luxel::Error& e) {
    GTEST_SKIP() << "no OpenGL 4.5 context: " << e.what();
  }
  glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_PERFORMANCE, 1, GL_DEBUG_SEVERITY_MEDIUM, -1,
                       "Buffer performance warning: copied from VIDEO memory to HOST memory");
  glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_PERFORMANCE, 2, GL_DEBUG_SEVERITY_HIGH, -1,
                       "a severe performance problem");
  glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_ERROR, 3, GL_DEBUG_SEVERITY_HIGH, -1,
                       "an error");
  glFinish();
  if (messages.empty()) GTEST_SKIP() << "this driver delivers no debug messages";
  ASSERT_EQ(messages.size(), 2u) << messages.front();
  EXPECT_NE(messages[0].find("a severe performance problem"), std::string::npos) << messages[0];
  EXPECT_NE(messages[1].find("an error"), std::string::npos) << messages[1];
}

}  // namespace
