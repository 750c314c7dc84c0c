// Compressing spherical-harmonic lightmaps (issue 17; seed 004 section 4.7): every texel's
// coefficients as one vector, and two ways to store far fewer bytes than the floats.
//  - Vector quantisation, as 004 did it: a codebook of representative vectors found by Lloyd's
//    iteration (004's "iterated closest points") with 004's stopping rule (stop when the largest
//    distance of any vector to its representative has not improved on its best for three
//    iterations), and an index per texel (16 bits in 004; here as many bits as the codebook needs).
//  - Clustered PCA (Sloan, Hall, Hart and Snyder, "Clustered Principal Components for
//    Precomputed Radiance Transfer", SIGGRAPH 2003): a few clusters, each with its mean and its
//    first principal components; per texel a cluster index and one 8-bit weight per component.
// docs/baking.md, "Compression", has the measurements.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace luxel {

// What a compressed set costs and how far it is from the original.
struct CompressionReport {
  double bytesPerVector = 0.0;  // indices and weights, plus the codebook or bases spread over the vectors
  double psnr = 0.0;            // dB: 10 log10(peak^2 / mean squared error per number), peak = largest |number|
  double rmsError = 0.0;
  int iterations = 0;
};

struct VectorQuantised {
  int dimension = 0;
  std::vector<float> codebook;    // codewords x dimension
  std::vector<uint32_t> indices;  // per vector
  int indexBits = 0;              // ceil(log2(codewords)), as stored
  int iterations = 0;
};

// Lloyd's iteration from `codewords` vectors far apart (each the farthest from those before), with
// 004's stopping rule, at most `maxIterations`. data: N x dimension. Throws Error on absurd sizes.
VectorQuantised vectorQuantise(std::span<const float> data, int dimension, int codewords, int maxIterations = 100);
std::vector<float> reconstruct(const VectorQuantised& vq);

struct ClusteredPca {
  int dimension = 0, components = 0;
  std::vector<float> means;        // clusters x dimension
  std::vector<float> bases;        // clusters x components x dimension (orthonormal rows)
  std::vector<float> scale;        // clusters x components: weight = (code / 255 * 2 - 1) * scale
  std::vector<uint32_t> cluster;   // per vector
  std::vector<uint8_t> weights;    // per vector x components, 8 bits each
  int clusterBits = 0;
  int iterations = 0;
};

// Clusters by Lloyd's iteration on the vectors (started as vectorQuantise's), then per cluster the
// mean and the `components` leading principal components (Eigen's symmetric eigensolver on the
// cluster's covariance), weights quantised to 8 bits; then each vector moves to the cluster that
// reconstructs it best, and the bases are fitted again, `refits` times (Sloan et al.'s iterative
// CPCA).
ClusteredPca clusteredPca(std::span<const float> data, int dimension, int clusters, int components, int refits = 4);
std::vector<float> reconstruct(const ClusteredPca& cpca);

// Bytes per vector and error of `decoded` against `original` (N x dimension each), with
// `fixedBytes` (a codebook, bases) spread over the N vectors and `bitsPerVector` for each.
CompressionReport compressionReport(std::span<const float> original, std::span<const float> decoded,
                                    double bitsPerVector, double fixedBytes, size_t vectors);

}  // namespace luxel
