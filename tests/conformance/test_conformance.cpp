// Every registered solver on every backend it registers, against closed forms and the converged
// CPU reference (pbrt-v4's habit: one parameterised suite over all integrators). Registering a
// solver puts it here with no test code to write: it runs with the settings it registers as
// converged, and is held to the tolerances it registers (SolverAccuracy), which say how exact its
// quadrature is. GL solvers skip, saying why, without an OpenGL 4.5 context.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numbers>

#include "analytic/half_shadow_scene.h"
#include "gl/gl_parity.h"
#include "gl/gl_test_context.h"
#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/session.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "solve/solver_registry.h"

namespace luxel {
namespace {

constexpr double kPi = std::numbers::pi;

// A test name: letters, digits and underscores only ("cross-redistribution" has a dash).
std::string nameOf(const SolverEntry& e) {
  std::string name = e.description.name + "_" + e.description.backend;
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

// The Cornell box at 200 elements: small enough to solve twice over in a test.
SurfaceSet smallCornell(const Scene& scene) {
  DiscretiseOptions d;
  d.elementBudget = 200;
  return discretise(scene, d);
}

class Conformance : public ::testing::TestWithParam<const SolverEntry*> {
 protected:
  void SetUp() override {
    const SolverEntry& e = *GetParam();
    if (e.description.backend == "gl") {
      std::string why;
      if (!test::glContextOr(why)) GTEST_SKIP() << "no OpenGL 4.5 context: " << why;
    }
  }
  const SolverEntry& entry() const { return *GetParam(); }
  SolveOptions converged() const {
    SolveOptions o;
    o.method = entry().description.name;
    o.backend = entry().description.backend;
    o.settings = entry().converged;
    return o;
  }
  Solution solveConverged(const Scene& scene, SurfaceSet& surfaces) const {
    const Solution s = solve(scene, surfaces, converged());
    EXPECT_EQ(s.stats.method, entry().description.name);
    EXPECT_EQ(s.stats.backend, entry().description.backend);
    return s;
  }
};

// A closed box, rho = 0.5 and Le = 1 everywhere: radiance Le / (1 - rho) = 2 on every element.
TEST_P(Conformance, FurnaceReachesLeOverOneMinusRho) {
  const float rho = 0.5f, le = 1.0f;
  const Scene scene = builtin::furnace(rho, le);
  DiscretiseOptions d;
  d.elementBudget = 300;
  SurfaceSet surfaces = discretise(scene, d);
  const Solution s = solveConverged(scene, surfaces);
  const double expected = le / (1.0 - rho), tolerance = entry().accuracy.furnace;
  double worst = 0.0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(s.radiosity[e][c] / kPi - expected) / expected);
  RecordProperty("worst", std::to_string(worst));
  EXPECT_LT(worst, tolerance) << "largest relative error over " << surfaces.elements.size() << " elements";
}

// CIE 171:2006 test case 5.8: a 4 m cube (S = 96 m^2), rho = 0.5, an isotropic 10,000 lm point
// light at the centre: mean illuminance Phi / (S (1 - rho)) = 208.33 lx.
TEST_P(Conformance, CieCase58MeanIlluminance) {
  const float rho = 0.5f;
  const Scene scene = builtin::cieCube(rho, 10000.0f);
  DiscretiseOptions d;
  d.elementBudget = 300;
  SurfaceSet surfaces = discretise(scene, d);
  const Solution s = solveConverged(scene, surfaces);
  double weighted = 0.0, area = 0.0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    weighted += surfaces.elements[e].area * s.irradiance[e].g;
    area += surfaces.elements[e].area;
  }
  const double expected = 10000.0 / (96.0 * (1.0 - rho));
  EXPECT_NEAR(weighted / area, expected, entry().accuracy.cie * expected);
}

// A receiver half in the shadow of a sheet: the visible share of the emitter's factor, weighted
// by where on the emitter it comes from (tests/analytic/half_shadow_scene.h).
TEST_P(Conformance, HalfShadowFactorMatchesTheClosedForm) {
  const Scene scene = test::halfShadowScene();
  SurfaceSet surfaces = test::halfShadowSurfaces(scene);
  const size_t receiver = test::halfShadowReceiver(surfaces);
  ASSERT_LT(receiver, surfaces.elements.size());
  const Solution s = solveConverged(scene, surfaces);
  const double factor = s.directIrradiance[receiver].g / kPi;  // exitance pi Le, Le = 1
  const double expected = test::halfShadowFactor(true);
  RecordProperty("factor", std::to_string(factor));
  EXPECT_NEAR(factor, expected, entry().accuracy.halfShadow * expected);
}

// The Cornell box at 300 elements against the CPU's converged gather (64 rays per pair). Every
// element is its own patch: with the default 8 x 8 elements a patch, each face of this box is one
// patch shooting its mean radiosity, and a solver that shoots from each element (the
// hierarchical one) is 25% off such a reference on faces lit only by interreflection while
// within 2% of the finer one (docs/algorithms.md, "Face-cluster radiosity").
TEST_P(Conformance, CornellAgreesWithTheConvergedCpuReference) {
  const test::CornellReference& ref = test::cornellReference(300, 1);
  SurfaceSet surfaces = ref.surfaces;
  const Solution s = solveConverged(ref.scene, surfaces);
  const double rms = bench::normalisedRmsError(surfaces, s.radiosity, ref.cpu.radiosity);
  std::printf("%s on %s: Cornell NRMSE %.4f\n", entry().description.name.c_str(), entry().description.backend.c_str(), rms);
  RecordProperty("nrmse", std::to_string(rms));
  EXPECT_LT(rms, entry().accuracy.cornell);
}

// A solver is an object that steps: stepping one unit of work at a time, and reading the solution
// between steps, reaches the answer of one call.
TEST_P(Conformance, SteppingReachesTheAnswerOfOneCall) {
  const Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = smallCornell(scene);
  SurfaceSet copy = surfaces;
  const Solution whole = solve(scene, copy, converged());

  Session session(scene, surfaces, {converged()});
  ASSERT_TRUE(session.step({0.0, 1}));  // one unit: the solve has only begun
  const Solution early = session.solution();
  ASSERT_EQ(early.radiosity.size(), surfaces.elements.size());
  EXPECT_GT(early.stats.shots + early.stats.iterations, 0u);
  EXPECT_FALSE(session.done());
  int steps = 1;
  while (session.step({0.0, 1})) ++steps;
  EXPECT_TRUE(session.done());
  const Solution last = session.solution();
  EXPECT_GT(steps, 1);
  EXPECT_EQ(last.stats.shots, whole.stats.shots);
  EXPECT_EQ(last.stats.iterations, whole.stats.iterations);
  for (size_t e = 0; e < surfaces.elements.size(); ++e)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(last.radiosity[e][c], whole.radiosity[e][c], 1e-5f * (1.0f + whole.radiosity[e][c])) << "element " << e;
}

// A solver that can be checkpointed (luxel/checkpoint.h) and is stopped part way, then resumed
// from its checkpoint by a new session, ends with the bits of one that ran through; one that
// cannot says so when asked.
TEST_P(Conformance, AResumedSolveEndsWhereAnUninterruptedOneDoes) {
  const Scene scene = builtin::cornellBox();
  SurfaceSet surfaces = smallCornell(scene);
  SurfaceSet copy = surfaces;
  const Solution whole = solve(scene, copy, converged());

  const std::filesystem::path file = std::filesystem::path(LUXEL_TEST_TMP) / ("conformance-" + nameOf(entry()) + ".ckpt");
  std::filesystem::create_directories(file.parent_path());
  std::filesystem::remove(file);
  SolveOptions writing = converged();
  writing.checkpoint = {.path = file, .intervalSeconds = 1e-9};  // after every step
  std::unique_ptr<Session> first;
  try {
    first = std::make_unique<Session>(scene, surfaces, SessionOptions{writing});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be checkpointed"), std::string::npos) << e.what();
    GTEST_SKIP() << "this solver cannot be checkpointed: " << e.what();
  }
  ASSERT_TRUE(first->step({0.0, 1}));
  ASSERT_TRUE(first->step({0.0, 1}));
  first.reset();  // as a killed process would leave it: the checkpoint of the last step

  SolveOptions resuming = converged();
  resuming.checkpoint.resume = file;
  Session resumed(scene, surfaces, {resuming});
  const Solution last = resumed.solve();
  EXPECT_EQ(last.stats.shots, whole.stats.shots);
  EXPECT_EQ(last.stats.iterations, whole.stats.iterations);
  EXPECT_EQ(last.stats.links, whole.stats.links);
  for (const auto [got, expected] : {std::pair{&last.radiosity, &whole.radiosity}, {&last.irradiance, &whole.irradiance},
                                     {&last.directIrradiance, &whole.directIrradiance}}) {
    ASSERT_EQ(got->size(), expected->size());
    EXPECT_EQ(std::memcmp(got->data(), expected->data(), got->size() * sizeof(Rgb)), 0);
  }
}

std::vector<const SolverEntry*> solversOn(const std::string& backend) {
  std::vector<const SolverEntry*> out;
  for (const SolverEntry& e : SolverRegistry::builtin().entries())
    if (e.description.backend == backend) out.push_back(&e);
  return out;
}

std::string solverName(const ::testing::TestParamInfo<const SolverEntry*>& info) { return nameOf(*info.param); }

// Every backend the registry holds must be instantiated here (RegistryHasNoOtherBackend). The GL
// ones are named Gl... so that `make asan` runs them in its GL batch (Mesa's allocations at exit
// are not leaks of ours).
INSTANTIATE_TEST_SUITE_P(Registered, Conformance, ::testing::ValuesIn(solversOn("cpu")), solverName);
INSTANTIATE_TEST_SUITE_P(GlRegistered, Conformance, ::testing::ValuesIn(solversOn("gl")), solverName);

TEST(ConformanceCoverage, RegistryHasNoOtherBackend) {
  for (const SolverEntry& e : SolverRegistry::builtin().entries())
    EXPECT_TRUE(e.description.backend == "cpu" || e.description.backend == "gl")
        << e.description.name << " on " << e.description.backend << " is registered but not instantiated here";
}

}  // namespace
}  // namespace luxel
