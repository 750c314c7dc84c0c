// Vector quantisation and clustered PCA of SH lightmaps: see luxel/sh_compression.h.
#include "luxel/sh_compression.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "luxel/error.h"

namespace luxel {
namespace {

int bitsFor(size_t count) {
  int bits = 0;
  while ((size_t(1) << bits) < count) ++bits;
  return std::max(bits, 1);
}

float distance2(const float* a, const float* b, int d) {
  float s = 0.0f;
  for (int k = 0; k < d; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
  return s;
}

void checkSizes(std::span<const float> data, int dimension, int groups, const char* what) {
  if (dimension < 1 || dimension > 256 || data.size() % size_t(dimension) != 0)
    throw Error(fmt::format("{}: {} numbers are not vectors of dimension {}", what, data.size(), dimension));
  const size_t n = data.size() / size_t(dimension);
  if (groups < 1 || size_t(groups) > n || groups > (1 << 24))
    throw Error(fmt::format("{}: {} groups for {} vectors", what, groups, n));
}

// Lloyd's iteration: centres (groups x dimension) from evenly spread vectors; each vector to its
// nearest centre, each centre to its vectors' mean. Stops by 004's rule: the largest distance of
// any vector to its centre, when it has not improved on its best for three iterations (the
// assignments alone can cycle for ever, 004 section 5.6).
int lloyd(std::span<const float> data, int d, int groups, int maxIterations, std::vector<float>& centres,
          std::vector<uint32_t>& assignment) {
  const size_t n = data.size() / size_t(d);
  // Start from vectors far apart (Gonzalez's farthest-point order: each next one the farthest from
  // those chosen), deterministic and with no two starts in one tight group.
  centres.assign(size_t(groups) * size_t(d), 0.0f);
  std::vector<float> gap(n, std::numeric_limits<float>::infinity());
  size_t next = 0;
  for (int g = 0; g < groups; ++g) {
    std::copy_n(data.data() + next * size_t(d), d, centres.data() + size_t(g) * size_t(d));
    const float* c = centres.data() + size_t(g) * size_t(d);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) gap[i] = std::min(gap[i], distance2(data.data() + i * size_t(d), c, d));
    });
    next = size_t(std::max_element(gap.begin(), gap.end()) - gap.begin());
  }
  assignment.assign(n, 0);
  float best = std::numeric_limits<float>::infinity();
  int sinceBest = 0, iterations = 0;
  std::vector<float> worst(n);
  while (iterations < maxIterations) {
    ++iterations;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i < r.end(); ++i) {
        const float* v = data.data() + i * size_t(d);
        float nearest = std::numeric_limits<float>::infinity();
        uint32_t at = 0;
        for (int g = 0; g < groups; ++g) {
          const float dist = distance2(v, centres.data() + size_t(g) * size_t(d), d);
          if (dist < nearest) nearest = dist, at = uint32_t(g);
        }
        assignment[i] = at;
        worst[i] = nearest;
      }
    });
    const float largest = *std::max_element(worst.begin(), worst.end());
    if (largest < best) best = largest, sinceBest = 0;
    else if (++sinceBest >= 3) break;
    std::vector<double> sum(centres.size(), 0.0);
    std::vector<size_t> count(size_t(groups), 0);
    for (size_t i = 0; i < n; ++i) {
      ++count[assignment[i]];
      for (int k = 0; k < d; ++k) sum[size_t(assignment[i]) * size_t(d) + size_t(k)] += data[i * size_t(d) + size_t(k)];
    }
    for (int g = 0; g < groups; ++g)
      if (count[size_t(g)] > 0)  // an empty group keeps its centre
        for (int k = 0; k < d; ++k)
          centres[size_t(g) * size_t(d) + size_t(k)] = float(sum[size_t(g) * size_t(d) + size_t(k)] / double(count[size_t(g)]));
    if (largest == 0.0f) break;
  }
  return iterations;
}

}  // namespace

VectorQuantised vectorQuantise(std::span<const float> data, int dimension, int codewords, int maxIterations) {
  checkSizes(data, dimension, codewords, "vector quantisation");
  VectorQuantised vq;
  vq.dimension = dimension;
  vq.iterations = lloyd(data, dimension, codewords, maxIterations, vq.codebook, vq.indices);
  vq.indexBits = bitsFor(size_t(codewords));
  return vq;
}

std::vector<float> reconstruct(const VectorQuantised& vq) {
  const size_t d = size_t(vq.dimension);
  std::vector<float> out(vq.indices.size() * d);
  for (size_t i = 0; i < vq.indices.size(); ++i)
    std::copy_n(vq.codebook.data() + size_t(vq.indices[i]) * d, d, out.data() + i * d);
  return out;
}

