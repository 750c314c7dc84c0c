#include "gl/gather_gl.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "gl/gpu_system.h"
#include "gl/hemicube.h"
#include "gl/hemicube_glsl.h"
#include "gl/layered_hemicubes.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "core/spherical_harmonics.h"
#include "core/stopwatch.h"
#include "solve/step_control.h"
#include "luxel/error.h"
#include "transport/form_factor.h"

namespace luxel::gl {
namespace {


// One work group per element of the batch: the sum over its k x k hemicubes' pixels of delta
// form factor times radiosity, reduced in shared memory (floats in a fixed order: the same
// answer every run), then the element's new radiosity B = E + rho (H0 + H); and, for directional
// bakes, the same pixels' radiance in spherical harmonics.
const char* kIntegrateCompute = R"(
layout(local_size_x = GATHER_GROUP) in;
layout(binding = DISTANCE_TEXTURE_UNIT) uniform sampler2DArray radiosityLayers;
layout(std430, binding = GATHER_DELTA_BINDING) readonly buffer Deltas { float deltas[]; };
layout(std430, binding = GATHER_ELEMENT_BINDING) readonly buffer GatherElements { GpuGatherElement gatherElements[]; };
layout(std430, binding = GATHER_RESIDUAL_BINDING) buffer Residual { uint maxChange; uint maxRadiosity; };
layout(std430, binding = ELEMENT_STATE_BINDING) buffer ElementStates { GpuElementState states[]; };
layout(std430, binding = SHOOTER_BINDING) readonly buffer Eyes { GpuShooter eyes[]; };
// Directional bakes (Solver::recordIncidentSh): the SH of what this iteration gathered, shCount
// (0, 4 or 9) per element, rgb: each pixel one direction, its centre's.
layout(std430, binding = ELEMENT_SH_BINDING) writeonly buffer ElementSh { vec4 elementSh[]; };
uniform int shCount;
uniform uint firstElement, samples;
uniform int resolution;
uniform bool firstIteration;
void main() {
  const uint local = gl_WorkGroupID.x, e = firstElement + local, tid = gl_LocalInvocationIndex;
  const int perHemicube = 3 * resolution * resolution;  // the top, and four upper halves
  vec3 sum = vec3(0.0), sh[9];
  for (int i = 0; i < 9; ++i) sh[i] = vec3(0.0);
  for (int i = int(tid); i < int(samples) * perHemicube; i += GATHER_GROUP) {
    const int h = i / perHemicube;
    int face, x, y, d;
    hemicubePixel(i % perHemicube, resolution, face, x, y, d);
    const vec3 b = texelFetch(radiosityLayers, ivec3(x, y, (int(local * samples) + h) * 5 + face), 0).rgb;
    sum += deltas[d] * b;
    if (shCount > 0) {
      // The pixel centre's direction.
      const GpuShooter eye = eyes[e * samples + uint(h)];
      const HemicubeFrame f = hemicubeFrame(eye.normal.xyz, eye.normal.w);
      const vec3 w = normalize(hemicubePixelDirection(f, face, x, y, resolution));
      // Radiance b / pi over the pixel's solid angle, pi delta / cos: b delta / cos.
      const vec3 weight = deltas[d] / max(dot(w, f.n), 1e-3) * b;
      // The real SH basis of core/spherical_harmonics.h, bands 0 to 2.
      sh[0] += 0.282095 * weight;
      sh[1] += 0.488603 * w.y * weight, sh[2] += 0.488603 * w.z * weight, sh[3] += 0.488603 * w.x * weight;
      if (shCount > 4) {
        sh[4] += 1.092548 * w.x * w.y * weight, sh[5] += 1.092548 * w.y * w.z * weight;
        sh[6] += 0.315392 * (3.0 * w.z * w.z - 1.0) * weight, sh[7] += 1.092548 * w.x * w.z * weight;
        sh[8] += 0.546274 * (w.x * w.x - w.y * w.y) * weight;
      }
    }
  }
  // One shared array, reduced once per number: the group stays within the 32 KiB OpenGL promises.
  for (int i = 0; i < shCount; ++i) {
    const vec3 total = groupSum(sh[i], tid);
    if (tid == 0u) elementSh[uint(shCount) * e + uint(i)] = vec4(total / float(samples), 0.0);
  }
  const vec3 gathered = groupSum(sum, tid);
  if (tid != 0u) return;
  GpuGatherElement g = gatherElements[e];
  const vec3 h = g.analytic.rgb + gathered / float(samples);
  const vec3 b = g.emissionArea.rgb + g.reflectance.rgb * h;
  GpuElementState st = states[e];
  const vec3 change = abs(b - st.radiosity.rgb);
  // Non-negative floats order as their bits do.
  atomicMax(maxChange, floatBitsToUint(change.r + change.g + change.b));
  atomicMax(maxRadiosity, floatBitsToUint(b.r + b.g + b.b));
  st.radiosity.rgb = b;
  st.irradiance.rgb = h;
  if (firstIteration) st.direct.rgb = h;  // B was E: what arrives is direct
  states[e] = st;
}
)";

// Each patch's area-weighted mean radiosity, which the next iteration renders.
const char* kPatchMeanCompute = R"(
layout(local_size_x = POWER_GROUP) in;
layout(std430, binding = PATCH_BINDING) readonly buffer Patches { GpuPatch patches[]; };
layout(std430, binding = PATCH_ELEMENT_BINDING) readonly buffer PatchElements { uint patchElements[]; };
layout(std430, binding = GATHER_ELEMENT_BINDING) readonly buffer GatherElements { GpuGatherElement gatherElements[]; };
layout(std430, binding = ELEMENT_STATE_BINDING) readonly buffer ElementStates { GpuElementState states[]; };
layout(std430, binding = PATCH_RADIOSITY_BINDING) writeonly buffer PatchRadiosity { vec4 patchRadiosity[]; };
uniform uint patchCount;
void main() {
  const uint p = gl_GlobalInvocationID.x;
  if (p >= patchCount) return;
  GpuPatch P = patches[p];
  vec3 sum = vec3(0.0);
  for (uint i = P.ids.x; i < P.ids.x + P.ids.y; ++i) {
    const uint e = patchElements[i];
    sum += gatherElements[e].emissionArea.w * states[e].radiosity.rgb;
  }
  patchRadiosity[p] = vec4(P.normalArea.w > 0.0 ? sum / P.normalArea.w : vec3(0.0), 0.0);
}
)";

