// bakeLightmaps (lightmap.h): solve on texels, then discard texels that see the inside of
// geometry and fill them from their chart, stitch seams, dilate into the gutters; page images and
// the RGBM encoding.
#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <stb_image_write.h>
#include <tbb/parallel_for.h>

#include "core/spherical_harmonics.h"
#include "lightmap/bake_steps.h"
#include "lightmap/seam_edges.h"
#include "lightmap/texel_geometry.h"
#include "luxel/directional_lightmap.h"
#include "luxel/error.h"
#include "luxel/lightmap.h"
#include "session/solver_host.h"
#include "trace/hemisphere_rays.h"
#include "trace/ray_tracer.h"

namespace luxel {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

float channelTotal(Rgb c) { return c.r + c.g + c.b; }

// Per element: 1 when at most maxShare of its hemisphere rays hit the back of a single-sided face.
std::vector<uint8_t> validity(const Scene& scene, const SurfaceSet& set, int rays, float maxShare) {
  std::vector<Polygon> polys;
  polys.reserve(set.faces.size());
  for (const SurfaceFace& f : set.faces) polys.push_back(Polygon{f.corners, f.triangle ? 3 : 4});
  RayTracer tracer(polys);
  const int side = strataSide(rays);
  const float offset = rayOffsetFor(set.sceneExtent);
  std::vector<uint8_t> valid(set.elements.size(), 1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, set.elements.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RTCRayHit> hits(size_t(side * side));
    std::vector<Vec3> dirs(hits.size());
    for (size_t ei = r.begin(); ei < r.end(); ++ei) {
      const Element& e = set.elements[ei];
      const Vec3 n = e.normal;
      HemisphereStrata(n, side, ei, 12345u).directions(HemisphereStrata::Warp::Cosine, dirs);
      for (size_t k = 0; k < hits.size(); ++k)
        hits[k].ray = makeRay(e.centroid + offset * n, dirs[k], 0.0f, std::numeric_limits<float>::infinity());
      tracer.intersect(hits, false);
      int back = 0;
      for (size_t k = 0; k < hits.size(); ++k) {
        if (hits[k].hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const SurfaceFace& f = set.faces[hits[k].hit.primID];
        if (scene.materials[f.material].twoSided) continue;
        if (glm::dot(dirs[k], f.normal) > 0.0f) ++back;
      }
      valid[ei] = float(back) <= maxShare * float(hits.size()) ? 1 : 0;
    }
  });
  return valid;
}

}  // namespace

namespace lightmap {

LightmapBake prepareTexels(const Scene& scene, const LightmapAtlas& atlas, const LightmapBakeOptions& options) {
  if (options.validityRays < 0 || options.dilation < 0 || !(options.maxBackfaceShare >= 0.0f))
    throw Error("lightmap bake: validity rays, dilation and backface share must be >= 0");
  LightmapBake bake;
  bake.pageSize = atlas.pageSize;
  auto t0 = Clock::now();
  bake.surfaces = texelSurfaces(scene, atlas, options.texelsPerPatchSide);
  SurfaceSet& set = bake.surfaces.surfaces;
  bake.texels = set.elements.size();
  bake.secondsSurfaces = since(t0);

  t0 = Clock::now();
  bake.valid = options.validityRays > 0 ? validity(scene, set, options.validityRays, options.maxBackfaceShare)
                                        : std::vector<uint8_t>(set.elements.size(), 1);
  // Texels inside geometry take no part in their patch's mean: their light is not real.
  for (size_t e = 0; e < set.elements.size(); ++e)
    if (!bake.valid[e]) set.elements[e].area *= 1e-6f, ++bake.invalidTexels;
  bake.secondsValidity = since(t0);

  return bake;
}

void finishPlanes(const LightmapBakeOptions& options, LightmapBake& bake, int pageCount,
                  const std::vector<std::vector<std::vector<Rgb>>*>& planes,
                  const std::function<Rgb(size_t plane, size_t element)>& value) {
  const auto t0 = Clock::now();
  const auto pages = size_t(pageCount);
  const int size = bake.pageSize;
  const SurfaceSet& set = bake.surfaces.surfaces;
  const size_t n = size_t(size) * size_t(size);
  bake.state.assign(pages, std::vector<uint8_t>(n, LightmapBake::Empty));
  std::vector<std::vector<int32_t>> chartOf(pages, std::vector<int32_t>(n, -1));
  std::vector<std::vector<int32_t>> elementOf(pages, std::vector<int32_t>(n, -1));
  const auto& texels = bake.surfaces.texels;
  for (auto* plane : planes) plane->assign(pages, std::vector<Rgb>(n, Rgb(0.0f)));
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const auto& t = texels[e];
    const size_t i = size_t(t.y) * size_t(size) + t.x;
    for (size_t k = 0; k < planes.size(); ++k) (*planes[k])[t.page][i] = value(k, e);
    bake.state[t.page][i] = bake.valid[e] ? LightmapBake::Solved : LightmapBake::Filled;
    chartOf[t.page][i] = int32_t(bake.surfaces.faceChart[set.elements[e].face]);
    elementOf[t.page][i] = int32_t(e);
  }

