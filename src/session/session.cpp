#include "luxel/session.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "luxel/error.h"
#include "core/spherical_harmonics.h"
#include "session/solver_host.h"

namespace luxel {

namespace {
void checkShCount(int count) {
  if (count != kShL1Coefficients && count != kShCoefficients)
    throw Error(fmt::format("incident SH: {} coefficients per channel; 4 (L1) or 9 (L2) expected", count));
}
}  // namespace

struct Session::State {
  Scene scene;
  SurfaceSet surfaces;
  std::unique_ptr<gl::Context> borrowed;  // the caller's context, wrapped; declared before the host
  std::unique_ptr<SolverHost> host;

  void makeHost(const SessionOptions& options) {
    BorrowedResources lent;
    if (options.borrowCurrentGlContext && options.solve.backend != "cpu") {
      borrowed = std::make_unique<gl::Context>(gl::Context::BorrowCurrent{});
      lent.glContext = borrowed.get();
    }
    if (options.incidentShCount != 0) checkShCount(options.incidentShCount);
    host = std::make_unique<SolverHost>(scene, surfaces, options.solve, lent, options.incidentShCount);
  }
};


Session::Session(Scene scene, const DiscretiseOptions& discretise, const SessionOptions& options)
    : state_(std::make_unique<State>()) {
  validateSolveOptions(options.solve);  // before the discretisation, which can take a while
  state_->scene = std::move(scene);
  state_->surfaces = luxel::discretise(state_->scene, discretise);
  if (!options.keepPatches && !mayShootFromPatches(options.solve, state_->surfaces)) state_->surfaces.dropPatches();
  state_->makeHost(options);
}

Session::Session(Scene scene, SurfaceSet surfaces, const SessionOptions& options) : state_(std::make_unique<State>()) {
  state_->scene = std::move(scene);
  state_->surfaces = std::move(surfaces);
  state_->makeHost(options);
}

Session::~Session() = default;

const Scene& Session::scene() const { return state_->scene; }
const SurfaceSet& Session::surfaces() const { return state_->surfaces; }
const std::string& Session::backend() const { return state_->host->backend(); }
bool Session::step(const StepLimit& limit, const ProgressCallback& progress) { return state_->host->step(limit, progress); }
bool Session::done() const { return state_->host->done(); }
Solution Session::solution() { return state_->host->solution(); }
SolveStats Session::stats() const { return state_->host->stats(); }

Session::Solved Session::release() && {
  state_->host.reset();  // the solver refers to the surfaces: it goes first
  state_->borrowed.reset();
  Solved out{std::move(state_->scene), std::move(state_->surfaces)};
  state_.reset();
  return out;
}

Solution Session::solve(const ProgressCallback& progress) {
  while (step({}, progress)) {
  }
  return solution();
}

void Session::placeObjects(const std::vector<std::pair<uint32_t, glm::mat4>>& placements) {
  // Every placement is checked before any is made: a bad one leaves the session as it was.
  for (const auto& [object, transform] : placements) state_->scene.checkPlacement(object, transform);
  std::vector<uint32_t> moved;
  for (const auto& [object, transform] : placements) {
    state_->scene.placeObject(object, transform);
    state_->surfaces.placeObject(state_->scene, object);
    moved.push_back(object);
  }
  state_->host->objectsMoved(moved);
}

void Session::setLights(std::vector<Light> lights) {
  Scene& scene = state_->scene;
  std::swap(scene.lights, lights);
  try {
    scene.validateLights();
  } catch (...) {
    std::swap(scene.lights, lights);
    throw;
  }
  state_->host->sourcesChanged();
}

void Session::setMaterial(uint32_t material, const Rgb& reflectance, const Rgb& emission) {
  Scene& scene = state_->scene;
  if (material >= scene.materials.size())
    throw Error(fmt::format("scene '{}' has no material {} ({} materials)", scene.name, material, scene.materials.size()));
  Material& m = scene.materials[material];
  const Material before = m;
  m.reflectance = reflectance, m.emission = emission;
  try {
    scene.validateMaterials();
  } catch (...) {
    m = before;
    throw;
  }
  state_->surfaces.refreshMaterials(scene);
  state_->host->sourcesChanged();
}

std::vector<Rgb> Session::incidentSh(int count) {
  checkShCount(count);
  return state_->host->incidentSh(count);
}

void Session::recordIncidentSh(int count) {
  checkShCount(count);
  state_->host->recordIncidentSh(count);
}

Camera Session::camera(const std::string& name, float fovY) const { return chooseCamera(state_->scene, name, fovY); }

std::vector<Rgb> Session::lightIrradiance(std::span<const uint32_t> lights) {
  for (uint32_t i : lights)
    if (i >= state_->scene.lights.size())
      throw Error(fmt::format("light {} does not exist: the scene has {} lights", i, state_->scene.lights.size()));
  return state_->host->lightIrradiance(lights);
}

Camera chooseCamera(const Scene& scene, const std::string& name, float fovY) {
  if (!name.empty()) {
    if (const Camera* c = scene.findCamera(name)) return *c;
    std::string names;
    for (const Camera& k : scene.cameras) names += (names.empty() ? "" : ", ") + k.name;
    throw Error(fmt::format("scene '{}' has no camera '{}' (cameras: {})", scene.name, name, names.empty() ? "none" : names));
  }
  if (const Camera* d = scene.findCamera("default")) return *d;
  if (!scene.cameras.empty()) return scene.cameras.front();
  // None: frame the bounding box from +z.
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Mesh& m : scene.meshes)
    for (const Vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const Vec3 centre = 0.5f * (lo + hi);
  const float radius = 0.5f * glm::length(hi - lo);
  Camera c;
  c.name = "framing";
  c.fovY = fovY > 0.0f ? fovY : 45.0f;
  c.target = centre;
  c.eye = centre + Vec3(0.0f, 0.0f, 1.1f * radius / std::tan(glm::radians(c.fovY) * 0.5f));
  c.up = Vec3(0, 1, 0);
  return c;
}

}  // namespace luxel
