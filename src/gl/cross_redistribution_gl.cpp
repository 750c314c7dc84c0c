#include "gl/cross_redistribution_gl.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <unordered_map>

#include "core/position_key.h"
#include "gl/gl_context.h"
#include "gl/gpu_system.h"
#include "gl/gpu_timeline.h"
#include "gl/hemicube.h"
#include "gl/hemicube_glsl.h"
#include "gl/layered_hemicubes.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "luxel/error.h"

namespace luxel::gl {

namespace {

// Point j of the k_e x k_e that a static emitter L's shots were drawn from (its hemicubes'
// centres, less their lift), and its weight seen from x (normal n): the point kernel
// cos cos / r^2, as the reconstruction weighs a shooter's hemicubes.
const char* kShootingPointsGlsl = R"(
layout(std430, binding = CROSS_EMITTER_BINDING) readonly buffer CrossEmitters { uint crossEmitters[]; };
uniform int crossEmitterSide;
uniform uint crossEmitterCount;
float shootingPoint(GpuPatch L, int j, vec3 x, vec3 n, out vec3 y) {
  const float ks = float(crossEmitterSide);
  y = polygonPoint(L.corners, int(L.corners[0].w), (float(j % crossEmitterSide) + 0.5) / ks,
                   (float(j / crossEmitterSide) + 0.5) / ks);
  const vec3 d = y - x;
  const float r2 = dot(d, d);
  return max(dot(n, d), 0.0) * max(-dot(L.normalArea.xyz, d), 0.0) / (r2 * r2);
}
)";

const char* kCrossProjectionCode = R"(
layout(binding = BACK_ITEM_TEXTURE_UNIT) uniform usampler2DArray backItems;
layout(binding = BACK_DISTANCE_TEXTURE_UNIT) uniform sampler2DArray backDistances;
layout(std430, binding = BACK_SHOOTER_BINDING) readonly buffer BackShooters { GpuShooter backShooters[]; };
layout(std430, binding = CROSS_PATCH_BINDING) readonly buffer CrossPatches { uvec2 crossPatches[]; };
layout(std430, binding = REDISTRIBUTION_AMOUNT_BINDING) readonly buffer CrossAmounts { vec4 crossAmounts[]; };
layout(std430, binding = CROSS_BEHIND_BINDING) buffer CrossBehind { vec4 crossBehind[]; };
uniform int backResolution, crossGrid;
uniform float backNear, backFar;

// The pixel of back hemicube k (frame f, centre eye) that direction r falls on; z < 0: none.
ivec3 backPixel(uint k, HemicubeFrame f, vec3 eye, vec3 r) {
  return hemicubePixelAt(eye + r, eye, f, backNear, backFar, backResolution, int(k));
}

// The patch of the static surface a back hemicube shows at `q` that faces the viewer looking
// along d (a two-sided face's other side where the drawn side turns away), or ~0u for none.
uint facingPatch(ivec3 q, vec3 d) {
  const uint item = texelFetch(backItems, q, 0).r;
  if (item == 0u) return 0xFFFFFFFFu;
  const uint p = item - 1u;
  return dot(patches[p].normalArea.xyz, d) < 0.0 ? p : crossPatches[p].y;
}

// How far past the surface the back hemicube shows in direction r the point eye + r lies
// (negative: in front of it).
float behindBy(uint k, HemicubeFrame f, vec3 eye, vec3 r, out ivec3 pixel) {
  pixel = backPixel(k, f, eye, r);
  if (pixel.z < 0) return -1.0;
  return length(r) - texelFetch(backDistances, pixel, 0).r;
}

// The static patch the ray from q along d meets first, marched through back hemicube k (centre
// eye): the hemicube's centre is not q, so the ray's hit is where its points pass from in front
// of the surface the hemicube shows to behind it. 001 took one step (the depth the parallel ray
// from the centre meets placed the hit); that is off by the patch's size where depth changes
// across it, as from a box's side face to a light just above the box (docs/algorithms.md,
// "Dynamic radiosity", has the figures). Steps grow geometrically from near the patch to the far plane;
// a crossing deeper than the step is the ray passing behind something nearer the centre, not a
// hit, and the march goes on; the crossing is then narrowed by bisection. ~0u: nothing.
uint marchedPatch(uint k, HemicubeFrame f, vec3 eye, vec3 q, vec3 d) {
  const float pixelAngle = 2.0 / float(backResolution);
  ivec3 pixel, first = ivec3(-1);
  // 001's step first: where the parallel ray from the centre meets a surface. When the ray from q
  // lies on that surface there too (within a pixel's depth), that is its hit: the common case of
  // a wall behind the patch, settled with two fetches.
  // Where the parallel ray meets nothing (an opening to the sky), the ray from q is taken to
  // meet nothing either, as 001 did: marching those rays as well costs several times the pass
  // and changes little (docs/algorithms.md, "Dynamic radiosity").
  const ivec3 parallel = backPixel(k, f, eye, d);
  if (parallel.z < 0) return 0xFFFFFFFFu;
  const float guess = texelFetch(backDistances, parallel, 0).r;
  if (!(guess < backFar)) return 0xFFFFFFFFu;
  const float off = behindBy(k, f, eye, q + guess * d - eye, pixel);
  if (pixel.z >= 0 && abs(off) <= 2.0 * pixelAngle * length(q + guess * d - eye)) return facingPatch(pixel, d);
  const int steps = 32;
  const float tMin = 1e-4 * backFar, ratio = pow(backFar / tMin, 1.0 / float(steps));
  float before = 0.0, t = tMin;
  for (int s = 0; s < steps; ++s, before = t, t *= ratio) {
    const float behind = behindBy(k, f, eye, q + t * d - eye, pixel);
    if (pixel.z < 0) return 0xFFFFFFFFu;
    if (behind < 0.0) continue;
    if (first.z < 0) first = pixel;
    if (behind > (t - before) + pixelAngle * t) continue;  // behind something nearer the centre
    float lo = before, hi = t;
    for (int i = 0; i < 6; ++i) {
      const float mid = 0.5 * (lo + hi);
      if (behindBy(k, f, eye, q + mid * d - eye, pixel) >= 0.0) hi = mid; else lo = mid;
    }
    behindBy(k, f, eye, q + hi * d - eye, pixel);
    return facingPatch(pixel, d);
  }
  // Every crossing was behind something nearer: the first of them is the best guess.
  return first.z < 0 ? 0xFFFFFFFFu : facingPatch(first, d);
}

// A sphere round polygon P: the corners' mean and the farthest corner's distance from it.
void boundingSphere(GpuPatch P, out vec3 centre, out float radius) {
  const int count = int(P.corners[0].w);
  centre = vec3(0.0);
  for (int i = 0; i < count; ++i) centre += P.corners[i].xyz / float(count);
  radius = 0.0;
  for (int i = 0; i < count; ++i) radius = max(radius, length(P.corners[i].xyz - centre));
}

// Whether the segment from x to y passes through polygon J (planar, convex).
bool segmentCrosses(vec3 x, vec3 y, GpuPatch J) {
  const vec3 nj = J.normalArea.xyz, d = y - x;
  const float along = dot(nj, d);
  if (!(abs(along) > 0.0)) return false;
  const float t = dot(nj, J.corners[0].xyz - x) / along;
  if (!(t > 0.0 && t < 1.0)) return false;
  const vec3 h = x + t * d;
  const int count = int(J.corners[0].w);
  bool inside = true, outside = true;  // on the inner side of every edge, for either winding
  for (int i = 0; i < count; ++i) {
    const vec3 a = J.corners[i].xyz, b = J.corners[i + 1 == count ? 0 : i + 1].xyz;
    const float side = dot(cross(b - a, h - a), nj);
    inside = inside && side >= 0.0;
    outside = outside && side <= 0.0;
  }
  return inside || outside;
}

// The irradiance at x (normal n) from the static emitters of the exact list that moved patch J
// hides: each emitter's unoccluded factor times the kernel-weighted share of the points its own
// shots were drawn from (k_e x k_e) whose segment to x crosses J. This is how its shot reached x
// (the reconstruction's estimator) with J for the blocker, so a small bright light is not left to
// the few rays through J that find it in the back hemicube.
void emittersHidden(vec3 x, vec3 n, GpuPatch J, out vec3 shot, out vec3 emitted) {
  shot = vec3(0.0);
  emitted = vec3(0.0);
  vec3 toJ;
  float radiusJ;
  boundingSphere(J, toJ, radiusJ);
  toJ -= x;
  const float distanceJ = length(toJ);
  for (uint i = 0u; i < crossEmitterCount; ++i) {
    const uint l = crossEmitters[i];
    const GpuPatch L = patches[l];
    // Seen from x, the cones round J and round L must overlap for any segment to cross both, and
    // L must reach beyond J.
    vec3 toL;
    float radiusL;
    boundingSphere(L, toL, radiusL);
    toL -= x;
    const float distanceL = length(toL);
    if (distanceL + radiusL < distanceJ - radiusJ) continue;
    if (distanceJ > radiusJ && distanceL > radiusL &&
        acos(clamp(dot(toJ, toL) / (distanceJ * distanceL), -1.0, 1.0)) > asin(radiusJ / distanceJ) + asin(radiusL / distanceL))
      continue;
    const int corners = int(L.corners[0].w);
    const float f = pointToPolygonFormFactor(x, n, L.corners, corners, L.normalArea.xyz);
    if (!(f > 0.0)) continue;
    float hidden = 0.0, all = 0.0;
    for (int j = 0; j < crossEmitterSide * crossEmitterSide; ++j) {
      vec3 y;
      const float g = shootingPoint(L, j, x, n, y);
      if (!(g > 0.0)) continue;
      all += g;
      if (segmentCrosses(x, y, J)) hidden += g;
    }
    if (!(hidden > 0.0)) continue;
    shot += f * hidden / all * crossAmounts[2u * l].rgb;
    emitted += f * hidden / all * crossAmounts[2u * l + 1u].rgb;
  }
}

// The shot radiosity of the static patches (but the exactly sampled emitters) that x sees
// through moved patch P, kernel-weighted mean over P's g x g rays; and their first-shot emission.
// Returns the rays' summed weight: 0 where x sees none of P.
float crossProjected(uint k, vec3 x, vec3 n, GpuPatch P, out vec3 shot, out vec3 emitted) {
  shot = vec3(0.0);
  emitted = vec3(0.0);
  const GpuShooter c = backShooters[k];
  const HemicubeFrame f = hemicubeFrame(c.normal.xyz, c.normal.w);
  const int corners = int(P.corners[0].w);
  const float g = float(crossGrid);
  float weight = 0.0;
  for (int j = 0; j < crossGrid; ++j)
    for (int i = 0; i < crossGrid; ++i) {
      const vec3 q = polygonPoint(P.corners, corners, (float(i) + 0.5) / g, (float(j) + 0.5) / g);
      vec3 d = q - x;
      const float r2 = dot(d, d);
      if (!(r2 > 0.0)) continue;
      d *= inversesqrt(r2);
      // The form factor's own weight of the ray through this point of the patch.
      const float w = max(dot(n, d), 0.0) * max(-dot(P.normalArea.xyz, d), 0.0) / r2;
      if (!(w > 0.0)) continue;
      weight += w;
      const uint p = marchedPatch(k, f, c.eye.xyz, q, d);
      if (p == 0xFFFFFFFFu || crossPatches[p].x != 0u) continue;
      shot += w * crossAmounts[2u * p].rgb;
      emitted += w * crossAmounts[2u * p + 1u].rgb;
    }
  if (weight > 0.0) shot /= weight, emitted /= weight;
  return weight;
}
)";

