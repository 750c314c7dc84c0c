// The CPU backend's form factors against an independent estimator that shares nothing with them
// (transport/monte_carlo_transport.h: cosine-distributed rays, hits tallied per patch), on the
// Cornell box cut into large patches, where partly hidden patches are the rule. Per face, the
// interreflected light of the two solutions must agree; the unweighted visibility share luxel
// used before was 2-22% dark here.
#include <cstdio>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "bench/reference.h"
#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"
#include "session/solver_host.h"
#include "transport/monte_carlo_transport.h"

namespace luxel {
namespace {

SolveOptions convergedGather() {
  SolveOptions o;
  o.method = "gather";
  o.settings.set("residual", 1e-6);
  return o;
}

TEST(MonteCarloReference, CornellInterreflectionsAgreeFaceByFace) {
  const Scene scene = builtin::cornellBox();
  DiscretiseOptions d;
  // About 1,100 elements in 20 patches: large patches, so that many are partly hidden, and
  // elements small enough that the receiver's midpoint rule does not matter. (At 300 elements
  // the 2 x 2 rule, which the GL gather shares, leaves the block faces by the floor 4-6% dark
  // against the exact element average.)
  d.elementBudget = 1200;
  d.elementsPerPatchSide = 16;
  SurfaceSet surfaces = discretise(scene, d);
  SurfaceSet mcSurfaces = surfaces;
  MonteCarloTransport monteCarlo(scene, mcSurfaces, 1 << 14);
  SolverHost host(scene, mcSurfaces, convergedGather(), {&monteCarlo, nullptr});
  while (host.step()) {
  }
  const Solution mc = host.solution();
  SolveOptions cpuOptions = convergedGather();
  cpuOptions.settings.set("rays-per-pair", 64);
  cpuOptions.settings.set("near-rays-per-pair", 64);
  cpuOptions.settings.set("emitter-rays-per-pair", 256);
  const Solution cpu = solve(scene, surfaces, cpuOptions);

  // Interreflected irradiance (all minus direct), area-weighted per face.
  std::map<uint32_t, std::pair<double, double>> perFace;
  for (size_t e = 0; e < surfaces.elements.size(); ++e) {
    const Element& el = surfaces.elements[e];
    const Rgb a = cpu.irradiance[e] - cpu.directIrradiance[e], b = mc.irradiance[e] - mc.directIrradiance[e];
    perFace[el.face].first += el.area * (a.r + a.g + a.b);
    perFace[el.face].second += el.area * (b.r + b.g + b.b);
  }
  double worst = 0.0;
  for (const auto& [face, sums] : perFace) {
    if (sums.second <= 0.0) continue;
    const double ratio = sums.first / sums.second;
    std::printf("face %u: CPU / Monte Carlo interreflected light %.3f\n", face, ratio);
    worst = std::max(worst, std::abs(ratio - 1.0));
  }
  std::printf("worst face %.1f%%; element radiosity NRMSE %.4f\n", 100.0 * worst,
              bench::normalisedRmsError(surfaces, cpu.radiosity, mc.radiosity));
  // Measured: the worst face (a block face by the floor) 2.6% dark, the rest within 1.3%; the
  // unweighted visibility share gave 23% (face 14) and 10-16% on six more faces.
  EXPECT_LT(worst, 0.05);
}

// `luxel bench --reference monte-carlo`: the same case measured against both kinds of reference,
// cached apart. Against the Monte Carlo one the error also holds that reference's noise and the
// CPU's 2 x 2 receiver rule on these large elements: measured 0.052, against 0.017.
TEST(MonteCarloReference, BenchErrorColumnAgainstEitherReference) {
  const std::filesystem::path cache = std::filesystem::temp_directory_path() / "luxel-mc-refs";
  std::filesystem::remove_all(cache);
  bench::Case c;
  c.name = "cornell-200";
  c.scene = "cornell";
  c.discretise.elementBudget = 200;
  c.solve.settings.set("unshot", 1e-4);
  bench::Options o;
  o.runs = 1;
  o.hardwareLimit = false;
  o.cacheDir = cache.string();
  const bench::CaseResult cpu = bench::runCase(c, o);
  o.referenceKind = bench::Options::ReferenceKind::MonteCarlo;
  const bench::CaseResult mc = bench::runCase(c, o);
  ASSERT_TRUE(cpu.error && mc.error);
  std::printf("error against the CPU reference %.4f, against Monte Carlo %.4f\n", *cpu.error, *mc.error);
  EXPECT_LT(*cpu.error, 0.02);
  EXPECT_GT(*mc.error, 0.0);
  EXPECT_LT(*mc.error, 0.06);
  size_t files = 0, monteCarloFiles = 0;
  for (const auto& f : std::filesystem::directory_iterator(cache)) {
    ++files;
    monteCarloFiles += f.path().filename().string().find("-mc-") != std::string::npos ? 1 : 0;
  }
  EXPECT_EQ(files, 2u);
  EXPECT_EQ(monteCarloFiles, 1u);
  std::filesystem::remove_all(cache);
}

TEST(MonteCarloReference, RejectsTwoSidedFacesAndNoRays) {
  Scene scene = builtin::cornellBox();
  scene.materials[0].twoSided = true;
  SurfaceSet surfaces = discretise(scene, DiscretiseOptions{.elementBudget = 200});
  EXPECT_THROW(MonteCarloTransport(scene, surfaces, 16), Error);
  Scene plain = builtin::cornellBox();
  SurfaceSet plainSurfaces = discretise(plain, DiscretiseOptions{.elementBudget = 200});
  EXPECT_THROW(MonteCarloTransport(plain, plainSurfaces, 0), Error);
}

}  // namespace
}  // namespace luxel
