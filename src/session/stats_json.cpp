#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "luxel/error.h"
#include "luxel/stats.h"

namespace luxel {

std::string statsJson(const RunRecord& r) {
  const SolveStats& s = r.solve;
  nlohmann::json j = {
      {"scene", r.scene},
      {"elements", s.elements},
      {"patches", s.patches},
      {"solver", s.method},
      {"backend", s.backend},
      {"device", s.device},
      {"shots", s.shots},
      {"iterations", s.iterations},
      {"rays", s.rays},
      {"rays_per_second", s.raysPerSecond()},
      {"residual", s.residual},
      {"unshot_fraction", s.unshotFraction},
      {"refined_elements", s.refinedElements},
      {"warnings", s.warnings},
      {"seconds", {{"setup", s.secondsSetup}, {"form_factors", s.secondsFormFactors}, {"solve", s.secondsSolve},
                   {"solve_total", s.secondsTotal}, {"render", r.image ? r.image->renderSeconds : 0.0},
                   {"total", r.totalSeconds}}},
      {"energy", {{"emitted", s.emittedPower}, {"absorbed", s.absorbedPower}}},
      {"threads", r.threads},
      {"outputs", r.outputs},
  };
  if (s.method == "hierarchical")
    j["hierarchy"] = {{"seconds", s.secondsHierarchy},
                      {"cached", s.hierarchyCached},
                      {"depth", s.hierarchyDepth},
                      {"mean_leaf_depth", s.hierarchyMeanLeafDepth},
                      {"bytes", s.hierarchyBytes},
                      {"links", s.links},
                      {"refinements",
                       {{"near", s.refinements[0]}, {"transfer", s.refinements[1]}, {"shadow", s.refinements[2]},
                        {"self", s.refinements[3]}}},
                      {"elements", s.clusterElements},
                      {"leaves", s.clusterLeaves}};
  if (s.redistributions > 0)
    j["redistribution"] = {{"count", s.redistributions},
                           {"factors_recomputed", s.factorsRecomputed},
                           {"seconds", s.secondsRedistribution}};
  for (const PhaseTime& p : s.phases)
    j["phases"][p.name] = {{"count", p.count}, {"seconds_gpu", p.secondsGpu}, {"seconds_cpu", p.secondsCpu}};
  if (r.image)
    j["image"] = {{"width", r.image->width},         {"height", r.image->height},
                  {"spp", r.image->samplesPerPixel}, {"mode", r.image->mode},
                  {"mean_luminance", r.image->meanLuminance}, {"render_rays", r.image->renderRays}};
  if (r.image && !r.image->indirect.empty()) j["image"]["indirect"] = r.image->indirect;
  return j.dump(2) + "\n";
}

void writeStatsJson(const RunRecord& record, const std::filesystem::path& path) {
  const std::string text = statsJson(record);
  writeTextAtomically(path, text);
}

}  // namespace luxel