  // Invalid texels: the mean of their valid (or already filled) 8-neighbours in the same chart,
  // wave by wave outwards from the valid ones.
  {
    std::vector<std::vector<uint8_t>> known(pages);
    for (size_t p = 0; p < pages; ++p) {
      known[p].resize(n);
      for (size_t i = 0; i < n; ++i) known[p][i] = bake.state[p][i] == LightmapBake::Solved;
    }
    size_t left = bake.invalidTexels;
    while (left > 0) {
      std::vector<std::pair<size_t, size_t>> wave;
      std::vector<Rgb> values;  // planes.size() per texel of the wave
      std::vector<Rgb> sum(planes.size());
      for (size_t e = 0; e < set.elements.size(); ++e) {
        const auto& t = texels[e];
        const size_t i = size_t(t.y) * size_t(size) + t.x;
        if (known[t.page][i]) continue;
        std::fill(sum.begin(), sum.end(), Rgb(0.0f));
        int count = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = int(t.x) + dx, y = int(t.y) + dy;
            if ((dx == 0 && dy == 0) || x < 0 || y < 0 || x >= size || y >= size) continue;
            const size_t j = size_t(y) * size_t(size) + size_t(x);
            if (!known[t.page][j] || chartOf[t.page][j] != chartOf[t.page][i]) continue;
            for (size_t k = 0; k < planes.size(); ++k) sum[k] += (*planes[k])[t.page][j];
            ++count;
          }
        if (count == 0) continue;
        wave.emplace_back(t.page, i);
        for (const Rgb& v : sum) values.push_back(v / float(count));
      }
      if (wave.empty()) break;
      for (size_t w = 0; w < wave.size(); ++w) {
        for (size_t k = 0; k < planes.size(); ++k) (*planes[k])[wave[w].first][wave[w].second] = values[w * planes.size() + k];
        known[wave[w].first][wave[w].second] = 1;
      }
      left -= wave.size();
    }
    bake.unfilledTexels = left;
  }

  // Seams: edges shared in 3D by faces of different charts on one smooth surface.
  if (options.stitchSeams) {
    const auto seamStart = Clock::now();
    const auto& faces = set.faces;
    std::vector<lightmap::FaceMap> maps;
    maps.reserve(faces.size());
    for (size_t f = 0; f < faces.size(); ++f) maps.emplace_back(faces[f], bake.surfaces.faceTexels[f]);
    const float cosLimit = std::cos(options.seamAngle * std::numbers::pi_v<float> / 180.0f);
    const float eps = 1e-5f * set.sceneExtent;
    std::vector<lightmap::SeamEdge> edges;
    for (uint32_t f = 0; f < faces.size(); ++f) {
      const int c = faces[f].triangle ? 3 : 4;
      for (int k = 0; k < c; ++k) edges.push_back({f, faces[f].corners[size_t(k)], faces[f].corners[size_t((k + 1) % c)]});
    }
    // The texel of face f's chart nearest to the point at texel coordinates q (nudged inside).
    auto texelFor = [&](uint32_t f, Vec3 p, size_t* out) {
      const lightmap::FaceMap& m = maps[f];
      glm::dvec2 q = m.clampInside(m.texelOf(p));
      glm::dvec2 mid(0.0);
      for (auto& v : m.clip) mid += v;
      q += 1e-3 * (mid / double(m.clip.size()) - q);
      const uint32_t page = bake.surfaces.facePage[f];
      const int chart = int(bake.surfaces.faceChart[f]);
      int bx = -1, by = -1;
      double bd = 1e300;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = int(std::floor(q.x)) + dx, y = int(std::floor(q.y)) + dy;
          if (x < 0 || y < 0 || x >= size || y >= size) continue;
          if (chartOf[page][size_t(y) * size_t(size) + size_t(x)] != chart) continue;
          const double d = (x + 0.5 - q.x) * (x + 0.5 - q.x) + (y + 0.5 - q.y) * (y + 0.5 - q.y);
          if (d < bd) bd = d, bx = x, by = y;
        }
      if (bx < 0) return false;
      *out = page * n + size_t(by) * size_t(size) + size_t(bx);
      return true;
    };
    std::vector<std::pair<size_t, size_t>> pairs;  // (page * n + index) on both sides
    // Overlapping edges from a spatial hash (seam_edges.h): the same pairs, in the same order, as
    // comparing all pairs, which is quadratic and was skipped beyond 20,000 edges.
    const auto overlaps = lightmap::overlappingEdges(edges, eps);
    for (const lightmap::EdgeOverlap& o : overlaps) {
      const lightmap::SeamEdge &e0 = edges[o.first], &e1 = edges[o.second];
      if (bake.surfaces.faceChart[e0.face] == bake.surfaces.faceChart[e1.face]) continue;
      if (glm::dot(faces[e0.face].normal, faces[e1.face].normal) < cosLimit) continue;
      ++bake.seamEdges;
      const Vec3 d = e0.b - e0.a;
      const Vec3 u = d / glm::length(d);  // as edgesOverlap computes it
      const float s0 = o.s0, s1 = o.s1;
      const float density = float(std::sqrt(maps[e0.face].texelArea /
                                            std::max(1e-30, double(Polygon{faces[e0.face].corners, maps[e0.face].n}.area()))));
      const int samples = std::max(2, int(std::ceil((s1 - s0) * density * 2.0f)));
      for (int k = 0; k < samples; ++k) {
        const Vec3 p = e0.a + u * (s0 + (s1 - s0) * (float(k) + 0.5f) / float(samples));
        size_t a, b;
        if (texelFor(e0.face, p, &a) && texelFor(e1.face, p, &b) && a != b) pairs.emplace_back(a, b);
      }
    }
    bake.seamSamples = pairs.size();
    std::vector<std::vector<Rgb>>* plane = planes.front();
    auto value = [&](size_t k) -> Rgb& { return (*plane)[k / n][k % n]; };
    auto worst = [&] {
      float w = 0.0f;
      for (auto [a, b] : pairs) {
        const float mean = 0.5f * (channelTotal(value(a)) + channelTotal(value(b)));
        if (mean > 0.0f) w = std::max(w, channelTotal(glm::abs(value(a) - value(b))) / mean);
      }
      return w;
    };
    bake.seamMaxBefore = worst();
    // A texel may sit on several pairs: average repeatedly, Jacobi style, until they agree. Each
    // pass sets a texel to the mean of its pairs' means; the texels and their pair counts are
    // found once, not sorted again every pass.
    std::vector<size_t> seamTexels;
    seamTexels.reserve(2 * pairs.size());
    for (auto [a, b] : pairs) seamTexels.push_back(a), seamTexels.push_back(b);
    std::sort(seamTexels.begin(), seamTexels.end());
    seamTexels.erase(std::unique(seamTexels.begin(), seamTexels.end()), seamTexels.end());
    auto slotOf = [&](size_t k) {
      return size_t(std::lower_bound(seamTexels.begin(), seamTexels.end(), k) - seamTexels.begin());
    };
    std::vector<std::pair<size_t, size_t>> slots(pairs.size());
    std::vector<float> pairCount(seamTexels.size(), 0.0f);
    for (size_t i = 0; i < pairs.size(); ++i) {
      slots[i] = {slotOf(pairs[i].first), slotOf(pairs[i].second)};
      pairCount[slots[i].first] += 1.0f, pairCount[slots[i].second] += 1.0f;
    }
    std::vector<Rgb> sum(seamTexels.size());
    for (auto* current : planes) {
      plane = current;
      for (int pass = 0; pass < 64 && !pairs.empty(); ++pass) {
        std::fill(sum.begin(), sum.end(), Rgb(0.0f));
        for (size_t i = 0; i < pairs.size(); ++i) {
          const Rgb m = 0.5f * (value(pairs[i].first) + value(pairs[i].second));
          sum[slots[i].first] += m, sum[slots[i].second] += m;
        }
        for (size_t k = 0; k < seamTexels.size(); ++k) value(seamTexels[k]) = sum[k] / pairCount[k];
        if (worst() < 1e-5f) break;
      }
      if (current == planes.front()) bake.seamMaxAfter = worst();
    }
    bake.secondsSeams = since(seamStart);
  }

  // Dilation into the empty texels round the charts.
  for (int pass = 0; pass < options.dilation; ++pass) {
    for (size_t p = 0; p < pages; ++p) {
      std::vector<size_t> fill;
      std::vector<Rgb> values;  // planes.size() per filled texel
      std::vector<Rgb> sum(planes.size());
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const size_t i = size_t(y) * size_t(size) + size_t(x);
          if (bake.state[p][i] != LightmapBake::Empty) continue;
          std::fill(sum.begin(), sum.end(), Rgb(0.0f));
          int count = 0;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int xx = x + dx, yy = y + dy;
              if (xx < 0 || yy < 0 || xx >= size || yy >= size) continue;
              const size_t j = size_t(yy) * size_t(size) + size_t(xx);
              if (bake.state[p][j] == LightmapBake::Empty) continue;
              for (size_t k = 0; k < planes.size(); ++k) sum[k] += (*planes[k])[p][j];
              ++count;
            }
          if (count == 0) continue;
          fill.push_back(i);
          for (const Rgb& v : sum) values.push_back(v / float(count));
        }
      for (size_t f = 0; f < fill.size(); ++f) {
        for (size_t k = 0; k < planes.size(); ++k) (*planes[k])[p][fill[f]] = values[f * planes.size() + k];
        bake.state[p][fill[f]] = LightmapBake::Dilated;
      }
      bake.dilatedTexels += fill.size();
    }
  }
  bake.secondsPost += since(t0);
}

}  // namespace lightmap