// What each static patch sees behind each moved patch of a crossing pass, crossProjected from the
// patch's centre, for its elements' points to share (crossBehind, 2 x (slot x patchCount + p)).
// Per element point it was two thirds of a cross-redistribution frame on a GPU, and what it
// estimates is the light reflected by the surfaces behind the moved patch, smooth across a
// receiver patch; the emitters it hides are sampled per point (emittersHidden), and a point whose
// patch centre sees none of the moved patch casts its own rays (w = 0 here).
const char* kCrossBehindCompute = R"(
layout(local_size_x = POWER_GROUP) in;
uniform uint patchCount, count, samples;
void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= patchCount * count) return;
  const uint r = i % patchCount, k = i / patchCount;
  vec3 shot = vec3(0.0), emitted = vec3(0.0);
  float weight = 0.0;
  if ((crossPatches[r].x & 1u) == 0u) {
    const GpuPatch R = patches[r];
    const int corners = int(R.corners[0].w);
    vec3 centre = vec3(0.0);
    for (int c = 0; c < corners; ++c) centre += R.corners[c].xyz / float(corners);
    weight = crossProjected(k, centre, R.normalArea.xyz, patches[shooters[k * samples].ids.x], shot, emitted);
  }
  crossBehind[2u * i] = vec4(shot, weight > 0.0 ? 1.0 : 0.0);
  crossBehind[2u * i + 1u] = vec4(emitted, 0.0);
}
)";

}  // namespace

