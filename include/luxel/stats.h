// The statistics of a run as JSON (`luxel render --stats FILE`): one schema, kept by the library
// so that every front end writes the same fields. docs/performance.md reads them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "luxel/solution.h"

namespace luxel {

struct RunRecord {
  std::string scene;
  SolveStats solve;
  struct Image {
    int width = 0, height = 0, samplesPerPixel = 0;
    std::string mode;
    double meanLuminance = 0.0;  // cd/m^2 (radiance weighted by Rec. 709 luminance)
    uint64_t renderRays = 0;
    double renderSeconds = 0.0;
    std::string indirect;  // hq mode's indirect light (--indirect); empty in other modes
  };
  std::optional<Image> image;
  int threads = 0;
  std::vector<std::string> outputs;
  double totalSeconds = 0.0;
};

// Fields: scene, elements, patches, solver, backend, device, shots, iterations, rays,
// rays_per_second, residual, unshot_fraction, refined_elements, warnings,
// seconds {setup, form_factors, solve, solve_total, render, total}, energy {emitted, absorbed},
// image {width, height, spp, mode, mean_luminance, render_rays}, threads, outputs.
std::string statsJson(const RunRecord& record);

// Writes statsJson(record) to `path` atomically (a temporary file renamed over it). Throws Error
// naming the path when it cannot.
void writeStatsJson(const RunRecord& record, const std::filesystem::path& path);

}  // namespace luxel
