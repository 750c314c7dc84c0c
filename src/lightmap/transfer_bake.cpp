// SH transfer lightmaps: see luxel/transfer_lightmap.h. Seed 004 section 4.5 (CaSHL) shoots
// transfer functions between patches as radiosity shoots light, and leaves the formula open
// (notes 4.11); here it is the radiosity system itself, T = T_direct + F rho T, with the CPU
// transport's form factors and one right-hand side per SH coefficient and channel.
#include "luxel/transfer_lightmap.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/spherical_harmonics.h"
#include "lightmap/bake_steps.h"
#include "luxel/error.h"
#include "trace/hemisphere_rays.h"
#include "trace/ray_tracer.h"
#include "transport/cpu_transport.h"
#include "transport/form_factor_options.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
constexpr float kPi = std::numbers::pi_v<float>;

int coefficientsOf(int bands) {
  if (bands < 2 || bands > 4) throw Error(fmt::format("SH transfer: {} bands (2, 3 or 4)", bands));
  return bands * bands;
}

std::array<float, kShBand3Coefficients> basis(Vec3 d) { return shBasis16(d); }

// T_direct per element: (pi / N) sum over N stratified cosine-weighted directions that escape of
// Y_i(w), the estimate of the integral of V cos Y_i over the hemisphere.
void directTransfer(const SurfaceSet& set, RayTracer& tracer, int rays, int count, std::vector<Rgb>& out) {
  const int side = strataSide(rays);
  const float offset = rayOffsetFor(set.sceneExtent);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, set.elements.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RTCRay> batch(size_t(side * side));
    std::vector<Vec3> dirs(batch.size());
    for (size_t ei = r.begin(); ei < r.end(); ++ei) {
      const Element& e = set.elements[ei];
      const Vec3 n = e.normal;
      HemisphereStrata(n, side, ei, 977u).directions(HemisphereStrata::Warp::Cosine, dirs);
      for (size_t k = 0; k < batch.size(); ++k)
        batch[k] = makeRay(e.centroid + offset * n, dirs[k], 0.0f, std::numeric_limits<float>::infinity());
      tracer.occluded(batch);
      Rgb* t = out.data() + ei * size_t(count);
      const float w = kPi / float(batch.size());
      for (size_t k = 0; k < batch.size(); ++k) {
        if (isOccluded(batch[k])) continue;
        const auto y = basis(dirs[k]);
        for (int i = 0; i < count; ++i) t[i] += Rgb(w * y[size_t(i)]);
      }
    }
  });
}

// Progressive shooting of transfer: every coefficient and channel is a separate "colour" of the
// same radiosity system with no emission and T_direct as the analytic irradiance.
struct TransferShooter {
  const SurfaceSet& set;
  Transport& transport;
  int count;
  std::vector<Rgb> transfer, unshot, patchUnshot;  // [element or patch][coefficient]
  std::vector<double> magnitude;                   // per patch: area-weighted sum of |unshot|
  std::vector<std::vector<float>> cache;
  size_t cachedBytes = 0;
  uint64_t shots = 0;

  double patchMagnitude(size_t p) const {
    double m = 0.0;
    for (int i = 0; i < count; ++i) {
      const Rgb& u = patchUnshot[p * size_t(count) + size_t(i)];
      m += double(std::abs(u.r)) + std::abs(u.g) + std::abs(u.b);
    }
    return m;
  }