std::string crossProjectionGlsl() {
  return std::string(kShootingPointsGlsl) + kCrossProjectionCode;
}

namespace {

// Centres of the moved elements' gather hemicubes, from the elements as the GPU holds them (the
// old geometry before the move's upload, the new after it): one at the element's centre, or, for
// elements large beside their distance to a light (kNearLight), the reconstruction's 2 x 2
// midpoint rule, so that the gather and the shots that lit the element before estimate the same
// mean: near a light the irradiance is far from linear over the element.
const char* kGatherEyesCompute = R"(
layout(local_size_x = POWER_GROUP) in;
layout(std430, binding = REDISTRIBUTION_LIST_BINDING) readonly buffer List { uint list[]; };
uniform uint first, count;
uniform float offset;
void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= count * GATHER_SAMPLES) return;
  const uint e = list[first + i / GATHER_SAMPLES], q = i % GATHER_SAMPLES;
  const GpuElement el = elements[e];
#if GATHER_SAMPLES == 1
  vec3 x = vec3(0.0);
  for (int c = 0; c < int(el.corners[0].w); ++c) x += el.corners[c].xyz / el.corners[0].w;
#else
  const vec3 x = polygonPoint(el.corners, int(el.corners[0].w), 0.25 + 0.5 * float(q & 1u), 0.25 + 0.5 * float(q >> 1));
#endif
  shooters[i] = GpuShooter(vec4(x + offset * el.normalArea.xyz, 0.0), vec4(el.normalArea.xyz, hemicubeTurn(e, q, 0x5EEDu)),
                           vec4(0.0), vec4(0.0), uvec4(e, 1u, 0u, 0u));
}
)";

