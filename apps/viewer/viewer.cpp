#include "viewer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>

#include "glb_lightmap_pages.h"
#include "luxel/error.h"
#include "luxel/lightmap.h"
#include "luxel/render.h"
#include "render/corner_values.h"
#include "scene_json_writer.h"
#include "transfer_light.h"
#include "view_shaders.h"

namespace luxel::viewer {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// Shift makes walking this much faster.
constexpr float kRunFactor = 4.0f;
// Mouse look: radians per pixel of motion.
constexpr float kLookPerPixel = 0.004f;

std::vector<Rgb> minus(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  std::vector<Rgb> out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = glm::max(a[i] - (i < b.size() ? b[i] : Rgb(0.0f)), Rgb(0.0f));
  return out;
}

bool isFalseColourView(ViewMode m) {
  return m == ViewMode::Patches || m == ViewMode::Elements || m == ViewMode::Density || m == ViewMode::Unshot ||
         m == ViewMode::Texels;
}

// The unshot view's heat per element: its unshot power (unshot radiosity times area, summed over
// channels) on a log scale over six decades below the most.
std::vector<float> unshotHeat(const SurfaceSet& surfaces, const std::vector<Rgb>& unshot) {
  if (unshot.size() != surfaces.elements.size()) return {};
  std::vector<float> power(unshot.size());
  float most = 0.0f;
  for (size_t e = 0; e < unshot.size(); ++e) {
    const Rgb& u = unshot[e];
    power[e] = std::abs(u.x) + std::abs(u.y) + std::abs(u.z);  // dynamic solvers shoot negative light too
    power[e] *= surfaces.elements[e].area;
    most = std::max(most, power[e]);
  }
  for (float& p : power) p = most > 0.0f && p > 0.0f ? std::clamp(1.0f + std::log10(p / most) / 6.0f, 0.0f, 1.0f) : 0.0f;
  return power;
}

}  // namespace

Viewer::Viewer(Scene scene, ViewerOptions options)
    : original_(scene),
      loaded_(std::move(scene)),
      options_(std::move(options)),
      camera_(options_.camera, loaded_.up, 1.0f) {
  if (options_.texelsPerMetre <= 0.0f) options_.texelsPerMetre = defaultTexelsPerMetre(loaded_);
  target_ = std::make_unique<HdrTarget>(options_.width, options_.height, /*fullFloat=*/false);
  tone_ = std::make_unique<ToneMapPass>(shaderSource("tone.vert", options_.shaderDir),
                                        shaderSource("tone.frag", options_.shaderDir));
  if (options_.baked) bakedRenderer_ = std::make_unique<BakedRenderer>(*options_.baked, options_.shaderDir);
  if (options_.baked && options_.baked->transfer.bands > 0) {
    transferLight_ = options_.baked->transfer;
    relightTransfer();
    if (!transferLight_.suns.empty()) {
      const auto [az, el] = sunAngles(loaded_.up, transferLight_.suns[0].direction);
      ui_.transferSun[0] = az, ui_.transferSun[1] = el;
    }
  }
  if (options_.mode == ViewMode::Baked && !bakedRenderer_)
    throw Error(fmt::format("the baked view needs a glb written by luxel bake; '{}' is not one", options_.sceneName));
  startSession();
  camera_ = ViewCamera(options_.camera, loaded_.up, session_->surfaces().sceneExtent);
  pivot_ = sceneCentre();
}

Viewer::~Viewer() = default;

void Viewer::startSession() {
  SessionOptions so;
  so.solve = options_.solve;
  so.solve.followsChanges = true;  // edits continue from the last solution where the solver can
  so.borrowCurrentGlContext = options_.shareContext;
  so.keepPatches = true;  // the patches view draws them
  // The new session gets the scene as it stands now (edited lights and poses included).
  Scene scene = session_ ? session_->scene() : loaded_;
  for (size_t i = 0; i < scene.objects.size() && i < loaded_.objects.size(); ++i)
    scene.objects[i].dynamic = loaded_.objects[i].dynamic;
  // Made before the old one goes: when it cannot be made (no GL backend, say) the viewer goes on
  // with the old one.
  auto next = std::make_unique<Session>(std::move(scene), options_.discretise, so);
  session_ = std::move(next);
  cornerGroups_.reset();
  texelRenderer_.reset();
  measureScene();
  if (!renderer_) {
    renderer_ = std::make_unique<SceneRenderer>(session_->scene(), session_->surfaces(), options_.shaderDir);
    renderer_->setShadowMethod(options_.shadows);
  } else
    renderer_->setGeometry(session_->scene(), session_->surfaces());
  afterSourcesChanged();
  zeroFields();
  solutionShown_ = false;
}

