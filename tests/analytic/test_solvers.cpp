// Solvers against closed forms, and against each other. Every test names the scene values it uses.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "luxel/error.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "solve/radiosity_system.h"

namespace luxel {
namespace {

constexpr double kPi = std::numbers::pi;

struct Solved {
  SurfaceSet surfaces;
  Solution solution;
};

Solved solveScene(const Scene& scene, const std::string& method, size_t elements, double tolerance = 1e-6) {
  DiscretiseOptions d;
  d.elementBudget = elements;
  Solved s{discretise(scene, d), {}};
  SolveOptions o;
  o.method = method;
  o.settings.set(method == "gather" ? "residual" : "unshot", tolerance);
  s.solution = solve(scene, s.surfaces, o);
  return s;
}

class BothSolvers : public ::testing::TestWithParam<std::string> {};

// Furnace: a closed unit cube, every wall rho = 0.5 and Le = 1 (grey): radiance 2 everywhere.
TEST_P(BothSolvers, FurnaceReachesLeOverOneMinusRho) {
  const float rho = 0.5f, le = 1.0f;
  Solved s = solveScene(builtin::furnace(rho, le), GetParam(), 600);
  const double expected = le / (1.0 - rho);
  for (size_t e = 0; e < s.surfaces.elements.size(); ++e) {
    const Rgb b = s.solution.radiosity[e];
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(b[c] / kPi, expected, 1e-3 * expected) << "element " << e;
  }
}

// Furnace at rho = 0.9 exercises ~100 bounces: radiance 10.
TEST_P(BothSolvers, FurnaceAtHighAlbedo) {
  Solved s = solveScene(builtin::furnace(0.9f, 1.0f), GetParam(), 300, 1e-7);
  for (size_t e = 0; e < s.surfaces.elements.size(); ++e)
    ASSERT_NEAR(s.solution.radiosity[e].g / kPi, 10.0, 1e-2) << "element " << e;
}

// CIE 171:2006 test case 5.8: 4 m cube (S = 96 m^2), isotropic 10,000 lm point source at the
// centre: mean illuminance 104.17, 130.21, 208.33, 520.83 lx for rho = 0, 0.2, 0.5, 0.8.
TEST_P(BothSolvers, CieCase58MeanIlluminance) {
  const double expected[] = {104.17, 130.21, 208.33, 520.83};
  const float rhos[] = {0.0f, 0.2f, 0.5f, 0.8f};
  for (int i = 0; i < 4; ++i) {
    Solved s = solveScene(builtin::cieCube(rhos[i], 10000.0f), GetParam(), 1500, 1e-6);
    double weighted = 0.0, area = 0.0;
    for (size_t e = 0; e < s.surfaces.elements.size(); ++e) {
      weighted += s.surfaces.elements[e].area * s.solution.irradiance[e].g;
      area += s.surfaces.elements[e].area;
    }
    EXPECT_NEAR(area, 96.0, 1e-3);
    EXPECT_NEAR(weighted / area, expected[i], 0.005 * expected[i]) << "rho = " << rhos[i];
    // And from first principles rather than the table: Phi / (S (1 - rho)).
    EXPECT_NEAR(weighted / area, 10000.0 / (96.0 * (1.0 - rhos[i])), 0.005 * expected[i]);
  }
}

// In a closed scene, what enters (emission, analytic light) is what the surfaces absorb.
TEST_P(BothSolvers, EnergyBalanceInClosedScenes) {
  for (const Scene& scene : {builtin::cieCube(0.6f), builtin::furnace(0.7f, 2.0f)}) {
    Solved s = solveScene(scene, GetParam(), 800, 1e-7);
    const SolveStats& st = s.solution.stats;
    ASSERT_GT(st.emittedPower, 0.0);
    EXPECT_NEAR(st.absorbedPower / st.emittedPower, 1.0, 2e-3) << scene.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Solvers, BothSolvers,
                         ::testing::Values("progressive", "gather"),
                         [](const auto& info) {
                           return info.param == "gather" ? "gather" : "progressive";
                         });

// The two solvers solve the same system: per element within 0.5% on the Cornell box.
TEST(SolverAgreement, ProgressiveMatchesGatherPerElementOnCornell) {
  Scene scene = builtin::cornellBox();
  Solved p = solveScene(scene, "progressive", 700, 1e-6);
  Solved g = solveScene(scene, "gather", 700, 1e-7);
  ASSERT_EQ(p.surfaces.elements.size(), g.surfaces.elements.size());
  double maxB = 0.0;
  for (const Rgb& b : g.solution.radiosity) maxB = std::max(maxB, double(b.r + b.g + b.b));
  for (size_t e = 0; e < p.surfaces.elements.size(); ++e) {
    const Rgb a = p.solution.radiosity[e], b = g.solution.radiosity[e];
    double scale = std::max(double(b.r + b.g + b.b), 1e-3 * maxB);
    ASSERT_NEAR(a.r + a.g + a.b, b.r + b.g + b.b, 0.005 * scale) << "element " << e;
  }
}

// The unshot energy really falls, and stopping early with the ambient term is a fair estimate.
TEST(Progressive, AmbientTermEstimatesUnshotLight) {
  Scene scene = builtin::furnace(0.8f, 1.0f);
  DiscretiseOptions d;
  d.elementBudget = 300;
  SurfaceSet surfaces = discretise(scene, d);
  SolveOptions o;
  o.settings.set("unshot", 0.2);  // stop very early
  o.settings.set("ambient", false);
  Solution raw = solve(scene, surfaces, o);
  o.settings.set("ambient", true);
  Solution amb = solve(scene, surfaces, o);
  EXPECT_GT(raw.stats.unshotFraction, 0.0);
  EXPECT_LE(raw.stats.unshotFraction, 0.2);
  double rawErr = 0.0, ambErr = 0.0;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    rawErr += std::abs(raw.radiosity[e].g / kPi - 5.0);
    ambErr += std::abs(amb.radiosity[e].g / kPi - 5.0);
  }
  EXPECT_LT(ambErr, 0.2 * rawErr);
}

TEST(Progressive, ShotBudgetStopsTheSolve) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 400;
  SurfaceSet surfaces = discretise(scene, d);
  SolveOptions o;
  o.settings.set("shot-budget", 5);
  Solution s = solve(scene, surfaces, o);
  EXPECT_EQ(s.stats.shots, 5u);
  EXPECT_GT(s.stats.unshotFraction, 1e-3);  // the default threshold
}

TEST(Solve, ProgressCallbackCancels) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 400;
  SurfaceSet surfaces = discretise(scene, d);
  int calls = 0;
  EXPECT_THROW(solve(scene, surfaces, SolveOptions{}, [&](const ProgressEvent&) { return ++calls < 3; }), Cancelled);
  EXPECT_EQ(calls, 3);
}