// R_g(C, M): one work group per moved element sums delta form factor times the shot radiosity
// (and the first-shot emission) of the static patch each pixel shows, in a fixed order, and adds
// sign times that to the element.
const char* kGatherIntegrateCompute = R"(
layout(local_size_x = GATHER_GROUP) in;
layout(binding = ITEM_TEXTURE_UNIT) uniform usampler2DArray items;
layout(std430, binding = CROSS_DELTA_BINDING) readonly buffer Deltas { float deltas[]; };
layout(std430, binding = REDISTRIBUTION_LIST_BINDING) readonly buffer List { uint list[]; };
layout(std430, binding = REDISTRIBUTION_AMOUNT_BINDING) readonly buffer Amounts { vec4 amounts[]; };
layout(std430, binding = CROSS_PATCH_BINDING) readonly buffer CrossPatches { uvec2 crossPatches[]; };
layout(binding = DISTANCE_TEXTURE_UNIT) uniform sampler2DArray distances;
uniform uint first;
uniform int resolution;
uniform float sign, nearPlane, farPlane, offset;

// What the sampled static emitters give point x (normal n), seen through gather hemicube h
// (centre eye): as the shots' reconstruction estimates it, each emitter's exact unoccluded factor
// times the kernel-weighted share of its shooting points (k_e x k_e) that the hemicube sees
// (the pixel shows the emitter, or nothing nearer than the point). The pixels of those emitters
// are left out of the hemicube's sum: a small lamp in a few pixels of it is coarser than the
// shots that lit the element, and that difference would not cancel from one pose to the next.
void emittersSeen(uint h, vec3 x, vec3 n, GpuShooter eye, out vec3 shot, out vec3 emitted) {
  shot = vec3(0.0);
  emitted = vec3(0.0);
  const HemicubeFrame f = hemicubeFrame(eye.normal.xyz, eye.normal.w);
  for (uint i = 0u; i < crossEmitterCount; ++i) {
    const uint l = crossEmitters[i];
    const GpuPatch L = patches[l];
    const int corners = int(L.corners[0].w);
    const float factor = pointToPolygonFormFactor(x, n, L.corners, corners, L.normalArea.xyz);
    if (!(factor > 0.0)) continue;
    float seen = 0.0, all = 0.0;
    for (int j = 0; j < crossEmitterSide * crossEmitterSide; ++j) {
      vec3 y;
      const float g = shootingPoint(L, j, x, n, y);
      if (!(g > 0.0)) continue;
      all += g;
      const ivec3 q = hemicubePixelAt(y, eye.eye.xyz, f, nearPlane, farPlane, resolution, int(h));
      if (q.z < 0) continue;
      const uint item = texelFetch(items, q, 0).r;
      const bool shows = item != 0u && (item - 1u == l || crossPatches[item - 1u].y == l);
      if (shows || texelFetch(distances, q, 0).r > length(y - eye.eye.xyz) * (1.0 - 1.0 / float(resolution))) seen += g;
    }
    if (!(seen > 0.0)) continue;
    shot += factor * seen / all * amounts[2u * l].rgb;
    emitted += factor * seen / all * amounts[2u * l + 1u].rgb;
  }
}

void main() {
  const uint local = gl_WorkGroupID.x, tid = gl_LocalInvocationIndex, e = list[first + local];
  const int perHemicube = 3 * resolution * resolution;  // the top, and four upper halves
  vec3 shot = vec3(0.0), emitted = vec3(0.0);
  for (int i = int(tid); i < GATHER_SAMPLES * perHemicube; i += GATHER_GROUP) {
    const int h = i / perHemicube;
    const GpuShooter eye = shooters[local * GATHER_SAMPLES + uint(h)];
    int face, x, y, d;
    hemicubePixel(i % perHemicube, resolution, face, x, y, d);
    const uint item = texelFetch(items, ivec3(x, y, (int(local) * GATHER_SAMPLES + h) * 5 + face), 0).r;
    if (item == 0u) continue;
    // Which side of the patch the pixel shows.
    const vec3 w = hemicubePixelDirection(hemicubeFrame(eye.normal.xyz, eye.normal.w), face, x, y, resolution);
    uint p = item - 1u;
    if (dot(patches[p].normalArea.xyz, w) >= 0.0) p = crossPatches[p].y;
    if (p == 0xFFFFFFFFu || crossPatches[p].x != 0u) continue;  // moved, or an emitter sampled below
    shot += deltas[d] * amounts[2u * p].rgb;
    emitted += deltas[d] * amounts[2u * p + 1u].rgb;
  }
  if (tid < uint(GATHER_SAMPLES)) {
    const GpuShooter eye = shooters[local * GATHER_SAMPLES + tid];
    const GpuElement el = elements[e];
    vec3 shotHere, emittedHere;
    emittersSeen(local * GATHER_SAMPLES + tid, eye.eye.xyz - offset * el.normalArea.xyz, el.normalArea.xyz, eye,
                 shotHere, emittedHere);
    shot += shotHere, emitted += emittedHere;
  }
  shot = groupSum(shot, tid) / float(GATHER_SAMPLES);
  emitted = groupSum(emitted, tid) / float(GATHER_SAMPLES);
  if (tid != 0u) return;
  GpuElementState st = states[e];
  const vec3 dh = sign * shot, db = elements[e].reflectance.rgb * dh;
  st.irradiance.rgb += dh;
  st.radiosity.rgb += db;
  st.unshot.rgb += db;
  st.direct.rgb += sign * emitted;
  states[e] = st;
}
)";