// A turn in [0, pi/2) from the element and sample index: hemicubeTurn of hemicube_glsl.h, in C++.
float hemicubeTurn(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t h = (a * 0x9E3779B1u) ^ (b * 0x85EBCA77u) ^ (c * 0xC2B2AE3Du);
  h ^= h >> 15, h *= 0x2C1B3C6Du, h ^= h >> 12;
  return float(h >> 8) / float(1u << 24) * 1.5707963f;
}

struct Buffers {
  GLuint deltas = 0, gatherElements = 0, residual = 0, states = 0, eyes = 0, patches = 0, patchElements = 0,
         patchRadiosity = 0, elementSh = 0;
  ~Buffers() {
    const GLuint all[] = {deltas, gatherElements, residual, states, eyes, patches, patchElements, patchRadiosity, elementSh};
    glDeleteBuffers(GLsizei(std::size(all)), all);
  }
  void bind() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGatherDeltaBinding, deltas);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGatherElementBinding, gatherElements);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGatherResidualBinding, residual);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementStateBinding, states);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, eyes);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchBinding, patches);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchElementBinding, patchElements);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPatchRadiosityBinding, patchRadiosity);
    if (elementSh) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kElementShBinding, elementSh);
  }
};

class GlGatherSolver final : public Solver {
 public:
  GlGatherSolver(const RadiositySystem& sys, Context& context, const GlGatherSettings& o)
      : sys_(sys), device_(context.renderer()), o_(o) {
    const Stopwatch watch;
    const SurfaceSet& set = sys.surfaces;
    const size_t ne = sys.elementCount(), np = sys.patchCount();
    samples_ = o.samplesPerSide * o.samplesPerSide;
    const float extent = set.sceneExtent > 0.0f ? set.sceneExtent : 1.0f;

    // Receivers: k x k hemicube centres per element (a midpoint rule), lifted off the surface.
    std::vector<GpuShooter> eyes(ne * size_t(samples_));
    std::vector<GpuGatherElement> gatherElements(ne);
    std::vector<GpuElementState> states(ne);
    for (size_t e = 0; e < ne; ++e) {
      const Element& el = set.elements[e];
      for (int j = 0; j < samples_; ++j) {
        const float k = float(o.samplesPerSide);
        const Vec3 x = polygonPoint(el.polygon, (float(j % o.samplesPerSide) + 0.5f) / k,
                                    (float(j / o.samplesPerSide) + 0.5f) / k);
        eyes[e * size_t(samples_) + size_t(j)] = {
            glm::vec4(x + o.offset * extent * el.normal, 0.0f),
            glm::vec4(el.normal, o.randomTurn ? hemicubeTurn(uint32_t(e), uint32_t(j), 0u) : 0.0f), glm::vec4(0.0f),
            glm::vec4(0.0f), glm::uvec4(0u, 1u, 0u, 0u)};
      }
      gatherElements[e] = {glm::vec4(sys.emission[e], sys.area[e]), glm::vec4(sys.reflectance[e], 0.0f),
                           glm::vec4(sys.analytic[e], 0.0f)};
      // Jacobi from B = E, so that the first iteration gathers the direct light alone.
      states[e] = {glm::vec4(sys.emission[e], 0.0f), glm::vec4(0.0f), glm::vec4(sys.analytic[e], 0.0f),
                   glm::vec4(sys.analytic[e], 0.0f)};
    }
    const GpuPatches patches = gpuPatches(sys);
    std::vector<Polygon> patchPolygons(np);
    std::vector<uint32_t> patchItems(np);
    std::vector<glm::vec4> patchRadiosity(np);  // B = E to start with
    for (size_t p = 0; p < np; ++p) {
      patchPolygons[p] = set.patches[p].polygon;
      patchItems[p] = uint32_t(p + 1);
      patchRadiosity[p] = patches.patches[p].emission;
    }

    // As many elements per batch as fit the layer memory: per pixel an item, an RGBA32F colour and
    // a depth, for the five faces of each of the element's k x k hemicubes.
    const size_t bytesPerElement = size_t(samples_) * 5 * size_t(o.resolution) * size_t(o.resolution) * 24;
    GLint maxLayers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (5 * size_t(samples_) > size_t(maxLayers))
      throw Error(fmt::format("{} hemicubes per element need more texture layers than this OpenGL's {}", samples_, maxLayers));
    batch_ = std::clamp<size_t>(o.layerBytes / bytesPerElement, 1,
                                std::min<size_t>(std::max<size_t>(ne, 1), size_t(maxLayers) / (5 * size_t(samples_))));
    hemicubes_ = std::make_unique<LayeredHemicubes>(patchPolygons, patchItems, LayeredHemicubes::Content::Radiosity,
                                                    o.resolution, int(batch_) * samples_, o.nearPlane * extent,
                                                    2.0f * extent);

    const DeltaFormFactors deltas(o.resolution);
    std::vector<float> deltaTable(deltas.top);
    deltaTable.insert(deltaTable.end(), deltas.side.begin(), deltas.side.end());
    buf_.deltas = storageBuffer(deltaTable.data(), deltaTable.size() * sizeof(float));
    buf_.gatherElements = storageBuffer(gatherElements.data(), gatherElements.size() * sizeof(GpuGatherElement));
    buf_.residual = storageBuffer(nullptr, 2 * sizeof(uint32_t));
    buf_.states = storageBuffer(states.data(), states.size() * sizeof(GpuElementState));
    buf_.eyes = storageBuffer(eyes.data(), eyes.size() * sizeof(GpuShooter));
    buf_.patches = storageBuffer(patches.patches.data(), patches.patches.size() * sizeof(GpuPatch));
    buf_.patchElements = storageBuffer(patches.elements.data(), patches.elements.size() * sizeof(uint32_t));
    buf_.patchRadiosity = storageBuffer(patchRadiosity.data(), patchRadiosity.size() * sizeof(glm::vec4));

    const std::string preamble = glslPreamble();
    integrate_ = std::make_unique<ShaderProgram>("radiosity hemicube integration",
                                                 preamble + kHemicubeGlsl + kGroupSumGlsl + kIntegrateCompute);
    patchMean_ = std::make_unique<ShaderProgram>("patch mean radiosity", preamble + kPatchMeanCompute);
    integrate_->use();
    glUniform1ui(glGetUniformLocation(integrate_->id(), "samples"), GLuint(samples_));
    glUniform1i(glGetUniformLocation(integrate_->id(), "resolution"), o.resolution);
    firstElement_ = glGetUniformLocation(integrate_->id(), "firstElement");
    firstIteration_ = glGetUniformLocation(integrate_->id(), "firstIteration");
    glUniform1i(glGetUniformLocation(integrate_->id(), "shCount"), 0);
    patchMean_->use();
    glUniform1ui(glGetUniformLocation(patchMean_->id(), "patchCount"), GLuint(np));
    Context::check("setting up GPU gathering");
    setupSeconds_ = watch.seconds();
  }

