#include "bake_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fnmatch.h>
#include <iostream>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "luxel/bake.h"
#include "luxel/directional_lightmap.h"
#include "luxel/error.h"
#include "luxel/image.h"
#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/session.h"
#include "luxel/solve.h"
#include "luxel/transfer_lightmap.h"
#include "baked_glb.h"
#include "glb_lightmap_pages.h"
#include "html_page.h"
#include "out_of_memory.h"
#include "output_paths.h"
#include "progress_bar.h"

namespace fs = std::filesystem;

namespace luxel::cli {

namespace {

// Per mesh, 1 when its name matches one of the globs (fnmatch: *, ?, [...]). A pattern that
// matches nothing is an error naming it and the meshes there are: a typo would otherwise bake
// a lightmap where vertex colours were asked for, silently.
std::vector<uint8_t> meshesMatching(const Scene& scene, const std::vector<std::string>& patterns) {
  std::vector<uint8_t> flags(scene.meshes.size(), 0);
  for (const std::string& pattern : patterns) {
    if (pattern.empty()) throw Error("--vertex-colors-for: empty pattern");
    bool any = false;
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      if (fnmatch(pattern.c_str(), scene.meshes[m].name.c_str(), 0) == 0) flags[m] = 1, any = true;
    if (!any) {
      std::string names;
      for (size_t m = 0; m < scene.meshes.size() && m < 20; ++m)
        names += fmt::format("{}'{}'", m ? ", " : "", scene.meshes[m].name);
      if (scene.meshes.size() > 20) names += fmt::format(", ... ({} meshes)", scene.meshes.size());
      throw Error(fmt::format("--vertex-colors-for: pattern '{}' matches no mesh of scene '{}' (meshes: {})", pattern,
                              scene.name, names));
    }
  }
  return flags;
}

// Baking a glb that `luxel bake` wrote with lightmaps again keeps its layout: meshes stay on the
// pages they shared, at the pages' size unless --lightmap-size says otherwise (each mesh's given
// UVs would otherwise fill a page of its own).
void keepGlbPages(const std::string& path, const Scene& scene, bool quiet, LightmapRecipe& recipe) {
  const std::string extension = fs::path(path).extension().string();
  if (extension != ".glb" && extension != ".gltf") return;
  if (std::none_of(scene.meshes.begin(), scene.meshes.end(), [](const Mesh& m) { return !m.lightmapUvs.empty(); }))
    return;  // no lightmap uvs: nothing to keep
  auto warn = [&](const std::string& why) {
    if (!quiet)
      std::cerr << "luxel: warning: " << path << ": its lightmap pages are not kept (" << why
                << "): each mesh's own lightmap uvs get a page of their own\n";
  };
  viewer::BakedGlb glb;
  try {
    glb = viewer::readBakedGlb(path);
  } catch (const Error& e) {
    warn(e.what());  // Assimp read the scene; only the layout is lost, so the bake goes on
    return;
  }
  if (!glb.hasLightmaps) return;  // uvs of its own, not a bake's: a page each, as for any file
  const viewer::GlbLightmapPages pages = viewer::glbLightmapPages(glb, scene);
  if (pages.pageSize <= 0) {
    warn(pages.whyNot);
    return;
  }
  recipe.givenUvPages = pages.meshPage;
  if (recipe.pageSize == 0) recipe.pageSize = pages.pageSize;
}

}  // namespace

void checkBakeArgs(const BakeArgs& a) {
  if (a.lightmaps && a.vertexColors)
    throw Error("--lightmaps and --vertex-colors exclude each other (--vertex-colors-for PATTERN picks meshes for "
                "vertex colours beside lightmaps)");
  if (!a.vertexColorsFor.empty() && !a.lightmaps)
    throw Error("--vertex-colors-for needs --lightmaps (the other meshes get lightmaps); --vertex-colors alone "
                "colours every mesh");
  if (parseDirectionalMode(a.directional) != DirectionalMode::None && !a.lightmaps && !a.vertexColors)
    throw Error("--directional records where the light comes from per lightmap texel or per vertex: it needs "
                "--lightmaps or --vertex-colors");
  if (a.transferBands > 0 && !a.lightmaps) throw Error("--transfer bakes transfer lightmaps: it needs --lightmaps");
  if (a.transferBands > 0 && (parseDirectionalMode(a.directional) != DirectionalMode::None || !a.vertexColorsFor.empty()))
    throw Error("--transfer excludes --directional and --vertex-colors-for");
  if (a.html) {
    if (lowerExtension(fs::path(a.output)) != ".glb")
      throw Error(fmt::format("--html writes a page beside the glb and embeds it: -o must name a .glb file (not '{}')",
                              a.output));
    if (!a.lightmaps && !a.vertexColors)
      throw Error("--html shows the baked light: add --lightmaps or --vertex-colors (a glb without either holds no "
                  "light to show)");
    checkHtmlPageAssets();
  }
  checkSolveArgs(a.solve);
}

int runBake(const BakeArgs& a) {
  // Check the output before the (possibly long) solve.
  const fs::path out(a.output);
  std::vector<OutputPath> paths{{"-o", a.output, {".glb"}}};
  if (a.html) paths.push_back({"--html", htmlPagePath(out).string(), {".html"}});
  if (!a.tracePath.empty()) paths.push_back({"--progress-trace", a.tracePath, {}});
  for (OutputPath& p : checkpointOutputs(a.solve)) paths.push_back(std::move(p));
  checkOutputPaths(paths);

  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(a.threads));