// An element is near a light, and gathers with 2 x 2 hemicubes, when it is wider than this share
// of its distance to the nearest emitting patch (from its centre to the patch's bounding sphere):
// the GPU test's box 2 cm under the lamp is; seed 001's boxes 8 cm under it are not, and there one
// hemicube gathers as well as four. Decided where the set stands when it first moves: an element
// keeps its gather's hemicubes from move to move, so that each move's two gathers still cancel.
constexpr float kNearLight = 1.0f;

// Up to this many static emitting patches are sampled exactly behind each moved patch
// (emittersHidden); with more, all of them are left to the back hemicubes.
constexpr size_t kMaxSampledEmitters = 64;

// The largest table of what each patch sees behind the movers (kCrossBehindCompute), 32 bytes a
// patch and pass slot: past it, each element point casts its own rays.
constexpr size_t kMostBehindBytes = size_t(256) << 20;

// The most memory the moved elements' gather hemicubes keep from one move to the next (one set
// of layers a batch); past it, one set is drawn again for each batch.
constexpr size_t kMostGatherBytes = size_t(512) << 20;

// Whether every one-sided face among `faces` has each edge shared with another of them: then
// nothing outside sees a back, and the cross projection (which follows only the light that passes
// a moved patch's front) sees every occlusion. Corners are matched bit for bit; a T-junction
// counts as open, which only costs the incremental path.
bool faceSetClosed(const SurfaceSet& set, const std::vector<uint32_t>& faces) {
  struct EdgeKey {
    PositionKey a, b;
    bool operator==(const EdgeKey&) const = default;
  };
  struct EdgeHash {
    size_t operator()(const EdgeKey& e) const {
      return PositionKeyHash{}(e.a) * 31u ^ PositionKeyHash {}(e.b);
    }
  };
  auto edge = [](Vec3 p, Vec3 q) {
    PositionKey a = positionKey(p), b = positionKey(q);
    if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
    return EdgeKey{a, b};
  };
  auto forEachEdge = [&](const SurfaceFace& f, auto&& use) {
    const int count = f.triangle ? 3 : 4;
    for (int i = 0; i < count; ++i)
      use(edge(f.corners[size_t(i)], f.corners[size_t((i + 1) % count)]));
  };
  std::unordered_map<EdgeKey, int, EdgeHash> uses;
  for (uint32_t f : faces) forEachEdge(set.faces[f], [&](const EdgeKey& e) { ++uses[e]; });
  bool closed = true;
  for (uint32_t f : faces)
    if (set.faces[f].twin < 0)
      forEachEdge(set.faces[f], [&](const EdgeKey& e) { closed = closed && uses[e] > 1; });
  return closed;
}

GLuint groupsOf(size_t n, int size) { return GLuint((n + size_t(size) - 1) / size_t(size)); }

// A two-sided face's patches are drawn once, from the face with the smaller index: the two sides
// coincide and would z-fight.
bool drawn(const SurfaceSet& set, uint32_t patch) {
  const int32_t twin = set.faces[set.patches[patch].face].twin;
  return twin < 0 || uint32_t(twin) > set.patches[patch].face;
}

}  // namespace