  bool step(const StepLimit& limit, const ProgressCallback& progress) override {
    const Stopwatch watch;
    buf_.bind();  // another solver may have used the context since the last step
    uint64_t units = 0;
    while (!done_) {
      if (sliceSpent(limit, units, watch)) break;
      iterate(progress);
      ++units;
    }
    seconds_ += watch.seconds();
    return !done_;
  }

  bool done() const override { return done_; }

  Solution solution() override {
    const Stopwatch watch;
    const size_t ne = sys_.elementCount();
    std::vector<GpuElementState> states(ne);
    glGetNamedBufferSubData(buf_.states, 0, GLsizeiptr(ne * sizeof(GpuElementState)), states.data());
    Context::check("reading back the GPU solution");
    Solution sol = solutionFromStates(states);
    seconds_ += watch.seconds();
    sol.stats = stats();
    return sol;
  }

  // L1 or L2. Each iteration gathers everything again, so its directions replace the last's: they
  // are the solution's once an iteration has run with them on.
  void recordIncidentSh(int count) override {
    if ((count != kShL1Coefficients && count != kShCoefficients) || buf_.elementSh) return;
    const std::vector<glm::vec4> zero(size_t(count) * sys_.elementCount(), glm::vec4(0.0f));
    buf_.elementSh = storageBuffer(zero.data(), zero.size() * sizeof(glm::vec4));
    shCount_ = count;
    buf_.bind();
    integrate_->use();
    glUniform1i(glGetUniformLocation(integrate_->id(), "shCount"), count);
    Context::check("recording directions on the GPU");
  }

