// Rendering a solution: ray-cast primary visibility against the elements, radiance
// L = Le + rho(x) / pi * H(x).
// - Radiosity mode: H interpolated smoothly from element corners (nodal averaging).
// - High-quality mode, a two-pass method (Wallace, Cohen and Greenberg, SIGGRAPH 1987; Chen et al.,
//   SIGGRAPH 1991): the direct part of H per pixel with shadow rays towards stratified points of
//   each light, and the indirect part from the solution, interpolated or gathered by rays that
//   read it one or two bounces away (render/final_gather.h; RenderOptions::Indirect).
// Normal maps (render/normal_map.h) tilt the receiver cosine of what is found per pixel (the
// direct light, and a per-pixel gather); radiosity mode ignores them.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/multi_jitter.h"
#include "core/random.h"
#include "luxel/error.h"
#include "luxel/render.h"
#include "render/camera_frame.h"
#include "render/corner_values.h"
#include "render/direct_light.h"
#include "render/final_gather.h"
#include "render/gather_mesh.h"
#include "render/gather_pipeline.h"
#include "render/gather_refinement.h"
#include "render/glossy_lobe.h"
#include "render/normal_map.h"
#include "trace/hemisphere_rays.h"
#include "trace/ray_tracer.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

constexpr float kInvPi = std::numbers::inv_pi_v<float>;
constexpr int kTile = 16;
constexpr int kMaxGatherRays = 65536;
constexpr uint64_t kMaxGatherRaysPerPixel = uint64_t(1) << 20;

// Salts of a pixel's sample patterns (core/multi_jitter.h), one per use.
enum PatternUse : uint32_t { kPixelFootprint = 1, kLightPoints = 2, kGatherDirections = 3, kGlossyDirections = 4 };

// Light points per camera sample in interior pixels (render(), lightsPerCamera).
constexpr int kLightsPerCameraSample = 4;

// Which pixels of the tile [x0, x1) x [y0, y1) are interior: a ray through each pixel corner, and
// a pixel whose four corners meet the front of one face, with no texture, has no edge or texture
// detail for extra camera samples to resolve (a feature smaller than a pixel between its corners
// can be missed). 1 for interior, per pixel at (y - y0) * kTile + (x - x0).
std::vector<uint8_t> interiorPixels(const RayTracer& tracer, const SurfaceSet& shown, const Scene& scene,
                                    const CameraFrame& cam, const RenderOptions& options, int x0, int y0, int x1,
                                    int y1) {
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  std::vector<RTCRayHit> corners(size_t(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      corners[size_t(y * w + x)].ray =
          makeRay(cam.eye, cam.direction(float(x0 + x) / float(options.width), float(y0 + y) / float(options.height)),
                  0.0f, std::numeric_limits<float>::infinity());
  tracer.intersect(corners);
  // The face each corner meets the front of, untextured; -1 otherwise.
  std::vector<int64_t> face(corners.size(), -1);
  for (size_t k = 0; k < corners.size(); ++k) {
    const RTCRayHit& rh = corners[k];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    const Element& el = shown.elements[rh.hit.primID];
    const Material& m = scene.materials[el.material];
    if (m.reflectanceTexture >= 0 || m.emissionTexture >= 0 || m.normalTexture >= 0) continue;
    if (glm::dot(el.normal, Vec3(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z)) >= 0.0f) continue;
    face[k] = el.face;
  }
  std::vector<uint8_t> interior(size_t(kTile * kTile), 0);
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x + 1 < w; ++x) {
      const int64_t f = face[size_t(y * w + x)];
      interior[size_t(y * kTile + x)] = f >= 0 && face[size_t(y * w + x + 1)] == f &&
                                        face[size_t((y + 1) * w + x)] == f && face[size_t((y + 1) * w + x + 1)] == f;
    }
  return interior;
}

// How many of the image's pixels see each element, from a ray through the centre of every pixel
// (every k-th pixel each way when there are more than kVisibilityRays, each then counting k^2):
// the vertex gather's rays go by it (VertexGather's element weights), so that a surface near the
// eye, few vertices over many pixels, gets the rays its share of the image needs.
constexpr size_t kVisibilityRays = size_t(1) << 18;
std::vector<float> pixelsSeen(const RayTracer& tracer, const SurfaceSet& shown, const CameraFrame& cam,
                              const RenderOptions& options) {
  const size_t pixels = size_t(options.width) * size_t(options.height);
  const int stride = int(std::ceil(std::sqrt(double(pixels) / double(kVisibilityRays))));
  const int w = (options.width + stride - 1) / stride, h = (options.height + stride - 1) / stride;
  std::vector<RTCRayHit> rays(size_t(w) * size_t(h));
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x)
      rays[size_t(y) * size_t(w) + size_t(x)].ray =
          makeRay(cam.eye,
                  cam.direction((float(x * stride) + 0.5f) / float(options.width),
                                (float(y * stride) + 0.5f) / float(options.height)),
                  0.0f, std::numeric_limits<float>::infinity());
  });
  tracer.intersect(rays);
  std::vector<float> seen(shown.elements.size(), 0.0f);
  for (const RTCRayHit& r : rays)
    if (r.hit.geomID != RTC_INVALID_GEOMETRY_ID) seen[r.hit.primID] += float(stride * stride);
  return seen;
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
  if (o.gatherBounces < 1 || o.gatherBounces > 4)
    throw Error(fmt::format("gather bounces {} must be between 1 and 4", o.gatherBounces));
  if (o.gatherRays < 0 || o.gatherRays > kMaxGatherRays)
    throw Error(fmt::format("gather rays {} must be between 0 and {}", o.gatherRays, kMaxGatherRays));
  if (o.indirect == RenderOptions::Indirect::PixelGather &&
      uint64_t(o.gatherRays) * uint64_t(o.samplesPerPixel) > kMaxGatherRaysPerPixel)
    throw Error(fmt::format("{} gather rays at {} samples per pixel is {} rays a pixel, over the limit of {}",
                            o.gatherRays, o.samplesPerPixel, uint64_t(o.gatherRays) * uint64_t(o.samplesPerPixel),
                            kMaxGatherRaysPerPixel));
  if (o.glossyRays < 0 || o.glossyRays > kMaxGatherRays)
    throw Error(fmt::format("glossy rays {} must be between 0 and {}", o.glossyRays, kMaxGatherRays));
  if (uint64_t(o.glossyRays) * uint64_t(o.samplesPerPixel) > kMaxGatherRaysPerPixel)
    throw Error(fmt::format("{} glossy rays at {} samples per pixel is {} rays a pixel, over the limit of {}",
                            o.glossyRays, o.samplesPerPixel, uint64_t(o.glossyRays) * uint64_t(o.samplesPerPixel),
                            kMaxGatherRaysPerPixel));
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