CrossRedistribution::CrossRedistribution(const RadiositySystem& system,
                                         std::vector<uint32_t> objectOfPatch,
                                         const CrossRedistributionSettings& settings,
                                         int backCapacity, float nearPlane, float farPlane,
                                         float offset, const std::string& preamble)
    : sys_(system),
      objectOfPatch_(std::move(objectOfPatch)),
      s_(settings),
      backCapacity_(backCapacity),
      offset_(offset) {
  const SurfaceSet& set = sys_.surfaces;
  const size_t np = set.patches.size();
  if (objectOfPatch_.size() != np)
    throw Error("cross-redistribution: an object for every patch is needed");
  if (s_.gatherResolution < 8 || s_.gatherResolution % 2 || s_.backResolution < 4 ||
      s_.backResolution % 2)
    throw Error(fmt::format(
        "cross-redistribution: hemicube resolutions {} and {} must be even and at least 8 and 4",
        s_.gatherResolution, s_.backResolution));
  if (s_.grid < 1 || s_.grid > 16)
    throw Error(fmt::format("cross-redistribution: grid {} must be in 1..16", s_.grid));
  // Twin patches: the discretiser gives a two-sided face's back the front's grid (discretise.cpp,
  // addTwinFaces), so each patch has one at its centroid on the other face.
  twinPatch_.assign(np, ~0u);
  std::vector<std::vector<uint32_t>> patchesOfFace(set.faces.size());
  for (uint32_t p = 0; p < np; ++p) patchesOfFace[set.patches[p].face].push_back(p);
  for (uint32_t p = 0; p < np; ++p) {
    const int32_t twin = set.faces[set.patches[p].face].twin;
    if (twin < 0) continue;
    float nearest = std::numeric_limits<float>::max();
    for (uint32_t q : patchesOfFace[size_t(twin)]) {
      const Vec3 d = set.patches[q].centroid - set.patches[p].centroid;
      if (glm::dot(d, d) < nearest) nearest = glm::dot(d, d), twinPatch_[p] = q;
    }
  }
  moved_.assign(np, 0);
  sampledEmitter_.assign(np, 0);

  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  gatherCapacity_ = std::clamp(int(maxLayers) / 5, 1, 128);  // hemicubes a batch
  std::vector<Polygon> polygons;
  std::vector<uint32_t> items;
  for (uint32_t p = 0; p < np; ++p)
    if (drawn(set, p)) polygons.push_back(set.patches[p].polygon), items.push_back(p + 1);
  gathers_.push_back(std::make_unique<LayeredHemicubes>(
      polygons, items, LayeredHemicubes::Content::ItemsAndDistances, s_.gatherResolution,
      gatherCapacity_, nearPlane, farPlane, s_.layering));
  gatherPolygons_ = polygons, gatherItems_ = items;
  back_ = std::make_unique<LayeredHemicubes>(
      polygons, items, LayeredHemicubes::Content::ItemsAndDistances, s_.backResolution,
      std::max(backCapacity_, 1), nearPlane, farPlane, s_.layering);
  const DeltaFormFactors deltas(s_.gatherResolution);
  std::vector<float> table(deltas.top);
  table.insert(table.end(), deltas.side.begin(), deltas.side.end());
  deltas_ = storageBuffer(table.data(), table.size() * sizeof(float));
  backShooters_ = storageBuffer(nullptr, size_t(std::max(backCapacity_, 1)) * sizeof(GpuShooter));
  gatherEyes_ = storageBuffer(nullptr, size_t(gatherCapacity_) * sizeof(GpuShooter));
  patchTable_ = storageBuffer(nullptr, std::max<size_t>(np, 1) * sizeof(glm::uvec2));
  uploadPatchTable();
  const size_t behindBytes = 2 * np * size_t(std::max(backCapacity_, 1)) * sizeof(glm::vec4);
  if (s_.behindPerPatch && np > 0 && behindBytes <= kMostBehindBytes) {
    behind_ = storageBuffer(nullptr, behindBytes);
    behindProgram_ = std::make_unique<ShaderProgram>(
        "cross-redistribution: what each patch sees behind the movers",
        preamble + crossProjectionGlsl() + kCrossBehindCompute);
    behindProgram_->use();
    glUniform1ui(glGetUniformLocation(behindProgram_->id(), "patchCount"), GLuint(np));
  }

  for (GatherRule& rule : rules_) {
    const std::string samples = fmt::format("#define GATHER_SAMPLES {}\n", rule.samples);
    rule.eyes = std::make_unique<ShaderProgram>("cross-redistribution gather centres",
                                                preamble + samples + kGatherEyesCompute);
    rule.integrate = std::make_unique<ShaderProgram>(
        "cross-redistribution gather",
        preamble + samples + kGroupSumGlsl + kShootingPointsGlsl + kGatherIntegrateCompute);
    rule.eyes->use();
    glUniform1f(glGetUniformLocation(rule.eyes->id(), "offset"), offset_);
    rule.integrate->use();
    glUniform1i(glGetUniformLocation(rule.integrate->id(), "resolution"), s_.gatherResolution);
    glUniform1f(glGetUniformLocation(rule.integrate->id(), "nearPlane"), gathers_[0]->nearPlane());
    glUniform1f(glGetUniformLocation(rule.integrate->id(), "farPlane"), gathers_[0]->farPlane());
    glUniform1f(glGetUniformLocation(rule.integrate->id(), "offset"), offset_);
  }
  Context::check("setting up GPU cross-redistribution");
}

CrossRedistribution::~CrossRedistribution() {
  const GLuint all[] = {patchTable_,  backShooters_,  gatherEyes_,    deltas_,
                        emitterList_, rules_[0].list, rules_[1].list, behind_};
  glDeleteBuffers(GLsizei(std::size(all)), all);
}

void CrossRedistribution::uploadPatchTable() {
  std::vector<glm::uvec2> table(moved_.size());
  for (size_t p = 0; p < table.size(); ++p)
    table[p] = glm::uvec2(moved_[p] | (sampledEmitter_[p] << 1), twinPatch_[p]);
  if (!table.empty())
    glNamedBufferSubData(patchTable_, 0, GLsizeiptr(table.size() * sizeof(glm::uvec2)),
                         table.data());
}

