// Rendering from baked lightmaps, as a real-time engine shows them: ray-cast primary visibility
// against the scene's own faces, radiance L = Le + rho(x) / pi * H(x) with the irradiance H
// sampled bilinearly from the lightmap page at the hit's lightmap coordinate (three.js's
// lightMap convention). It shows the bake itself, texel grid, dilation and seams included. A
// directional bake on a normal-mapped material reads H at the normal map's normal
// (luxel/directional_lightmap.h), as an engine's shader would.
#include <atomic>
#include <chrono>
#include <numbers>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/random.h"
#include "luxel/bake.h"
#include "luxel/directional_lightmap.h"
#include "luxel/error.h"
#include "luxel/lightmap.h"
#include "render/camera_frame.h"
#include "render/normal_map.h"
#include "trace/ray_tracer.h"
#include "transport/light_sampling.h"

namespace luxel {
namespace {

constexpr float kInvPi = std::numbers::inv_pi_v<float>;

struct FaceRef {
  uint32_t mesh, face;
};

// Bilinear lookup at (x, y) in texel units (texel centres at half-integers), clamped to the page.
Rgb samplePage(const std::vector<Rgb>& page, int size, Vec2 t) {
  const float fx = std::clamp(t.x - 0.5f, 0.0f, float(size - 1)), fy = std::clamp(t.y - 0.5f, 0.0f, float(size - 1));
  const int x0 = int(fx), y0 = int(fy), x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
  const float ax = fx - float(x0), ay = fy - float(y0);
  auto at = [&](int x, int y) { return page[size_t(y) * size_t(size) + size_t(x)]; };
  return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) + ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1));
}

}  // namespace

Image renderLightmapped(const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                        const RenderOptions& options, const ProgressCallback& progress, RenderStats* stats) {
  validateRenderOptions(options);
  if (atlas.faces.size() != scene.meshes.size() || bake.pageSize != atlas.pageSize)
    throw Error("lightmapped render: the atlas or the bake does not belong to this scene");
  const auto start = std::chrono::steady_clock::now();

  std::vector<Polygon> polygons;
  std::vector<FaceRef> refs;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
      Polygon p;
      p.count = mesh.faces[f].vertexCount();
      for (int k = 0; k < 4; ++k) p.v[size_t(k)] = mesh.positions[mesh.faces[f].v[size_t(k)]];
      polygons.push_back(p);
      refs.push_back({m, f});
    }
  }
  RayTracer tracer(polygons);
  // The bake turned round the faces whose back got the light (walls wound out of the room) and
  // baked that side: it is the one to show, and the other is the culled back.
  const std::vector<std::vector<uint8_t>> turned = flippedFaceFlags(scene, bake.surfaces.surfaces);
  const Vec3 up = glm::normalize(scene.up);
  std::vector<const Light*> skies;
  for (const Light& l : scene.lights)
    if (l.type == Light::Type::Sky || l.type == Light::Type::CieOvercastSky) skies.push_back(&l);

  const int shCount = directionalCoefficients(bake.directional);
  const bool directional = shCount > 0 && bake.sh.size() == size_t(shCount);
  Image image(options.width, options.height);
  image.coverage.assign(image.pixels.size(), 0.0f);
  const CameraFrame cam(options.camera, options.width, options.height);
  const int spp = options.samplesPerPixel;
  std::atomic<int> rowsDone{0};
  std::atomic<bool> cancelled{false};
  tbb::parallel_for(0, options.height, [&](int y) {
    if (cancelled.load(std::memory_order_relaxed)) return;
    std::vector<RTCRayHit> hits(size_t(options.width) * size_t(spp));
    for (int x = 0; x < options.width; ++x)
      for (int s = 0; s < spp; ++s) {
        Rng rng(hashCombine(hashCombine(options.seed, uint32_t(y * options.width + x)), uint32_t(s)));
        const float sx = (float(x) + rng.next()) / float(options.width), sy = (float(y) + rng.next()) / float(options.height);
        hits[size_t(x) * spp + size_t(s)].ray = makeRay(cam.eye, cam.direction(sx, sy), 0.0f, std::numeric_limits<float>::infinity());
      }
    tracer.intersect(hits);
    for (int x = 0; x < options.width; ++x) {
      Rgb sum(0.0f);
      int hitSamples = 0;
      for (int s = 0; s < spp; ++s) {
        const RTCRayHit& rh = hits[size_t(x) * spp + size_t(s)];
        const Vec3 dir(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
          for (const Light* sky : skies) sum += skyRadiance(*sky, dir, up);
          continue;
        }
        ++hitSamples;
        const FaceRef ref = refs[rh.hit.primID];
        const Mesh& mesh = scene.meshes[ref.mesh];
        const Face& face = mesh.faces[ref.face];
        const Polygon& poly = polygons[rh.hit.primID];
        const Material& mat = scene.materials[mesh.material];
        const bool facesAway = glm::dot(poly.normal(), dir) >= 0.0f;
        if (!mat.twoSided && facesAway != bool(turned[ref.mesh][ref.face])) continue;  // a one-sided back is black
        // The bake rasterised quads as triangles (0,1,2) and (0,2,3), the ones the tracer hits.
        const auto [i1, i2, w] = hitTriangle(poly.count, rh.hit.u, rh.hit.v);
        const LightmapAtlas::FaceUv& fuv = atlas.faces[ref.mesh][ref.face];
        const Vec2 texel = w.x * fuv.texel[0] + w.y * fuv.texel[size_t(i1)] + w.z * fuv.texel[size_t(i2)];
        Rgb irradiance = samplePage(bake.pages[fuv.page], bake.pageSize, texel);
        Rgb rho = mat.reflectance, le = mat.emission;
        const Vec2 uv = mesh.uvs.empty() ? Vec2(0.0f)
                                         : w.x * mesh.uvs[face.v[0]] + w.y * mesh.uvs[face.v[size_t(i1)]] +
                                               w.z * mesh.uvs[face.v[size_t(i2)]];
        if (directional && mat.normalTexture >= 0 && !mesh.uvs.empty()) {
          // The baked side's normal, and the normal map's normal on it: the direction of the light
          // says how the irradiance changes between them.
          const Vec3 n0 = turned[ref.mesh][ref.face] ? -poly.normal() : poly.normal();
          const Vec3 n = shadingNormal(scene, ref.mesh, ref.face, uv, n0);
          Rgb c[kMaxDirectionalCoefficients];
          for (int k = 0; k < shCount; ++k) c[k] = samplePage(bake.sh[size_t(k)][fuv.page], bake.pageSize, texel);
          irradiance = directionalIrradiance(bake.directional, c, irradiance, n0, n);
        }
        if (!mesh.uvs.empty() && (mat.reflectanceTexture >= 0 || mat.emissionTexture >= 0)) {
          if (mat.reflectanceTexture >= 0) rho *= scene.textures[size_t(mat.reflectanceTexture)].sample(uv);
          if (mat.emissionTexture >= 0 && mat.isEmissive()) le *= scene.textures[size_t(mat.emissionTexture)].sample(uv);
        }
        sum += le + rho * kInvPi * irradiance;
      }
      image.at(x, y) = sum / float(spp);
      image.coverage[size_t(y) * size_t(options.width) + size_t(x)] = float(hitSamples) / float(spp);
    }
    const int done = ++rowsDone;
    if (progress && (done % 16 == 0 || done == options.height))
      if (!progress(ProgressEvent{"render", double(done) / options.height, {}})) cancelled = true;
  });
  if (cancelled) throw Cancelled();
  if (stats) {
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats->rays = tracer.raysTraced();
  }
  return image;
}

}  // namespace luxel
