// Rendering a solution: ray-cast primary visibility against the elements, radiance
// L = Le + rho(x) / pi * H(x) with H interpolated smoothly from element corners (nodal averaging),
// and, in high-quality mode, the direct part of H evaluated per pixel with shadow rays (the
// "final gather of direct light" of two-pass methods, e.g. Chen et al., SIGGRAPH 1991).
// Normal maps (render/normal_map.h) reach only that per-pixel direct light: its receiver cosine
// is taken at the perturbed normal. The indirect part stays the element irradiance, which carries
// no direction to tilt, and radiosity mode ignores normal maps altogether.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/random.h"
#include "luxel/error.h"
#include "luxel/render.h"
#include "render/camera_frame.h"
#include "render/direct_light.h"
#include "render/normal_map.h"
#include "trace/ray_tracer.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

constexpr float kInvPi = std::numbers::inv_pi_v<float>;
constexpr int kTile = 16;

template <typename T>
T interpolate(const T* c, int count, float u, float v) {
  if (count == 3) return (1.0f - u - v) * c[0] + u * c[1] + v * c[2];
  return (1.0f - u) * (1.0f - v) * c[0] + u * (1.0f - v) * c[1] + u * v * c[2] + (1.0f - u) * v * c[3];
}

}  // namespace

void validateRenderOptions(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide)
    throw Error(fmt::format("image size {}x{} must be between 1 and {} a side", o.width, o.height, kMaxImageSide));
  if (uint64_t(o.width) * uint64_t(o.height) > kMaxImagePixels)
    throw Error(fmt::format("image size {}x{} is {:.0f} megapixels, over the limit of {:.0f} ({:.1f} GiB of radiance "
                            "before any sampling)",
                            o.width, o.height, double(o.width) * o.height / 1e6, double(kMaxImagePixels) / 1e6,
                            double(o.width) * o.height * sizeof(Rgb) / double(1u << 30)));
  if (o.samplesPerPixel < 1 || o.samplesPerPixel > 65536)
    throw Error(fmt::format("samples per pixel {} must be between 1 and 65536", o.samplesPerPixel));
  const Camera& c = o.camera;
  if (!(c.fovY > 0.0f && c.fovY < 180.0f))
    throw Error(fmt::format("camera '{}': field of view {} must be in (0, 180) degrees", c.name, c.fovY));
  for (const Vec3& p : {c.eye, c.target, c.up})
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || std::abs(p.x) > kMaxCoordinate ||
        std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate)
      throw Error(fmt::format("camera '{}': eye ({:g}, {:g}, {:g}) and target ({:g}, {:g}, {:g}) must be finite and "
                              "within {:g} scene units of the origin",
                              c.name, c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, kMaxCoordinate));
  const Vec3 f = c.target - c.eye;
  if (!(glm::length(f) > 0.0f) || !(glm::length(glm::cross(f, c.up)) > 0.0f))
    throw Error(fmt::format("camera '{}': eye, target and up must span a frame", c.name));
}

RenderOptions::Mode parseRenderMode(const std::string& name) {
  if (name == "radiosity") return RenderOptions::Mode::Radiosity;
  if (name == "hq" || name == "high-quality") return RenderOptions::Mode::HighQuality;
  throw Error(fmt::format("unknown render mode '{}' (expected hq or radiosity)", name));
}