void CrossRedistribution::begin(std::span<const uint32_t> objects) {
  std::vector<uint32_t> sorted(objects.begin(), objects.end());
  std::sort(sorted.begin(), sorted.end());
  const bool sameSet = sorted == movedObjects_;
  movedObjects_ = std::move(sorted);
  const SurfaceSet& set = sys_.surfaces;
  for (size_t p = 0; p < moved_.size(); ++p)
    moved_[p] =
        std::binary_search(movedObjects_.begin(), movedObjects_.end(), objectOfPatch_[p]) ? 1 : 0;
  // The static emitters sampled exactly: every move, as a light edit may have lit or put out one.
  const std::vector<Rgb> emission = sys_.patchMeans(sys_.emission);
  std::vector<uint32_t> emitters;
  for (uint32_t p = 0; p < moved_.size(); ++p)
    if (!moved_[p] && channelSum(emission[p]) > 0.0) emitters.push_back(p);
  if (emitters.size() > kMaxSampledEmitters) emitters.clear();
  std::fill(sampledEmitter_.begin(), sampledEmitter_.end(), 0);
  for (uint32_t p : emitters) sampledEmitter_[p] = 1;
  glDeleteBuffers(1, &emitterList_);
  emitterList_ =
      storageBuffer(emitters.data(), std::max<size_t>(emitters.size(), 1) * sizeof(uint32_t));
  for (const GLuint program :
       {reconstruction_, rules_[0].integrate->id(), rules_[1].integrate->id()}) {
    glUseProgram(program);
    glUniform1ui(glGetUniformLocation(program, "crossEmitterCount"), GLuint(emitters.size()));
  }
  uploadPatchTable();
  if (sameSet) return;
  std::vector<uint32_t> movedFaces;
  for (uint32_t p = 0; p < moved_.size(); ++p)
    if (moved_[p]) movedFaces.push_back(set.patches[p].face);
  std::sort(movedFaces.begin(), movedFaces.end());
  movedFaces.erase(std::unique(movedFaces.begin(), movedFaces.end()), movedFaces.end());
  closed_ = faceSetClosed(set, movedFaces);
  // The emitting patches' bounding spheres, for the rule that picks each moved element's gather.
  std::vector<glm::vec4> lights;
  for (size_t p = 0; p < set.patches.size(); ++p) {
    if (!(channelSum(emission[p]) > 0.0)) continue;
    const Patch& patch = set.patches[p];
    float radius = 0.0f;
    for (int c = 0; c < patch.polygon.count; ++c)
      radius = std::max(radius, glm::length(patch.polygon.v[size_t(c)] - patch.centroid));
    lights.emplace_back(patch.centroid, radius);
  }
  for (GatherRule& rule : rules_) rule.elements.clear();
  for (uint32_t e = 0; e < set.elements.size(); ++e) {
    if (!moved_[set.elements[e].patch]) continue;
    const Element& el = set.elements[e];
    const Vec3 centre = el.polygon.centroid();
    float width = 0.0f, distance = std::numeric_limits<float>::max();
    for (int c = 0; c < el.polygon.count; ++c)
      width = std::max(width, 2.0f * glm::length(el.polygon.v[size_t(c)] - centre));
    for (const glm::vec4& l : lights)
      distance = std::min(distance, std::max(glm::length(Vec3(l) - centre) - l.w, 0.0f));
    rules_[width > kNearLight * distance ? 1 : 0].elements.push_back(e);
  }
  for (GatherRule& rule : rules_) {
    glDeleteBuffers(1, &rule.list);
    rule.list = storageBuffer(rule.elements.data(),
                              std::max<size_t>(rule.elements.size(), 1) * sizeof(uint32_t));
  }
  // The back hemicubes show the patches that stay: those do not move, so once per moved set.
  std::vector<Polygon> polygons;
  std::vector<uint32_t> items;
  for (uint32_t p = 0; p < moved_.size(); ++p)
    if (!moved_[p] && drawn(set, p))
      polygons.push_back(set.patches[p].polygon), items.push_back(p + 1);
  back_->setPolygons(polygons, items);
  // A set of gather hemicubes per batch where they fit, drawing what the first draws.
  imagesKept_ = false;
  size_t batches = 0;
  for (const GatherRule& rule : rules_) batches += (rule.elements.size() + perBatch(rule) - 1) / perBatch(rule);
  const size_t setBytes = size_t(5 * gatherCapacity_) * size_t(s_.gatherResolution) * size_t(s_.gatherResolution) *
                          (sizeof(uint32_t) + 2 * sizeof(float));  // item, distance, depth
  keepGathers_ = s_.keepGathers && batches * setBytes <= kMostGatherBytes;
  if (keepGathers_) {
    const LayeredHemicubes& first = *gathers_[0];
    while (gathers_.size() < batches)
      gathers_.push_back(std::make_unique<LayeredHemicubes>(
          gatherPolygons_, gatherItems_, LayeredHemicubes::Content::ItemsAndDistances, s_.gatherResolution,
          gatherCapacity_, first.nearPlane(), first.farPlane(), s_.layering));
  } else {
    gathers_.resize(1);
  }
  Context::check("GPU cross-redistribution: the moved set");
}