LightmapBake bakeLightmaps(const Scene& scene, const LightmapAtlas& atlas, const LightmapBakeOptions& options,
                           const ProgressCallback& progress) {
  if (options.solve.refine.budget > 0)
    throw Error("lightmap bake: texels are not refined (--refine needs elements, not lightmaps)");
  validateSolveOptions(options.solve);  // before the atlas's texels and validity rays
  LightmapBake bake = lightmap::prepareTexels(scene, atlas, options);
  SurfaceSet& set = bake.surfaces.surfaces;
  auto t0 = Clock::now();
  const int shCount = directionalCoefficients(options.directional);
  std::vector<Rgb> incident;  // per element, shCount coefficients
  {
    SolverHost host(scene, set, options.solve, {}, shCount);
    while (host.step({}, progress)) {
    }
    bake.solution = host.solution();
    bake.secondsSolve = since(t0);
    if (shCount > 0) {
      const auto shStart = Clock::now();
      bool gathered = false;
      incident = host.incidentSh(shCount, &gathered);
      bake.directionsFrom = gathered ? "gathered" : "solver";
      bake.secondsDirectional = since(shStart);
    }
  }

  bake.directional = options.directional;
  bake.sh.resize(size_t(shCount));
  t0 = Clock::now();
  // L2 is read linearly: window each element's coefficients until no normal gets negative light.
  // Done before filling: every texel is then a convex combination of elements' sets (filling
  // copies, stitching and dilation average), and irradiance at or above a share of the mean for
  // every normal survives averaging, so the dilated and stitched texels need no search.
  if (options.directional == DirectionalMode::ShL2)
    tbb::parallel_for(size_t(0), set.elements.size(), [&](size_t e) {
      Rgb* c = &incident[e * size_t(kShCoefficients)];
      const float s = shNonNegativeWindow(c, kShCoefficients);
      if (s < 1.0f) shApplyWindow(c, kShCoefficients, s);
    });
  bake.secondsPost += since(t0);
  // Every texel value is a plane: the irradiance first, then each SH coefficient. Filling,
  // stitching and dilation treat them alike, so a texel's coefficients stay those of its value.
  std::vector<std::vector<std::vector<Rgb>>*> planes{&bake.pages};
  for (auto& plane : bake.sh) planes.push_back(&plane);
  lightmap::finishPlanes(options, bake, atlas.pageCount, planes, [&](size_t k, size_t e) {
    return k == 0 ? bake.solution.irradiance[e] : incident[e * size_t(shCount) + (k - 1)];
  });
  return bake;
}