namespace {

// Mean and leading components of the vectors assigned to cluster c; their 8-bit weights.
void fitCluster(std::span<const float> data, ClusteredPca& p, int c) {
  const int d = p.dimension, m = p.components;
  const size_t n = p.cluster.size();
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(d);
  size_t count = 0;
  for (size_t i = 0; i < n; ++i)
    if (p.cluster[i] == uint32_t(c)) {
      mean += Eigen::Map<const Eigen::VectorXf>(data.data() + i * size_t(d), d).cast<double>();
      ++count;
    }
  if (count == 0) return;  // keeps what it had
  mean /= double(count);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(d, d);
  for (size_t i = 0; i < n; ++i)
    if (p.cluster[i] == uint32_t(c)) {
      const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXf>(data.data() + i * size_t(d), d).cast<double>() - mean;
      cov.noalias() += x * x.transpose();
    }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
  for (int k = 0; k < d; ++k) p.means[size_t(c) * size_t(d) + size_t(k)] = float(mean(k));
  for (int j = 0; j < m; ++j) {
    const Eigen::VectorXd axis = eig.eigenvectors().col(d - 1 - j);  // ascending order: the largest last
    for (int k = 0; k < d; ++k) p.bases[(size_t(c) * size_t(m) + size_t(j)) * size_t(d) + size_t(k)] = float(axis(k));
  }
  // The weights' range, for 8 bits.
  std::vector<float> largest(size_t(m), 0.0f);
  for (size_t i = 0; i < n; ++i)
    if (p.cluster[i] == uint32_t(c))
      for (int j = 0; j < m; ++j) {
        float w = 0.0f;
        for (int k = 0; k < d; ++k)
          w += (data[i * size_t(d) + size_t(k)] - p.means[size_t(c) * size_t(d) + size_t(k)]) *
               p.bases[(size_t(c) * size_t(m) + size_t(j)) * size_t(d) + size_t(k)];
        largest[size_t(j)] = std::max(largest[size_t(j)], std::abs(w));
      }
  for (int j = 0; j < m; ++j) p.scale[size_t(c) * size_t(m) + size_t(j)] = std::max(largest[size_t(j)], 1e-30f);
}

// Vector i encoded in cluster c: its quantised weights into w, the squared error returned.
float encodeIn(std::span<const float> data, const ClusteredPca& p, size_t i, int c, uint8_t* w) {
  const int d = p.dimension, m = p.components;
  float rec[256];
  const float* mean = p.means.data() + size_t(c) * size_t(d);
  std::copy_n(mean, d, rec);
  for (int j = 0; j < m; ++j) {
    const float* axis = p.bases.data() + (size_t(c) * size_t(m) + size_t(j)) * size_t(d);
    float dot = 0.0f;
    for (int k = 0; k < d; ++k) dot += (data[i * size_t(d) + size_t(k)] - mean[k]) * axis[k];
    const float s = p.scale[size_t(c) * size_t(m) + size_t(j)];
    const int code = std::clamp(int(std::lround((dot / s * 0.5f + 0.5f) * 255.0f)), 0, 255);
    w[j] = uint8_t(code);
    const float q = (float(code) / 255.0f * 2.0f - 1.0f) * s;
    for (int k = 0; k < d; ++k) rec[k] += q * axis[k];
  }
  return distance2(rec, data.data() + i * size_t(d), d);
}

}  // namespace

ClusteredPca clusteredPca(std::span<const float> data, int dimension, int clusters, int components, int refits) {
  checkSizes(data, dimension, clusters, "clustered PCA");
  if (components < 1 || components > dimension)
    throw Error(fmt::format("clustered PCA: {} components of vectors of dimension {}", components, dimension));
  ClusteredPca p;
  p.dimension = dimension, p.components = components;
  std::vector<float> centres;
  p.iterations = lloyd(data, dimension, clusters, 100, centres, p.cluster);
  p.clusterBits = bitsFor(size_t(clusters));
  p.means.assign(size_t(clusters) * size_t(dimension), 0.0f);
  p.bases.assign(size_t(clusters) * size_t(components) * size_t(dimension), 0.0f);
  p.scale.assign(size_t(clusters) * size_t(components), 1.0f);
  const size_t n = p.cluster.size();
  p.weights.assign(n * size_t(components), 0);
  for (int round = 0; round <= refits; ++round) {
    tbb::parallel_for(0, clusters, [&](int c) { fitCluster(data, p, c); });
    // Each vector to the cluster whose mean and components reconstruct it best.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), [&](const tbb::blocked_range<size_t>& r) {
      std::vector<uint8_t> w(static_cast<size_t>(components));
      for (size_t i = r.begin(); i < r.end(); ++i) {
        float best = std::numeric_limits<float>::infinity();
        for (int c = 0; c < clusters; ++c) {
          const float e = encodeIn(data, p, i, c, w.data());
          if (e < best) best = e, p.cluster[i] = uint32_t(c), std::copy(w.begin(), w.end(), p.weights.begin() + long(i * size_t(components)));
        }
      }
    });
  }
  return p;
}

std::vector<float> reconstruct(const ClusteredPca& p) {
  const size_t d = size_t(p.dimension), m = size_t(p.components);
  std::vector<float> out(p.cluster.size() * d);
  for (size_t i = 0; i < p.cluster.size(); ++i) {
    const size_t c = p.cluster[i];
    float* o = out.data() + i * d;
    std::copy_n(p.means.data() + c * d, d, o);
    for (size_t j = 0; j < m; ++j) {
      const float q = (float(p.weights[i * m + j]) / 255.0f * 2.0f - 1.0f) * p.scale[c * m + j];
      for (size_t k = 0; k < d; ++k) o[k] += q * p.bases[(c * m + j) * d + k];
    }
  }
  return out;
}

CompressionReport compressionReport(std::span<const float> original, std::span<const float> decoded,
                                    double bitsPerVector, double fixedBytes, size_t vectors) {
  if (original.size() != decoded.size() || vectors == 0)
    throw Error("compression report: the original and the decoded sets differ in size");
  double peak = 0.0, se = 0.0;
  for (size_t i = 0; i < original.size(); ++i) {
    peak = std::max(peak, double(std::abs(original[i])));
    const double e = double(original[i]) - double(decoded[i]);
    se += e * e;
  }
  CompressionReport r;
  const double mse = se / double(original.size());
  r.rmsError = std::sqrt(mse);
  r.psnr = mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
  r.bytesPerVector = bitsPerVector / 8.0 + fixedBytes / double(vectors);
  return r;
}

}  // namespace luxel