void Viewer::afterSourcesChanged() {
  const Scene& scene = session_->scene();
  perPixel_.clear();
  for (uint32_t i = 0; i < scene.lights.size() && perPixel_.size() < size_t(kMaxPerPixelLights); ++i)
    if (drawnPerPixel(scene.lights[i])) perPixel_.push_back(i);
  perPixelIrradiance_ = session_->lightIrradiance(perPixel_);
  renderer_->setLights(scene, perPixel_);
  fieldsStale_ = true;
}

void Viewer::afterGeometryChanged() {
  cornerGroups_.reset();
  texelRenderer_.reset();  // validity depends on where everything is
  measureScene();
  renderer_->setGeometry(session_->scene(), session_->surfaces());
  perPixelIrradiance_ = session_->lightIrradiance(perPixel_);
  renderer_->setLights(session_->scene(), perPixel_);
  fieldsStale_ = true;
}

void Viewer::zeroFields() {
  const std::vector<Rgb> zero(session_->surfaces().elements.size() * 4, Rgb(0.0f));
  renderer_->setFields(zero, zero, zero);
}

void Viewer::refreshFields() {
  const auto start = Clock::now();
  const SurfaceSet& surfaces = session_->surfaces();
  Solution sol = session_->solution();
  // Adaptive refinement (--refine) splits elements as the solve goes: draw the new cut.
  if (perPixelIrradiance_.size() != surfaces.elements.size()) afterGeometryChanged();
  // Which elements meet at each corner changes only with the geometry.
  if (!cornerGroups_) cornerGroups_ = std::make_unique<CornerGroups>(surfaces, kDefaultCreaseCosine);
  const std::vector<Rgb> field = elementCornerValues(surfaces, *cornerGroups_, minus(sol.irradiance, perPixelIrradiance_));
  const std::vector<Rgb> direct = elementCornerValues(surfaces, *cornerGroups_, minus(sol.directIrradiance, perPixelIrradiance_));
  const std::vector<Rgb> perPixel = elementCornerValues(surfaces, *cornerGroups_, perPixelIrradiance_);
  renderer_->setFields(field, direct, perPixel);
  renderer_->setUnshot(unshotHeat(surfaces, sol.unshot));
  unshotKnown_ = !sol.unshot.empty();
  lastRefresh_ = Clock::now();
  lastRefreshSeconds_ = std::chrono::duration<double>(lastRefresh_ - start).count();
  fieldsStale_ = false;
  solutionShown_ = true;
}

void Viewer::markEdit(const std::string& what) { pendingEdits_.push_back({what, Clock::now(), false}); }

Vec3 Viewer::sceneCentre() const { return centre_; }

void Viewer::measureScene() {
  const SurfaceSet& s = session_->surfaces();
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const SurfaceFace& f : s.faces)
    for (int k = 0; k < (f.triangle ? 3 : 4); ++k) lo = glm::min(lo, f.corners[size_t(k)]), hi = glm::max(hi, f.corners[size_t(k)]);
  centre_ = s.faces.empty() ? Vec3(0.0f) : 0.5f * (lo + hi);
}

std::string Viewer::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }

std::string Viewer::status() const {
  const SolveStats st = session_->stats();
  return fmt::format("{} on {} | {} elements | {}{} | {:.2e} unshot", st.method, session_->backend(),
                     session_->surfaces().elements.size(), session_->done() ? "converged" : options_.paused ? "paused" : "solving",
                     solutionShown_ ? "" : " (unlit)", st.unshotFraction);
}

