// The bench's independent judge (transport/path_traced_irradiance.h, bench/probe_reference.h)
// against closed forms: a furnace, where every point's irradiance is E / (1 - rho), and a lamp
// over a floor, the exact area-to-area form factor. Tolerances are the estimates' own measured
// standard errors: 4 of them, a 1-in-16,000 miss for a normal estimate.
#include <array>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "bench/probe_reference.h"
#include "error_message.h"
#include "scene/builtin/builtin_scenes.h"
#include "transport/form_factor.h"
#include "transport/path_traced_irradiance.h"

namespace luxel {
namespace {
using test::errorOf;

TEST(PathTracedIrradiance, TheFurnaceReceivesEOverOneMinusRho) {
  // Every wall emits Le = 1 (exitance pi) and reflects 0.5: H = B = pi / (1 - 0.5) everywhere.
  const Scene s = builtin::furnace(0.5f, 1.0f);
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 600});
  const std::vector<uint32_t> probes = {0, 17, uint32_t(set.elements.size() / 2), uint32_t(set.elements.size() - 1)};
  const PathTracingOptions options{.minPaths = 4096, .maxPaths = 1u << 16, .relativeError = 0.003};
  const auto estimates = pathTraceElementIrradiance(s, set, probes, options);
  const double expected = std::numbers::pi / 0.5;
  for (size_t i = 0; i < probes.size(); ++i) {
    const ElementIrradianceEstimate& e = estimates[i];
    SCOPED_TRACE(probes[i]);
    ASSERT_GT(e.standardError.g, 0.0f);
    EXPECT_LE(e.standardError.g, 0.01 * expected);  // the stop rule bounds it
    EXPECT_NEAR(e.mean.g, expected, 4.0 * e.standardError.g);
    // Grey light in a grey room: the channels follow the same paths.
    EXPECT_EQ(e.mean.r, e.mean.g);
  }
}

TEST(PathTracedIrradiance, ALampOverAFloorGivesTheExactFormFactor) {
  // A 1 x 1 lamp 1 m over a 4 x 4 floor, facing it; nothing else, and the lamp reflects nothing,
  // so a floor element receives the lamp's exitance times its form factor to the lamp, exactly.
  Scene s;
  s.name = "lamp over floor";
  s.materials = {Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(1.0f)},
                 Material{.name = "floor", .reflectance = Rgb(0.6f)}};
  Mesh lamp{.name = "lamp", .material = 0};
  builtin::addQuad(lamp, {-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f});  // normal -y
  Mesh floor{.name = "floor", .material = 1};
  builtin::addQuad(floor, {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2});  // normal +y
  s.meshes = {lamp, floor};
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 200});
  std::vector<uint32_t> probes;
  for (uint32_t e = 0; e < set.elements.size(); e += 23)
    if (set.elements[e].material == 1) probes.push_back(e);
  ASSERT_GE(probes.size(), 4u);
  const auto estimates =
      pathTraceElementIrradiance(s, set, probes, PathTracingOptions{.minPaths = 2048, .maxPaths = 1u << 15});
  Polygon lampPolygon;
  for (const Element& e : set.elements)
    if (e.material == 0) lampPolygon = Polygon{set.faces[e.face].corners, 4};
  for (size_t i = 0; i < probes.size(); ++i) {
    SCOPED_TRACE(probes[i]);
    const double expected =
        std::numbers::pi * polygonToPolygonFormFactor(set.elements[probes[i]].polygon, lampPolygon, 48);
    ASSERT_GT(expected, 0.01);
    // The lamp is unoccluded from every floor point, so each path's direct light is the exact
    // form factor of its own point: the only noise is where on the element the path starts.
    EXPECT_NEAR(estimates[i].mean.g, expected, 4.0 * estimates[i].standardError.g + 1e-4 * expected);
  }
}

TEST(PathTracedIrradiance, TheEstimateDoesNotDependOnTheThreadCount) {
  const Scene s = builtin::furnace(0.7f, 1.0f);
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 200});
  std::vector<uint32_t> probes;
  for (uint32_t e = 0; e < set.elements.size(); e += 3) probes.push_back(e);
  const PathTracingOptions options{.minPaths = 256, .maxPaths = 1024};
  std::vector<ElementIrradianceEstimate> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = pathTraceElementIrradiance(s, set, probes, options);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = pathTraceElementIrradiance(s, set, probes, options);
  }
  for (size_t i = 0; i < probes.size(); ++i) {
    EXPECT_EQ(one[i].mean.g, two[i].mean.g);
    EXPECT_EQ(one[i].paths, two[i].paths);
  }
}