  bool incidentSh(int count, std::span<Rgb> out) override {
    if (count != shCount_ || !shRecorded_) return false;  // the owner gathers them by rays
    std::vector<glm::vec4> sh(size_t(count) * sys_.elementCount());
    glGetNamedBufferSubData(buf_.elementSh, 0, GLsizeiptr(sh.size() * sizeof(glm::vec4)), sh.data());
    Context::check("reading back the GPU's directions");
    for (size_t i = 0; i < sh.size(); ++i) out[i] = Rgb(sh[i]);
    return true;
  }

  // The element states and patch means, read back from the GPU, and the iteration's counters.
  // Recorded directions are not kept: a resumed solve records them at its next iteration.
  bool checkpoints() const override { return true; }
  void saveState(StateWriter& out) const override {
    for (GLuint b : {buf_.states, buf_.patchRadiosity}) saveBuffer(b, out);
    out.value(iteration_), out.value(residual_), out.value(uint64_t(rendered_)), out.value(seconds_), out.value(done_);
    stagnation_.saveState(out);
  }
  void restoreState(StateReader& in) override {
    for (GLuint b : {buf_.states, buf_.patchRadiosity}) restoreBuffer(b, in);
    shRecorded_ = false;
    in.value(iteration_), in.value(residual_);
    rendered_ = size_t(in.value<uint64_t>());
    in.value(seconds_), in.value(done_);
    stagnation_.restoreState(in);
  }