TEST(Solve, RejectsAbsurdOptions) {
  Scene scene = builtin::furnace();
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
  SolveOptions o;
  o.settings.set("unshot", 0.0);
  EXPECT_THROW(solve(scene, surfaces, o), Error);
  o = SolveOptions{};
  o.settings.set("rays-per-pair", 100000);
  EXPECT_THROW(solve(scene, surfaces, o), Error);
  o = SolveOptions{};
  o.settings.set("shooters-per-pass", kMaxShootersPerPass + 1);
  EXPECT_THROW(solve(scene, surfaces, o), Error);
}

// One shooter per pass or many: the same converged answer, and the staler choices of larger
// batches cost a few more shots.
TEST(Progressive, ShootersPerPassChangeTheOrderNotTheAnswer) {
  Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  d.elementBudget = 400;
  SurfaceSet surfaces = discretise(scene, d);
  SolveOptions o;
  o.settings.set("unshot", 1e-6);
  o.settings.set("ambient", false);
  o.settings.set("shooters-per-pass", 1);
  const Solution one = solve(scene, surfaces, o);
  o.settings.set("shooters-per-pass", kMaxShootersPerPass);
  const Solution many = solve(scene, surfaces, o);
  EXPECT_LT(one.stats.shots, many.stats.shots);
  for (size_t e = 0; e < surfaces.elements.size(); ++e)
    ASSERT_NEAR(one.radiosity[e].g, many.radiosity[e].g, 1e-3f * (1.0f + many.radiosity[e].g)) << "element " << e;
}

}  // namespace
}  // namespace luxel
