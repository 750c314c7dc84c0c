// The face-cluster hierarchy's disk cache (cluster/face_cluster_cache.h): a stored tree comes back
// byte for byte, the key changes with anything the build reads, a file that does not check out
// (torn, corrupt, another layout) is rebuilt rather than trusted, and a solve from the cache is
// bit-identical to one that built the tree.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "cluster/face_cluster_cache.h"
#include "luxel/import.h"
#include "luxel/solve.h"
#include "scene/builtin/builtin_scenes.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

fs::path freshDirectory(const std::string& name) {
  const fs::path dir = fs::path(LUXEL_TEST_TMP) / "face-cluster-cache" / name;
  fs::remove_all(dir);
  return dir;
}

bool sameTree(const FaceClusterTree& a, const FaceClusterTree& b) {
  return a.inner.size() == b.inner.size() && a.order == b.order && a.leafParent == b.leafParent &&
         a.leafAt == b.leafAt && a.root == b.root && a.components == b.components &&
         std::memcmp(a.inner.data(), b.inner.data(), a.inner.size() * sizeof(FaceCluster)) == 0;
}

SurfaceSet cornellSurfaces() { return discretise(builtinScene("cornell"), DiscretiseOptions{}); }

TEST(FaceClusterCache, AStoredTreeComesBackWhole) {
  const SurfaceSet surfaces = cornellSurfaces();
  const fs::path dir = freshDirectory("round-trip");
  const CachedFaceClusterTree first = cachedFaceClusterTree(surfaces, dir);
  EXPECT_FALSE(first.loaded);
  EXPECT_TRUE(first.warning.empty()) << first.warning;
  const CachedFaceClusterTree second = cachedFaceClusterTree(surfaces, dir);
  EXPECT_TRUE(second.loaded);
  EXPECT_TRUE(sameTree(first.tree, second.tree));
  EXPECT_TRUE(sameTree(first.tree, buildFaceClusterTree(surfaces)));
}

TEST(FaceClusterCache, TheKeyFollowsWhatTheBuildReads) {
  const SurfaceSet surfaces = cornellSurfaces();
  const uint64_t key = faceClusterKey(surfaces);
  EXPECT_EQ(key, faceClusterKey(cornellSurfaces()));
  SurfaceSet moved = surfaces;
  moved.elements[7].polygon.v[1].x += 1e-6f;
  EXPECT_NE(faceClusterKey(moved), key);
  SurfaceSet repainted = surfaces;
  repainted.elements[7].reflectance.g += 0.01f;
  EXPECT_NE(faceClusterKey(repainted), key);
  SurfaceSet fewer = surfaces;
  fewer.elements.pop_back();
  EXPECT_NE(faceClusterKey(fewer), key);
}

// Each way a file can be wrong: cut short, a flipped byte in the clusters, a wrong element count
// in the header. Each is rebuilt (not loaded) and rewritten, so the next call loads again.
TEST(FaceClusterCache, AFileThatDoesNotCheckOutIsRebuilt) {
  const SurfaceSet surfaces = cornellSurfaces();
  const fs::path dir = freshDirectory("corrupt");
  const FaceClusterTree built = cachedFaceClusterTree(surfaces, dir).tree;
  ASSERT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  const fs::path file = fs::directory_iterator(dir)->path();
  const auto size = fs::file_size(file);
  auto damage = [&](const std::function<void(std::fstream&)>& how) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    how(f);
  };
  const std::vector<std::pair<std::string, std::function<void()>>> cases = {
      {"cut short", [&] { fs::resize_file(file, size / 2); }},
      {"a flipped byte", [&] { damage([&](std::fstream& f) {
         f.seekg(std::streamoff(size - 8 * surfaces.elements.size() - 40));
         char c = 0;
         f.read(&c, 1);
         c = char(c ^ 0x10);
         f.seekp(std::streamoff(size - 8 * surfaces.elements.size() - 40));
         f.write(&c, 1);
       }); }},
      {"another element count", [&] { damage([&](std::fstream& f) {
         const uint64_t wrong = surfaces.elements.size() + 1;
         f.seekp(24);  // magic, key, joined nodes: then the order's length
         f.write(reinterpret_cast<const char*>(&wrong), sizeof wrong);
       }); }},
  };
  for (const auto& [name, spoil] : cases) {
    spoil();
    EXPECT_FALSE(loadFaceClusterTree(dir, faceClusterKey(surfaces), surfaces.elements.size())) << name;
    const CachedFaceClusterTree again = cachedFaceClusterTree(surfaces, dir);
    EXPECT_FALSE(again.loaded) << name;
    EXPECT_TRUE(sameTree(again.tree, built)) << name;
    EXPECT_TRUE(cachedFaceClusterTree(surfaces, dir).loaded) << name << ": rewritten";
    ASSERT_EQ(fs::file_size(file), size) << name;
  }
}

// A tree an older luxel wrote in another layout is never read again: saving a tree removes it,
// and leaves alone what is not a tree or not a cache file.
TEST(FaceClusterCache, TreesOfAnOlderLayoutGoWhenATreeIsSaved) {
  const SurfaceSet surfaces = cornellSurfaces();
  const fs::path dir = freshDirectory("stale");
  fs::create_directories(dir);
  auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
  };
  write("0123456789abcdef.fct", std::string("LXFCT001") + std::string(64, 'x'));  // format 2's magic
  write("other.fct", "not a tree at all");
  write("keep.bin", std::string("LXFCT001") + std::string(64, 'x'));
  ASSERT_FALSE(cachedFaceClusterTree(surfaces, dir).loaded);
  EXPECT_FALSE(fs::exists(dir / "0123456789abcdef.fct"));
  EXPECT_TRUE(fs::exists(dir / "other.fct"));
  EXPECT_TRUE(fs::exists(dir / "keep.bin"));
  EXPECT_TRUE(cachedFaceClusterTree(surfaces, dir).loaded);  // the new tree stays
}

TEST(FaceClusterCache, ASolveFromTheCacheIsTheSameSolve) {
  const Scene scene = builtinScene("cornell");
  ::setenv("LUXEL_CACHE_DIR", freshDirectory("solve").c_str(), 1);
  auto run = [&](bool cache) {
    SurfaceSet surfaces = discretise(scene, DiscretiseOptions{});
    SolveOptions o;
    o.method = "hierarchical";
    o.settings.set("cache", cache);
    return solve(scene, surfaces, o);
  };
  const Solution built = run(true), loaded = run(true), uncached = run(false);
  EXPECT_FALSE(built.stats.hierarchyCached);
  EXPECT_TRUE(loaded.stats.hierarchyCached);
  EXPECT_FALSE(uncached.stats.hierarchyCached);
  for (const Solution* s : {&loaded, &uncached}) {
    ASSERT_EQ(s->radiosity.size(), built.radiosity.size());
    EXPECT_EQ(std::memcmp(s->radiosity.data(), built.radiosity.data(), built.radiosity.size() * sizeof(Rgb)), 0);
    EXPECT_EQ(s->stats.links, built.stats.links);
  }
}

}  // namespace
}  // namespace luxel