Image lightmapPageImage(const LightmapBake& bake, int page) {
  if (page < 0 || size_t(page) >= bake.pages.size()) throw Error(fmt::format("lightmap page {} does not exist", page));
  const int s = bake.pageSize;
  Image image(s, s);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) image.at(x, s - 1 - y) = bake.pages[size_t(page)][size_t(y) * size_t(s) + size_t(x)];
  return image;
}

float rgbmRange(const Image& image) {
  float peak = 0.0f;
  for (const Rgb& c : image.pixels) peak = std::max({peak, c.r, c.g, c.b});
  return peak > 1.0f ? std::exp2(std::ceil(std::log2(peak))) : 1.0f;
}

namespace {
void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const auto* p = static_cast<const uint8_t*>(data);
  out->insert(out->end(), p, p + size);
}
}  // namespace

std::vector<uint8_t> encodeDirectionalPng(const LightmapBake& bake, int page, int texture) {
  if (bake.directional == DirectionalMode::None || page < 0 || size_t(page) >= bake.pages.size() || texture < 0 ||
      texture >= directionalTextureCount(bake.directional))
    throw Error(fmt::format("lightmap page {} has no direction texture {}", page, texture));
  const int s = bake.pageSize;
  const int count = directionalCoefficients(bake.directional);
  std::vector<uint8_t> rgb(size_t(s) * size_t(s) * 3);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const size_t i = size_t(y) * size_t(s) + size_t(x);
      Rgb c[kShCoefficients];
      for (int k = 0; k < count; ++k) c[k] = bake.sh[size_t(k)][size_t(page)][i];
      const Rgb v = encodeDirectionalTexel(bake.directional, c, texture);
      const size_t row = size_t(s - 1 - y);  // row 0 at the top, as lightmapPageImage
      for (int ch = 0; ch < 3; ++ch) rgb[(row * size_t(s) + size_t(x)) * 3 + size_t(ch)] = uint8_t(std::lround(v[ch] * 255.0f));
    }
  std::vector<uint8_t> png;
  if (!stbi_write_png_to_func(appendBytes, &png, s, s, 3, rgb.data(), s * 3))
    throw Error("cannot encode a direction texture as PNG");
  return png;
}

