// A session: one scene, its surfaces, and everything that solves them (the transport, the GL
// context, the solver), owned together and alive as long as the session. The command line's
// render, bake and bench use it, and so will the viewer and the Python bindings: step it, show
// its solution between steps, read its statistics.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "luxel/progress.h"
#include "luxel/scene.h"
#include "luxel/solution.h"
#include "luxel/solve.h"
#include "luxel/solver.h"
#include "luxel/surface.h"

namespace luxel {

struct SessionOptions {
  SolveOptions solve;
  // The GL backend draws in the caller's OpenGL 4.5 context, current on the calling thread (a
  // viewer's window), instead of making a headless one. It must stay current, on that thread,
  // for every call of the session.
  bool borrowCurrentGlContext = false;
  // Directional bakes: the SH coefficients (4 or 9; 0 for none) that incidentSh will be asked for.
  // Said here rather than by recordIncidentSh, the analytic lights' directions come from the same
  // rays as their irradiance instead of being traced again when asked.
  int incidentShCount = 0;
  // The surfaces keep their patches when the solver does not shoot from them (the hierarchy):
  // for a caller that shows them, as the viewer does. Otherwise the session drops them.
  bool keepPatches = false;
};

class Session {
 public:
  // Discretises `scene` and makes the chosen solver. Throws Error on an unknown method, backend
  // or option, or a scene that cannot be discretised.
  Session(Scene scene, const DiscretiseOptions& discretise, const SessionOptions& options);
  // On surfaces made by the caller (lightmap texels, a test's own cut).
  Session(Scene scene, SurfaceSet surfaces, const SessionOptions& options);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const Scene& scene() const;
  const SurfaceSet& surfaces() const;  // refined in place when options.solve.refine asks for it
  const std::string& backend() const;  // "cpu" or "gl", after "auto" has chosen

  // Advances the solve by at most `limit` (StepLimit{}: to the end). Returns true while there is
  // work left. Throws Cancelled when `progress` says stop; the session stays usable.
  bool step(const StepLimit& limit = {}, const ProgressCallback& progress = {});
  bool done() const;
  // Steps to the end and returns the solution.
  Solution solve(const ProgressCallback& progress = {});
  // The solution so far, with every statistic (energy balance included).
  Solution solution();
  SolveStats stats() const;

  // Ends the session for a caller that only renders from here on: frees the solver (a face-cluster
  // hierarchy, ray tracers, caches) and hands back the scene and its surfaces. The session can do
  // nothing more.
  struct Solved {
    Scene scene;
    SurfaceSet surfaces;
  };
  Solved release() &&;

  // Moves dynamic objects (Scene::objects[i].dynamic) to new transforms (object to world, each a
  // similarity of the pose they were loaded in): the scene's meshes, the surfaces and the ray
  // tracer's instances follow (a transform and a commit, no rebuild), and the solve continues
  // from the last solution where the solver can follow moves, or starts again where it cannot.
  // Throws Error naming the object when it is not dynamic or the transform is not a similarity.
  void placeObjects(const std::vector<std::pair<uint32_t, glm::mat4>>& placements);
  void placeObject(uint32_t object, const glm::mat4& transform) { placeObjects({{object, transform}}); }

  // Replaces the scene's lights (moved, turned, recoloured, added or removed): the analytic light
  // is recomputed exactly, and the solve continues from the last solution where the solver can
  // follow light changes (it shoots the difference, Puech et al. 1990), or starts again where it
  // cannot. Throws Error naming the light when one is invalid, and changes nothing then.
  void setLights(std::vector<Light> lights);
  // Edits a material's reflectance and emission (textures and sides stay): every element made of
  // it follows, and the solve continues as for setLights. Throws Error on an invalid material.
  void setMaterial(uint32_t material, const Rgb& reflectance, const Rgb& emission);

  // Irradiance per element from the scene lights `lights` (indices into Scene::lights), with
  // shadows: exactly the part of Solution::directIrradiance those lights bring, sample for sample.
  // A viewer that draws some lights per pixel takes this out of the field it interpolates. Throws
  // Error naming a light that does not exist.
  std::vector<Rgb> lightIrradiance(std::span<const uint32_t> lights);

  // Where each element's light comes from: count (4 or 9) real SH coefficients per channel of the
  // incident radiance, per element (docs/baking.md, "Directional lightmaps"; what a directional
  // lightmap bake records per texel). Throws Error for another count.
  std::vector<Rgb> incidentSh(int count);
  // Before solve(), when incidentSh(count) will be asked: solvers that record directions only as
  // they solve (the GPU's, the hierarchy's) then start doing so instead of leaving them to a final
  // gather of rays. SessionOptions::incidentShCount does the same from the start, and saves the
  // analytic lights a second trace.
  void recordIncidentSh(int count);

  // The camera a render of this session's scene uses: the one called `name` (Error listing the
  // scene's cameras when there is none), else the one called "default", else the first, else one
  // framing the scene's bounding box from +z with `fovY` degrees (45 when 0).
  Camera camera(const std::string& name = {}, float fovY = 0.0f) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The camera choice of Session::camera, for a scene without a session.
Camera chooseCamera(const Scene& scene, const std::string& name = {}, float fovY = 0.0f);

}  // namespace luxel
