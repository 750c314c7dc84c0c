#include "bake_command.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "luxel/bake.h"
#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/solve.h"
#include "progress_bar.h"

namespace fs = std::filesystem;

namespace luxel::cli {

int runBake(const BakeArgs& a) {
  // Check the output before the (possibly long) solve.
  const fs::path out(a.output);
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext != ".glb") throw Error(fmt::format("{}: output must end in .glb", a.output));
  const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) throw Error(fmt::format("{}: directory '{}' does not exist", a.output, dir.string()));

  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  ProgressBar bar(a.quiet);
  const auto start = std::chrono::steady_clock::now();
  Scene scene = loadScene(a.scene);
  if (!a.quiet)
    for (const std::string& w : scene.warnings) std::cerr << "luxel: warning: " << w << "\n";

  const SolveOptions so = solveOptions(a.solve);
  SurfaceSet surfaces = discretise(scene, discretiseOptions(a.solve));
  Solution solution = solve(scene, surfaces, so, bar.callback());
  if (!a.quiet)
    for (const std::string& w : solution.stats.warnings) std::cerr << "luxel: warning: " << w << "\n";

  GlbOptions go;
  go.flippedFaces = flippedFaceFlags(scene, surfaces);
  if (a.vertexColors) {  // on the element tessellation: a one-quad floor has no vertex under the light
    go.elements = &surfaces;
    go.elementColors = elementRadiance(surfaces, solution);
  }
  writeGlb(scene, out, go);
  bar.finish();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!a.quiet) {
    const SolveStats& s = solution.stats;
    std::cout << fmt::format("luxel: {} — {} elements in {} patches, {} ({} shots, {} iterations), unshot {:.3f}%\n",
                             scene.name, s.elements, s.patches, s.method, s.shots, s.iterations,
                             100.0 * s.unshotFraction);
    if (a.vertexColors)
      std::cout << fmt::format("luxel: bake {} elements with vertex colours (radiance); total {:.3f} s\n",
                               surfaces.elements.size(), total);
    else
      std::cout << fmt::format("luxel: bake {} triangles; total {:.3f} s\n", scene.triangleCount(), total);
    std::cout << "luxel: wrote " << a.output << "\n";
  }
  return 0;
}

}  // namespace luxel::cli
