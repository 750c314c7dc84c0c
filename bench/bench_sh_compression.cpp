// Compressing directional (RGB L1) lightmaps of real levels (issue 17's target: at most 1.5 bytes
// a texel at 40 dB or better against the floats, on Sibenik and Sponza), beside seed 004's vector
// quantisation: Sibenik and Sponza under a sun and a sky, baked at 2 texels per metre with
// --directional sh-l1 (every covered and dilated texel: 12 numbers), then compressed each way. The
// counters are the results (bytes per texel, PSNR in dB against the floats; half floats are 24
// bytes); the time is the compression's. docs/baking.md, "Compression", keeps the figures.
// Transfer maps (--transfer 4: 48 numbers a texel, 96 bytes as half floats) the same way, with the
// error that matters there too: of the lightmap relit under the bench's sun and sky.
// Run: build/luxel-bench --benchmark_filter='VectorQuantised|ClusteredPrincipal' (minutes on 2 cores: the bakes).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <benchmark/benchmark.h>

#include "luxel/import.h"
#include "luxel/lightmap.h"
#include "luxel/sh_compression.h"
#include "luxel/transfer_lightmap.h"

namespace luxel {
namespace {

// `file` (relative to the shared scenes) under the bench's sun and sky.
Scene sunAndSky(const std::string& file) {
  Scene s = loadScene((std::filesystem::path(LUXEL_BENCH_SCENES) / file).string());
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(Vec3(0.3f, -1.0f, 0.2f));
  sun.intensity = 100000.0f;
  Light sky;
  sky.type = Light::Type::Sky;
  sky.intensity = 2000.0f;
  s.lights = {sun, sky};
  return s;
}

// The L1 coefficients of every non-empty texel of `file`, baked once.
const std::vector<float>& l1Texels(const std::string& file) {
  static std::map<std::string, std::vector<float>> baked;
  auto it = baked.find(file);
  if (it != baked.end()) return it->second;
  const Scene s = sunAndSky(file);
  LightmapRecipe r;
  r.texelsPerMetre = 2.0f;
  r.directional = DirectionalMode::ShL1;
  const BakedLightmaps b = bakeLightmaps(s, r);
  std::vector<float> data;
  for (size_t p = 0; p < b.bake.state.size(); ++p)
    for (size_t i = 0; i < b.bake.state[p].size(); ++i) {
      if (b.bake.state[p][i] == LightmapBake::Empty) continue;
      for (int k = 0; k < 4; ++k)
        for (int ch = 0; ch < 3; ++ch) data.push_back(b.bake.sh[size_t(k)][p][i][ch]);
    }
  return baked[file] = std::move(data);
}

void report(benchmark::State& state, const CompressionReport& r, size_t texels) {
  state.counters["bytes_per_texel"] = r.bytesPerVector;
  state.counters["psnr_db"] = r.psnr;
  state.counters["texels"] = double(texels);
  state.counters["ratio_to_half"] = 24.0 / r.bytesPerVector;
}

// 004's scheme: a codebook of `codewords` and an index a texel.
void VectorQuantised(benchmark::State& state, const std::string& file) {
  const std::vector<float>& data = l1Texels(file);
  const size_t n = data.size() / 12;
  const int codewords = int(state.range(0));
  CompressionReport r;
  for (auto _ : state) {
    const luxel::VectorQuantised vq = vectorQuantise(data, 12, codewords, 60);
    r = compressionReport(data, reconstruct(vq), vq.indexBits, double(codewords) * 12 * 2, n);
    r.iterations = vq.iterations;
  }
  report(state, r, n);
  state.counters["iterations"] = r.iterations;
}

// Clustered PCA: range(0) clusters, range(1) components of 8 bits; means and bases as half floats,
// each component's scale as a half float.
void ClusteredPrincipalComponents(benchmark::State& state, const std::string& file) {
  const std::vector<float>& data = l1Texels(file);
  const size_t n = data.size() / 12;
  const int clusters = int(state.range(0)), components = int(state.range(1));
  CompressionReport r;
  for (auto _ : state) {
    const ClusteredPca p = clusteredPca(data, 12, clusters, components);
    r = compressionReport(data, reconstruct(p), p.clusterBits + 8 * components,
                          double(clusters) * (12 + components * 13) * 2, n);
  }
  report(state, r, n);
}

// A 4-band transfer bake of every non-empty texel of `file` at 2 texels per metre, baked once:
// [texel][coefficient][channel], and the sun and sky's SH.
struct TransferTexels {
  std::vector<float> data;
  DistantLightSh light;
};
constexpr int kTransferNumbers = 16 * 3;
const TransferTexels& transferTexels(const std::string& file) {
  static std::map<std::string, TransferTexels> baked;
  auto it = baked.find(file);
  if (it != baked.end()) return it->second;
  const Scene s = sunAndSky(file);
  LightmapRecipe r;
  r.texelsPerMetre = 2.0f;
  const BakedTransfer b = bakeTransfer(s, r, 4);
  TransferTexels t;
  t.light = distantLightSh(s, 4);
  const LightmapBake& texels = b.transfer.texels;
  for (size_t p = 0; p < texels.state.size(); ++p)
    for (size_t i = 0; i < texels.state[p].size(); ++i) {
      if (texels.state[p][i] == LightmapBake::Empty) continue;
      for (int k = 0; k < 16; ++k)
        for (int ch = 0; ch < 3; ++ch) t.data.push_back(b.transfer.planes[size_t(k)][p][i][ch]);
    }
  return baked[file] = std::move(t);
}

// PSNR of the relit irradiance (sum_i T_i L_i per channel, at least 0) of `decoded` against the
// original's, peak = the largest original irradiance.
double relitPsnr(const TransferTexels& t, const std::vector<float>& decoded) {
  const size_t n = t.data.size() / kTransferNumbers;
  double peak = 0.0, squared = 0.0;
  for (size_t v = 0; v < n; ++v)
    for (int ch = 0; ch < 3; ++ch) {
      double a = 0.0, b = 0.0;
      for (int k = 0; k < 16; ++k) {
        const size_t at = v * kTransferNumbers + size_t(k) * 3 + size_t(ch);
        a += double(t.data[at]) * t.light.coefficients[size_t(k)][ch];
        b += double(decoded[at]) * t.light.coefficients[size_t(k)][ch];
      }
      a = std::max(a, 0.0), b = std::max(b, 0.0);
      peak = std::max(peak, a);
      squared += (a - b) * (a - b);
    }
  const double mse = squared / double(3 * n);
  return mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : 999.0;
}

void TransferVectorQuantised(benchmark::State& state, const std::string& file) {
  const TransferTexels& t = transferTexels(file);
  const size_t n = t.data.size() / kTransferNumbers;
  const int codewords = int(state.range(0));
  CompressionReport r;
  double relit = 0.0;
  for (auto _ : state) {
    const luxel::VectorQuantised vq = vectorQuantise(t.data, kTransferNumbers, codewords, 60);
    const std::vector<float> decoded = reconstruct(vq);
    r = compressionReport(t.data, decoded, vq.indexBits, double(codewords) * kTransferNumbers * 2, n);
    relit = relitPsnr(t, decoded);
  }
  report(state, r, n);
  state.counters["ratio_to_half"] = kTransferNumbers * 2.0 / r.bytesPerVector;
  state.counters["relit_psnr_db"] = relit;
}

void TransferClusteredPca(benchmark::State& state, const std::string& file) {
  const TransferTexels& t = transferTexels(file);
  const size_t n = t.data.size() / kTransferNumbers;
  const int clusters = int(state.range(0)), components = int(state.range(1));
  CompressionReport r;
  double relit = 0.0;
  for (auto _ : state) {
    const ClusteredPca p = clusteredPca(t.data, kTransferNumbers, clusters, components);
    const std::vector<float> decoded = reconstruct(p);
    r = compressionReport(t.data, decoded, p.clusterBits + 8 * components,
                          double(clusters) * (kTransferNumbers + components * (kTransferNumbers + 1)) * 2, n);
    relit = relitPsnr(t, decoded);
  }
  report(state, r, n);
  state.counters["ratio_to_half"] = kTransferNumbers * 2.0 / r.bytesPerVector;
  state.counters["relit_psnr_db"] = relit;
}

BENCHMARK_CAPTURE(VectorQuantised, sibenik, "sibenik-cathedral/sibenik.obj")->Arg(4096)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(VectorQuantised, sponza, "dabrovic-sponza/sponza.obj")->Arg(4096)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ClusteredPrincipalComponents, sibenik, "sibenik-cathedral/sibenik.obj")
    ->Args({8, 1})->Args({16, 1})->Args({16, 2})->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(ClusteredPrincipalComponents, sponza, "dabrovic-sponza/sponza.obj")
    ->Args({8, 1})->Args({16, 1})->Args({16, 2})->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(TransferVectorQuantised, sibenik, "sibenik-cathedral/sibenik.obj")
    ->Arg(4096)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(TransferClusteredPca, sibenik, "sibenik-cathedral/sibenik.obj")
    ->Args({8, 1})->Args({8, 4})->Args({16, 4})->Args({16, 8})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace luxel