std::vector<uint8_t> encodeRgbmPng(const Image& image, float range) {
  if (!(range > 0.0f)) throw Error("RGBM range must be positive");
  std::vector<uint8_t> rgba(image.pixels.size() * 4);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    Rgb c = glm::clamp(image.pixels[i] / range, Rgb(0.0f), Rgb(1.0f));
    if (!(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b))) c = Rgb(0.0f);
    const float m = std::max({c.r, c.g, c.b, 1e-6f});
    const int a = std::clamp(int(std::ceil(m * 255.0f)), 1, 255);
    const float scale = 255.0f / float(a);
    for (int k = 0; k < 3; ++k) rgba[i * 4 + size_t(k)] = uint8_t(std::clamp(std::lround(c[k] * scale * 255.0f), 0L, 255L));
    rgba[i * 4 + 3] = uint8_t(a);
  }
  std::vector<uint8_t> png;
  if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 4, rgba.data(), image.width * 4))
    throw Error("cannot encode a lightmap page as PNG");
  return png;
}

}  // namespace luxel

#include "luxel/bake.h"

namespace luxel {

namespace {

// Planes of a lightmap bake (each [page][texel], as LightmapBake::pages) at the face corners of the
// flagged meshes: lightmapCornerIrradiance's texel choice and smoothing, one FaceCornerValues per
// plane. Every plane is read at the same texels and averaged with the same weights, so the SH
// planes of a directional bake stay those of the irradiance.
std::vector<FaceCornerValues> lightmapCornerPlanes(const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                                                   const std::vector<uint8_t>& meshes,
                                                   const std::vector<const std::vector<std::vector<Rgb>>*>& planes) {
  if (meshes.size() != scene.meshes.size() || atlas.faces.size() != scene.meshes.size())
    throw Error(fmt::format("lightmap vertex colours: {} mesh flags and an atlas of {} meshes for {} meshes",
                            meshes.size(), atlas.faces.size(), scene.meshes.size()));
  const auto& set = bake.surfaces.surfaces;
  const int size = bake.pageSize;
  const size_t n = size_t(size) * size_t(size);
  // Which chart owns each covered texel, on the pages the flagged meshes use.
  std::vector<std::vector<int32_t>> chartOf(bake.pages.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (meshes[m])
      for (const auto& uv : atlas.faces[m])
        if (uv.page < chartOf.size() && chartOf[uv.page].empty()) chartOf[uv.page].assign(n, -1);
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const auto& t = bake.surfaces.texels[e];
    if (!chartOf[t.page].empty())
      chartOf[t.page][size_t(t.y) * size_t(size) + t.x] = int32_t(bake.surfaces.faceChart[set.elements[e].face]);
  }
  // The lit side's normal of every mesh face the bake kept (split quads: their first half).
  std::vector<std::vector<Vec3>> litNormal(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (meshes[m]) litNormal[m].assign(scene.meshes[m].faces.size(), Vec3(0.0f));
  for (const SurfaceFace& f : set.faces)
    if (meshes[f.mesh] && litNormal[f.mesh][f.meshFace] == Vec3(0.0f)) litNormal[f.mesh][f.meshFace] = f.normal;

  std::vector<FaceCornerValues> out(planes.size(), FaceCornerValues(scene.meshes.size()));
  const float cosSmooth = std::cos(45.0f * std::numbers::pi_v<float> / 180.0f);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (!meshes[m]) continue;
    const Mesh& mesh = scene.meshes[m];
    struct Corner {
      Vec3 p, normal;
      uint32_t page = 0;
      std::array<size_t, 4> texel{};  // the texels read, with their weights
      std::array<float, 4> weight{};
      int taps = 0;
      bool found = false;
    };
    std::vector<Corner> corners(mesh.faces.size() * 4);
    std::vector<uint32_t> used;
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const auto& uv = atlas.faces[m][f];
      const int count = mesh.faces[f].vertexCount();
      glm::dvec2 mid(0.0);
      for (int k = 0; k < count; ++k) mid += glm::dvec2(uv.texel[size_t(k)]);
      mid /= double(count);
      for (int k = 0; k < count; ++k) {
        Corner& c = corners[f * 4 + size_t(k)];
        c.p = mesh.positions[mesh.faces[f].v[size_t(k)]];
        c.normal = litNormal[m][f];
        used.push_back(uint32_t(f * 4 + size_t(k)));
        if (c.normal == Vec3(0.0f) || uv.page >= chartOf.size()) continue;  // skipped by the bake: no texels
        // The lightmap at the corner (nudged inside, as the seams do) as a renderer samples it:
        // bilinearly, from the four texels around it that belong to the face's chart. A texel's
        // value alone stands up to half a texel off the vertex, which shows under a lamp's
        // fall-off (docs/baking.md, "Vertex colours for some meshes").
        const glm::dvec2 q = glm::dvec2(uv.texel[size_t(k)]) + 1e-3 * (mid - glm::dvec2(uv.texel[size_t(k)]));
        const int bx = int(std::floor(q.x - 0.5)), by = int(std::floor(q.y - 0.5));
        const double fx = q.x - 0.5 - bx, fy = q.y - 0.5 - by;
        float total = 0.0f;
        c.page = uv.page;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) {
            const int x = bx + i, y = by + j;
            if (x < 0 || y < 0 || x >= size || y >= size) continue;
            const size_t t = size_t(y) * size_t(size) + size_t(x);
            const float w = float((i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy));
            if (chartOf[uv.page][t] != int32_t(uv.chart) || !(w > 0.0f)) continue;
            c.texel[size_t(c.taps)] = t, c.weight[size_t(c.taps)] = w, ++c.taps, total += w;
          }
        if (total > 1e-3f) {
          for (int t = 0; t < c.taps; ++t) c.weight[size_t(t)] /= total;
          c.found = true;
          continue;
        }
        // None of them (a corner of a chart a texel or two across): its texel nearest the corner.
        c.taps = 0;
        double best = 1e300;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = int(std::floor(q.x)) + dx, y = int(std::floor(q.y)) + dy;
            if (x < 0 || y < 0 || x >= size || y >= size) continue;
            const size_t i = size_t(y) * size_t(size) + size_t(x);
            if (chartOf[uv.page][i] != int32_t(uv.chart)) continue;
            const double d = (x + 0.5 - q.x) * (x + 0.5 - q.x) + (y + 0.5 - q.y) * (y + 0.5 - q.y);
            if (d < best) best = d, c.texel[0] = i, c.weight[0] = 1.0f, c.taps = 1, c.found = true;
          }
      }
    }
    // One value per vertex of a smooth surface: the mean over the corners at the same position
    // whose faces turn by less than 45 degrees (all of them for a corner without a normal).
    std::sort(used.begin(), used.end(), [&](uint32_t x, uint32_t y) {
      const Vec3 &a = corners[x].p, &b = corners[y].p;
      return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    });
    for (auto& plane : out) plane[m].assign(corners.size(), Rgb(0.0f));
    for (size_t g0 = 0; g0 < used.size();) {
      size_t g1 = g0;
      while (g1 < used.size() && corners[used[g1]].p == corners[used[g0]].p) ++g1;
      for (size_t i = g0; i < g1; ++i) {
        const Corner& c = corners[used[i]];
        for (size_t k = 0; k < planes.size(); ++k) {
          Rgb sum(0.0f);
          int count = 0;
          for (size_t j = g0; j < g1; ++j) {
            const Corner& o = corners[used[j]];
            if (!o.found) continue;
            if (c.normal != Vec3(0.0f) && glm::dot(c.normal, o.normal) < cosSmooth) continue;
            for (int t = 0; t < o.taps; ++t) sum += o.weight[size_t(t)] * (*planes[k])[o.page][o.texel[size_t(t)]];
            ++count;
          }
          out[k][m][used[i]] = count > 0 ? sum / float(count) : Rgb(0.0f);
        }
      }
      g0 = g1;
    }
  }
  return out;
}

}  // namespace

