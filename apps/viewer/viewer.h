// The interactive viewer's state and behaviour, independent of where it draws: a Session stepped a
// little every frame, its solution drawn by SceneRenderer into an HdrTarget, the camera, and every
// edit a user can make as a named Action (view_script.h), so that keys, menus and scripts all go
// through perform(). The window (viewer_window.cpp) and the headless driver (viewer_headless.cpp)
// own the GL context and feed it input.
#pragma once

#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "baked_glb.h"
#include "baked_renderer.h"
#include "frame_stats.h"
#include "mesh/corner_groups.h"
#include "hdr_target.h"
#include "luxel/image.h"
#include "luxel/session.h"
#include "luxel/texel_diagnostics.h"
#include "scene_renderer.h"
#include "texel_renderer.h"
#include "view_camera.h"
#include "view_script.h"

namespace luxel::viewer {

struct ViewerOptions {
  std::string sceneName;  // for titles and stats
  std::string sceneSpec;  // what loads the scene again (a built-in name or an absolute path), for `save`
  DiscretiseOptions discretise;
  SolveOptions solve;
  Camera camera;
  int width = 1280, height = 720;
  ToneMap tone;
  ViewMode mode = ViewMode::Final;
  ShadowMethod shadows = ShadowMethod::Maps;
  bool paused = false;       // start with the solver paused
  double stepSeconds = 0.012;  // solver time per frame while solving
  std::filesystem::path shaderDir;
  // The GL backend solves in the viewer's context (current on this thread) instead of a headless
  // one of its own.
  bool shareContext = true;
  float texelsPerMetre = 0.0f;  // the density view's checker (0: luxel bake's default for the scene)
  bool showUi = true;
  // What `luxel bake` put in the glb being viewed (the baked view), or null.
  std::shared_ptr<const BakedGlb> baked;
};

class Viewer {
 public:
  // Needs the viewer's OpenGL 4.5 context current on this thread. Throws luxel::Error when the
  // scene cannot be discretised or solved as asked.
  Viewer(Scene scene, ViewerOptions options);
  ~Viewer();

  // Performs a named action (a key, a menu item, a script line). Throws luxel::Error naming the
  // action when its arguments are wrong; the viewer is unchanged then.
  void perform(const Action& action);
  // Keys held for walking: w a s d (forward, left, back, right), q e (down, up), shift (faster).
  void setKey(const std::string& key, bool down);
  // Mouse motion in pixels: looks (walk mode) or orbits about the pivot.
  void mouseLook(float dx, float dy);
  void mouseOrbit(float dx, float dy);
  void scroll(float steps);
  // Picks the object under window pixel (x, y) (y down) from the last frame; returns its name, or
  // empty for none.
  std::string pick(int x, int y);

  // One frame: walks by the keys held over `dt` seconds, steps the solver (unless paused),
  // refreshes the drawn fields, draws into the offscreen picture (width x height), and does what
  // was asked for after a frame (screenshots).
  void frame(double dt, int width, int height);
  // Puts the picture on the bound framebuffer, tone-mapped.
  void present(int width, int height);
  // The panels (Dear ImGui; the caller opens and ends the ImGui frame).
  void drawUi();

  bool quitRequested() const { return quit_; }
  void toggleHelp() { showHelp_ = !showHelp_; }
  void toggleUi() { options_.showUi = !options_.showUi; }
  void setOrbitPivotToCentre() { pivot_ = sceneCentre(); }
  bool uiVisible() const { return options_.showUi; }
  const FrameStats& stats() const { return stats_; }
  const Session& session() const { return *session_; }
  const ViewCamera& camera() const { return camera_; }
  ViewMode mode() const { return options_.mode; }
  bool paused() const { return options_.paused; }
  int64_t frameCount() const { return frameIndex_; }
  std::string renderer() const;  // GL_RENDERER
  std::string status() const;    // one line: solver, step, unshot, frame time
  // The radiance of the last frame (row 0 at the top), in full floats: drawn again unscaled into a
  // full-float picture, as a screenshot is.
  Image readRadiance();
  // The scene as edited, for `save`.
  const Scene& scene() const { return session_->scene(); }
  std::vector<std::string> takeMessages();  // what happened since last asked (errors of edits, saved files)

