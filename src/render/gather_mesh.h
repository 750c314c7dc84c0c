// The mesh an hq render's vertex gather runs on (render/final_gather.h): the solution's elements,
// each split into 4^k by SurfaceSet::splitElement. A vertex gather reads the solution two or three
// bounces away, where its discretisation hardly shows, but interpolates its own result over elements, so
// the picture wants finer elements than the solve does: beside a crease or a contact the gathered
// light bends within an element, and coarse elements show it as dark bands. Splitting decouples
// the two, so the solve (whose cost grows with elements times patches) runs on a quarter or a
// sixteenth of the elements the gather interpolates over (docs/algorithms.md, "Rendering").
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "luxel/scene.h"
#include "luxel/surface.h"

namespace luxel {

// The most elements a split may make (each takes about 100 bytes beside its gathered corners).
inline constexpr size_t kMaxGatherElements = size_t(1) << 22;
// The most splits an element larger than GatherMesh's maxArea takes (4^6 = 4,096 pieces).
inline constexpr int kMaxLargeSplits = 6;

class GatherMesh {
 public:
  // The splits that bring `solved` elements nearest `wanted` (by their ratio; none when wanted is
  // 0 or not above solved), at most 4 and never past kMaxGatherElements.
  static int splitsFor(size_t solved, size_t wanted);

  // `solved` split `splits` times (0: the solved elements themselves, nothing copied), and then
  // each element larger than `maxArea` split again until it is not (at most kMaxLargeSplits more
  // times): a solve that keeps faces whole (the hierarchical solver's walls of tens of square
  // metres) would give the gather a wall's four corners to interpolate across it. The split set
  // has no patches. `solved` must outlive this.
  GatherMesh(const Scene& scene, const SurfaceSet& solved, int splits,
             float maxArea = std::numeric_limits<float>::infinity());

  const SurfaceSet& surfaces() const { return split_ ? *split_ : solved_; }
  const SurfaceSet& solved() const { return solved_; }
  bool isSplit() const { return split_.has_value(); }
  // The solved element that element e of surfaces() lies in, and whether e is that element whole.
  uint32_t parent(uint32_t e) const { return split_ ? parent_[e] : e; }
  bool whole(uint32_t e) const {
    return !split_ || local_[e] == wholeCorners(split_->faces[split_->elements[e].face].triangle);
  }
  // Corner c of element e of surfaces() in its parent's coordinates (as interpolateCorners takes
  // them); only when isSplit().
  Vec2 local(uint32_t e, int c) const { return local_[e][size_t(c)]; }
  // A corner field of the solved elements (4 slots each, as elementCornerValues lays them out),
  // at the corners of surfaces()'s elements: each interpolated in its parent the way a hit there
  // is (barycentric on triangles, bilinear on quads), so the field is the same function of
  // position on either mesh.
  std::vector<Rgb> corners(const std::vector<Rgb>& solvedCorners) const;

 private:
  const SurfaceSet& solved_;
  std::optional<SurfaceSet> split_;
  std::vector<uint32_t> parent_;
  std::vector<std::array<Vec2, 4>> local_;  // each element's corners in its parent's coordinates
  // A whole element's corners in its own coordinates (a triangle's fourth repeats its third).
  static std::array<Vec2, 4> wholeCorners(bool triangle) {
    return {Vec2(0.0f, 0.0f), Vec2(1.0f, 0.0f), triangle ? Vec2(0.0f, 1.0f) : Vec2(1.0f, 1.0f), Vec2(0.0f, 1.0f)};
  }
};

}  // namespace luxel