FaceCornerValues lightmapCornerIrradiance(const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                                          const std::vector<uint8_t>& meshes) {
  return std::move(lightmapCornerPlanes(scene, atlas, bake, meshes, {&bake.pages}).front());
}

std::vector<FaceCornerValues> lightmapCornerDirections(const Scene& scene, const LightmapAtlas& atlas,
                                                       const LightmapBake& bake, const std::vector<uint8_t>& meshes) {
  const int count = directionalCoefficients(bake.directional);
  if (count == 0 || bake.sh.size() != size_t(count))
    throw Error(fmt::format("lightmap vertex directions: a bake with {} SH planes for mode '{}'", bake.sh.size(),
                            directionalModeName(bake.directional)));
  std::vector<const std::vector<std::vector<Rgb>>*> planes;
  for (const auto& plane : bake.sh) planes.push_back(&plane);
  const std::vector<FaceCornerValues> coefficients = lightmapCornerPlanes(scene, atlas, bake, meshes, planes);
  // Averages of the texels' sets: an L2 texel's window (at least 0.5% of the mean irradiance
  // for every normal) holds for them too, so they are encoded as they are.
  const int textures = directionalTextureCount(bake.directional);
  std::vector<FaceCornerValues> out(size_t(textures), FaceCornerValues(scene.meshes.size()));
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const size_t corners = coefficients[0][m].size();
    for (auto& list : out) list[m].assign(corners, Rgb(0.0f));
    for (size_t i = 0; i < corners; ++i) {
      Rgb c[kMaxDirectionalCoefficients];
      for (int k = 0; k < count; ++k) c[k] = coefficients[size_t(k)][m][i];
      for (int t = 0; t < textures; ++t) out[size_t(t)][m][i] = encodeDirectionalTexel(bake.directional, c, t);
    }
  }
  return out;
}