  ProgressBar bar(a.quiet);
  if (!a.tracePath.empty()) bar.traceTo(a.tracePath);
  const auto start = std::chrono::steady_clock::now();
  nowDoing(fmt::format("loading scene '{}'", a.scene), "the scene is too big for this machine's memory");
  Scene scene = loadScene(a.scene);
  addCommandLineLights(scene, a.solve);
  if (!a.quiet)
    for (const std::string& w : scene.warnings) std::cerr << "luxel: warning: " << w << "\n";

  const SolveOptions so = solveOptions(a.solve);  // checked by the session or recipe before any work
  nowDoing(fmt::format("baking scene '{}' ({})", scene.name, a.lightmaps && a.texelsPerMetre > 0.0f
                                                                ? fmt::format("--texels-per-metre {:g}", a.texelsPerMetre)
                                                                : solveSize(a.solve)),
           solveSizeHint(a.solve, a.lightmaps));
  if (a.lightmaps) {
    const std::vector<uint8_t> vertexColored = meshesMatching(scene, a.vertexColorsFor);  // before the solve
    LightmapRecipe recipe;
    recipe.texelsPerMetre = a.texelsPerMetre;
    recipe.texelBudget = size_t(a.solve.elements);
    recipe.pageSize = a.lightmapSize;
    keepGlbPages(a.scene, scene, a.quiet, recipe);
    recipe.solve = so;
    recipe.directional = parseDirectionalMode(a.directional);
    // A transfer bake (--transfer): the transfer, and its lightmaps relit by the scene's distant lights.
    std::optional<TransferBake> transfer;
    BakedLightmaps baked;
    if (a.transferBands > 0) {
      BakedTransfer t = bakeTransfer(scene, recipe, a.transferBands, bar.callback());
      baked.atlas = std::move(t.atlas);
      transfer = std::move(t.transfer);
      const DistantLightSh light = distantLightSh(scene, a.transferBands);
      baked.bake = relitLightmaps(*transfer, light);
      baked.bake.solution.stats.warnings = light.warnings;
    } else {
      baked = bakeLightmaps(scene, recipe, bar.callback());
    }
    const LightmapAtlas& atlas = baked.atlas;
    const LightmapBake& bake = baked.bake;
    if (!a.quiet)
      for (const std::string& w : bake.solution.stats.warnings) std::cerr << "luxel: warning: " << w << "\n";
    GlbOptions go;
    go.flippedFaces = flippedFaceFlags(scene, bake.surfaces.surfaces);
    if (transfer) addTransferLightmaps(go, scene, atlas, *transfer, bake);
    else addLightmaps(go, scene, atlas, bake, vertexColored);
    writeGlb(scene, out, go);
    for (int p = 0; p < int(bake.pages.size()); ++p) {
      fs::path exr = out;
      exr.replace_extension(fmt::format(".lightmap{}.exr", p));
      writeExr(lightmapPageImage(bake, p), exr);
    }
    if (a.html)
      writeHtmlPage(out, htmlPagePath(out),
                    {scene.name, out.filename().string(),
                     a.vertexColorsFor.empty() ? "lightmaps (irradiance)"
                                               : "lightmaps, and vertex colours (irradiance) on some meshes"});
    bar.finish();
    bar.writeTrace();
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!a.quiet) {
      // Given UVs (a glb baked before) set their own density; luxel's charts have the atlas's.
      const std::string density =
          atlas.texelsPerMetre > 0.0f ? fmt::format("{:.1f} texels per metre", atlas.texelsPerMetre) : "given uvs";
      std::cout << fmt::format("luxel: lightmaps — {} pages of {}², {}, {} texels in {} patches, "
                               "{} invalid, {} dilated, seams {:.3g} -> {:.3g} ({} edges, {:.3f} s); total {:.3f} s\n",
                               bake.pages.size(), atlas.pageSize, density, bake.texels,
                               bake.surfaces.surfaces.patches.size(), bake.invalidTexels, bake.dilatedTexels,
                               bake.seamMaxBefore, bake.seamMaxAfter, bake.seamEdges, bake.secondsSeams, total);
      if (bake.directional != DirectionalMode::None)
        std::cout << fmt::format("luxel: directions ({}, {}) — {:.3f} s after a solve of {:.3f} s; filling, "
                                 "stitching and dilating every plane {:.3f} s\n",
                                 directionalModeName(bake.directional),
                                 bake.directionsFrom == "solver" ? "from the solver" : "gathered by rays",
                                 bake.secondsDirectional, bake.secondsSolve, bake.secondsPost);
      if (!a.vertexColorsFor.empty()) {  // the names once each, with how many meshes carry them
        std::vector<std::pair<std::string, size_t>> names;
        size_t count = 0;
        for (size_t m = 0; m < scene.meshes.size(); ++m) {
          if (!vertexColored[m]) continue;
          ++count;
          auto it = std::find_if(names.begin(), names.end(), [&](auto& n) { return n.first == scene.meshes[m].name; });
          if (it == names.end()) names.emplace_back(scene.meshes[m].name, 1);
          else ++it->second;
        }
        std::string list;
        for (size_t i = 0; i < names.size() && i < 20; ++i)
          list += fmt::format("{}{}{}", i ? ", " : "", names[i].first,
                              names[i].second > 1 ? fmt::format(" ({})", names[i].second) : std::string());
        if (names.size() > 20) list += ", ...";
        std::cout << fmt::format("luxel: vertex colours (irradiance{}) instead of lightmaps on {} mesh{}: {}\n",
                                 bake.directional == DirectionalMode::None
                                     ? std::string()
                                     : fmt::format(", with directions: {}", directionalModeName(bake.directional)),
                                 count, count == 1 ? "" : "es", list);
      }
      std::cout << "luxel: wrote " << a.output << "\n";
      if (a.html) std::cout << "luxel: wrote " << htmlPagePath(out).string() << " (open it in a browser)\n";
    }
    return 0;
  }
  const DirectionalMode vertexDirections = a.vertexColors ? parseDirectionalMode(a.directional) : DirectionalMode::None;
  SessionOptions sessionOptions{so};
  sessionOptions.incidentShCount = directionalCoefficients(vertexDirections);
  Session session(std::move(scene), discretiseOptions(a.solve), sessionOptions);
  const Solution solution = session.solve(bar.callback());
  const SurfaceSet& surfaces = session.surfaces();
  const Scene& solved = session.scene();
  if (!a.quiet)
    for (const std::string& w : solution.stats.warnings) std::cerr << "luxel: warning: " << w << "\n";

  GlbOptions go;
  go.flippedFaces = flippedFaceFlags(solved, surfaces);
  double secondsDirectional = 0.0;
  if (a.vertexColors) {  // on the element tessellation: a one-quad floor has no vertex under the light
    go.elements = &surfaces;
    go.elementColors = elementRadiance(surfaces, solution);
    if (vertexDirections != DirectionalMode::None) {
      const auto shStart = std::chrono::steady_clock::now();
      go.vertexDirectionalMode = directionalModeName(vertexDirections);
      go.elementDirections =
          elementDirections(surfaces, vertexDirections, session.incidentSh(directionalCoefficients(vertexDirections)));
      secondsDirectional = std::chrono::duration<double>(std::chrono::steady_clock::now() - shStart).count();
    }
  }
  writeGlb(solved, out, go);
  if (a.html) writeHtmlPage(out, htmlPagePath(out), {solved.name, out.filename().string(), "vertex colours (radiance)"});
  bar.finish();
  bar.writeTrace();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!a.quiet) {
    const SolveStats& s = solution.stats;
    std::cout << fmt::format("luxel: {} — {}, {} ({} shots, {} iterations), unshot {:.3f}%\n",
                             solved.name, elementsAndPatches(s), s.method, s.shots, s.iterations,
                             100.0 * s.unshotFraction);
    if (a.vertexColors)
      std::cout << fmt::format("luxel: bake {} elements with vertex colours (radiance){}; total {:.3f} s\n",
                               surfaces.elements.size(),
                               go.vertexDirectionalMode.empty()
                                   ? std::string()
                                   : fmt::format(" and directions ({}, {:.3f} s)", go.vertexDirectionalMode,
                                                 secondsDirectional),
                               total);
    else
      std::cout << fmt::format("luxel: bake {} triangles; total {:.3f} s\n", solved.triangleCount(), total);
    std::cout << "luxel: wrote " << a.output << "\n";
    if (a.html) std::cout << "luxel: wrote " << htmlPagePath(out).string() << " (open it in a browser)\n";
  }
  return 0;
}