Image render(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution,
             const RenderOptions& options, const ProgressCallback& progress, RenderStats* stats) {
  validateRenderOptions(options);
  if (solution.irradiance.size() != surfaces.elements.size())
    throw Error(fmt::format("the solution has {} elements but the surfaces have {}",
                            solution.irradiance.size(), surfaces.elements.size()));
  const auto start = std::chrono::steady_clock::now();
  const bool hq = options.mode == RenderOptions::Mode::HighQuality;

  // The irradiance field to interpolate: all of it, or only the indirect part in HQ mode.
  std::vector<Rgb> field = solution.irradiance;
  if (hq)
    for (size_t e = 0; e < field.size(); ++e)
      field[e] = glm::max(field[e] - solution.directIrradiance[e], Rgb(0.0f));
  const std::vector<Rgb> corners = elementCornerValues(surfaces, field);

  // The two sides of a two-sided face are coplanar twins, and a ray would hit either at random.
  // Only the side facing the camera goes into the BVH (its twin is the same geometry, so shadow
  // rays still see everything); slots of the other side hold an empty polygon.
  std::vector<Polygon> polygons(surfaces.elements.size());
  for (size_t e = 0; e < polygons.size(); ++e) {
    const Element& el = surfaces.elements[e];
    const bool hasTwin = surfaces.faces[el.face].twin >= 0;
    if (!hasTwin || glm::dot(el.normal, options.camera.eye - el.centroid) > 0.0f)
      polygons[e] = el.polygon;
    else
      polygons[e] = Polygon{{el.centroid, el.centroid, el.centroid, el.centroid}, 3};
  }
  RayTracer tracer(polygons);
  DirectLight direct(scene, surfaces);
  const float rayOffset = rayOffsetFor(surfaces.sceneExtent);
  const Vec3 up = glm::normalize(scene.up);

  // Background: the sky where there is one.
  std::vector<const Light*> skies;
  for (const Light& l : scene.lights)
    if (l.type == Light::Type::Sky || l.type == Light::Type::CieOvercastSky) skies.push_back(&l);

  Image image(options.width, options.height);
  image.coverage.assign(image.pixels.size(), 0.0f);
  const CameraFrame cam(options.camera, options.width, options.height);
  const int tilesX = (options.width + kTile - 1) / kTile, tilesY = (options.height + kTile - 1) / kTile;
  const int tileCount = tilesX * tilesY;
  const int spp = options.samplesPerPixel;
  std::atomic<int> tilesDone{0};
  std::atomic<bool> cancelled{false};

  tbb::parallel_for(0, tileCount, [&](int tile) {
    if (cancelled.load(std::memory_order_relaxed)) return;
    const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
    const int x1 = std::min(x0 + kTile, options.width), y1 = std::min(y0 + kTile, options.height);
    std::vector<RTCRayHit> hits;
    std::vector<Rgb> sums(size_t(kTile * kTile), Rgb(0.0f));
    std::vector<int> hitSamples(size_t(kTile * kTile), 0);  // for Image::coverage
    std::vector<RTCRay> shadowRays;
    std::vector<Rgb> shadowValues;
    std::vector<Rgb*> shadowTargets;
    std::vector<Rgb> weights;  // rho(x) / pi per primary hit, for the direct light
    for (int s = 0; s < spp; ++s) {
      hits.clear();
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          Rng rng(hashCombine(hashCombine(options.seed, uint32_t(y * options.width + x)), uint32_t(s)));
          float sx = (float(x) + rng.next()) / float(options.width);
          float sy = (float(y) + rng.next()) / float(options.height);
          Vec3 d = cam.direction(sx, sy);
          RTCRayHit rh;
          rh.ray = makeRay(cam.eye, d, 0.0f, std::numeric_limits<float>::infinity());
          hits.push_back(rh);
        }
      tracer.intersect(hits);

      shadowRays.clear();
      shadowValues.clear();
      shadowTargets.clear();
      size_t i = 0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++i) {
          Rgb& sum = sums[size_t((y - y0) * kTile + (x - x0))];
          const RTCRayHit& rh = hits[i];
          Vec3 dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
          if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            for (const Light* sky : skies) sum += skyRadiance(*sky, dir, up);
            continue;
          }
          ++hitSamples[size_t((y - y0) * kTile + (x - x0))];
          const uint32_t e = rh.hit.primID;
          const Element& el = surfaces.elements[e];
          const SurfaceFace& face = surfaces.faces[el.face];
          const Material& m = scene.materials[el.material];
          const float u = rh.hit.u, v = rh.hit.v;
          const int count = el.polygon.count;
          const bool front = glm::dot(el.normal, dir) < 0.0f;
          if (!front) continue;  // the back of a one-sided surface takes no part in transport

          Vec2 uv = face.uv(interpolate(el.param.data(), count, u, v));
          Rgb rho = m.reflectance;
          if (m.reflectanceTexture >= 0) rho *= scene.textures[size_t(m.reflectanceTexture)].sample(uv);
          Rgb le = m.emission;
          if (m.emissionTexture >= 0 && m.isEmissive()) le *= scene.textures[size_t(m.emissionTexture)].sample(uv);
          sum += le;
          sum += rho * (kInvPi * interpolate(&corners[size_t(e) * 4], count, u, v));

          if (hq) {
            Vec3 p = cam.eye + dir * rh.ray.tfar;
            Rng rng(hashCombine(hashCombine(options.seed ^ 0x5bd1e995u, uint32_t(y * options.width + x)), uint32_t(s)));
            const size_t before = shadowRays.size();
            const Vec3 shading = m.normalTexture >= 0 ? shadingNormal(scene, face.mesh, face.meshFace, uv, el.normal)
                                                      : el.normal;
            direct.sample(p, el.normal, shading, Sides::Front, rng, rayOffset, shadowRays, shadowValues);
            for (size_t k = before; k < shadowRays.size(); ++k) {
              shadowValues[k] *= rho * kInvPi;
              shadowTargets.push_back(&sum);
            }
          }
        }
      tracer.occluded(shadowRays);
      for (size_t k = 0; k < shadowRays.size(); ++k)
        if (!isOccluded(shadowRays[k])) *shadowTargets[k] += shadowValues[k];
    }
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t t = size_t((y - y0) * kTile + (x - x0));
        image.at(x, y) = sums[t] / float(spp);
        image.coverage[size_t(y) * size_t(options.width) + size_t(x)] = float(hitSamples[t]) / float(spp);
      }

    int done = ++tilesDone;
    if (progress && (done % 16 == 0 || done == tileCount)) {
      if (!progress(ProgressEvent{"render", double(done) / tileCount, {}})) cancelled = true;
    }
  });
  if (cancelled) throw Cancelled();

  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->rays = tracer.raysTraced();
  }
  return image;
}

}  // namespace luxel