  SolveStats stats() const override {
    SolveStats st;
    st.method = "gather";
    st.backend = "gl";
    st.device = device_;
    st.iterations = uint64_t(iteration_);
    st.residual = residual_;
    st.hemicubes = rendered_;
    st.secondsFormFactors = setupSeconds_ + seconds_;
    return st;
  }

 private:
  void iterate(const ProgressCallback& progress) {
    const size_t ne = sys_.elementCount(), np = sys_.patchCount();
    ++iteration_;
    const uint32_t zero[2] = {0, 0};
    glNamedBufferSubData(buf_.residual, 0, sizeof zero, zero);
    for (size_t first = 0; first < ne; first += batch_) {
      const size_t count = std::min(batch_, ne - first);
      hemicubes_->render(int(first) * samples_, int(count) * samples_);
      rendered_ += count * size_t(samples_);
      hemicubes_->bindTextures();
      integrate_->use();
      glUniform1ui(firstElement_, GLuint(first));
      glUniform1i(firstIteration_, iteration_ == 1);
      glDispatchCompute(GLuint(count), 1, 1);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    patchMean_->use();
    glDispatchCompute(GLuint((np + kPowerGroup - 1) / kPowerGroup), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    shRecorded_ = buf_.elementSh != 0;
    uint32_t bits[2] = {0, 0};
    glGetNamedBufferSubData(buf_.residual, 0, sizeof bits, bits);
    Context::check("GPU gathering");
    float change = 0.0f, largest = 0.0f;
    std::memcpy(&change, &bits[0], sizeof change);
    std::memcpy(&largest, &bits[1], sizeof largest);
    residual_ = largest > 0.0f ? double(change) / double(largest) : 0.0;
    if (iteration_ >= o_.maxIterations) done_ = true;
    if (iteration_ > 1 && residual_ <= o_.residualThreshold) done_ = true;  // the first only starts from E
    if (stagnation_.stalled(residual_)) done_ = true;
    // Last, so that a cancel read here leaves the iteration's state whole (a checkpoint saves it).
    reportProgress(progress, "solve",
                   std::clamp(std::log(std::max(residual_, 1e-30)) / std::log(o_.residualThreshold), 0.0, 1.0),
                   fmt::format("residual {:.2e}", residual_));
  }

  const RadiositySystem& sys_;
  // Read once: stats() may be asked while another session's context is current (luxel animate
  // --error solves each frame's reference in its own).
  const std::string device_;
  const GlGatherSettings o_;
  Buffers buf_;
  std::unique_ptr<LayeredHemicubes> hemicubes_;
  std::unique_ptr<ShaderProgram> integrate_, patchMean_;
  GLint firstElement_ = -1, firstIteration_ = -1;
  int samples_ = 0;
  size_t batch_ = 1;
  double residual_ = 1.0;
  StagnationStop stagnation_;
  int iteration_ = 0;
  uint64_t rendered_ = 0;
  double setupSeconds_ = 0.0, seconds_ = 0.0;
  bool done_ = false;
  bool shRecorded_ = false;  // the last iteration recorded its directions in buf_.elementSh
  int shCount_ = 0;          // recordIncidentSh's count
};

}  // namespace

std::unique_ptr<Solver> makeGlGatherSolver(const RadiositySystem& system, Context& context,
                                           const GlGatherSettings& settings) {
  if (settings.samplesPerSide < 1 || settings.samplesPerSide > 8)
    throw Error("hemicubes per element side must be in 1..8");
  return std::make_unique<GlGatherSolver>(system, context, settings);
}

}  // namespace luxel::gl
