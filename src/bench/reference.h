// Converged reference solutions for the benchmark's error column, as van de Hoef (2013, section
// 5.2) did: gathering at high settings on the same discretisation. They take seconds to minutes,
// so they are cached on disk under a hash of everything that determines them.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "io/atomic_file.h"

#include "luxel/bench.h"
#include "luxel/progress.h"
#include "luxel/scene.h"
#include "luxel/solve.h"

namespace luxel {
class ContentHash;
}

namespace luxel::bench {

struct Reference {
  std::vector<Rgb> radiosity;
  double seconds = 0.0;  // time to compute it; 0 when it came from the cache
  std::string path;      // the cache file
};

// A cache file: 8 magic bytes, the 64-bit key it was made for, a count, then that many records.
// readCacheFile is false (and `out` unspecified) unless the magic, key and count all match.
template <typename T>
bool readCacheFile(const std::filesystem::path& path, const char (&magic)[8], uint64_t key, size_t n, std::vector<T>& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char stored[8];
  uint64_t storedKey = 0, count = 0;
  in.read(stored, 8);
  in.read(reinterpret_cast<char*>(&storedKey), 8);
  in.read(reinterpret_cast<char*>(&count), 8);
  if (!in || std::memcmp(stored, magic, 8) != 0 || storedKey != key || count != n) return false;
  out.resize(n);
  in.read(reinterpret_cast<char*>(out.data()), std::streamsize(n * sizeof(T)));
  return bool(in);
}
template <typename T>
void writeCacheFile(const std::filesystem::path& path, const char (&magic)[8], uint64_t key, const std::vector<T>& records) {
  const uint64_t n = records.size();
  writeFileAtomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp);
    out.write(magic, 8);
    out.write(&key, 8);
    out.write(&n, 8);
    out.write(records.data(), n * sizeof(T));
    out.close();
  });
}

// Adds what fixes the light on `surfaces` to `h`: every element's polygon, reflectance and
// exitance, and the scene's analytic lights.
void hashLightingProblem(ContentHash& h, const Scene& scene, const SurfaceSet& surfaces);

// The settings references are solved with: Gauss-Seidel gathering to a 1e-6 residual, 64
// visibility rays for every pair, no pair classification, 64 samples per analytic light.
SolveOptions referenceSolveOptions();

// Rays per element of Monte Carlo references.
inline constexpr int kMonteCarloReferenceRays = 1 << 14;

// Loads the reference for `surfaces` from `cacheDir`, or solves and stores it there: with
// `solver` when given (any solver on the CPU backend), else with referenceSolveOptions() over
// the CPU's factors or Monte Carlo ones as `kind` says.
Reference loadOrComputeReference(const Scene& scene, const SurfaceSet& surfaces, const std::string& cacheDir,
                                 const ProgressCallback& progress,
                                 Options::ReferenceKind kind = Options::ReferenceKind::Cpu,
                                 const std::optional<SolveOptions>& solver = std::nullopt);

}  // namespace luxel::bench