void CrossRedistribution::geometryMoved() {
  const SurfaceSet& set = sys_.surfaces;
  std::vector<Polygon> polygons;
  std::vector<uint32_t> items;
  for (uint32_t p = 0; p < set.patches.size(); ++p)
    if (drawn(set, p)) polygons.push_back(set.patches[p].polygon), items.push_back(p + 1);
  for (const auto& gather : gathers_) gather->setPolygons(polygons, items);
  gatherPolygons_ = std::move(polygons), gatherItems_ = std::move(items);
  imagesKept_ = false;
}

void CrossRedistribution::renderBackHemicubes(int count) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, backShooters_);
  back_->render(0, count);
}

void CrossRedistribution::bindForReconstruction() const {
  back_->bindTextures(kBackItemTextureUnit, kBackDistanceTextureUnit);
  if (behind_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossBehindBinding, behind_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossPatchBinding, patchTable_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBackShooterBinding, backShooters_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossEmitterBinding, emitterList_);
}

void CrossRedistribution::projectBehind(int count, int samples) {
  if (!behindProgram_ || count <= 0) return;
  behindProgram_->use();
  glUniform1ui(glGetUniformLocation(behindProgram_->id(), "count"), GLuint(count));
  glUniform1ui(glGetUniformLocation(behindProgram_->id(), "samples"), GLuint(samples));
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glDispatchCompute(groupsOf(sys_.patchCount() * size_t(count), kPowerGroup), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void CrossRedistribution::setReconstructionUniforms(GLuint program, int emitterSide) {
  reconstruction_ = program;
  // The back hemicubes' march, in both programs that cast rays through them.
  for (const GLuint p : {program, behindProgram_ ? behindProgram_->id() : 0u}) {
    if (!p) continue;
    glUseProgram(p);
    glUniform1i(glGetUniformLocation(p, "backResolution"), s_.backResolution);
    glUniform1i(glGetUniformLocation(p, "crossGrid"), s_.grid);
    glUniform1f(glGetUniformLocation(p, "backNear"), back_->nearPlane());
    glUniform1f(glGetUniformLocation(p, "backFar"), back_->farPlane());
  }
  glUseProgram(program);
  glUniform1ui(glGetUniformLocation(program, "crossPatchCount"), behindProgram_ ? GLuint(sys_.patchCount()) : 0u);
  glUniform1i(glGetUniformLocation(program, "crossEmitterSide"), emitterSide);
  glUniform1ui(glGetUniformLocation(program, "crossEmitterCount"), 0u);
  for (const GatherRule& rule : rules_) {
    rule.integrate->use();
    glUniform1i(glGetUniformLocation(rule.integrate->id(), "crossEmitterSide"), emitterSide);
    glUniform1ui(glGetUniformLocation(rule.integrate->id(), "crossEmitterCount"), 0u);
  }
}

void CrossRedistribution::gatherMoved(float sign, GLuint elements, GLuint patches, GLuint states,
                                      GLuint amounts, GpuTimeline& timeline) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementBinding, elements);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchBinding, patches);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementStateBinding, states);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionAmountBinding, amounts);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossPatchBinding, patchTable_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossDeltaBinding, deltas_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, gatherEyes_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossEmitterBinding, emitterList_);
  const bool reuse = sign < 0.0f && imagesKept_;
  size_t batch = 0;
  for (const GatherRule& rule : rules_) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionListBinding, rule.list);
    for (size_t first = 0; first < rule.elements.size(); first += perBatch(rule), ++batch) {
      LayeredHemicubes& gather = *gathers_[keepGathers_ ? batch : 0];
      const int count = int(std::min(perBatch(rule), rule.elements.size() - first));
      timeline.mark("gather: eyes");
      rule.eyes->use();
      glUniform1ui(glGetUniformLocation(rule.eyes->id(), "first"), GLuint(first));
      glUniform1ui(glGetUniformLocation(rule.eyes->id(), "count"), GLuint(count));
      glDispatchCompute(groupsOf(size_t(count * rule.samples), kPowerGroup), 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
      if (!reuse) {
        timeline.mark("gather: hemicubes");
        gather.render(0, count * rule.samples);
      }
      timeline.mark("gather: integrate");
      gather.bindTextures();
      rule.integrate->use();
      glUniform1ui(glGetUniformLocation(rule.integrate->id(), "first"), GLuint(first));
      glUniform1f(glGetUniformLocation(rule.integrate->id(), "sign"), sign);
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      glDispatchCompute(GLuint(count), 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
  imagesKept_ = keepGathers_ && sign > 0.0f;
  Context::check("GPU cross-redistribution: the moved elements' gather");
}

}  // namespace luxel::gl