RenderOptions::Indirect parseIndirect(const std::string& name) {
  if (name == "auto") return RenderOptions::Indirect::Auto;
  if (name == "interpolated") return RenderOptions::Indirect::Interpolated;
  if (name == "vertex-gather") return RenderOptions::Indirect::VertexGather;
  if (name == "pixel-gather") return RenderOptions::Indirect::PixelGather;
  if (name == "none") return RenderOptions::Indirect::None;
  throw Error(fmt::format("unknown indirect light '{}' (expected auto, interpolated, vertex-gather, pixel-gather or none)",
                          name));
}

const char* indirectName(RenderOptions::Indirect indirect) {
  switch (indirect) {
    case RenderOptions::Indirect::Auto: return "auto";
    case RenderOptions::Indirect::Interpolated: return "interpolated";
    case RenderOptions::Indirect::VertexGather: return "vertex-gather";
    case RenderOptions::Indirect::PixelGather: return "pixel-gather";
    case RenderOptions::Indirect::None: return "none";
  }
  return "?";
}

RenderOptions::Indirect resolvedIndirect(const RenderOptions& options, const SurfaceSet& surfaces) {
  if (options.indirect != RenderOptions::Indirect::Auto) return options.indirect;
  return surfaces.elements.size() <= kMaxAutoGatherElements ? RenderOptions::Indirect::VertexGather
                                                            : RenderOptions::Indirect::Interpolated;
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
  using Indirect = RenderOptions::Indirect;
  const Indirect indirect = hq ? resolvedIndirect(options, surfaces) : Indirect::Interpolated;
  const bool pixelGather = indirect == Indirect::PixelGather;
  const bool vertexGather = indirect == Indirect::VertexGather;

  // The elements the pixels find, the field at their corners, and what gather rays read.
  const GatherPipeline pipeline(scene, surfaces, solution, options, indirect, hq);
  const GatherMesh& mesh = pipeline.mesh();
  const SurfaceSet& shown = pipeline.shown();
  const std::vector<Rgb>& corners = pipeline.corners();
  const RayTracer& tracer = pipeline.tracer();
  const DirectLight& direct = pipeline.direct();
  const FinalGather& finalGather = pipeline.finalGather();
  const float rayOffset = rayOffsetFor(surfaces.sceneExtent);
  const Vec3 up = glm::normalize(scene.up);
  // What the pixels interpolate: the solution's (indirect) irradiance, or the one gathered at the
  // vertices of the elements the pixels see (an element a pixel centre misses, gathered when a
  // sample first needs it), refined into lattices where the corners cannot say the light's shape.
  // A vertex gather takes the skies as well (VertexGather's skiesOf), and the pixels trace the
  // other lights.
  // The skies: the background where no surface is, and light for the gather or the pixels.
  std::vector<const Light*> skies;
  for (const Light& l : scene.lights)
    if (isSkyLight(l)) skies.push_back(&l);
  std::optional<VertexGather> vertexGathered;
  std::optional<GatherRefinement> refinement;
  std::optional<DirectLight> skyless;
  if (vertexGather) {
    const std::vector<float> seen =
        pixelsSeen(tracer, shown, CameraFrame(options.camera, options.width, options.height), options);
    vertexGathered.emplace(shown, finalGather, options.gatherRays, options.seed, seen, &mesh,
                           skies.empty() ? nullptr : &scene);
    refinement.emplace(shown, *vertexGathered, seen, seen);
    if (!skies.empty()) skyless.emplace(scene, surfaces, &shown, /*skies=*/false);
  }
  const DirectLight& pixelDirect = skyless ? *skyless : direct;
  const int gatherRays = !pixelGather ? 0 : options.gatherRays > 0 ? options.gatherRays : kDefaultPixelGatherRays;

  Image image(options.width, options.height);
  image.coverage.assign(image.pixels.size(), 0.0f);
  const CameraFrame cam(options.camera, options.width, options.height);
  const int tilesX = (options.width + kTile - 1) / kTile, tilesY = (options.height + kTile - 1) / kTile;
  const int tileCount = tilesX * tilesY;
  const int spp = options.samplesPerPixel;
  const MultiJitter pixelPattern{uint32_t(spp)}, gatherPattern{uint32_t(spp) * uint32_t(gatherRays)};
  const bool anyGlossy = std::any_of(scene.materials.begin(), scene.materials.end(),
                                    [](const Material& m) { return m.hasSpecular(); });
  const int glossyRays = hq && anyGlossy ? options.glossyRays : 0;
  // Highlights follow the smooth surface, as the viewer's do: per corner of each glossy element,
  // the normal of the surface its corner group makes (a coarse sphere's highlight shows no facets).
  std::vector<Vec3> smoothNormals;
  if (glossyRays > 0) {
    const CornerGroups groups(shown, kDefaultCreaseCosine);
    smoothNormals.resize(shown.elements.size() * 4);
    tbb::parallel_for(uint32_t(0), uint32_t(shown.elements.size()), [&](uint32_t e) {
      const Element& el = shown.elements[e];
      if (!scene.materials[el.material].hasSpecular()) return;
      for (int c = 0; c < el.polygon.count; ++c)
        smoothNormals[size_t(e) * 4 + size_t(c)] = smoothCornerNormal(shown, groups, e, c);
    });
  }
  const MultiJitter glossyPattern{uint32_t(spp) * uint32_t(std::max(1, glossyRays))};
  // Interior pixels (smoothPixels) take spp / lightsPerCamera camera samples, each with
  // lightsPerCamera of the pixel's spp light points: the light points are what a penumbra needs,
  // and the camera samples only cost there. Not with a per-pixel gather (its rays go with the camera
  // samples), nor with lights whose shadows are hard (point, spot, sun): their edges cross a face
  // and want the camera samples.
  int lightsPerCamera = hq && !pixelGather && spp % kLightsPerCameraSample == 0 ? kLightsPerCameraSample : 1;
  for (const Light& l : scene.lights)
    if (l.type == Light::Type::Point || l.type == Light::Type::Spot || l.type == Light::Type::Directional)
      lightsPerCamera = 1;
  const MultiJitter interiorPattern{uint32_t(spp / lightsPerCamera)};
  const float perGatherRay = gatherRays > 0 ? 1.0f / float(gatherRays) : 0.0f;
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
    std::vector<Rgb> shadowThrough;  // what glass passes of each
    std::vector<Rgb> shadowValues;
    std::vector<Rgb*> shadowTargets;
    std::vector<RTCRayHit> gathers;
    std::vector<Rgb> gatherWeights;  // what a gather ray's radiance is multiplied by
    std::vector<Rgb*> gatherTargets;
    std::vector<RTCRayHit> glossy;  // rays drawn from glossy lobes
    std::vector<Rgb> glossyWeights;
    std::vector<Rgb*> glossyTargets;
    std::vector<uint16_t> active;  // the tile's pixels (y * kTile + x) that take sample s
    const std::vector<uint8_t> interior = lightsPerCamera > 1
                                              ? interiorPixels(tracer, shown, scene, cam, options, x0, y0, x1, y1)
                                              : std::vector<uint8_t>(size_t(kTile * kTile), 0);
    for (int s = 0; s < spp; ++s) {
      hits.clear();
      active.clear();
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const size_t t = size_t((y - y0) * kTile + (x - x0));
          if (interior[t] && s >= spp / lightsPerCamera) continue;
          const uint32_t pixel = uint32_t(y * options.width + x);
          const uint32_t footprint = hashCombine(hashCombine(options.seed, pixel), kPixelFootprint);
          const Vec2 j = interior[t] ? interiorPattern(uint32_t(s), footprint) : pixelPattern(uint32_t(s), footprint);
          Vec3 d = cam.direction((float(x) + j.x) / float(options.width), (float(y) + j.y) / float(options.height));
          RTCRayHit rh;
          rh.ray = makeRay(cam.eye, d, 0.0f, std::numeric_limits<float>::infinity());
          hits.push_back(rh);
          active.push_back(uint16_t(t));
        }
      tracer.intersect(hits);

      shadowRays.clear();
      shadowValues.clear();
      shadowTargets.clear();
      gathers.clear();
      gatherWeights.clear();
      gatherTargets.clear();
      glossy.clear();
      glossyWeights.clear();
      glossyTargets.clear();
      for (size_t i = 0; i < active.size(); ++i) {
        const size_t t = active[i];
        const int x = x0 + int(t % kTile), y = y0 + int(t / kTile);
        // An interior pixel's camera sample stands for `weight` of its spp samples.
        const int weight = interior[t] ? lightsPerCamera : 1;
        Rgb& sum = sums[t];
        const RTCRayHit& rh = hits[i];
        Vec3 dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
          for (const Light* sky : skies) sum += float(weight) * skyRadiance(*sky, dir, up);
          continue;
        }
        hitSamples[t] += weight;
        const uint32_t e = rh.hit.primID;
        const Element& el = shown.elements[e];
        const SurfaceFace& face = shown.faces[el.face];
        const Material& m = scene.materials[el.material];
        const float u = rh.hit.u, v = rh.hit.v;
        const int count = el.polygon.count;
        const bool front = glm::dot(el.normal, dir) < 0.0f;
        if (!front) continue;  // the back of a one-sided surface takes no part in transport

        Vec2 uv = face.uv(interpolateCorners(el.param.data(), count, u, v));
        Rgb rho = m.reflectance;
        if (m.reflectanceTexture >= 0) rho *= scene.textures[size_t(m.reflectanceTexture)].sample(uv);
        Rgb le = m.emission;
        if (m.emissionTexture >= 0 && m.isEmissive()) le *= scene.textures[size_t(m.emissionTexture)].sample(uv);
        sum += float(weight) * le;
        if (indirect == Indirect::Interpolated || vertexGather) {
          const Rgb irradiance = refinement ? refinement->irradianceAt(e, u, v)
                                            : interpolateCorners(&corners[size_t(e) * 4], count, u, v);
          sum += float(weight) * rho * (kInvPi * irradiance);
        }
        if (!hq) continue;

        const uint32_t pixel = uint32_t(y * options.width + x);
        const uint32_t pattern = hashCombine(options.seed, pixel);
        const Vec3 p = cam.eye + dir * rh.ray.tfar;
        const Vec3 shading = m.normalTexture >= 0 ? shadingNormal(scene, face.mesh, face.meshFace, uv, el.normal)
                                                  : el.normal;
        Rng rng(hashCombine(hashCombine(options.seed ^ 0x5bd1e995u, pixel), uint32_t(s)));
        const size_t before = shadowRays.size();
        std::array<Vec2, kLightsPerCameraSample> lightPoints;
        for (int l = 0; l < weight; ++l)
          lightPoints[size_t(l)] = pixelPattern(uint32_t(s * weight + l), hashCombine(pattern, kLightPoints));
        sum += rho * kInvPi *
               pixelDirect.sample(p, el.normal, shading, Sides::Front, std::span(lightPoints.data(), size_t(weight)), rng,
                             rayOffset, shadowRays, shadowValues, e);
        for (size_t k = before; k < shadowRays.size(); ++k) {
          shadowValues[k] *= rho * kInvPi;
          shadowTargets.push_back(&sum);
        }

        // A glossy material's highlight (render/glossy_lobe.h): lamps, spots and suns by a shadow
        // ray each towards a point of them; everything else (emitting surfaces, skies, the light
        // surfaces reflect) by rays drawn from the lobe, which read it where they land.
        if (glossyRays > 0 && m.hasSpecular()) {
          const Vec3 smooth = m.normalTexture >= 0
                                  ? shading
                                  : glm::normalize(interpolateCorners(&smoothNormals[size_t(e) * 4], count, u, v));
          const GlossyLobe lobe(smooth, -glm::normalize(dir), m.shininess);
          const Vec3 from = p + el.normal * rayOffset;
          for (const Light& light : scene.lights) {
            if (isSkyLight(light)) continue;
            const LightSample ls = sampleLight(light, from, el.normal, Sides::Front, up, rng.next(), rng.next());
            const float f = ls.valid() ? lobe.value(glm::normalize(ls.direction)) : 0.0f;  // a ray's, not unit
            if (!(f > 0.0f)) continue;
            shadowRays.push_back(makeRay(from, ls.direction, 0.0f, ls.tfar));
            shadowValues.push_back((float(weight) * f) * m.specular * ls.irradiance);
            shadowTargets.push_back(&sum);
          }
          for (int r = 0; r < glossyRays; ++r) {
            const Vec2 g = glossyPattern(uint32_t(s) * uint32_t(glossyRays) + uint32_t(r),
                                         hashCombine(pattern, kGlossyDirections));
            const GlossyLobe::Sample ls = lobe.sample(g.x, g.y);
            // Rays leave the geometric surface, whatever a normal map tilts.
            if (ls.weight <= 0.0f || glm::dot(el.normal, ls.toLight) <= 0.0f) continue;
            glossy.emplace_back().ray = makeRay(from, ls.toLight, 0.0f, std::numeric_limits<float>::infinity());
            glossyWeights.push_back(m.specular * (float(weight) * ls.weight / float(glossyRays)));
            glossyTargets.push_back(&sum);
          }
        }

        // Cosine-distributed about the geometric normal, so the estimate of rho / pi * H is
        // rho * L; a normal map's cosine enters as the ratio max(0, shading . d) / (n . d).
        // (FinalGather::add multiplies by rho / pi at the hit; the weights carry the rest.)
        const HemisphereFrame frame(el.normal);
        const Vec3 origin = p + el.normal * rayOffset;
        for (int r = 0; r < gatherRays; ++r) {
          const Vec2 g = gatherPattern(uint32_t(s) * uint32_t(gatherRays) + uint32_t(r),
                                       hashCombine(pattern, kGatherDirections));
          const Vec3 d = frame.cosine(g.x, g.y);
          float w = perGatherRay;
          if (shading != el.normal) {
            const float cn = glm::dot(el.normal, d);
            w *= cn > 1e-6f ? std::max(0.0f, glm::dot(shading, d)) / cn : 0.0f;
          }
          if (w <= 0.0f) continue;
          gathers.emplace_back().ray = makeRay(origin, d, 0.0f, std::numeric_limits<float>::infinity());
          gatherWeights.push_back(rho * w);
          gatherTargets.push_back(&sum);
        }
      }
      tracer.transmitted(shadowRays, shadowThrough);
      for (size_t k = 0; k < shadowRays.size(); ++k)
        if (!isOccluded(shadowRays[k])) *shadowTargets[k] += shadowValues[k] * shadowThrough[k];
      if (!gathers.empty())
        finalGather.add(gathers, gatherWeights, gatherTargets, hashCombine(uint32_t(tile) * 0x9E3779B9u, uint32_t(s)));
      if (!glossy.empty()) {
        // The light surfaces reflect where the rays land, read from the solution (none with
        // --indirect none): through a lobe it is blurred, and reading the coarse gathers instead
        // would gather their vertices wherever rays land (2 s more at 1.5M faces). Then what a
        // gather leaves to the pixel's own direct light: emission met, and the skies past the scene.
        if (indirect == Indirect::None) tracer.intersect(glossy, false);
        else
          pipeline.solutionGather().add(glossy, glossyWeights, glossyTargets,
                                        hashCombine(uint32_t(tile) * 0x85EBCA6Bu, uint32_t(s)));
        for (size_t k = 0; k < glossy.size(); ++k) {
          const RTCRayHit& rh = glossy[k];
          const Vec3 d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
          if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            for (const Light* sky : skies) *glossyTargets[k] += glossyWeights[k] * skyRadiance(*sky, d, up);
            continue;
          }
          const Element& hit = shown.elements[rh.hit.primID];
          if (glm::dot(hit.normal, d) < 0.0f) *glossyTargets[k] += glossyWeights[k] * (kInvPi * hit.exitance);
        }
      }
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
    stats->indirect = indirect;
    stats->gatherElements = vertexGather ? shown.elements.size() : 0;
  }
  return image;
}

}  // namespace luxel
