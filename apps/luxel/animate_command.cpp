#include "animate_command.h"

#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "luxel/animation.h"
#include "luxel/bench.h"
#include "luxel/error.h"
#include "luxel/image.h"
#include "luxel/import.h"
#include "luxel/render.h"
#include "luxel/session.h"
#include "io/atomic_file.h"
#include "frame_pattern.h"
#include "out_of_memory.h"
#include "output_paths.h"
#include "progress_bar.h"
#include "video_encoder.h"

namespace luxel::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The solver's time by phase over one frame (GL solvers; gl/gpu_timeline.h), in milliseconds on
// the GPU and on the CPU.
nlohmann::ordered_json phaseMilliseconds(const std::vector<PhaseTime>& before, const std::vector<PhaseTime>& after) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const PhaseTime& d : phasesSince(before, after))
    out[d.name] = {{"count", d.count}, {"gpu", 1e3 * d.secondsGpu}, {"cpu", 1e3 * d.secondsCpu}};
  return out;
}

// A folder of its own under the system's temporary folder, removed with everything in it.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string name = (fs::temp_directory_path() / "luxel-frames-XXXXXX").string();
    if (!::mkdtemp(name.data()))
      throw Error(fmt::format("cannot make a temporary folder {}", name));
    path_ = name;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

bool sameLight(const Light& a, const Light& b) {
  return a.position == b.position && a.direction == b.direction && a.color == b.color &&
         a.intensity == b.intensity;
}

// Brings `session` to time `t`: the animated objects that are not already where they belong are
// placed, and the lights are set when one of them changed. Nothing is touched when nothing moved,
// so that a still frame keeps the solver's state as it is.
void poseAt(Session& session, double t) {
  const Scene& scene = session.scene();
  std::vector<std::pair<uint32_t, glm::mat4>> moves;
  for (const auto& [object, transform] : animatedPlacements(scene, t))
    if (transform != scene.objects[object].transform) moves.emplace_back(object, transform);
  if (!moves.empty()) session.placeObjects(moves);
  if (scene.animation.lights.empty()) return;
  std::vector<Light> lights = lightsAt(scene, t);
  bool changed = false;
  for (size_t j = 0; j < lights.size(); ++j)
    changed = changed || !sameLight(lights[j], scene.lights[j]);
  if (changed) session.setLights(std::move(lights));
}

// The NRMSE of `solution` against a solve from scratch of the same scene posed at time `t`: a
// second session made at rest with the same options, posed, and solved to the end. It shares the
// frame's discretisation (both are cut at rest, then moved), so the elements correspond.
double errorAgainstFromScratch(const Scene& atRest, const AnimateArgs& a, double t,
                               const Session& frame, const Solution& solution,
                               const ProgressCallback& cancel) {
  Session reference(atRest, discretiseOptions(a.solve), {solveOptions(a.solve)});
  poseAt(reference, t);
  const Solution converged = reference.solve(cancel);
  return bench::normalisedRmsError(frame.surfaces(), solution.radiosity, converged.radiosity);
}

}  // namespace