  // Shoots until the unshot transfer is below `threshold` of the first, returns that fraction.
  double run(double threshold, const ProgressCallback& progress) {
    const size_t np = set.patches.size(), ne = set.elements.size();
    patchUnshot.assign(np * size_t(count), Rgb(0.0f));
    for (size_t e = 0; e < ne; ++e)
      for (int i = 0; i < count; ++i)
        patchUnshot[set.elements[e].patch * size_t(count) + size_t(i)] += set.elements[e].area * unshot[e * size_t(count) + size_t(i)];
    magnitude.resize(np);
    double first = 0.0;
    for (size_t p = 0; p < np; ++p) first += magnitude[p] = patchMagnitude(p);
    if (!(first > 0.0)) return 0.0;
    cache.assign(np, {});
    constexpr size_t kBatch = 8;
    double left = first;
    // Every shot takes its patch's unshot transfer out and sends back at most rho < 1 of it, so the
    // loop ends; the cap guards against rounding holding it just above the threshold.
    const uint64_t maxShots = 200 * uint64_t(np) + 1000;
    while (left > threshold * first && shots < maxShots) {
      std::vector<uint32_t> order(np);
      for (uint32_t p = 0; p < np; ++p) order[p] = p;
      const size_t batch = std::min(kBatch, np);
      std::partial_sort(order.begin(), order.begin() + long(batch), order.end(),
                        [&](uint32_t a, uint32_t b) { return magnitude[a] > magnitude[b]; });
      const float* columns[kBatch];
      std::vector<Rgb> shot(batch * size_t(count));
      std::vector<std::vector<float>> scratch(batch);
      size_t used = 0;
      for (size_t k = 0; k < batch; ++k) {
        const uint32_t p = order[k];
        if (magnitude[p] <= 0.0) break;
        std::vector<float>* column = &cache[p];
        if (column->empty()) {
          const bool keep = cachedBytes + ne * sizeof(float) <= (size_t(1) << 30);
          column = keep ? &cache[p] : &scratch[k];
          column->resize(ne);
          transport.columns({&p, 1}, *column);
          if (keep) cachedBytes += ne * sizeof(float);
        }
        columns[k] = column->data();
        const float area = std::max(set.patches[p].area, 1e-30f);
        for (int i = 0; i < count; ++i) shot[k * size_t(count) + size_t(i)] = patchUnshot[p * size_t(count) + size_t(i)] / area;
        for (uint32_t e : set.patches[p].elements)
          for (int i = 0; i < count; ++i) unshot[e * size_t(count) + size_t(i)] = Rgb(0.0f);
        for (int i = 0; i < count; ++i) patchUnshot[p * size_t(count) + size_t(i)] = Rgb(0.0f);
        magnitude[p] = 0.0;
        ++used;
      }
      if (used == 0) break;
      tbb::parallel_for(tbb::blocked_range<size_t>(0, np, 4), [&](const tbb::blocked_range<size_t>& r) {
        std::vector<Rgb> dt(static_cast<size_t>(count));
        for (size_t q = r.begin(); q < r.end(); ++q) {
          for (uint32_t e : set.patches[q].elements) {
            std::fill(dt.begin(), dt.end(), Rgb(0.0f));
            bool any = false;
            for (size_t k = 0; k < used; ++k) {
              const float f = columns[k][e];
              if (f == 0.0f) continue;
              any = true;
              for (int i = 0; i < count; ++i) dt[size_t(i)] += f * shot[k * size_t(count) + size_t(i)];
            }
            if (!any) continue;
            const Rgb rho = set.elements[e].reflectance;
            const float area = set.elements[e].area;
            for (int i = 0; i < count; ++i) {
              transfer[e * size_t(count) + size_t(i)] += dt[size_t(i)];
              const Rgb db = rho * dt[size_t(i)];
              unshot[e * size_t(count) + size_t(i)] += db;
              patchUnshot[q * size_t(count) + size_t(i)] += area * db;
            }
          }
          magnitude[q] = patchMagnitude(q);
        }
      });
      shots += used;
      left = 0.0;
      for (size_t p = 0; p < np; ++p) left += magnitude[p];
      reportProgress(progress, "transfer",
                     std::clamp(std::log(left / first) / std::log(threshold), 0.0, 1.0),
                     fmt::format("unshot {:.3f}%", 100.0 * left / first));
    }
    return left / first;
  }
};

}  // namespace

DistantLightSh distantLightSh(const Scene& scene, int bands) {
  DistantLightSh out;
  out.bands = bands;
  const int count = coefficientsOf(bands);
  out.coefficients.assign(size_t(count), Rgb(0.0f));
  const Vec3 up = glm::normalize(scene.up);
  bool anySky = false;
  for (const Light& l : scene.lights) {
    if (l.type == Light::Type::Directional) {
      const auto y = basis(-glm::normalize(l.direction));
      for (int i = 0; i < count; ++i) out.coefficients[size_t(i)] += y[size_t(i)] * l.power();
    } else if (l.type == Light::Type::Sky || l.type == Light::Type::CieOvercastSky) {
      anySky = true;
    } else {
      out.warnings.push_back(fmt::format("light '{}' is not distant: a transfer bake relights suns and skies only", l.name));
    }
  }
  for (const Mesh& mesh : scene.meshes)
    if (!mesh.faces.empty() && scene.materials[mesh.material].isEmissive()) {
      out.warnings.push_back(fmt::format("material '{}' emits: a transfer bake relights suns and skies only, not "
                                         "emitting surfaces", scene.materials[mesh.material].name));
      break;
    }
  if (anySky) {
    // A Fibonacci lattice of 20,000 directions, each 4 pi / N of solid angle.
    constexpr int n = 20000;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    std::vector<glm::dvec3> sum(size_t(count), glm::dvec3(0.0));
    for (int k = 0; k < n; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / n, r = std::sqrt(1.0 - z * z);
      const Vec3 d(float(r * std::cos(golden * k)), float(r * std::sin(golden * k)), float(z));
      Rgb radiance(0.0f);
      for (const Light& l : scene.lights)
        if (l.type == Light::Type::Sky || l.type == Light::Type::CieOvercastSky) radiance += skyRadiance(l, d, up);
      if (radiance == Rgb(0.0f)) continue;
      const auto y = basis(d);
      for (int i = 0; i < count; ++i) sum[size_t(i)] += glm::dvec3(radiance) * double(y[size_t(i)]);
    }
    const double w = 4.0 * std::numbers::pi / n;
    for (int i = 0; i < count; ++i) out.coefficients[size_t(i)] += Rgb(sum[size_t(i)] * w);
  }
  return out;
}