void addLightmapOptions(CLI::App& bake, BakeArgs& a) {
  bake.add_flag("--lightmaps", a.lightmaps, "Bake lightmaps (TEXCOORD_1, RGBM pages in the glb, EXR pages beside it)");
  bake.add_option("--texels-per-metre", a.texelsPerMetre,
                  "Lightmap density (default: about --elements texels when given, else 5 texels per metre, Godot's "
                  "0.2 m texel, or more on a small scene: about 10,000 texels)")
      ->check(finiteRange(0.0, 1e6));
  bake.add_option("--lightmap-size", a.lightmapSize,
                  "Lightmap page size in texels (default: each bake's pages sized to their content, up to 1024)")
      ->check(CLI::Range(16, 16384));
  bake.add_option("--directional", a.directional,
                  "With --lightmaps or --vertex-colors: none, sh-l1 (L1 spherical harmonics), sh-l2 or dominant (one "
                  "direction): where each texel's or vertex's light comes from, for normal maps (the "
                  "LUXEL_lightmap_directional or LUXEL_vertex_directional extension)")
      ->check(CLI::IsMember({"none", "sh-l1", "sh-l2", "dominant"}))
      ->capture_default_str();
  bake.add_option("--transfer", a.transferBands,
                  "With --lightmaps: SH transfer lightmaps of this many bands (2, 3 or 4), relit by the scene's suns "
                  "and skies for the plain lightmap, and carried whole in the LUXEL_lightmap_transfer extension")
      ->check(CLI::Range(2, 4));
  bake.add_option("--vertex-colors-for", a.vertexColorsFor,
                  "With --lightmaps: meshes whose names match these globs (comma-separated) get vertex colours "
                  "(COLOR_0, irradiance) instead of a lightmap")
      ->delimiter(',')
      ->allow_extra_args(false);  // one word (of comma-separated globs) per use, never the scene after it
}

}  // namespace luxel::cli