std::vector<std::string> Viewer::takeMessages() { return std::exchange(messages_, {}); }

void Viewer::setKey(const std::string& key, bool down) {
  if (down)
    keys_.insert(key);
  else
    keys_.erase(key);
}

void Viewer::mouseLook(float dx, float dy) { camera_.look(-dx * kLookPerPixel, -dy * kLookPerPixel); }
void Viewer::mouseOrbit(float dx, float dy) { camera_.orbit(pivot_, -dx * kLookPerPixel, -dy * kLookPerPixel); }
void Viewer::scroll(float steps) { camera_.dolly(pivot_, std::clamp(0.1f * steps, -0.5f, 0.5f)); }

std::string Viewer::pick(int x, int y) {
  const int64_t e = target_->elementAt(x, y);
  selected_ = -1;
  if (e < 0 || size_t(e) >= session_->surfaces().elements.size()) return {};
  const SurfaceSet& s = session_->surfaces();
  const Element& el = s.elements[size_t(e)];
  const uint32_t mesh = s.faces[el.face].mesh;
  pivot_ = el.centroid;
  const uint32_t object = session_->scene().meshes[mesh].object;
  if (object == kNoObject) {
    messages_.push_back(fmt::format("picked mesh '{}': geometry in world space, not an object that can move",
                                    session_->scene().meshes[mesh].name));
    return session_->scene().meshes[mesh].name;
  }
  selected_ = int64_t(object);
  return session_->scene().objects[object].name;
}

uint32_t Viewer::objectByName(const Action& a, const std::string& name) const {
  const Scene& scene = session_->scene();
  const int found = scene.findObject(name);
  if (found >= 0) return uint32_t(found);
  char* end = nullptr;
  const long index = std::strtol(name.c_str(), &end, 10);
  if (*end == '\0' && index >= 0 && size_t(index) < scene.objects.size()) return uint32_t(index);
  std::string names;
  for (const Object& o : scene.objects) names += (names.empty() ? "" : ", ") + o.name;
  throw Error(fmt::format("{}{}'{}': the scene has no object '{}' (it has: {})", a.where, a.where.empty() ? "" : ": ",
                          a.name, name, names.empty() ? "none" : names));
}

void Viewer::moveObject(uint32_t object, const glm::mat4& delta, bool aboutCentre) {
  const Scene& scene = session_->scene();
  glm::mat4 d = delta;
  if (aboutCentre) {
    Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const Mesh& m : scene.meshes)
      if (m.object == object)
        for (const Vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const Vec3 c = 0.5f * (lo + hi);
    d = glm::translate(glm::mat4(1.0f), c) * delta * glm::translate(glm::mat4(1.0f), -c);
  }
  const glm::mat4 to = d * scene.objects[object].transform;
  if (!scene.objects[object].dynamic) {
    // A static object lives in the ray tracer's one BVH: make it an instance, which means a new
    // session (a solve from the start); its later moves are followed.
    Scene edited = session_->scene();
    edited.objects[object].dynamic = true;
    edited.checkPlacement(object, to);  // a bad transform throws before anything changes
    SessionOptions so;
    so.solve = options_.solve;
    so.solve.followsChanges = true;
    so.borrowCurrentGlContext = options_.shareContext;
    so.keepPatches = true;
    auto next = std::make_unique<Session>(std::move(edited), options_.discretise, so);
    session_ = std::move(next);
    loaded_.objects[object].dynamic = true;
    messages_.push_back(fmt::format("object '{}' made dynamic: the solve starts again, and follows its moves from now on",
                                    scene.objects[object].name));
    session_->placeObject(object, to);
    afterGeometryChanged();
    zeroFields();
    solutionShown_ = false;
    return;
  }
  session_->placeObject(object, to);
  afterGeometryChanged();
}

void Viewer::setLights(std::vector<Light> lights) {
  session_->setLights(std::move(lights));
  afterSourcesChanged();
}

void Viewer::screenshot(const std::filesystem::path& path) { pendingScreenshots_.push_back(path); }

void Viewer::relightTransfer() { bakedRenderer_->setTransferLight(transferLightSh(transferLight_, skyScale_)); }

