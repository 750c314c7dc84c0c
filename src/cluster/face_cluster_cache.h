// The face-cluster hierarchy kept on disk, keyed by the content of the surfaces it is built over,
// so that solving a large scene again (another light, another camera, another threshold) skips
// the build. Seed 002 built its hierarchy once per model, offline (464 s for 1.5M faces).
// A file is used only when its key, format, sizes and checksum all match; anything else (another
// scene, an older luxel, a torn or corrupt file) rebuilds the tree and rewrites the file, which is
// written beside its final name and renamed into place.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "cluster/face_cluster_tree.h"

namespace luxel {

// $LUXEL_CACHE_DIR/face-clusters, else $XDG_CACHE_HOME/luxel/face-clusters, else
// $HOME/.cache/luxel/face-clusters; empty when none of them is set.
std::filesystem::path defaultFaceClusterCacheDirectory();

// Everything buildFaceClusterTree reads of `surfaces` (each element's polygon, parameters, face
// corners, centroid, normal, area, reflectance and exitance), with the tree's format.
uint64_t faceClusterKey(const SurfaceSet& surfaces);

// The tree stored under `directory` for `key` over `elementCount` elements, or nothing when there
// is none or it does not check out.
std::optional<FaceClusterTree> loadFaceClusterTree(const std::filesystem::path& directory, uint64_t key,
                                                   size_t elementCount);
// Stores `tree` under `directory` (created when missing), and removes the trees there that an
// older luxel wrote in another layout. Throws Error when it cannot store it.
void saveFaceClusterTree(const std::filesystem::path& directory, uint64_t key, const FaceClusterTree& tree);

struct CachedFaceClusterTree {
  FaceClusterTree tree;     // tree.seconds: hashing and loading, or hashing, building and saving
  bool loaded = false;      // read from the cache
  std::string warning;      // why the tree could not be saved, if it could not
};

// Loads the tree from `directory` or builds it and saves it there; builds only when `directory`
// is empty.
CachedFaceClusterTree cachedFaceClusterTree(const SurfaceSet& surfaces, const std::filesystem::path& directory);

}  // namespace luxel