TransferBake bakeTransfer(const Scene& scene, const LightmapAtlas& atlas, const TransferBakeOptions& options,
                          const ProgressCallback& progress) {
  const int count = coefficientsOf(options.bands);
  if (options.directRays < 1 || options.directRays > 65536)
    throw Error(fmt::format("SH transfer: {} direct rays per texel (1 to 65536)", options.directRays));
  if (!(options.unshot > 0.0 && options.unshot < 1.0))
    throw Error(fmt::format("SH transfer: unshot threshold {} must be in (0, 1)", options.unshot));
  TransferBake out;
  out.bands = options.bands;
  out.texels = lightmap::prepareTexels(scene, atlas, options.texels);
  const SurfaceSet& set = out.texels.surfaces.surfaces;
  if (set.elements.empty()) throw Error(fmt::format("scene '{}' has no texels to bake transfer into", scene.name));
  const size_t ne = set.elements.size();

  // The transport's ray tracer (over the same faces) serves the visibility rays too.
  CpuTransport transport(scene, set, FormFactorOptions{});
  auto t0 = Clock::now();
  std::vector<Rgb> direct(ne * size_t(count), Rgb(0.0f));
  directTransfer(set, transport.tracer(), options.directRays, count, direct);
  out.secondsDirect = since(t0);

  t0 = Clock::now();
  TransferShooter shooter{set, transport, count, direct, {}, {}, {}, {}, 0, 0};
  shooter.unshot.resize(ne * size_t(count));
  for (size_t e = 0; e < ne; ++e)
    for (int i = 0; i < count; ++i)
      shooter.unshot[e * size_t(count) + size_t(i)] = set.elements[e].reflectance * direct[e * size_t(count) + size_t(i)];
  out.unshotFraction = shooter.run(options.unshot, progress);
  out.shots = shooter.shots;
  out.secondsShoot = since(t0);

  out.planes.resize(size_t(count));
  std::vector<std::vector<std::vector<Rgb>>*> planes;
  for (auto& p : out.planes) planes.push_back(&p);
  lightmap::finishPlanes(options.texels, out.texels, atlas.pageCount, planes,
                         [&](size_t k, size_t e) { return shooter.transfer[e * size_t(count) + k]; });
  return out;
}

BakedTransfer bakeTransfer(const Scene& scene, const LightmapRecipe& recipe, int bands, const ProgressCallback& progress) {
  const AtlasOptions ao = lightmapAtlasOptions(scene, recipe);
  coefficientsOf(bands);  // before the atlas, which can take a while
  BakedTransfer out{buildLightmapAtlas(scene, ao), {}};
  TransferBakeOptions to;
  to.bands = bands;
  to.texels.dilation = ao.gutter;
  out.transfer = bakeTransfer(scene, out.atlas, to, progress);
  return out;
}

std::vector<std::vector<Rgb>> relightTransfer(const TransferBake& transfer, const DistantLightSh& light) {
  if (light.bands != transfer.bands)
    throw Error(fmt::format("relighting a {}-band transfer with {}-band light", transfer.bands, light.bands));
  const size_t count = transfer.planes.size();
  const size_t n = size_t(transfer.texels.pageSize) * size_t(transfer.texels.pageSize);
  std::vector<std::vector<Rgb>> out(transfer.texels.state.size(), std::vector<Rgb>(n, Rgb(0.0f)));
  for (size_t p = 0; p < out.size(); ++p) {
    const auto& state = transfer.texels.state[p];
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) {
        if (state[i] == LightmapBake::Empty) continue;  // outside every chart and gutter
        Rgb h(0.0f);
        for (size_t k = 0; k < count; ++k) h += transfer.planes[k][p][i] * light.coefficients[k];
        out[p][i] = glm::max(h, Rgb(0.0f));  // band-limited light rings below zero in deep shadow
      }
    });
  }
  return out;
}

LightmapBake relitLightmaps(const TransferBake& transfer, const DistantLightSh& light) {
  LightmapBake bake = transfer.texels;
  bake.pages = relightTransfer(transfer, light);
  return bake;
}

}  // namespace luxel