void Viewer::perform(const Action& a) {
  const auto start = Clock::now();
  const size_t editsBefore = pendingEdits_.size();
  performNow(a);
  if (pendingEdits_.size() > editsBefore) pendingEdits_.back().editMs = msSince(start);
}

void Viewer::performNow(const Action& a) {
  checkAction(a);
  const std::string& n = a.name;
  const Scene& scene = session_->scene();
  auto lightIndex = [&](size_t arg) {
    const int64_t i = argInt(a, arg);
    if (i < 0 || size_t(i) >= scene.lights.size())
      throw Error(fmt::format("{}{}'{}': no light {} (the scene has {})", a.where, a.where.empty() ? "" : ": ", n, i,
                              scene.lights.size()));
    return size_t(i);
  };
  if (n == "camera") {
    Camera c = camera_.toCamera();
    c.eye = Vec3(argFloat(a, 0), argFloat(a, 1), argFloat(a, 2));
    c.target = Vec3(argFloat(a, 3), argFloat(a, 4), argFloat(a, 5));
    if (a.args.size() > 6) c.fovY = argFloat(a, 6);
    if (!(c.fovY > 0.0f && c.fovY < 180.0f) || glm::length(c.target - c.eye) <= 0.0f)
      throw Error(fmt::format("{}: camera: the eye must differ from the target and the field of view lie in (0, 180)", a.where));
    camera_ = ViewCamera(c, scene.up, session_->surfaces().sceneExtent);
  } else if (n == "camera.scene") {
    if (scene.cameras.empty()) throw Error("camera.scene: the scene has no cameras");
    const Camera* c = nullptr;
    if (!a.args.empty()) {
      c = scene.findCamera(a.args[0]);
      if (!c) throw Error(fmt::format("camera.scene: no camera '{}'", a.args[0]));
    } else {
      c = &scene.cameras[nextSceneCamera_++ % scene.cameras.size()];
    }
    camera_ = ViewCamera(*c, scene.up, session_->surfaces().sceneExtent);
  } else if (n == "key") {
    const std::string& how = a.args[1];
    if (how != "down" && how != "up" && how != "tap")
      throw Error(fmt::format("{}: key: '{}' is not down, up or tap", a.where, how));
    setKey(a.args[0], how != "up");
    if (how == "tap") tapped_.insert(a.args[0]);  // held for the next frame only
  } else if (n == "look") {
    camera_.look(glm::radians(argFloat(a, 0)), glm::radians(argFloat(a, 1)));
  } else if (n == "orbit") {
    camera_.orbit(pivot_, glm::radians(argFloat(a, 0)), glm::radians(argFloat(a, 1)));
  } else if (n == "click") {
    const std::string picked = pick(int(argInt(a, 0)), int(argInt(a, 1)));
    messages_.push_back(picked.empty() ? "picked nothing" : "picked " + picked);
  } else if (n == "solve.pause") {
    options_.paused = true;
  } else if (n == "solve.resume") {
    options_.paused = false;
  } else if (n == "solve.toggle") {
    options_.paused = !options_.paused;
  } else if (n == "solve.reset") {
    startSession();
  } else if (n == "solve.backend") {
    if (a.args[0] != "cpu" && a.args[0] != "gl") throw Error(fmt::format("{}: solve.backend: '{}' is not cpu or gl", a.where, a.args[0]));
    const std::string old = options_.solve.backend;
    options_.solve.backend = a.args[0];
    try {
      startSession();
    } catch (...) {
      options_.solve.backend = old;  // the old session goes on
      throw;
    }
  } else if (n == "solve.budget") {
    const int64_t budget = argInt(a, 0);
    if (budget < 10 || budget > 50'000'000) throw Error(fmt::format("{}: solve.budget: {} is not between 10 and 50,000,000", a.where, budget));
    options_.discretise.elementBudget = size_t(budget);
    options_.discretise.elementSize = 0.0f;
    startSession();
  } else if (n == "view") {
    const ViewMode mode = parseViewMode(a.args[0]);
    if (mode == ViewMode::Baked && !bakedRenderer_)
      throw Error(fmt::format("{}{}view baked: '{}' is not a glb written by luxel bake (`luxel bake SCENE -o OUT.glb "
                              "--lightmaps` writes one)",
                              a.where, a.where.empty() ? "" : ": ", options_.sceneName));
    if (mode == ViewMode::Texels) buildTexelView();  // first, so that an error is the action's and changes nothing
    options_.mode = mode;
  } else if (n == "exposure") {
    options_.tone.exposure = argFloat(a, 0);
  } else if (n == "shadows") {
    renderer_->setShadowMethod(parseShadowMethod(a.args[0]));
    options_.shadows = renderer_->shadowMethod();
  } else if (n == "shading") {
    if (a.args[0] != "pixel" && a.args[0] != "vertex")
      throw Error(fmt::format("{}{}shading: '{}' is not pixel or vertex", a.where, a.where.empty() ? "" : ": ", a.args[0]));
    renderer_->setPerVertex(a.args[0] == "vertex");
  } else if (n == "tonemap") {
    options_.tone.curve = parseToneCurve(a.args[0]);
  } else if (n == "edges") {
    if (a.args[0] == "elements") elementEdges_ = !elementEdges_;
    else if (a.args[0] == "patches") patchEdges_ = !patchEdges_;
    else if (a.args[0] == "off") elementEdges_ = patchEdges_ = false;
    else throw Error(fmt::format("{}: edges: '{}' is not elements, patches or off", a.where, a.args[0]));
  } else if (n == "shaders.reload") {
    renderer_->reloadShaders();
    tone_ = std::make_unique<ToneMapPass>(shaderSource("tone.vert", options_.shaderDir), shaderSource("tone.frag", options_.shaderDir));
    messages_.push_back("shaders reloaded");
  } else if (n == "light.add-at-camera" || n == "light.add") {
    std::vector<Light> lights = scene.lights;
    Light l;
    l.type = Light::Type::Point;
    l.name = fmt::format("lamp{}", lights.size());
    if (n == "light.add") {
      l.position = Vec3(argFloat(a, 0), argFloat(a, 1), argFloat(a, 2));
      l.intensity = argFloat(a, 3);
      if (a.args.size() == 7) l.color = Rgb(argFloat(a, 4), argFloat(a, 5), argFloat(a, 6));
    } else {
      l.position = camera_.position();
      // 10 W/m^2 at a quarter of the scene's size: visible beside a room's own lights.
      const float r = 0.25f * session_->surfaces().sceneExtent;
      l.intensity = 10.0f * r * r;
    }
    lights.push_back(l);
    markEdit(n);
    setLights(std::move(lights));
  } else if (n == "light.move") {
    std::vector<Light> lights = scene.lights;
    lights[lightIndex(0)].position = Vec3(argFloat(a, 1), argFloat(a, 2), argFloat(a, 3));
    markEdit(n);
    setLights(std::move(lights));
  } else if (n == "light.color") {
    std::vector<Light> lights = scene.lights;
    Light& l = lights[lightIndex(0)];
    l.color = Rgb(argFloat(a, 1), argFloat(a, 2), argFloat(a, 3));
    l.intensity = argFloat(a, 4);
    markEdit(n);
    setLights(std::move(lights));
  } else if (n == "light.delete") {
    std::vector<Light> lights = scene.lights;
    lights.erase(lights.begin() + std::ptrdiff_t(lightIndex(0)));
    markEdit(n);
    setLights(std::move(lights));
  } else if (n == "sun") {
    std::vector<Light> lights = scene.lights;
    // Azimuth from the scene's east towards its north, elevation above the horizon; light travels down.
    const Vec3 travel = sunTravelDirection(scene.up, argFloat(a, 0), argFloat(a, 1));
    auto it = std::find_if(lights.begin(), lights.end(), [](const Light& l) { return l.type == Light::Type::Directional; });
    if (it == lights.end()) {
      Light sun;
      sun.type = Light::Type::Directional;
      sun.name = "sun";
      sun.intensity = 1000.0f;
      sun.angularRadius = 0.00465f;
      lights.push_back(sun);
      it = lights.end() - 1;
    }
    it->direction = travel;
    if (a.args.size() > 2) it->intensity = argFloat(a, 2);
    markEdit(n);
    setLights(std::move(lights));
  } else if (n == "sky") {
    std::vector<Light> lights = scene.lights;
    lights.erase(std::remove_if(lights.begin(), lights.end(), [](const Light& l) { return l.type == Light::Type::Sky; }), lights.end());
    const float radiance = argFloat(a, 0);
    if (radiance > 0.0f) {
      Light sky;
      sky.type = Light::Type::Sky;
      sky.name = "sky";
      sky.intensity = radiance;
      if (a.args.size() == 4) sky.color = Rgb(argFloat(a, 1), argFloat(a, 2), argFloat(a, 3));
      lights.push_back(sky);
    }
    markEdit(n);
    setLights(std::move(lights));
  } else if (n == "sun-direction" || n == "sun-irradiance" || n == "sky-scale") {
    // The transfer bake's light (the baked view), not the live scene's: relit at once, no solve.
    const std::string what = fmt::format("{}{}{}", a.where, a.where.empty() ? "" : ": ", n);
    if (transferLight_.bands == 0)
      throw Error(fmt::format("{}: '{}' holds no transfer bake to relight (`luxel bake SCENE -o OUT.glb --lightmaps "
                              "--transfer 4` writes one)",
                              what, options_.sceneName));
    if (n != "sky-scale" && transferLight_.suns.empty())
      throw Error(fmt::format("{}: the transfer bake has no sun (bake a scene with one: --sun X,Y,Z)", what));
    BakedGlb::TransferLight light = transferLight_;
    Rgb skyScale = skyScale_;
    if (n == "sun-direction") {
      const Vec3 d = parseDirection(a.args[0], what);
      for (BakedGlb::TransferSun& sun : light.suns) sun.direction = d;
    } else if (n == "sun-irradiance") {
      const Rgb e = parseColour(a.args[0], what);
      for (BakedGlb::TransferSun& sun : light.suns) sun.irradiance = e;
    } else {
      skyScale = parseColour(a.args[0], what);
    }
    transferLight_ = std::move(light);
    skyScale_ = skyScale;
    relightTransfer();
  } else if (n == "object.move" || n == "selected.move") {
    const bool sel = n == "selected.move";
    if (sel && selected_ < 0) throw Error(fmt::format("{}: selected.move: nothing is picked (click an object first)", a.where));
    const uint32_t o = sel ? uint32_t(selected_) : objectByName(a, a.args[0]);
    const size_t k = sel ? 0 : 1;
    const Vec3 t(argFloat(a, k), argFloat(a, k + 1), argFloat(a, k + 2));
    markEdit(n);
    moveObject(o, glm::translate(glm::mat4(1.0f), t), false);
  } else if (n == "object.rotate" || n == "selected.rotate") {
    const bool sel = n == "selected.rotate";
    if (sel && selected_ < 0) throw Error(fmt::format("{}: selected.rotate: nothing is picked (click an object first)", a.where));
    const uint32_t o = sel ? uint32_t(selected_) : objectByName(a, a.args[0]);
    const size_t k = sel ? 0 : 1;
    const Vec3 axis(argFloat(a, k), argFloat(a, k + 1), argFloat(a, k + 2));
    if (!(glm::length(axis) > 0.0f)) throw Error(fmt::format("{}: {}: the axis is zero", a.where, n));
    markEdit(n);
    moveObject(o, glm::rotate(glm::mat4(1.0f), glm::radians(argFloat(a, k + 3)), glm::normalize(axis)), true);
  } else if (n == "screenshot") {
    screenshot(a.args[0]);
  } else if (n == "save") {
    writeSceneJson(a.args[0], session_->scene(), original_, options_.sceneSpec, camera_.toCamera());
    messages_.push_back("saved " + a.args[0]);
  } else if (n == "ui") {
    if (a.args[0] != "on" && a.args[0] != "off") throw Error(fmt::format("{}: ui: '{}' is not on or off", a.where, a.args[0]));
    options_.showUi = a.args[0] == "on";
  } else if (n == "quit") {
    quit_ = true;
  }
}

