#include "bench/reference.h"

#include <chrono>
#include <filesystem>

#include <fmt/format.h>

#include "core/content_hash.h"
#include "luxel/error.h"
#include "session/solver_host.h"
#include "transport/form_factor_options.h"
#include "transport/monte_carlo_transport.h"

namespace luxel::bench {
namespace {

constexpr char kMagic[8] = {'L', 'X', 'R', 'E', 'F', '0', '0', '1'};

// Everything the reference solution depends on: the elements (geometry, patch, reflectance,
// emission), the analytic lights and the solver settings.
uint64_t referenceKey(const Scene& scene, const SurfaceSet& surfaces, const SolveOptions& o, Options::ReferenceKind kind) {
  ContentHash h;
  // Bump when the transport's numbers change (quadrature, sampling, visibility weighting), and
  // when the hierarchical solver does: its self-convergence references are its own solutions.
  h.text("luxel-reference-6");
  h.bytes(o.method.data(), o.method.size());
  for (const auto& [name, value] : o.settings.values()) h.bytes(name.data(), name.size()), h.bytes(value.data(), value.size());
  if (kind == Options::ReferenceKind::MonteCarlo) h.bytes("monte-carlo", 11), h.value(kMonteCarloReferenceRays);
  for (const Element& e : surfaces.elements) h.value(e.patch);
  hashLightingProblem(h, scene, surfaces);
  const SolverOptionValues values("reference", SolverRegistry::builtin().get(o.method, o.backend).description.options,
                                  o.settings);
  const FormFactorOptions f = formFactorOptions(values);
  h.value(f.raysPerPair), h.value(f.nearRaysPerPair), h.value(f.emitterRaysPerPair), h.value(f.nearFactor);
  h.value(f.classifyVisibility), h.value(f.lightSamples), h.value(f.seed);
  return h.digest();
}

}  // namespace

void hashLightingProblem(ContentHash& h, const Scene& scene, const SurfaceSet& surfaces) {
  for (const Element& e : surfaces.elements) {
    h.value(e.polygon.count);
    h.bytes(e.polygon.v.data(), sizeof(Vec3) * 4);
    h.value(e.reflectance), h.value(e.exitance);
  }
  for (const Light& l : scene.lights) {
    h.value(l.type), h.value(l.color), h.value(l.intensity), h.value(l.position), h.value(l.direction);
    h.value(l.innerConeAngle), h.value(l.outerConeAngle), h.value(l.angularRadius);
  }
  h.value(scene.up);
}

SolveOptions referenceSolveOptions() {
  SolveOptions o;
  o.method = "gather";
  o.settings.set("residual", 1e-6).set("max-iterations", 100000);
  o.settings.set("rays-per-pair", 64).set("near-rays-per-pair", 64).set("emitter-rays-per-pair", 256);
  o.settings.set("classify-visibility", false).set("light-samples", 256);
  o.settings.set("seed", 7);  // independent of the default seed the benchmarked runs use
  return o;
}

Reference loadOrComputeReference(const Scene& scene, const SurfaceSet& surfaces, const std::string& cacheDir,
                                 const ProgressCallback& progress, Options::ReferenceKind kind,
                                 const std::optional<SolveOptions>& solver) {
  const SolveOptions options = solver ? *solver : referenceSolveOptions();
  const bool monteCarlo = !solver && kind == Options::ReferenceKind::MonteCarlo;
  const uint64_t key = referenceKey(scene, surfaces, options, kind);
  std::filesystem::path dir(cacheDir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("{}: cannot create the reference cache: {}", cacheDir, ec.message()));
  Reference ref;
  ref.path = (dir / fmt::format("{}-{}{:016x}.ref", scene.name, monteCarlo ? "mc-" : "", key)).string();
  if (readCacheFile(ref.path, kMagic, key, surfaces.elements.size(), ref.radiosity)) return ref;

  const auto start = std::chrono::steady_clock::now();
  SurfaceSet copy = surfaces;  // solve() may refine in place; references never do, but stay safe
  Solution sol;
  if (monteCarlo) {
    const SolverOptionValues values("reference", SolverRegistry::builtin().get("gather", "cpu").description.options,
                                    options.settings);
    MonteCarloTransport transport(scene, copy, kMonteCarloReferenceRays, formFactorOptions(values));
    SolverHost host(scene, copy, options, {&transport, nullptr});
    while (host.step({}, progress)) {
    }
    sol = host.solution();
  } else {
    sol = solve(scene, copy, options, progress);
  }
  ref.radiosity = std::move(sol.radiosity);
  ref.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeCacheFile(ref.path, kMagic, key, ref.radiosity);
  return ref;
}

}  // namespace luxel::bench