void addLightmaps(GlbOptions& o, const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                  const std::vector<uint8_t>& vertexColorMeshes) {
  if (!vertexColorMeshes.empty() && vertexColorMeshes.size() != scene.meshes.size())
    throw Error(fmt::format("lightmaps: {} vertex-colour flags for {} meshes", vertexColorMeshes.size(),
                            scene.meshes.size()));
  auto lightmapped = [&](size_t m) { return vertexColorMeshes.empty() || !vertexColorMeshes[m]; };
  const float s = float(atlas.pageSize);
  // Only the pages that lightmapped faces use go into the file (a page of vertex-coloured
  // meshes alone would be an unused image).
  std::vector<int32_t> imageOf(bake.pages.size(), -1);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (lightmapped(m))
      for (const auto& uv : atlas.faces[m])
        if (uv.page < imageOf.size()) imageOf[uv.page] = 0;
  // The images are named and placed first, then encoded in parallel: zlib's deflate is a single
  // thread each, and a directional bake has four to ten of them a page.
  std::vector<std::function<void(GlbImage&)>> encode;
  const size_t firstImage = o.images.size();
  for (int p = 0; p < int(bake.pages.size()); ++p) {
    if (imageOf[size_t(p)] < 0) continue;
    imageOf[size_t(p)] = int32_t(o.images.size());
    GlbImage g;
    g.name = fmt::format("lightmap{}", p);
    o.images.push_back(std::move(g));
    encode.push_back([&bake, p](GlbImage& g) {
      const Image image = lightmapPageImage(bake, p);
      g.rgbmRange = rgbmRange(image);
      g.png = encodeRgbmPng(image, g.rgbmRange);
    });
  }
  if (bake.directional != DirectionalMode::None) {
    o.directionalMode = directionalModeName(bake.directional);
    o.directionalImages.assign(o.images.size(), {});
    for (int p = 0; p < int(bake.pages.size()); ++p) {
      if (imageOf[size_t(p)] < 0) continue;
      for (int k = 0; k < directionalTextureCount(bake.directional); ++k) {
        o.directionalImages[size_t(imageOf[size_t(p)])].push_back(int32_t(o.images.size()));
        GlbImage g;
        g.name = fmt::format("lightmap{}_direction{}", p, k);
        g.clamped = true;
        o.images.push_back(std::move(g));
        encode.push_back([&bake, p, k](GlbImage& g) { g.png = encodeDirectionalPng(bake, p, k); });
      }
    }
    o.directionalImages.resize(o.images.size());
  }
  tbb::parallel_for(size_t(0), encode.size(), [&](size_t i) { encode[i](o.images[firstImage + i]); });
  o.secondUvs.assign(scene.meshes.size(), {});
  o.faceLightmap.assign(scene.meshes.size(), {});
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    if (!lightmapped(m)) continue;
    o.secondUvs[m].assign(scene.meshes[m].faces.size() * 4, Vec2(0.0f));
    o.faceLightmap[m].assign(scene.meshes[m].faces.size(), -1);
    for (size_t f = 0; f < scene.meshes[m].faces.size(); ++f) {
      const auto& uv = atlas.faces[m][f];
      for (int k = 0; k < 4; ++k) o.secondUvs[m][f * 4 + size_t(k)] = uv.texel[size_t(k)] / s;
      if (uv.page < imageOf.size()) o.faceLightmap[m][f] = imageOf[uv.page];
    }
  }
  if (std::any_of(vertexColorMeshes.begin(), vertexColorMeshes.end(), [](uint8_t v) { return v != 0; })) {
    o.vertexColors = lightmapCornerIrradiance(scene, atlas, bake, vertexColorMeshes);
    o.vertexColorQuantity = "irradiance";  // as the lightmaps: the material's colour and texture still apply
    if (bake.directional != DirectionalMode::None) {
      o.vertexDirectionalMode = directionalModeName(bake.directional);
      o.vertexDirections = lightmapCornerDirections(scene, atlas, bake, vertexColorMeshes);
    }
  }
}

}  // namespace luxel