void addAnimateOptions(CLI::App& c, AnimateArgs& a) {
  c.add_option("scene", a.scene, "Built-in name, a scene file (.json) or a mesh file")->required();
  c.add_option("-o,--output", a.output,
               "Frames: an image name with the frame number as %d or %04d (.png tone-mapped, .exr "
               "linear), or a video (.mp4, .mkv, .webm; needs ffmpeg on PATH)")
      ->required();
  c.add_option("--frames", a.frames, "Frames to render")
      ->required()
      ->check(CLI::Range(int64_t(1), int64_t(10'000'000)));
  c.add_option("--fps", a.fps, "Frames per second of animation time")
      ->check(finiteRange(1e-3, 1e6))
      ->capture_default_str();
  c.add_option("--start", a.start, "Time of the first frame, in seconds")
      ->check(finiteRange(-1e9, 1e9))
      ->capture_default_str();
  c.add_option("--frame-budget", a.frameBudget,
               "Seconds of solving per frame, after which the frame is rendered as far as it got "
               "(default: solve each frame to the end)")
      ->check(finiteRange(1e-6, 1e6));
  c.add_flag("--error", a.error,
             "Add each frame's error (NRMSE of element radiosities) against a solve from scratch "
             "at the same pose (slow: one more solve per frame)");
  addViewOptions(c, a);
  c.add_option("--mode", a.mode,
               "hq (exact direct light per pixel) or radiosity (the seeds' display)")
      ->capture_default_str();
  addSolveOptions(c, a.solve);
  c.add_option("--threads", a.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  c.add_flag("-q,--quiet", a.quiet, "Print nothing but errors (and no stats on stdout)");
  c.add_option("--stats", a.statsPath,
               "Write the per-frame stats as JSON lines to this file (default: stdout)");
}

void checkAnimateArgs(const AnimateArgs& a) {
  checkViewArgs(a);
  if (a.mode == "lightmap")
    throw Error(
        "--mode lightmap: animate renders hq or radiosity (lightmaps are baked for a still scene: "
        "luxel render)");
  checkSolveArgs(a.solve);
  if (!a.solve.checkpoint.empty() || !a.solve.resume.empty())
    throw Error(
        "--checkpoint and --resume are for one long solve (luxel render, bake); animate solves "
        "every frame");
  if (a.error && a.solve.refine > 0)
    throw Error(
        "--error with --refine: refinement cuts each solve its own way, so a frame's elements and "
        "the from-scratch solve's would not correspond");
  if (isVideoPath(a.output)) return;
  const FramePattern pattern(a.output, "-o");
  const std::string ext = lowerExtension(pattern.at(0));
  if (ext != ".png" && ext != ".exr")
    throw Error(fmt::format(
        "-o {}: the name must end in .png or .exr (frames), or .mp4, .mkv or .webm (a video)",
        a.output));
  if (a.frames > 1 && !pattern.numbered())
    throw Error(
        fmt::format("-o {}: {} frames need the frame number in the name, as %d or %04d (e.g. "
                    "frames/frame%04d.png)",
                    a.output, a.frames));
}

int runAnimate(const AnimateArgs& a) {
  // Every output is checked before the scene is read: the first and the last frame's names (the
  // others differ from them only in the number), the video and ffmpeg, the stats.
  const bool video = isVideoPath(a.output);
  std::optional<fs::path> ffmpeg;
  std::optional<FramePattern> pattern;
  std::vector<OutputPath> paths;
  if (video) {
    ffmpeg = findOnPath("ffmpeg");
    if (!ffmpeg)
      throw Error(
          fmt::format("-o {}: writing a video needs ffmpeg, and there is none on PATH (Debian: "
                      "apt-get install ffmpeg); or write frames, e.g. -o frames/frame%04d.png",
                      a.output));
    paths.push_back({"-o", a.output, {".mp4", ".mkv", ".webm"}});
  } else {
    pattern.emplace(a.output, "-o");
    paths.push_back({"-o", pattern->at(0), {".exr", ".png"}});
    if (a.frames > 1) paths.push_back({"-o", pattern->at(a.frames - 1), {".exr", ".png"}});
  }
  if (!a.statsPath.empty()) paths.push_back({"--stats", a.statsPath, {}});
  checkOutputPaths(paths);
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    size_t(a.threads));

  ProgressBar bar(a.quiet);
  const ProgressCallback cancel = [](const ProgressEvent&) { return !ProgressBar::interrupted(); };
  const auto started = Clock::now();
  nowDoing(fmt::format("loading scene '{}'", a.scene),
           "the scene is too big for this machine's memory");
  Scene scene = loadScene(a.scene);
  addCommandLineLights(scene, a.solve);
  const std::string sceneName = scene.name;
  if (!a.quiet) {
    for (const std::string& w : scene.warnings) std::cerr << "luxel: warning: " << w << "\n";
    if (!hasAnimation(scene))
      std::cerr << fmt::format(
          "luxel: warning: scene '{}' has no animation: every frame will be the same\n", sceneName);
  }
  const RenderOptions ro = renderOptionsFor(scene, a);  // checked before the first solve
  // Later frames keep the first frame's exposure: automatic exposure per frame would pump as the
  // light changes. The first frame is exposed as `luxel render` exposes it.
  ToneMap tm{.curve = parseToneCurve(a.toneCurve), .exposure = a.exposure};

  std::optional<Scene> atRest;
  if (a.error) atRest = scene;
  nowDoing(fmt::format("solving scene '{}' ({})", sceneName, solveSize(a.solve)),
           solveSizeHint(a.solve, false));
  SolveOptions solve = solveOptions(a.solve);
  solve.followsChanges = true;  // auto: a solver that corrects its solution frame to frame
  Session session(std::move(scene), discretiseOptions(a.solve), {solve});
  std::optional<TemporaryFolder> frames;
  if (video) frames.emplace();

  std::string statsLines;
  for (int64_t k = 0; k < a.frames; ++k) {
    const double t = a.start + double(k) / a.fps;
    const std::vector<PhaseTime> phasesBefore = session.stats().phases;
    auto clock = Clock::now();
    poseAt(session, t);
    const double msUpdate = msSince(clock);
    const SolveStats before = session.stats();
    clock = Clock::now();
    // The first solve may be long: it shows the bar. Later ones are a frame's worth.
    const ProgressCallback& progress = k == 0 ? bar.callback() : cancel;
    if (a.frameBudget > 0.0)
      session.step({.seconds = a.frameBudget}, progress);
    else
      while (session.step({}, progress)) {
      }
    const Solution solution = session.solution();
    const double msSolve = msSince(clock);
    if (k == 0) bar.finish();

    nowDoing(fmt::format("rendering frame {} of scene '{}' ({} image, {} samples per pixel)", k,
                         sceneName, a.size, a.spp),
             "use a smaller image (--size)");
    clock = Clock::now();
    const Image image = render(session.scene(), session.surfaces(), solution, ro, cancel);
    const double msRender = msSince(clock);
    if (k == 0) {
      tm.exposure = float(a.exposure + std::log2(autoExposureScale(image)));
      tm.autoExposure = false;
      if (!video)
        writeImage(image, pattern->at(k), ToneMap{.curve = tm.curve, .exposure = a.exposure});
    } else if (!video) {
      writeImage(image, pattern->at(k), tm);
    }
    if (video)
      writePng(image, frames->path() / videoFrameName(long(k)),
               k == 0 ? ToneMap{.curve = tm.curve, .exposure = a.exposure} : tm);

    const SolveStats after = session.stats();
    nlohmann::ordered_json line = {
        {"frame", k},
        {"time", t},
        {"ms_update", msUpdate},
        {"ms_solve", msSolve},
        {"ms_render", msRender},
        // A solver that started again counts from zero.
        {"shots", after.shots >= before.shots ? after.shots - before.shots : after.shots},
        {"unshot_fraction", after.unshotFraction}};
    if (!after.phases.empty()) line["phases_ms"] = phaseMilliseconds(phasesBefore, after.phases);
    if (atRest) {
      nowDoing(fmt::format("solving frame {} of scene '{}' from scratch (--error)", k, sceneName),
               solveSizeHint(a.solve, false));
      line["error"] = errorAgainstFromScratch(*atRest, a, t, session, solution, cancel);
    }
    if (!a.statsPath.empty())
      statsLines += line.dump() + "\n";
    else if (!a.quiet)
      std::cout << line.dump() << std::endl;  // a line at a time, for a reader that follows along
  }
  if (video) {
    nowDoing(fmt::format("encoding {} with ffmpeg", a.output),
             "use fewer frames or a smaller image");
    encodeVideo(*ffmpeg, frames->path(), a.fps, a.output);
  }
  if (!a.statsPath.empty()) writeTextAtomically(a.statsPath, statsLines);
  bar.finish();
  if (!a.quiet) {
    const SolveStats s = session.stats();
    std::cerr << fmt::format(
        "luxel: {} — {} frames from t = {:g} s at {:g} fps, {} elements, {} on {}; {:.3f} s\n",
        sceneName, a.frames, a.start, a.fps, s.elements, s.method, s.backend,
        std::chrono::duration<double>(Clock::now() - started).count());
    std::cerr << "luxel: wrote " << (video ? a.output : a.output + " (" + pattern->at(0) + " ...)")
              << "\n";
  }
  return 0;
}

}  // namespace luxel::cli