 private:
  void startSession();                 // a new session on the current scene and options (reset)
  void afterSourcesChanged();          // lights or materials changed: per-pixel lights and shadows
  void afterGeometryChanged();         // objects moved: renderer geometry and shadows
  void refreshFields();                // solution to the renderer's corner values
  void zeroFields();
  void markEdit(const std::string& what);
  void performNow(const Action& action);
  void setLights(std::vector<Light> lights);
  void moveObject(uint32_t object, const glm::mat4& delta, bool aboutCentre);
  uint32_t objectByName(const Action& a, const std::string& name) const;
  void screenshot(const std::filesystem::path& path);
  Vec3 sceneCentre() const;  // of the bounds, measured when the geometry changes
  void measureScene();
  Vec3 centre_{0.0f};

  Scene original_;  // the scene as loaded, untouched: what `save` writes edits against
  Scene loaded_;    // the scene as loaded, dynamic flags as edited (a new session starts from it)
  ViewerOptions options_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<SceneRenderer> renderer_;
  std::unique_ptr<BakedRenderer> bakedRenderer_;  // when options_.baked
  // The texels view, made when first drawn and again after the geometry or density changes.
  std::unique_ptr<TexelRenderer> texelRenderer_;
  TexelDiagnostics texels_;
  float texelsPerMetreShown_ = 0.0f;
  void buildTexelView();  // throws luxel::Error (a scene too large to lay out at the density)
  // A transfer bake's light as edited (sun-direction, sun-irradiance, sky-scale), bands 0 without one.
  BakedGlb::TransferLight transferLight_;
  Rgb skyScale_{1.0f};
  void relightTransfer();  // hands the edited light to the baked renderer
  void drawPicture(const SceneRenderer::Frame& frame);  // the scene, or the glb's bake
  std::unique_ptr<HdrTarget> target_;
  std::unique_ptr<ToneMapPass> tone_;
  ViewCamera camera_;
  std::vector<uint32_t> perPixel_;     // lights drawn per pixel
  std::vector<Rgb> perPixelIrradiance_;  // their part of the solution, per element
  std::unique_ptr<CornerGroups> cornerGroups_;  // of the current surfaces; reset when they change
  std::set<std::string> keys_;
  std::set<std::string> tapped_;  // keys to release after the next frame
  size_t nextSceneCamera_ = 0;
  bool orbitMode_ = false;
  Vec3 pivot_{0.0f};
  bool elementEdges_ = false, patchEdges_ = false;
  int64_t selected_ = -1;  // picked object
  double exposureScale_ = 1.0;  // automatic exposure of the radiance (autoExposureScale)
  float storedScale_ = 1.0f;    // what the on-screen picture's radiance is multiplied by
  std::unique_ptr<HdrTarget> shotTarget_;  // full floats, for screenshots
  SceneRenderer::Frame lastFrame_;
  int64_t frameIndex_ = 0;
  bool fieldsStale_ = true, steppedSinceRefresh_ = false, solutionShown_ = false;
  std::chrono::steady_clock::time_point lastRefresh_{}, frameStart_{};
  double lastRefreshSeconds_ = 0.0;
  struct PendingEdit {
    std::string action;
    std::chrono::steady_clock::time_point start;
    bool stepped = false;
    double editMs = 0.0, solveMs = 0.0;
  };
  std::vector<PendingEdit> pendingEdits_;
  std::vector<std::filesystem::path> pendingScreenshots_;
  FrameStats stats_;
  std::vector<std::string> messages_;
  bool quit_ = false;
  bool showHelp_ = false;
  // What the panels keep between frames.
  struct UiState {
    std::deque<float> unshot, frameMs;  // plotted histories
    int budget = 0;                     // the element budget being typed
    float sun[2] = {45.0f, 45.0f};      // azimuth, elevation
    float transferSun[2] = {45.0f, 45.0f};  // the transfer bake's sun: azimuth, elevation
    char savePath[256] = "edited-scene.json";
  } ui_;
  bool unshotKnown_ = false;  // the solver gives unshot radiosity (the unshot view)
  std::string lastError_;
};

}  // namespace luxel::viewer