TEST(PathTracedIrradiance, RefusesWhatItCannotEstimate) {
  Scene s = builtin::furnace(0.5f, 1.0f);
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 100});
  const std::vector<uint32_t> past = {uint32_t(set.elements.size())};
  EXPECT_NE(errorOf([&] { pathTraceElementIrradiance(s, set, past, {}); }).find("does not exist"), std::string::npos);
  const std::vector<uint32_t> first = {0};
  EXPECT_NE(errorOf([&] { pathTraceElementIrradiance(s, set, first, {.minPaths = 10, .maxPaths = 5}); })
                .find("make no estimate"),
            std::string::npos);
  s.materials[0].twoSided = true;
  const SurfaceSet twoSided = discretise(s, DiscretiseOptions{.elementBudget = 100});
  EXPECT_NE(errorOf([&] { pathTraceElementIrradiance(s, twoSided, first, {}); }).find("two-sided"), std::string::npos);
}

TEST(ProbeReference, ProbesAreDrawnByAreaAmongElementsThatDoNotEmit) {
  // The lamp's elements are never probes; the floor's are, in proportion to their area.
  Scene s = builtin::furnace(0.5f, 0.0f);
  s.materials.push_back(Material{.name = "lamp", .reflectance = Rgb(0.0f), .emission = Rgb(1.0f)});
  s.meshes[0].material = 0;
  Mesh lamp{.name = "lamp", .material = 1};
  builtin::addQuad(lamp, {0.4f, 0.99f, 0.4f}, {0.6f, 0.99f, 0.4f}, {0.6f, 0.99f, 0.6f}, {0.4f, 0.99f, 0.6f});
  s.meshes.push_back(lamp);
  const SurfaceSet set = discretise(s, DiscretiseOptions{.elementBudget = 2000});
  const std::vector<uint32_t> probes = bench::chooseProbeElements(set, 300);
  ASSERT_GT(probes.size(), 250u);
  EXPECT_EQ(probes, bench::chooseProbeElements(set, 300));  // fixed by the surfaces alone
  for (uint32_t p : probes) EXPECT_EQ(set.elements[p].material, 0u);
  // Six walls of equal area: each takes about a sixth of the probes (stratified, so closely).
  std::array<int, 6> perWall{};
  for (uint32_t p : probes) {
    const Vec3 n = set.elements[p].normal;
    const int axis = std::abs(n.x) > 0.5f ? 0 : std::abs(n.y) > 0.5f ? 1 : 2;
    ++perWall[size_t(axis * 2 + ((n.x + n.y + n.z) > 0.0f ? 1 : 0))];
  }
  for (int count : perWall) EXPECT_NEAR(count, double(probes.size()) / 6.0, 0.1 * double(probes.size()) / 6.0 + 2);
}

TEST(ProbeReference, TheErrorTakesTheProbesNoiseOut) {
  bench::ProbeReference probes;
  probes.elements = {0, 1, 2, 3};
  for (int i = 0; i < 4; ++i)
    probes.estimates.push_back({.mean = Rgb(float(1 + i)), .standardError = Rgb(0.0f), .paths = 100});
  std::vector<Rgb> exact = {Rgb(1.0f), Rgb(2.0f), Rgb(3.0f), Rgb(4.0f)};
  bench::ProbeError e = bench::probeError(probes, exact);
  EXPECT_EQ(e.probes, 4u);
  EXPECT_EQ(e.nrmse, 0.0);
  EXPECT_EQ(e.bias, 0.0);
  EXPECT_EQ(e.withinThreePercent, 1.0);
  std::vector<Rgb> high = exact;
  for (Rgb& h : high) h *= 1.1f;
  e = bench::probeError(probes, high);
  EXPECT_NEAR(e.nrmse, 0.1, 1e-6);
  EXPECT_NEAR(e.bias, 0.1, 1e-6);
  EXPECT_NEAR(e.worst, 0.1, 1e-6);
  EXPECT_EQ(e.withinThreePercent, 0.0);
  // A difference the probes' noise explains is not counted as error.
  for (auto& est : probes.estimates) est.standardError = Rgb(0.2f * est.mean.g);
  e = bench::probeError(probes, high);
  EXPECT_EQ(e.nrmse, 0.0);
  EXPECT_NEAR(e.noise, 0.2, 1e-6);
  EXPECT_EQ(e.withinThreePercent, 1.0);
  // Channels the solution cannot give (NaN: no reflectance to divide by) are left out.
  high[0].r = std::nanf("");
  EXPECT_NO_THROW(bench::probeError(probes, high));
}

}  // namespace
}  // namespace luxel
