// A session can draw in the caller's OpenGL context (a viewer's window) instead of making its
// own: here the test makes a headless context, keeps it current, and lends it.
#include <gtest/gtest.h>

#include "gl/gl_test_context.h"
#include "luxel/bench.h"
#include "luxel/session.h"
#include "scene/builtin/builtin_scenes.h"

namespace {

TEST(GlBorrowedContext, SessionSolvesInTheCallersContext) {
  std::string why;
  const std::unique_ptr<luxel::gl::Context> mine = luxel::test::glContextOr(why);
  if (!mine) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
  luxel::SessionOptions options;
  options.solve.method = "progressive";
  options.solve.backend = "gl";
  options.solve.settings.set("unshot", 1e-3).set("hemicube-resolution", 32);
  options.borrowCurrentGlContext = true;
  luxel::Solution a;
  {  // the session's GL objects go while the lent context is still current
    luxel::Session borrowed(luxel::builtin::cornellBox(), luxel::DiscretiseOptions{.elementBudget = 300}, options);
    a = borrowed.solve();
  }
  EXPECT_EQ(a.stats.backend, "gl");
  EXPECT_EQ(a.stats.device, mine->renderer());
  EXPECT_GT(a.stats.shots, 0u);
  // The same solve in a context of the session's own gives the same answer: the borrowed
  // context was really used, and left usable.
  options.borrowCurrentGlContext = false;
  luxel::Session own(luxel::builtin::cornellBox(), luxel::DiscretiseOptions{.elementBudget = 300}, options);
  const luxel::Solution b = own.solve();
  EXPECT_EQ(a.stats.shots, b.stats.shots);
  EXPECT_LT(luxel::bench::normalisedRmsError(own.surfaces(), a.radiosity, b.radiosity), 1e-5);
}

}  // namespace
