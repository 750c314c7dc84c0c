#include "gl/cross_redistribution_gl.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "gl/gpu_system.h"
#include "gl/hemicube.h"
#include "gl/layered_hemicubes.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "luxel/error.h"

namespace luxel::gl {

const char* const kCrossProjectionGlsl = R"(
layout(binding = BACK_ITEM_TEXTURE_UNIT) uniform usampler2DArray backItems;
layout(binding = BACK_DISTANCE_TEXTURE_UNIT) uniform sampler2DArray backDistances;
layout(std430, binding = BACK_SHOOTER_BINDING) readonly buffer BackShooters { GpuShooter backShooters[]; };
layout(std430, binding = CROSS_PATCH_BINDING) readonly buffer CrossPatches { uvec2 crossPatches[]; };
layout(std430, binding = REDISTRIBUTION_AMOUNT_BINDING) readonly buffer CrossAmounts { vec4 crossAmounts[]; };
uniform int backResolution, crossGrid;
uniform float backNear, backFar;

// The pixel of back hemicube k (frame f, centre eye) that direction r falls on; z < 0: none.
ivec3 backPixel(uint k, HemicubeFrame f, vec3 eye, vec3 r) {
  const int face = hemicubeFace(r, f);
  const vec4 c = hemicubeClip(eye + r, eye, f, face, backNear, backFar);
  if (!(c.w > 0.0)) return ivec3(-1);
  const vec2 pixel = (c.xy / c.w * 0.5 + 0.5) * float(backResolution);
  return ivec3(clamp(ivec2(floor(pixel)), ivec2(0), ivec2(backResolution - 1)), int(k) * 5 + face);
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
// across it, as from a box's side face to a light just above the box (the GPU test's scene:
// static direct light 70% off). Steps grow geometrically from near the patch to the far plane;
// a crossing deeper than the step is the ray passing behind something nearer the centre, not a
// hit, and the march goes on; the crossing is then narrowed by bisection. ~0u: nothing.
uint marchedPatch(uint k, HemicubeFrame f, vec3 eye, vec3 q, vec3 d) {
  const int steps = 32;
  const float tMin = 1e-4 * backFar, ratio = pow(backFar / tMin, 1.0 / float(steps));
  const float pixelAngle = 2.0 / float(backResolution);
  float before = 0.0, t = tMin;
  ivec3 pixel, first = ivec3(-1);
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

void crossProjected(uint k, vec3 x, vec3 n, GpuPatch P, out vec3 shot, out vec3 emitted) {
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
}
)";

namespace {

// Centres of the moved elements' gather hemicubes, from the elements as the GPU holds them (the
// old geometry before the move's upload, the new after it): the reconstruction's 2 x 2 midpoint
// rule over each element, so that the gather and the shots that lit the element before estimate
// the same mean (one hemicube at the centre left the box's elements under the Cornell light 6%
// from the shots' figure).
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
  const vec3 x = polygonPoint(el.corners, int(el.corners[0].w), 0.25 + 0.5 * float(q & 1u), 0.25 + 0.5 * float(q >> 1));
  GpuShooter s;
  s.eye = vec4(x + offset * el.normalArea.xyz, 0.0);
  s.normal = vec4(el.normalArea.xyz, hemicubeTurn(e, q, 0x5EEDu));
  s.unshot = vec4(0.0);
  s.emission = vec4(0.0);
  s.ids = uvec4(e, 1u, 0u, 0u);
  shooters[i] = s;
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
uniform uint first;
uniform int resolution;
uniform float sign;
shared vec3 partial[GATHER_GROUP];

vec3 groupSum(vec3 value, uint tid) {
  barrier();
  partial[tid] = value;
  barrier();
  for (uint w = GATHER_GROUP / 2; w > 0u; w >>= 1) {
    if (tid < w) partial[tid] += partial[tid + w];
    barrier();
  }
  return partial[0];
}

void main() {
  const uint local = gl_WorkGroupID.x, tid = gl_LocalInvocationIndex, e = list[first + local];
  const int half_ = resolution / 2, top = resolution * resolution, side = resolution * half_;
  vec3 shot = vec3(0.0), emitted = vec3(0.0);
  for (int i = int(tid); i < GATHER_SAMPLES * (top + 4 * side); i += GATHER_GROUP) {
    const int h = i / (top + 4 * side), k = i % (top + 4 * side);
    const GpuShooter eye = shooters[local * GATHER_SAMPLES + uint(h)];
    const HemicubeFrame f = hemicubeFrame(eye.normal.xyz, eye.normal.w);
    int face, x, y, d;
    if (k < top) {
      face = 0; x = k % resolution; y = k / resolution; d = k;
    } else {  // the upper half of a side face: rows half_ .. resolution-1
      const int j = k - top, r = j % side;
      face = 1 + j / side; x = r % resolution; y = half_ + r / resolution; d = top + r;
    }
    const uint item = texelFetch(items, ivec3(x, y, (int(local) * GATHER_SAMPLES + h) * 5 + face), 0).r;
    if (item == 0u) continue;
    // The pixel centre's direction (hemicubeClip's conventions inverted), to tell which side of
    // the patch it shows.
    vec3 fwd, up;
    if (face == 0) { fwd = f.n; up = f.b; }
    else { up = f.n; fwd = face == 1 ? f.t : face == 2 ? -f.t : face == 3 ? f.b : -f.b; }
    const vec3 s = normalize(cross(fwd, up)), u = cross(s, fwd);
    const vec2 ndc = (vec2(x, y) + 0.5) / float(resolution) * 2.0 - 1.0;
    const vec3 w = fwd + ndc.x * s + ndc.y * u;
    uint p = item - 1u;
    if (dot(patches[p].normalArea.xyz, w) >= 0.0) p = crossPatches[p].y;
    if (p == 0xFFFFFFFFu || crossPatches[p].x != 0u) continue;
    shot += deltas[d] * amounts[2u * p].rgb;
    emitted += deltas[d] * amounts[2u * p + 1u].rgb;
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

// Gather hemicubes per moved element (the 2 x 2 rule above).
constexpr int kGatherSamples = 4;
const std::string kGatherSamplesGlsl = fmt::format("#define GATHER_SAMPLES {}\n", kGatherSamples);

GLuint groupsOf(size_t n, int size) { return GLuint((n + size_t(size) - 1) / size_t(size)); }

// A two-sided face's patches are drawn once, from the face with the smaller index: the two sides
// coincide and would z-fight.
bool drawn(const SurfaceSet& set, uint32_t patch) {
  const int32_t twin = set.faces[set.patches[patch].face].twin;
  return twin < 0 || uint32_t(twin) > set.patches[patch].face;
}

}  // namespace

CrossRedistribution::CrossRedistribution(const RadiositySystem& system, std::vector<uint32_t> objectOfPatch,
                                         const CrossRedistributionSettings& settings, int backCapacity,
                                         float nearPlane, float farPlane, float offset, const std::string& preamble)
    : sys_(system), objectOfPatch_(std::move(objectOfPatch)), s_(settings), backCapacity_(backCapacity),
      offset_(offset) {
  const SurfaceSet& set = sys_.surfaces;
  const size_t np = set.patches.size();
  if (objectOfPatch_.size() != np) throw Error("cross-redistribution: an object for every patch is needed");
  if (s_.gatherResolution < 8 || s_.gatherResolution % 2 || s_.backResolution < 4 || s_.backResolution % 2)
    throw Error(fmt::format("cross-redistribution: hemicube resolutions {} and {} must be even and at least 8 and 4",
                            s_.gatherResolution, s_.backResolution));
  if (s_.grid < 1 || s_.grid > 16) throw Error(fmt::format("cross-redistribution: grid {} must be in 1..16", s_.grid));
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

  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  gatherCapacity_ = std::clamp(int(maxLayers) / (5 * kGatherSamples), 1, 32);  // elements a batch
  std::vector<Polygon> polygons;
  std::vector<uint32_t> items;
  for (uint32_t p = 0; p < np; ++p)
    if (drawn(set, p)) polygons.push_back(set.patches[p].polygon), items.push_back(p + 1);
  gather_ = std::make_unique<LayeredHemicubes>(polygons, items, LayeredHemicubes::Content::ItemsAndDistances,
                                               s_.gatherResolution, gatherCapacity_ * kGatherSamples, nearPlane,
                                               farPlane);
  back_ = std::make_unique<LayeredHemicubes>(polygons, items, LayeredHemicubes::Content::ItemsAndDistances,
                                             s_.backResolution, std::max(backCapacity_, 1), nearPlane, farPlane);
  const DeltaFormFactors deltas(s_.gatherResolution);
  std::vector<float> table(deltas.top);
  table.insert(table.end(), deltas.side.begin(), deltas.side.end());
  deltas_ = storageBuffer(table.data(), table.size() * sizeof(float));
  backShooters_ = storageBuffer(nullptr, size_t(std::max(backCapacity_, 1)) * sizeof(GpuShooter));
  gatherEyes_ = storageBuffer(nullptr, size_t(gatherCapacity_ * kGatherSamples) * sizeof(GpuShooter));
  patchTable_ = storageBuffer(nullptr, std::max<size_t>(np, 1) * sizeof(glm::uvec2));
  uploadPatchTable();

  eyes_ = std::make_unique<ShaderProgram>("cross-redistribution gather centres",
                                          preamble + kGatherSamplesGlsl + kGatherEyesCompute);
  integrate_ = std::make_unique<ShaderProgram>("cross-redistribution gather",
                                               preamble + kGatherSamplesGlsl + kGatherIntegrateCompute);
  eyes_->use();
  glUniform1f(glGetUniformLocation(eyes_->id(), "offset"), offset_);
  integrate_->use();
  glUniform1i(glGetUniformLocation(integrate_->id(), "resolution"), s_.gatherResolution);
  Context::check("setting up GPU cross-redistribution");
}

CrossRedistribution::~CrossRedistribution() {
  const GLuint all[] = {patchTable_, backShooters_, gatherEyes_, elementList_, deltas_};
  glDeleteBuffers(GLsizei(std::size(all)), all);
}

void CrossRedistribution::uploadPatchTable() {
  std::vector<glm::uvec2> table(moved_.size());
  for (size_t p = 0; p < table.size(); ++p) table[p] = glm::uvec2(moved_[p], twinPatch_[p]);
  if (!table.empty()) glNamedBufferSubData(patchTable_, 0, GLsizeiptr(table.size() * sizeof(glm::uvec2)), table.data());
}

void CrossRedistribution::begin(std::span<const uint32_t> objects) {
  std::vector<uint32_t> sorted(objects.begin(), objects.end());
  std::sort(sorted.begin(), sorted.end());
  if (sorted == movedObjects_) return;
  movedObjects_ = std::move(sorted);
  const SurfaceSet& set = sys_.surfaces;
  for (size_t p = 0; p < moved_.size(); ++p)
    moved_[p] = std::binary_search(movedObjects_.begin(), movedObjects_.end(), objectOfPatch_[p]) ? 1 : 0;
  uploadPatchTable();
  movedElements_.clear();
  for (uint32_t e = 0; e < set.elements.size(); ++e)
    if (moved_[set.elements[e].patch]) movedElements_.push_back(e);
  glDeleteBuffers(1, &elementList_);
  elementList_ = storageBuffer(movedElements_.data(), std::max<size_t>(movedElements_.size(), 1) * sizeof(uint32_t));
  // The back hemicubes show the patches that stay: those do not move, so once per moved set.
  std::vector<Polygon> polygons;
  std::vector<uint32_t> items;
  for (uint32_t p = 0; p < moved_.size(); ++p)
    if (!moved_[p] && drawn(set, p)) polygons.push_back(set.patches[p].polygon), items.push_back(p + 1);
  back_->setPolygons(polygons, items);
  Context::check("GPU cross-redistribution: the moved set");
}

void CrossRedistribution::geometryMoved() {
  const SurfaceSet& set = sys_.surfaces;
  std::vector<Polygon> polygons;
  std::vector<uint32_t> items;
  for (uint32_t p = 0; p < set.patches.size(); ++p)
    if (drawn(set, p)) polygons.push_back(set.patches[p].polygon), items.push_back(p + 1);
  gather_->setPolygons(polygons, items);
}

void CrossRedistribution::renderBackHemicubes(int count) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, backShooters_);
  back_->render(0, count);
  hemicubes_ += uint64_t(count);
}

void CrossRedistribution::bindForReconstruction() const {
  back_->bindTextures(kBackItemTextureUnit, kBackDistanceTextureUnit);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossPatchBinding, patchTable_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBackShooterBinding, backShooters_);
}

void CrossRedistribution::setReconstructionUniforms(GLuint program) const {
  glUseProgram(program);
  glUniform1i(glGetUniformLocation(program, "backResolution"), s_.backResolution);
  glUniform1i(glGetUniformLocation(program, "crossGrid"), s_.grid);
  glUniform1f(glGetUniformLocation(program, "backNear"), back_->nearPlane());
  glUniform1f(glGetUniformLocation(program, "backFar"), back_->farPlane());
}

void CrossRedistribution::gatherMoved(float sign, GLuint elements, GLuint patches, GLuint states, GLuint amounts) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementBinding, elements);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchBinding, patches);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementStateBinding, states);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionAmountBinding, amounts);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kRedistributionListBinding, elementList_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossPatchBinding, patchTable_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCrossDeltaBinding, deltas_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, gatherEyes_);
  for (size_t first = 0; first < movedElements_.size(); first += size_t(gatherCapacity_)) {
    const int count = int(std::min(size_t(gatherCapacity_), movedElements_.size() - first));
    eyes_->use();
    glUniform1ui(glGetUniformLocation(eyes_->id(), "first"), GLuint(first));
    glUniform1ui(glGetUniformLocation(eyes_->id(), "count"), GLuint(count));
    glDispatchCompute(groupsOf(size_t(count * kGatherSamples), kPowerGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gather_->render(0, count * kGatherSamples);
    gather_->bindTextures();
    integrate_->use();
    glUniform1ui(glGetUniformLocation(integrate_->id(), "first"), GLuint(first));
    glUniform1f(glGetUniformLocation(integrate_->id(), "sign"), sign);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glDispatchCompute(GLuint(count), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    hemicubes_ += uint64_t(count * kGatherSamples);
  }
  Context::check("GPU cross-redistribution: the moved elements' gather");
}

}  // namespace luxel::gl
