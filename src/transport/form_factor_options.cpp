#include "transport/form_factor_options.h"

namespace luxel {

std::vector<SolverOption> analyticLightOptions() {
  const FormFactorOptions d;
  return {integerOption("light-samples", d.lightSamples, 1, 256, "shadow rays per element for each analytic light (a sky takes 4 times as many; a lamp or sun 16 times as many where a shadow's edge crosses the element)"),
          integerOption("seed", int(d.seed), 0, 1 << 30, "random seed of the CPU transport's rays")};
}

std::vector<SolverOption> cpuTransportOptions() {
  const FormFactorOptions d;
  std::vector<SolverOption> o = {
      integerOption("rays-per-pair", d.raysPerPair, 1, 256, "visibility rays per element-patch pair (rounded down to a square)"),
      integerOption("near-rays-per-pair", d.nearRaysPerPair, 1, 256, "rays for pairs nearer than near-factor times their sizes"),
      integerOption("emitter-rays-per-pair", d.emitterRaysPerPair, 1, 256, "rays for pairs whose source patch emits"),
      realOption("near-factor", d.nearFactor, 0.0, 1e6, "pairs nearer than this times their summed sizes are near"),
      flagOption("classify-visibility", d.classifyVisibility, "shaft-cull patch pairs first (exact; off to measure it)")};
  for (SolverOption& a : analyticLightOptions()) o.push_back(std::move(a));
  return o;
}

FormFactorOptions formFactorOptions(const SolverOptionValues& v) {
  FormFactorOptions f;
  if (v.declares("rays-per-pair")) f.raysPerPair = v.integer("rays-per-pair");
  if (v.declares("near-rays-per-pair")) f.nearRaysPerPair = v.integer("near-rays-per-pair");
  if (v.declares("emitter-rays-per-pair")) f.emitterRaysPerPair = v.integer("emitter-rays-per-pair");
  if (v.declares("near-factor")) f.nearFactor = float(v.real("near-factor"));
  if (v.declares("classify-visibility")) f.classifyVisibility = v.flag("classify-visibility");
  if (v.declares("light-samples")) f.lightSamples = v.integer("light-samples");
  if (v.declares("seed")) f.seed = uint32_t(v.integer("seed"));
  return f;
}

}  // namespace luxel