void Viewer::frame(double dt, int width, int height) {
  const auto start = Clock::now();
  FrameSample sample;
  if (frameIndex_ > 0) sample.frameMs = std::chrono::duration<double, std::milli>(start - frameStart_).count();
  frameStart_ = start;

  // Walking.
  Vec3 move(0.0f);
  if (keys_.count("w")) move.z += 1.0f;
  if (keys_.count("s")) move.z -= 1.0f;
  if (keys_.count("d")) move.x += 1.0f;
  if (keys_.count("a")) move.x -= 1.0f;
  if (keys_.count("e")) move.y += 1.0f;
  if (keys_.count("q")) move.y -= 1.0f;
  if (glm::length(move) > 0.0f)
    camera_.walk(glm::normalize(move) * float(dt) * camera_.walkSpeed() * (keys_.count("shift") ? kRunFactor : 1.0f));
  for (const std::string& k : std::exchange(tapped_, {})) keys_.erase(k);

  // Solving.
  sample.solving = !options_.paused && !session_->done();
  if (sample.solving) {
    const auto solveStart = Clock::now();
    session_->step(StepLimit{options_.stepSeconds, 0});
    steppedSinceRefresh_ = true;
    sample.solveMs = msSince(solveStart);
    for (PendingEdit& e : pendingEdits_) e.stepped = true, e.solveMs += sample.solveMs;
  }
  // The fields follow the solution as often as reading it costs at most a quarter of the time.
  const double sinceRefresh = std::chrono::duration<double>(Clock::now() - lastRefresh_).count();
  const bool editWaiting = std::any_of(pendingEdits_.begin(), pendingEdits_.end(), [](const PendingEdit& e) { return e.stepped; });
  if ((steppedSinceRefresh_ && (session_->done() || editWaiting || sinceRefresh >= 4.0 * lastRefreshSeconds_)) ||
      (fieldsStale_ && solutionShown_)) {
    const auto refreshStart = Clock::now();
    refreshFields();
    steppedSinceRefresh_ = false;
    sample.solveMs += msSince(refreshStart);
  }

  // Drawing.
  const auto drawStart = Clock::now();
  target_->resize(width, height);
  target_->bind();
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  SceneRenderer::Frame f;
  f.mode = options_.mode;
  const Vec3 centre = sceneCentre();
  f.viewProjection = camera_.projection(float(width) / float(height), centre) * camera_.view();
  f.eye = camera_.position();
  f.texelSize = 1.0f / options_.texelsPerMetre;
  f.elementEdges = elementEdges_;
  f.patchEdges = patchEdges_;
  // The picture holds radiance times the exposure metered so far (values near middle grey), which
  // half floats hold without overflow; the tone pass divides it out again.
  storedScale_ = float(std::clamp(exposureScale_, 1e-30, 1e30));
  f.outputScale = storedScale_;
  drawPicture(f);
  // Metering the stored picture gives the exposure of the radiance divided by the scale it holds.
  if (frameIndex_ % 8 == 0) exposureScale_ = target_->meterExposure() * double(storedScale_);
  lastFrame_ = f;
  if (!pendingScreenshots_.empty()) {
    const Image shot = readRadiance();
    ToneMap tone = options_.tone;
    if (isFalseColourView(options_.mode)) tone = ToneMap{ToneMap::Curve::Clamp, 0.0f, false};  // colours as they are
    for (const std::filesystem::path& p : std::exchange(pendingScreenshots_, {})) {
      writeImage(shot, p, tone);
      messages_.push_back("wrote " + p.string());
    }
  }
  sample.drawMs = msSince(drawStart);

  // Edits whose indirect light this frame shows.
  for (auto it = pendingEdits_.begin(); it != pendingEdits_.end();) {
    if (it->stepped && !steppedSinceRefresh_) {
      glFinish();
      stats_.addEdit({it->action, msSince(it->start), it->editMs, it->solveMs});
      it = pendingEdits_.erase(it);
    } else {
      ++it;
    }
  }
  if (frameIndex_ > 0) stats_.addFrame(sample);
  ++frameIndex_;
}

