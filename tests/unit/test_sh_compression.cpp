// Compressing SH lightmaps (luxel/sh_compression.h): vector quantisation with 004's stopping rule
// and clustered PCA, on sets whose best compression is known, and the report's closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "luxel/error.h"
#include "luxel/sh_compression.h"

namespace {

// `groups` points repeated (with `jitter`) `copies` times each, in dimension d.
std::vector<float> clustersOf(int groups, int copies, int d, float jitter, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> centres(size_t(groups) * size_t(d));
  for (float& c : centres) c = 10.0f * u(rng);
  std::vector<float> data;
  for (int k = 0; k < copies; ++k)
    for (int g = 0; g < groups; ++g)
      for (int i = 0; i < d; ++i) data.push_back(centres[size_t(g) * size_t(d) + size_t(i)] + jitter * u(rng));
  return data;
}

TEST(ShCompression, VectorQuantisationFindsExactClusters) {
  const std::vector<float> data = clustersOf(16, 20, 12, 0.0f, 1);
  const luxel::VectorQuantised vq = luxel::vectorQuantise(data, 12, 16);
  EXPECT_EQ(vq.indexBits, 4);
  const std::vector<float> back = luxel::reconstruct(vq);
  // The farthest-point start takes one vector of every group (a vector of a group not yet taken is
  // always farther than 0), so the codebook is the groups themselves and nothing is lost.
  for (size_t i = 0; i < data.size(); ++i) ASSERT_EQ(back[i], data[i]);
  const luxel::CompressionReport r = luxel::compressionReport(data, back, vq.indexBits, 16 * 12 * 2, 320);
  EXPECT_TRUE(std::isinf(r.psnr));
  EXPECT_DOUBLE_EQ(r.bytesPerVector, 0.5 + 384.0 / 320.0);
}

TEST(ShCompression, VectorQuantisationStopsAndImprovesWithCodewords) {
  const std::vector<float> data = clustersOf(64, 40, 12, 1.0f, 2);
  double previous = 0.0;
  for (int codewords : {8, 64, 512}) {
    const luxel::VectorQuantised vq = luxel::vectorQuantise(data, 12, codewords, 100);
    EXPECT_LT(vq.iterations, 100) << "004's rule stops it before the cap";
    const auto r = luxel::compressionReport(data, luxel::reconstruct(vq), vq.indexBits, 0, data.size() / 12);
    EXPECT_GT(r.psnr, previous + 1.0) << codewords;
    previous = r.psnr;
  }
}

TEST(ShCompression, ClusteredPcaHoldsLinesToEightBits) {
  // Each of 8 clusters lies on a line through its centre: one component reconstructs it up to the
  // 8-bit weight, half a step of the cluster's range: |error| <= scale / 255 along the line.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const int d = 12, clusters = 8;
  std::vector<float> data;
  std::vector<float> centre(size_t(clusters) * d), dir(size_t(clusters) * d);
  for (float& c : centre) c = 20.0f * u(rng);
  for (int c = 0; c < clusters; ++c) {
    float len = 0.0f;
    for (int k = 0; k < d; ++k) dir[size_t(c * d + k)] = u(rng), len += dir[size_t(c * d + k)] * dir[size_t(c * d + k)];
    for (int k = 0; k < d; ++k) dir[size_t(c * d + k)] /= std::sqrt(len);
  }
  for (int i = 0; i < 50; ++i)
    for (int c = 0; c < clusters; ++c) {
      const float t = 3.0f * u(rng);
      for (int k = 0; k < d; ++k) data.push_back(centre[size_t(c * d + k)] + t * dir[size_t(c * d + k)]);
    }
  const luxel::ClusteredPca p = luxel::clusteredPca(data, d, clusters, 1);
  const std::vector<float> back = luxel::reconstruct(p);
  double worst = 0.0;
  for (size_t i = 0; i < data.size(); ++i) worst = std::max(worst, double(std::abs(back[i] - data[i])));
  EXPECT_LT(worst, 3.0 / 255.0 + 1e-3);
  EXPECT_EQ(p.clusterBits, 3);
}

TEST(ShCompression, ReportMatchesItsClosedFormAndRefusesMismatches) {
  const std::vector<float> a = {4.0f, -2.0f, 1.0f, 0.0f};
  const std::vector<float> b = {4.04f, -1.96f, 1.04f, 0.04f};  // every number 0.04 off, peak 4
  const auto r = luxel::compressionReport(a, b, 8, 0, 4);
  EXPECT_NEAR(r.psnr, 20.0 * std::log10(4.0 / 0.04), 1e-3);
  EXPECT_THROW(luxel::compressionReport(a, std::vector<float>(3, 0.0f), 8, 0, 4), luxel::Error);
  EXPECT_THROW(luxel::vectorQuantise(a, 3, 1), luxel::Error);     // 4 numbers are not vectors of 3
  EXPECT_THROW(luxel::vectorQuantise(a, 2, 3), luxel::Error);     // 3 codewords for 2 vectors
  EXPECT_THROW(luxel::clusteredPca(a, 2, 1, 3), luxel::Error);    // 3 components of dimension 2
}

}  // namespace

