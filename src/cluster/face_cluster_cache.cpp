#include "cluster/face_cluster_cache.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <type_traits>

#include <fmt/format.h>

#include "core/content_hash.h"
#include "mesh/surface_hash.h"
#include "core/stopwatch.h"
#include "io/atomic_file.h"
#include "luxel/error.h"

namespace luxel {
namespace {

// Bump when buildFaceClusterTree would build a different tree from the same surfaces.
constexpr char kFormat[] = "luxel-face-clusters-3";  // 3: leaves not stored
constexpr char kMagic[8] = {'L', 'X', 'F', 'C', 'T', '0', '0', '2'};

static_assert(std::is_trivially_copyable_v<FaceCluster>, "clusters are written as bytes");

struct Header {
  char magic[8];
  uint64_t key;
  uint64_t inner, order;  // joined nodes; elements (each with its place in order and its leaf's parent)
  uint32_t root, components;
  uint64_t clusterSize;  // sizeof(FaceCluster): another layout is another format
  uint64_t checksum;     // of the joined nodes', order's and leaf parents' bytes
};

std::filesystem::path fileFor(const std::filesystem::path& directory, uint64_t key) {
  return directory / fmt::format("{:016x}.fct", key);
}

uint64_t checksum(const FaceClusterTree& tree) {
  ContentHash h;
  h.bytes(tree.inner.data(), tree.inner.size() * sizeof(FaceCluster));
  h.bytes(tree.order.data(), tree.order.size() * sizeof(uint32_t));
  h.bytes(tree.leafParent.data(), tree.leafParent.size() * sizeof(uint32_t));
  return h.digest();
}

// Indices that a corrupt file with a good checksum (a collision, or a bug that wrote it) could
// still get wrong would send the solver out of bounds: checked once more.
bool consistent(const FaceClusterTree& t, size_t n) {
  const size_t nodes = t.nodeCount();
  if (t.order.size() != n || t.leafParent.size() != n || t.inner.size() > n - 1 || t.root >= nodes) return false;
  std::vector<uint8_t> seen(n, 0);
  for (uint32_t e : t.order) {
    if (e >= n || seen[e]) return false;
    seen[e] = 1;
  }
  for (uint32_t p : t.leafParent)
    if (p != kNoCluster && (p < n || p >= nodes)) return false;
  for (const FaceCluster& c : t.inner) {
    if (size_t(c.begin) + c.count > n) return false;
    if (c.parent != kNoCluster && (c.parent < n || c.parent >= nodes)) return false;
    for (uint32_t k : c.child)
      if (k >= nodes) return false;
  }
  return true;
}

}  // namespace

std::filesystem::path defaultFaceClusterCacheDirectory() {
  if (const char* d = std::getenv("LUXEL_CACHE_DIR"); d && *d) return std::filesystem::path(d) / "face-clusters";
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::filesystem::path(d) / "luxel" / "face-clusters";
  if (const char* d = std::getenv("HOME"); d && *d) return std::filesystem::path(d) / ".cache" / "luxel" / "face-clusters";
  return {};
}

uint64_t faceClusterKey(const SurfaceSet& surfaces) {
  ContentHash h;
  h.text(kFormat);
  hashSurfaces(h, surfaces);
  return h.digest();
}

std::optional<FaceClusterTree> loadFaceClusterTree(const std::filesystem::path& directory, uint64_t key,
                                                   size_t elementCount) {
  std::ifstream in(fileFor(directory, key), std::ios::binary);
  if (!in || elementCount == 0) return std::nullopt;
  Header h{};
  in.read(reinterpret_cast<char*>(&h), sizeof h);
  if (!in || std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.key != key || h.clusterSize != sizeof(FaceCluster) ||
      h.order != elementCount || h.inner > elementCount - 1)
    return std::nullopt;
  FaceClusterTree t;
  t.inner.resize(h.inner);
  t.order.resize(h.order);
  t.leafParent.resize(h.order);
  t.root = h.root, t.components = h.components;
  in.read(reinterpret_cast<char*>(t.inner.data()), std::streamsize(t.inner.size() * sizeof(FaceCluster)));
  in.read(reinterpret_cast<char*>(t.order.data()), std::streamsize(t.order.size() * sizeof(uint32_t)));
  in.read(reinterpret_cast<char*>(t.leafParent.data()), std::streamsize(t.leafParent.size() * sizeof(uint32_t)));
  if (!in || in.peek() != std::char_traits<char>::eof() || checksum(t) != h.checksum || !consistent(t, elementCount))
    return std::nullopt;
  t.leafAt.resize(t.order.size());
  for (uint32_t k = 0; k < t.order.size(); ++k) t.leafAt[t.order[k]] = k;
  return t;
}

namespace {

// Trees in a layout this luxel cannot read (an older one's) are never loaded again, and at
// millions of faces each is hundreds of MB: they go when a tree is saved beside them. Files that
// are not trees (no "LXFCT" at their start) are left alone.
void removeStaleTrees(const std::filesystem::path& directory) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    if (entry.path().extension() != ".fct") continue;
    char magic[sizeof kMagic] = {};
    {
      std::ifstream in(entry.path(), std::ios::binary);
      in.read(magic, sizeof magic);
      if (!in || std::memcmp(magic, kMagic, 5) != 0 || std::memcmp(magic, kMagic, sizeof kMagic) == 0) continue;
    }
    std::filesystem::remove(entry.path(), ec);
  }
}

}  // namespace

void saveFaceClusterTree(const std::filesystem::path& directory, uint64_t key, const FaceClusterTree& tree) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error(fmt::format("{}: cannot create the face-cluster cache: {}", directory.string(), ec.message()));
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.key = key;
  h.inner = tree.inner.size(), h.order = tree.order.size();
  h.root = tree.root, h.components = tree.components;
  h.clusterSize = sizeof(FaceCluster);
  h.checksum = checksum(tree);
  writeFileAtomically(fileFor(directory, key), [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp);
    out.write(&h, sizeof h);
    out.write(tree.inner.data(), tree.inner.size() * sizeof(FaceCluster));
    out.write(tree.order.data(), tree.order.size() * sizeof(uint32_t));
    out.write(tree.leafParent.data(), tree.leafParent.size() * sizeof(uint32_t));
    out.close();
  });
  removeStaleTrees(directory);
}

CachedFaceClusterTree cachedFaceClusterTree(const SurfaceSet& surfaces, const std::filesystem::path& directory) {
  const Stopwatch watch;
  CachedFaceClusterTree out;
  if (directory.empty()) {
    out.tree = buildFaceClusterTree(surfaces);
    return out;
  }
  const uint64_t key = faceClusterKey(surfaces);
  if (std::optional<FaceClusterTree> t = loadFaceClusterTree(directory, key, surfaces.elements.size())) {
    out.tree = std::move(*t);
    out.loaded = true;
  } else {
    out.tree = buildFaceClusterTree(surfaces);
    try {
      saveFaceClusterTree(directory, key, out.tree);
    } catch (const Error& e) {
      out.warning = fmt::format("the face-cluster hierarchy was not cached: {}", e.what());
    }
  }
  out.tree.seconds = watch.seconds();
  return out;
}

}  // namespace luxel