Image Viewer::readRadiance() {
  // The last frame again, in full floats and unscaled (the screen's picture is half floats).
  const int width = target_->width(), height = target_->height();
  if (!shotTarget_) shotTarget_ = std::make_unique<HdrTarget>(width, height, /*fullFloat=*/true);
  shotTarget_->resize(width, height);
  shotTarget_->bind();
  SceneRenderer::Frame f = lastFrame_;
  f.outputScale = 1.0f;
  drawPicture(f);
  return shotTarget_->readRadiance();
}

void Viewer::drawPicture(const SceneRenderer::Frame& f) {
  if (f.mode == ViewMode::Texels) {
    if (!texelRenderer_) {
      try {
        buildTexelView();
      } catch (const Error& e) {
        messages_.push_back(std::string("texels view: ") + e.what());
        options_.mode = ViewMode::Final;
        SceneRenderer::Frame final = f;
        final.mode = ViewMode::Final;
        renderer_->draw(final);
        return;
      }
    }
    texelRenderer_->draw(f.viewProjection, f.outputScale);
  } else if (f.mode == ViewMode::Baked && bakedRenderer_) {
    bakedRenderer_->draw(f.viewProjection, f.outputScale);
  } else {
    renderer_->draw(f);
  }
}

void Viewer::buildTexelView() {
  // The atlas luxel bake would make at the view's density, given UVs kept even where they
  // overlap (a bake refuses them: here they are shown), and the bake's own validity test.
  const Scene& scene = session_->scene();
  LightmapRecipe recipe;
  recipe.texelsPerMetre = options_.texelsPerMetre;
  AtlasOptions ao = lightmapAtlasOptions(scene, recipe);
  ao.keepOverlappingUvs = true;
  // A baked glb's lightmap UVs address its own pages: shown on those, at their size.
  std::string pagesFrom;
  if (options_.baked && options_.baked->hasLightmaps) {
    const GlbLightmapPages pages = glbLightmapPages(*options_.baked, scene);
    if (pages.pageSize > 0) {
      ao.givenUvPages = pages.meshPage;
      ao.pageSize = pages.pageSize;
      pagesFrom = " (the glb's pages)";
    } else {
      messages_.push_back(fmt::format("texels: the glb's own pages are not shown ({}): each mesh's lightmap uvs on a "
                                      "page of its own",
                                      pages.whyNot));
    }
  }
  const LightmapAtlas atlas = buildLightmapAtlas(scene, ao);
  texels_ = diagnoseTexels(scene, atlas);
  texelsPerMetreShown_ = atlas.texelsPerMetre;
  texelRenderer_ = std::make_unique<TexelRenderer>(scene, session_->surfaces(), atlas, texels_, options_.shaderDir);
  // Given UVs set their own density; luxel's charts have the atlas's.
  const std::string density =
      atlas.texelsPerMetre > 0.0f ? fmt::format(" at {:.3g} texels/m", atlas.texelsPerMetre) : " from given UVs";
  messages_.push_back(fmt::format("texels: {} on {} page{} of {}^2{}{}: {} invalid (red), {} overlapping "
                                  "(magenta), {} next to another chart (yellow), {:.2f} s",
                                  texels_.covered, atlas.pageCount, atlas.pageCount == 1 ? "" : "s", atlas.pageSize,
                                  pagesFrom, density, texels_.invalid, texels_.overlapping, texels_.bleeding,
                                  texels_.seconds));
  for (const std::string& w : atlas.warnings) messages_.push_back(w);
}

void Viewer::present(int width, int height) {

  if (isFalseColourView(options_.mode)) {
    // Colours, not radiance: shown as they are, neither exposed nor curved.
    tone_->draw(target_->radianceTexture(), width, height, float(1.0 / double(storedScale_)), ToneMap::Curve::Clamp);
    return;
  }
  const double exposure = std::exp2(double(options_.tone.exposure)) * (options_.tone.autoExposure ? exposureScale_ : 1.0);
  const float scale = float(exposure / double(storedScale_));
  tone_->draw(target_->radianceTexture(), width, height, scale, options_.tone.curve);
}

}  // namespace luxel::viewer
