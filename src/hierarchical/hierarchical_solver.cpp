// Hierarchical face-cluster radiosity with vector irradiance in higher-order bases: Gobbetti,
// Spano and Agus, "Hierarchical Higher Order Face Cluster Radiosity for Global Illumination
// Walkthroughs of Complex Non-Diffuse Environments", Eurographics 2003 (Algorithm 1), over the
// face-cluster hierarchy of Garland, Willmott and Heckbert 2001 (cluster/face_cluster_tree.h).
//
// Each iteration is a Jacobi sweep (one bounce): every element shoots the unshot radiosity it
// gathered in the previous one. Receivers are visited top-down, each with its list of potential
// shooters; a link is refined (receiver or emitter split, whichever is larger) until its transfer
// error is below a fraction of the emitted power, and links are never stored. Irradiance is a
// vector per colour channel per basis function, kept only at the leaves of the element tree.
// The choices the paper leaves open are settled in docs/algorithms.md ("Face-cluster
// radiosity"); the short form is in the comments where each is made.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <tbb/concurrent_vector.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "cluster/cluster_visibility.h"
#include "cluster/face_cluster_cache.h"
#include "cluster/face_cluster_tree.h"
#include "core/content_hash.h"
#include "core/spherical_harmonics.h"
#include "core/stopwatch.h"
#include "hierarchical/cluster_points.h"
#include "hierarchical/legendre_basis.h"
#include "luxel/error.h"
#include "solve/emitter_direct.h"
#include "solve/solver_registry.h"
#include "solve/step_control.h"
#include "trace/ray_tracer.h"
#include "transport/form_factor.h"
#include "transport/form_factor_options.h"

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr uint32_t kNever = std::numeric_limits<uint32_t>::max();
// Receiver subtrees of at least this many faces are traversed as parallel tasks.
constexpr uint32_t kParallelFaces = 2048;
// How far below a receiver cluster's horizon (a sine: 0.1 is 5.7 degrees) an emitter may reach
// and still send it one vector (cluster/cluster_geometry.h, whollyFaces).
constexpr float kHorizonSlack = 0.1f;

// Changes of the analytic light are followed (HierarchicalSolver::sourcesChanged) until their power,
// summed since the solve started, reaches this share of the light's: past it the links, chosen
// for a light that is no longer there, are made again (a followed solution drifts from the
// converged light as the changes add up: docs/performance.md, "Moving the sun over Sibenik").
constexpr double kMostChangeFollowed = 0.5;

// A receiver point nearer an emitter cluster than this times the cluster's half diagonal makes the
// link refine (HierarchicalSolver::transportLight).
constexpr float kSeparation = 1.0f;

struct HierarchicalSettings {
  int basis;               // irradiance basis functions: 1, 3, 4, 6 or 10
  double error;            // link error threshold, relative to the emitted power
  double unshot;           // stop when the unshot power falls below this share of the emitted
  int maxIterations;
  int receiverSide;        // receiver points: about side^2
  int emitterSide;         // emitter points
  bool cache;              // keep the hierarchy on disk (cluster/face_cluster_cache.h)
  // The emitting surfaces' direct light per element (solve/emitter_direct.h), or through links as
  // the paper shoots it (also where there are more emitting polygons than per-element visits allow).
  bool emitterLightPerElement;
  // Changes of the analytic light are followed from the last solution (sourcesChanged), or solved
  // again from scratch.
  bool followLight = true;
  // The links' visibility: exact rays (Embree), or the hierarchy's multiresolution visibility
  // (cluster/cluster_visibility.h), whose descent stops at clusters whose shadow is smaller than
  // `visibilityStop` times the receiver's point spacing.
  bool clusterVisibility = false;
  float visibilityStop = 1.0f;
};

// Vector irradiance of one element: per basis function, per channel, a vector (Gobbetti et al.
// section 3.2). Coefficient (alpha, channel) is at alpha * 3 + channel.
struct Field {
  std::array<Vec3, kMaxBasisFunctions * 3> c{};
  // Light from links that some of the receiver's faces see from behind (not whollyFaces), as
  // radiance in spherical harmonics (core/spherical_harmonics.h), constant over the element:
  // coefficient (channel, i) at channel * 9 + i. Summed as vectors, light from around a round
  // cluster (a statue lit by every wall) cancels.
  std::array<float, 3 * kShCoefficients> sh{};
  // L1 directional bakes only (Solver::recordIncidentSh), for the light that came as vectors:
  // its radiance integrated over the sphere, the vector's companion that band 0 of the incident
  // SH needs, per basis function per channel at alpha * 3 + channel.
  std::array<float, kMaxBasisFunctions * 3> radiance{};

  Field& operator+=(const Field& o) {
    for (size_t k = 0; k < c.size(); ++k) c[k] += o.c[k];
    for (size_t k = 0; k < sh.size(); ++k) sh[k] += o.sh[k];
    for (size_t k = 0; k < radiance.size(); ++k) radiance[k] += o.radiance[k];
    return *this;
  }
  Field& operator-=(const Field& o) {
    for (size_t k = 0; k < c.size(); ++k) c[k] -= o.c[k];
    for (size_t k = 0; k < sh.size(); ++k) sh[k] -= o.sh[k];
    for (size_t k = 0; k < radiance.size(); ++k) radiance[k] -= o.radiance[k];
    return *this;
  }
};

float maxChannel(const Rgb& c) { return std::max({c.r, c.g, c.b}); }

// A square of area `a` centred on point y, in y's tangent plane, its sides along the cluster
// box's axes as far as the plane allows; wound so that its normal is y's.
Polygon squareAround(const SurfacePoint& y, float a, const OrientedBox& box) {
  Vec3 u = box.axis[0] - glm::dot(box.axis[0], y.normal) * y.normal;
  if (glm::dot(u, u) < 1e-6f) u = box.axis[1] - glm::dot(box.axis[1], y.normal) * y.normal;
  u = glm::normalize(u);
  const Vec3 v = glm::cross(y.normal, u);
  const float h = 0.5f * std::sqrt(a);
  Polygon square;
  square.count = 4;
  square.v = {y.position - h * u - h * v, y.position + h * u - h * v, y.position + h * u + h * v, y.position - h * u + h * v};
  return square;
}

// The hierarchy over `surfaces`, from the disk cache when `cache`.
CachedFaceClusterTree faceClusterTree(const SurfaceSet& surfaces, bool cache) {
  return cachedFaceClusterTree(surfaces, cache ? defaultFaceClusterCacheDirectory() : std::filesystem::path());
}

class HierarchicalSolver final : public Solver {
 public:
  // `prepared`: the hierarchy, built or loaded by the registry's prepare before the transport was;
  // null to make it here.
  HierarchicalSolver(const RadiositySystem& sys, Transport& transport, const HierarchicalSettings& s,
                     std::shared_ptr<CachedFaceClusterTree> prepared)
      : sys_(sys), s_(s) {
    tracer_ = transport.rayTracer();
    if (!tracer_) throw Error("the hierarchical solver needs a transport that traces rays (the CPU transport)");
    const Stopwatch watch;
    const bool wasPrepared = prepared != nullptr;
    CachedFaceClusterTree cached = prepared ? std::move(*prepared) : faceClusterTree(sys.surfaces, s.cache);
    if (cached.tree.elementCount() != sys.elementCount())
      throw Error("hierarchical solver: the prepared hierarchy is of other surfaces");
    tree_ = std::move(cached.tree);
    treeLoaded_ = cached.loaded;
    treeDepth_ = tree_.depth();
    if (!cached.warning.empty()) warnings_.push_back(cached.warning);
    points_ = std::make_unique<ClusterPoints>(tree_, sys.surfaces);
    rayOffset_ = rayOffsetFor(sys.surfaces.sceneExtent);
    // Boxes padded by a tenth of the rays' offset: a ray leaving a flat cluster has left its box
    // before its first point, so the walk does not descend the cluster it starts on.
    if (s.clusterVisibility)
      clusterVisibility_ = std::make_unique<ClusterVisibility>(tree_, sys.surfaces, 0.1f * rayOffset_);
    const size_t nodes = tree_.nodeCount(), ne = sys.elementCount();
    // The emitting surfaces' direct light, per element as the analytic lights' is: through the
    // hierarchy's links it was the largest error where lamps are surfaces (docs/algorithms.md,
    // "Direct light first").
    exactDirect_ = s.emitterLightPerElement;
    if (exactDirect_ && emittingPolygonCount(sys.surfaces) > kMaxEmittingPolygons) {
      exactDirect_ = false;
      warnings_.push_back(fmt::format("the emitting surfaces' direct light goes through the hierarchy's links: more than "
                                      "{} emitting polygons are too many to visit from every element",
                                      kMaxEmittingPolygons));
    }
    if (exactDirect_) emitterDirect_ = emitterDirectLight(sys.surfaces, *tracer_, 0, kEmitterDirectSeed);
    else emitterDirect_.irradiance.assign(ne, Rgb(0.0f));
    // What each cluster sends in the first iteration, its first unshot radiosity: the reflected
    // direct light (analytic lights and emitting surfaces), averaged over its area, and the
    // emission where the emitters' light goes through the links. (When it is taken per element,
    // the emission has arrived already and no emission array is kept: 12 bytes a node, 240 MB at
    // 10 million faces.)
    unshot_.assign(nodes, Rgb(0.0f));
    if (!exactDirect_) emission_.assign(nodes, Rgb(0.0f));
    for (uint32_t i = 0; i < nodes; ++i) {
      if (tree_.isLeaf(i)) {
        if (!exactDirect_) emission_[i] = sys.emission[i];
        unshot_[i] = firstUnshot(i);
      } else {
        const FaceCluster& c = tree_.joined(i);
        const float a = areaOf(c.child[0]), b = areaOf(c.child[1]);
        const float w = c.area > 0.0f ? 1.0f / c.area : 0.0f;
        if (!exactDirect_) emission_[i] = (a * emission_[c.child[0]] + b * emission_[c.child[1]]) * w;
        unshot_[i] = (a * unshot_[c.child[0]] + b * unshot_[c.child[1]]) * w;
      }
    }
    for (size_t e = 0; e < ne; ++e) emittedPower_ += double(sys.area[e]) * maxChannel(unshot_[e]);
    startPower_ = emittedPower_;
    iterationLimit_ = uint32_t(s.maxIterations);
    analyticShot_ = sys.analytic;
    materials_ = materialsDigest();
    prepareSweeps();
    split_.assign(nodes, 0);
    field_ = std::make_unique<std::atomic<uint32_t>[]>(nodes);
    since_ = std::make_unique<std::atomic<uint32_t>[]>(nodes);
    for (size_t i = 0; i < nodes; ++i) field_[i].store(kNever), since_[i].store(kNever);
    since_[tree_.root].store(0);
    field_[tree_.root].store(newField());
    unshotFraction_ = emittedPower_ > 0.0 ? 1.0 : 0.0;
    done_ = emittedPower_ <= 0.0;
    setupSeconds_ = watch.seconds() + (wasPrepared ? tree_.seconds : 0.0);  // the tree counts as the solve's, wherever built
  }

  bool step(const StepLimit& limit, const ProgressCallback& progress) override {
    const Stopwatch watch;
    uint64_t units = 0;
    while (!done_ && !sliceSpent(limit, units, watch)) {
      reportProgress(progress, "solve", progressFraction());
      iterate();
      ++units;
      reportProgress(progress, "solve", progressFraction(),
                     fmt::format("iteration {}, unshot {:.3f}%, {} links", iterations_, 100.0 * unshotFraction_, links_.load()));
    }
    return !done_;
  }

  bool done() const override { return done_; }

  // The analytic light changed (a lamp or the sun moved or was recoloured): the difference is shot
  // from the last solution, as Puech et al.'s surface-property edits shoot it (seed 001, notes
  // 2.5). Its reflection rho * (H0' - H0) is split into where light arrived and where it left, each
  // shot as a positive series of Jacobi sweeps with the links refined against the new light's
  // power, the second taken off the fields; clamped fields and the push's half-space test hold
  // only for positive light. An edit of the emission or the reflectance, a first change before
  // any sweep, or light fallen below half of what the solve started with (whose error was sized
  // to it) starts again.
  bool sourcesChanged() override {
    const size_t ne = sys_.elementCount();
    if (!s_.followLight || iterations_ == 0 || recordSh_ || sys_.analytic.size() != ne || materialsDigest() != materials_) return false;
    double power = 0.0, change = 0.0;
    for (size_t e = 0; e < ne; ++e) {
      power += double(sys_.area[e]) * maxChannel(firstUnshot(e));
      change += double(sys_.area[e]) * maxChannel(glm::abs(sys_.reflectance[e] * (sys_.analytic[e] - analyticShot_[e])));
    }
    if (!(power > 0.5 * startPower_) || changeFollowed_ + change / power > kMostChangeFollowed) return false;
    changeFollowed_ += change / power;
    const Stopwatch watch;
    if (faces_.empty()) prepareSweeps();
    // What either series left unshot at the last stop is netted with the difference: dropped,
    // the negative series' remainder would stay in the solution as light, frame after frame.
    negative_.resize(tree_.nodeCount(), Rgb(0.0f));
    nextNegative_.assign(ne, Rgb(0.0f));
    double unshotPower = 0.0;
    for (size_t e = 0; e < ne; ++e) {
      const Rgb net = unshot_[e] - negative_[e] + sys_.reflectance[e] * (sys_.analytic[e] - analyticShot_[e]);
      unshot_[e] = glm::max(net, Rgb(0.0f));
      negative_[e] = glm::max(-net, Rgb(0.0f));
      unshotPower += double(sys_.area[e]) * (maxChannel(unshot_[e]) + maxChannel(negative_[e]));
    }
    analyticShot_ = sys_.analytic;
    mixClusters(unshot_), mixClusters(negative_);
    emittedPower_ = power;
    iterationLimit_ = iterations_ + uint32_t(s_.maxIterations);
    unshotFraction_ = unshotPower / emittedPower_;
    done_ = unshotFraction_ < s_.unshot;
    if (done_) releaseSweeps();
    ++redistributions_;
    seconds_ += watch.seconds();
    return true;
  }

  Solution solution() override {
    Solution out;
    const SurfaceSet& surfaces = sys_.surfaces;
    const size_t ne = sys_.elementCount();
    out.radiosity.resize(ne), out.irradiance.resize(ne), out.directIrradiance.resize(ne);
    // Leaf by leaf of the element tree, each field's box found once for all of its faces (read
    // every frame of an animation, this was a walk up the tree and a box per face).
    const std::vector<uint32_t> leaves = elementLeaves();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves.size(), 8), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i != range.end(); ++i) {
        const uint32_t m = leaves[i];
        const FaceCluster c = node(m);
        const uint32_t f = field_[m].load(std::memory_order_relaxed);
        for (uint32_t k = c.begin; k < c.begin + c.count; ++k) {
          const uint32_t e = tree_.order[k];
          const Element& el = surfaces.elements[e];
          Rgb h(0.0f), hd(0.0f);
          if (f != kNever) {
            h = irradiance(fields_[f], c.box, el.centroid, el.normal);
            // With the emitters' light per element, no link carries emitted light: zero.
            if (!exactDirect_) hd = irradiance(fields_[f + 1], c.box, el.centroid, el.normal);
          }
          out.irradiance[e] = h + sys_.analytic[e] + emitterDirect_.irradiance[e];
          out.directIrradiance[e] = hd + sys_.analytic[e] + emitterDirect_.irradiance[e];
          out.radiosity[e] = sys_.emission[e] + sys_.reflectance[e] * out.irradiance[e];
        }
      }
    });
    out.stats = stats();
    return out;
  }

  // L1 directions are recorded from the first sweep on, or not at all (a record that missed a
  // bounce would be short of it). L2's band 2 is left to its owner's final gather: kept constant
  // over each element from the clusters' points, it was far less accurate than the gather
  // (docs/baking.md, "Directions from the hierarchy").
  void recordIncidentSh(int count) override {
    if (iterations_ != 0 || count != kShL1Coefficients) return;
    recordSh_ = count;
    // The emitters' direct light again, with its directions: the same samples, so the same
    // irradiance to the bit.
    if (exactDirect_)
      emitterDirect_ = emitterDirectLight(sys_.surfaces, *tracer_, count, kEmitterDirectSeed);
  }

  // The incident L1 at each face from the field that holds it: band 0 from the radiance's
  // integral and band 1 from the vector irradiance, both in the element's basis and evaluated at
  // the face's centroid as its irradiance is (Gobbetti et al.'s vectors are exactly the integral
  // of L(w) w, so band 1 is the vector times kShY1), plus the light that came as harmonics.
  bool incidentSh(int count, std::span<Rgb> out) override {
    if (recordSh_ != count) return false;
    const size_t ne = sys_.elementCount();
    if (out.size() != ne * size_t(count)) throw Error("hierarchical solver: incidentSh's output has the wrong size");
    tbb::parallel_for(uint32_t(0), uint32_t(ne), [&](uint32_t e) {
      Rgb* c = &out[size_t(e) * size_t(count)];
      std::fill(c, c + count, Rgb(0.0f));
      uint32_t m = e;
      while (since_[m].load(std::memory_order_relaxed) == kNever) m = tree_.parent(m);
      const uint32_t f = field_[m].load(std::memory_order_relaxed);
      if (f == kNever) return;
      const Field& field = fields_[f];
      float basis[kMaxBasisFunctions];
      evaluateBasis(node(m).box.planeParameters(sys_.surfaces.elements[e].centroid), s_.basis, basis);
      for (int ch = 0; ch < 3; ++ch) {
        float radiance = 0.0f;
        Vec3 v(0.0f);
        for (int a = 0; a < s_.basis; ++a) {
          radiance += basis[a] * field.radiance[size_t(a * 3 + ch)];
          v += basis[a] * field.c[size_t(a * 3 + ch)];
        }
        // The integral of L is at least the length of the integral of L w; fitted separately
        // over a large element, the two can cross near its corners.
        c[0][ch] = kShY0 * std::max(radiance, glm::length(v));
        c[1][ch] = kShY1 * v.y, c[2][ch] = kShY1 * v.z, c[3][ch] = kShY1 * v.x;
        for (int i = 0; i < count; ++i) c[i][ch] += field.sh[size_t(ch * kShCoefficients + i)];
      }
      if (!emitterDirect_.sh.empty())
        for (int i = 0; i < count; ++i) c[i] += emitterDirect_.sh[size_t(e) * size_t(count) + size_t(i)];
    });
    return true;
  }

  // The tree and the cluster points are made again from the surfaces, to the same bits; the
  // element tree and its fields are saved. Between sweeps nothing is in flight (next_ is zero).
  bool checkpoints() const override { return true; }
  void saveState(StateWriter& out) const override {
    const size_t nodes = tree_.nodeCount();
    out.array(unshot_), out.array(split_);
    std::vector<uint32_t> field(nodes), since(nodes);
    for (size_t i = 0; i < nodes; ++i) field[i] = field_[i].load(), since[i] = since_[i].load();
    out.array(field), out.array(since);
    out.value(uint64_t(fields_.size()));
    for (const Field& f : fields_) out.value(f);
    out.value(iterations_), out.value(unshotFraction_), out.value(done_), out.value(seconds_);
    for (const auto* counter : {&links_, &refinedNear_, &refinedTransfer_, &refinedShadow_, &refinedSelf_})
      out.value(counter->load());
    out.value(uint64_t(leaves_.load())), out.value(uint64_t(elements_.load()));
    out.value(recordSh_);
    out.array(analyticShot_), out.array(negative_);
    out.value(emittedPower_), out.value(iterationLimit_), out.value(redistributions_);
    out.value(changeFollowed_);
  }
  void restoreState(StateReader& in) override {
    const size_t nodes = tree_.nodeCount();
    in.array(unshot_, nodes), in.array(split_, nodes);
    std::vector<uint32_t> field, since;
    in.array(field, nodes), in.array(since, nodes);
    const uint64_t pool = in.arrayLength(StateReader::kAnyLength, sizeof(Field));
    for (size_t i = 0; i < nodes; ++i) {
      // A field index past the pool would send the solver out of bounds: checked.
      if (field[i] != kNever && (pool < 2 || field[i] > pool - 2))
        throw Error(fmt::format("checkpoint: cluster {} names field {} of a pool of {}", i, field[i], pool));
      field_[i].store(field[i]), since_[i].store(since[i]);
    }
    fields_.clear();
    fields_.grow_by(size_t(pool));
    for (Field& f : fields_) in.value(f);
    in.value(iterations_), in.value(unshotFraction_), in.value(done_), in.value(seconds_);
    if (!done_ && faces_.empty())
      throw Error("hierarchical solver: an unfinished state restored into a solver that has finished");
    for (auto* counter : {&links_, &refinedNear_, &refinedTransfer_, &refinedShadow_, &refinedSelf_})
      counter->store(in.value<uint64_t>());
    leaves_.store(size_t(in.value<uint64_t>())), elements_.store(size_t(in.value<uint64_t>()));
    // The directions saved are whole for what was recorded then: enough for what is asked now,
    // or none at all (incidentSh then says so, and its owner gathers them).
    if (in.value<int>() != recordSh_) recordSh_ = 0;
    in.array(analyticShot_, sys_.elementCount());
    in.array(negative_);
    if (!negative_.empty() && negative_.size() != nodes)
      throw Error(fmt::format("checkpoint: the negative series has {} clusters, the tree {}", negative_.size(), nodes));
    nextNegative_.assign(negative_.empty() ? 0 : sys_.elementCount(), Rgb(0.0f));
    in.value(emittedPower_), in.value(iterationLimit_), in.value(redistributions_);
    in.value(changeFollowed_);
  }

  SolveStats stats() const override {
    SolveStats s;
    s.method = "hierarchical";
    s.backend = "cpu";
    s.iterations = iterations_;
    s.redistributions = redistributions_;
    s.residual = s.unshotFraction = unshotFraction_;
    s.links = links_.load();
    s.rays = emitterDirect_.rays;
    s.refinements = {refinedNear_.load(), refinedTransfer_.load(), refinedShadow_.load(), refinedSelf_.load()};
    s.clusterLeaves = leaves_.load();
    s.clusterElements = elements_.load();
    s.secondsHierarchy = tree_.seconds;
    s.hierarchyCached = treeLoaded_;
    s.hierarchyDepth = treeDepth_.max, s.hierarchyMeanLeafDepth = treeDepth_.meanLeaf;
    s.warnings = warnings_;
    s.hierarchyBytes = tree_.bytes();
    s.secondsFormFactors = seconds_;
    s.secondsSolve = setupSeconds_;  // the tree and the clusters' sources
    return s;
  }

 private:
  // How far the unshot power has fallen towards the stop, on a log scale.
  double progressFraction() const {
    if (unshotFraction_ <= 0.0) return 1.0;
    return std::clamp(std::log(unshotFraction_) / std::log(s_.unshot), 0.0, 1.0);
  }

  // The leaves of the element tree, which hold the fields.
  std::vector<uint32_t> elementLeaves() const {
    std::vector<uint32_t> leaves, stack{tree_.root};
    while (!stack.empty()) {
      const uint32_t i = stack.back();
      stack.pop_back();
      if (split_[i]) stack.push_back(tree_.joined(i).child[1]), stack.push_back(tree_.joined(i).child[0]);
      else leaves.push_back(i);
    }
    return leaves;
  }

  // What element e shoots first, its light from the sources: the reflected direct light (analytic
  // lights and emitting surfaces), and its emission where the emitters' light goes through links.
  Rgb firstUnshot(size_t e) const {
    return (exactDirect_ ? Rgb(0.0f) : sys_.emission[e]) +
           sys_.reflectance[e] * (sys_.analytic[e] + emitterDirect_.irradiance[e]);
  }

  // Two fields (all light, direct light) in the pool; returns the index of the first.
  uint32_t newField() {
    auto it = fields_.grow_by(2);
    return uint32_t(it - fields_.begin());
  }

  // The mean unshot radiosity cluster j sends in this iteration: in the first, its emission plus
  // the reflected analytic light; later, what its elements gathered in the previous one.
  Rgb emitterUnshot(uint32_t j) const { return unshot_[j]; }
  // The share of it that is emitted (the direct light), in the first iteration only, and only
  // where the emitters' light goes through the links.
  Rgb emitterEmission(uint32_t j) const { return iterations_ == 0 && !emission_.empty() ? emission_[j] : Rgb(0.0f); }

  // Node i of the tree, a leaf made from its element (FaceClusterTree::node).
  FaceCluster node(uint32_t i) const { return tree_.node(i, sys_.surfaces); }
  float areaOf(uint32_t i) const { return tree_.isLeaf(i) ? sys_.surfaces.elements[i].area : tree_.joined(i).area; }

  bool facing(const FaceCluster& a, const FaceCluster& b) const {
    return mayFace(b.cone, b.box, a.box) && mayFace(a.cone, a.box, b.box);
  }

  // The receiver's points with the least-squares projection onto its basis:
  // coefficient alpha = sum_p projection[alpha][p] * value(p). Under the points' own measure the
  // Legendre functions are not exactly orthonormal, so the projection solves the normal equations
  // (with a small ridge for clusters too thin to tell u from v).
  struct Receiver {
    std::vector<SurfacePoint> points;
    float spacing = 0.0f;           // between its points: sqrt(area / points)
    std::vector<float> projection;  // basis x points
    std::vector<float> basisAt;     // points x basis: the functions at each point
  };
  void prepareReceiver(uint32_t i, const FaceCluster& c, Receiver& r) const {
    const OrientedBox& box = c.box;
    points_->points(i, s_.receiverSide, r.points);
    r.spacing = std::sqrt(c.area / float(std::max<size_t>(1, r.points.size())));
    const int nb = s_.basis;
    const size_t np = r.points.size();
    r.basisAt.resize(np * size_t(nb));
    for (size_t p = 0; p < np; ++p)
      evaluateBasis(box.planeParameters(r.points[p].position), nb, &r.basisAt[p * size_t(nb)]);
    project(r, nullptr, r.projection);
  }

  // The least-squares projection over the receiver's points, or over those `mask` keeps.
  void project(const Receiver& r, const uint8_t* mask, std::vector<float>& projection) const {
    const int nb = s_.basis;
    const size_t np = r.points.size();
    projection.assign(size_t(nb) * np, 0.0f);
    auto weight = [&](size_t p) { return mask && !mask[p] ? 0.0 : double(r.points[p].weight); };
    if (nb == 1) {
      double sum = 0.0;
      for (size_t p = 0; p < np; ++p) sum += weight(p);
      for (size_t p = 0; p < np; ++p) projection[p] = sum > 0.0 ? float(weight(p) / sum) : 0.0f;
      return;
    }
    double g[kMaxBasisFunctions][kMaxBasisFunctions] = {};
    for (size_t p = 0; p < np; ++p)
      for (int a = 0; a < nb; ++a)
        for (int b = 0; b < nb; ++b)
          g[a][b] += weight(p) * r.basisAt[p * size_t(nb) + size_t(a)] * r.basisAt[p * size_t(nb) + size_t(b)];
    for (int a = 0; a < nb; ++a) g[a][a] += 1e-4;
    // Cholesky, then the inverse applied to each point's weighted basis row.
    double l[kMaxBasisFunctions][kMaxBasisFunctions] = {};
    for (int a = 0; a < nb; ++a)
      for (int b = 0; b <= a; ++b) {
        double sum = g[a][b];
        for (int k = 0; k < b; ++k) sum -= l[a][k] * l[b][k];
        l[a][b] = a == b ? std::sqrt(std::max(sum, 1e-12)) : sum / l[b][b];
      }
    for (size_t p = 0; p < np; ++p) {
      double y[kMaxBasisFunctions];
      for (int a = 0; a < nb; ++a) {
        double sum = weight(p) * r.basisAt[p * size_t(nb) + size_t(a)];
        for (int k = 0; k < a; ++k) sum -= l[a][k] * y[k];
        y[a] = sum / l[a][a];
      }
      for (int a = nb - 1; a >= 0; --a) {
        double sum = y[a];
        for (int k = a + 1; k < nb; ++k) sum -= l[k][a] * y[k];
        y[a] = sum / l[a][a];
        projection[size_t(a) * np + p] = float(y[a]);
      }
    }
  }

  // A field given on a parent, re-expressed on child `r` (Gobbetti et al. section 3.3.4's push:
  // the parent's function at the child's points, projected on the child's basis). A channel whose
  // mean vector points behind the child's surface is dropped, as the paper does: vector
  // irradiance is valid in one half-space only. The harmonics are pushed whole.
  void push(const Field& from, const OrientedBox& parent, const Receiver& r, Vec3 childVectorArea, Field& to) const {
    const int nb = s_.basis;
    const size_t np = r.points.size();
    const Vec3 normal = childVectorArea;
    std::array<bool, 3> keep;
    for (int ch = 0; ch < 3; ++ch) keep[size_t(ch)] = glm::dot(normal, from.c[size_t(ch)]) > 0.0f;
    // The directions' record goes with the vectors it belongs to.
    if (nb == 1) {
      to = from;
      for (int ch = 0; ch < 3; ++ch)
        if (!keep[size_t(ch)]) to.c[size_t(ch)] = Vec3(0.0f), to.radiance[size_t(ch)] = 0.0f;
      return;
    }
    to = Field{};
    to.sh = from.sh;
    const bool record = recordSh_ > 0;
    for (size_t p = 0; p < np; ++p) {
      float basis[kMaxBasisFunctions];
      evaluateBasis(parent.planeParameters(r.points[p].position), nb, basis);
      for (int ch = 0; ch < 3; ++ch) {
        if (!keep[size_t(ch)]) continue;
        Vec3 value(0.0f);
        for (int a = 0; a < nb; ++a) value += basis[a] * from.c[size_t(a * 3 + ch)];
        for (int a = 0; a < nb; ++a) to.c[size_t(a * 3 + ch)] += r.projection[size_t(a) * np + p] * value;
        if (!record) continue;
        float radiance = 0.0f;
        for (int a = 0; a < nb; ++a) radiance += basis[a] * from.radiance[size_t(a * 3 + ch)];
        for (int a = 0; a < nb; ++a) to.radiance[size_t(a * 3 + ch)] += r.projection[size_t(a) * np + p] * radiance;
      }
    }
  }

  // Irradiance at a face (position, unit normal) from a field given on cluster `on`: the vector
  // part dotted with the normal plus the harmonics' part, each clamped at zero.
  Rgb irradiance(const Field& f, const OrientedBox& on, Vec3 position, Vec3 normal) const {
    float basis[kMaxBasisFunctions];
    evaluateBasis(on.planeParameters(position), s_.basis, basis);
    std::array<float, kShCoefficients> y = shBasis(normal);
    for (int i = 0; i < kShCoefficients; ++i) y[size_t(i)] *= kShCosine[size_t(i)];
    Rgb out(0.0f);
    for (int ch = 0; ch < 3; ++ch) {
      Vec3 v(0.0f);
      for (int a = 0; a < s_.basis; ++a) v += basis[a] * f.c[size_t(a * 3 + ch)];
      float fromSh = 0.0f;
      for (int i = 0; i < kShCoefficients; ++i) fromSh += y[size_t(i)] * f.sh[size_t(ch * kShCoefficients + i)];
      out[ch] = std::max(0.0f, glm::dot(normal, v)) + std::max(0.0f, fromSh);
    }
    return out;
  }

  // Per receiver traversal: links refined, coefficients computed, rays traced. One per task.
  struct Scratch {
    std::vector<SurfacePoint> emitterPoints;
    std::vector<RTCRay> rays;     // one per receiver x emitter point pair; flags 1: not traced
    std::vector<RTCRay> traced;   // the pairs that can exchange light, as one stream
    std::vector<size_t> where;    // each traced ray's pair
    std::vector<float> visible;   // per pair: the share of light that passes
    std::vector<uint8_t> sees;    // per receiver point: some emitter point is above its horizon
    std::vector<float> projection;  // the receiver's projection restricted to the points that see
    // Per receiver point, per channel: the vector irradiance the emitter's unshot radiosity
    // brings (all light), and the part its emission brings (direct light).
    std::vector<std::array<Vec3, 3>> transport, direct;
    // The same light as harmonics, for receivers that take it so (couple's `asHarmonics`): per
    // receiver point, per channel, kShCoefficients numbers.
    std::vector<float> transportSh, directSh;
    // L1 directional bakes, for light that comes as vectors: per receiver point, its radiance
    // integrated over the sphere (all light).
    std::vector<Rgb> radiance;
  };

  // Point-to-point estimates of the power per unit radiosity between every receiver and emitter
  // point, with the projected areas' upper and lower bounds in place of A cos (Gobbetti et al.
  // section 3.3.2): the largest upper bounds the transfer, and its spread from the smallest lower
  // is how far a constant transfer can be off.
  struct TransferBounds {
    float upper = 0.0f, spread = 0.0f;
  };
  TransferBounds transferBounds(const FaceCluster& a, const FaceCluster& b, const Receiver& r,
                                const std::vector<SurfacePoint>& q) const {
    float hi = 0.0f, lo = std::numeric_limits<float>::max();
    for (const SurfacePoint& x : r.points)
      for (const SurfacePoint& y : q) {
        const Vec3 d = x.position - y.position;  // emitter to receiver
        const float r2 = glm::dot(d, d);
        if (r2 <= 0.0f) return {std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
        const float r4 = kPi * r2 * r2;
        hi = std::max(hi, b.maxProjectedArea(d) * a.maxProjectedArea(-d) / r4);
        lo = std::min(lo, b.minProjectedArea(d) * a.minProjectedArea(-d) / r4);
      }
    return {hi, hi - std::min(lo, hi)};
  }

  // The vector irradiance emitter j (whose points s.emitterPoints holds) sends to each receiver
  // point, with visibility; returns the share of rays that were blocked among those that count.
  // Each emitter point carries the radiosity of its own element, not the cluster's mean: light
  // leaving a cluster towards a receiver comes from the faces that face it, and those are often
  // the lit ones (a floor beside the dark sides of a block on it), so the mean would be too dark
  // one way and too bright the other. After a change of the light the difference shot is mostly
  // thin strips along the shadows that moved, which a cluster's few points catch or miss by
  // chance, so there each point carries the cluster's mean (once a change has been followed).
  float couple(uint32_t j, const FaceCluster& b, const Receiver& r, Scratch& s, bool asHarmonics) const {
    const size_t np = r.points.size();
    s.transport.assign(np, {Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)});
    s.direct.assign(np, {Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)});
    if (asHarmonics) {
      s.transportSh.assign(np * 3 * kShCoefficients, 0.0f);
      s.directSh.assign(np * 3 * kShCoefficients, 0.0f);
    }
    // For the directions' record, each polygon's exact moments over the part in front of the
    // point: radiance b / pi over its solid angle (at least pi |vector|, which rounding can
    // break), as solve/incident_sh.cpp takes them. The vectors the irradiance takes are computed
    // as without the record, so that the solution stays the same to the bit.
    const bool record = !asHarmonics && recordSh_ > 0;
    if (record) s.radiance.assign(np, Rgb(0.0f));
    auto addIncident = [&](size_t p, const Polygon& poly, Vec3 polyNormal, float visible, const Rgb& unshot) {
      const SurfacePoint& x = r.points[p];
      const PolygonMoments m = clippedPolygonMoments(x.position, x.normal, poly, polyNormal);
      s.radiance[p] += (visible * std::max(m.solidAngle, kPi * glm::length(m.vector)) / kPi) * unshot;
    };
    // Light from one emitter point (or face) as a delta of radiance along its irradiance vector,
    // whose length is what it brings. Kept per emitter point rather than for their sum: the sum's
    // length is less than what a surface facing each point in turn receives. The vector is the
    // whole emitter's, not clipped to the receiver point's horizon: harmonics hold the light
    // arriving near the point from every direction, and the faces they are evaluated on turn
    // other ways than the point (clipped, a grazing point's light is short for the faces that
    // look straight at the emitter).
    auto addHarmonics = [&](size_t p, Vec3 m, const Rgb& unshot, const Rgb& emitted) {
      const float e = glm::length(m);
      if (e <= 0.0f) return;
      const std::array<float, kShCoefficients> y = shBasis(m / e);
      for (int ch = 0; ch < 3; ++ch) {
        float* t = &s.transportSh[(p * 3 + size_t(ch)) * kShCoefficients];
        float* d = &s.directSh[(p * 3 + size_t(ch)) * kShCoefficients];
        for (int k = 0; k < kShCoefficients; ++k) t[k] += unshot[ch] * e * y[size_t(k)], d[k] += emitted[ch] * e * y[size_t(k)];
      }
    };
    const std::vector<SurfacePoint>& q = s.emitterPoints;
    s.rays.clear();
    s.sees.assign(np, 0);
    // Ray for pair (p, k) where the pair can exchange light.
    for (size_t p = 0; p < np; ++p)
      for (const SurfacePoint& y : q) {
        const Vec3 d = y.position - r.points[p].position;
        const float len = std::sqrt(glm::dot(d, d));
        const bool above = glm::dot(r.points[p].normal, d) > 0.0f;
        s.sees[p] |= above;
        if (len <= 2.0f * rayOffset_ || !above || glm::dot(y.normal, d) >= 0.0f) {
          s.rays.push_back(makeRay(r.points[p].position, d, 1.0f, 0.0f));  // placeholder, not traced
          s.rays.back().tfar = -std::numeric_limits<float>::infinity();
          // Skipped; 2: only because it is below the receiver point's horizon.
          s.rays.back().flags = len > 2.0f * rayOffset_ && glm::dot(y.normal, d) < 0.0f ? 2 : 1;
          continue;
        }
        s.rays.push_back(makeRay(r.points[p].position, d, rayOffset_ / len, 1.0f - rayOffset_ / len));
      }
    // Trace the pairs that count, in one stream.
    std::vector<RTCRay>& traced = s.traced;
    std::vector<size_t>& where = s.where;
    traced.clear(), where.clear();
    for (size_t k = 0; k < s.rays.size(); ++k)
      if (s.rays[k].flags == 0) traced.push_back(s.rays[k]), where.push_back(k);
    std::vector<float>& visible = s.visible;
    visible.assign(s.rays.size(), 0.0f);
    if (!clusterVisibility_ && !traced.empty()) tracer_->occluded(traced);
    const float stop = s_.visibilityStop * r.spacing;
    float blocked = 0.0f;
    for (size_t k = 0; k < traced.size(); ++k) {
      const RTCRay& ray = traced[k];
      const float passed = !clusterVisibility_ ? (isOccluded(ray) ? 0.0f : 1.0f)
                                               : clusterVisibility_->transmittance(
                                                     Vec3(ray.org_x, ray.org_y, ray.org_z),
                                                     Vec3(ray.dir_x, ray.dir_y, ray.dir_z), ray.tnear, ray.tfar, stop);
      visible[where[k]] = passed;
      blocked += 1.0f - passed;
    }
    const bool leaf = b.leaf();
    const Element* el = leaf ? &sys_.surfaces.elements[j] : nullptr;
    for (size_t p = 0; p < np; ++p) {
      const SurfacePoint& x = r.points[p];
      if (leaf) {
        // One planar face: its exact vector form factor (Lambert's contour integral), times the
        // share of it the rays see, each ray weighted by its point-to-point kernel.
        const Vec3 phi = polygonIrradianceVector(x.position, x.normal, el->polygon, el->normal);
        if (phi == Vec3(0.0f)) continue;
        const Rgb unshot = emitterUnshot(j), emitted = emitterEmission(j);
        float seen = 0.0f, all = 0.0f;
        for (size_t k = 0; k < q.size(); ++k) {
          const size_t idx = p * q.size() + k;
          if (s.rays[idx].flags) continue;
          const Vec3 d = q[k].position - x.position;
          const float r2 = glm::dot(d, d);
          const float w = glm::dot(x.normal, d) * -glm::dot(q[k].normal, d) / (r2 * r2);
          all += w;
          seen += visible[idx] * w;
        }
        const Vec3 m = all > 0.0f ? (seen / all) * phi : phi;
        for (int ch = 0; ch < 3; ++ch) s.transport[p][size_t(ch)] = unshot[ch] * m, s.direct[p][size_t(ch)] = emitted[ch] * m;
        if (record) addIncident(p, el->polygon, el->normal, all > 0.0f ? seen / all : 1.0f, unshot);
        if (asHarmonics) {
          const Vec3 whole = polygonIrradianceVector(x.position, -el->normal, el->polygon, el->normal);
          addHarmonics(p, all > 0.0f ? (seen / all) * whole : whole, unshot, emitted);
        }
        continue;
      }
      // A cluster: its points, each a square of its share of the area, with the square's exact
      // vector form factor. Wallace et al.'s disc form A cos / (pi r^2 + A), which this replaced,
      // is low on average at the distances a link is taken at, and a bias that is the same on
      // every link compounds with each bounce (docs/algorithms.md, "Energy").
      // For harmonics, emitter points below the receiver point's horizon count too, seen as
      // often as those above it are: at a point of a convex cluster its own tangent plane hides
      // them, but the cluster's faces that turn towards them do see them, and the harmonics are
      // the light for all of its faces (without them a ball lit by a wall comes out short when
      // its few points lie near the terminator: tests/unit/test_hierarchical_energy.cpp).
      float seenAbove = 0.0f, tracedAbove = 0.0f;
      if (asHarmonics)
        for (size_t k = 0; k < q.size(); ++k) {
          const size_t idx = p * q.size() + k;
          if (!s.rays[idx].flags) tracedAbove += 1.0f, seenAbove += visible[idx];
        }
      for (size_t k = 0; k < q.size(); ++k) {
        const size_t idx = p * q.size() + k;
        // With multiresolution visibility a ray passes a share of the light.
        const float passes = s.rays[idx].flags ? 0.0f : visible[idx];
        const bool counts = passes > 0.0f;
        const bool hidden = asHarmonics && s.rays[idx].flags == 2 && seenAbove > 0.0f;
        if (!counts && !hidden) continue;
        const float a = q[k].weight * b.area;
        const Polygon square = squareAround(q[k], a, b.box);
        const Rgb unshot = emitterUnshot(redistributions_ > 0 ? j : q[k].element), emitted = emitterEmission(q[k].element);
        if (counts) {
          const Vec3 m = passes * polygonIrradianceVector(x.position, x.normal, square, q[k].normal);
          for (int ch = 0; ch < 3; ++ch) s.transport[p][size_t(ch)] += unshot[ch] * m, s.direct[p][size_t(ch)] += emitted[ch] * m;
          if (record) addIncident(p, square, q[k].normal, passes, unshot);
        }
        if (asHarmonics) {
          const float seen = counts ? passes : seenAbove / tracedAbove;
          addHarmonics(p, seen * polygonIrradianceVector(x.position, -q[k].normal, square, q[k].normal), unshot, emitted);
        }
      }
    }
    return traced.empty() ? 0.0f : blocked / float(traced.size());
  }

  // Splits receiver element i: its children become elements, its field goes down to them.
  void splitReceiver(uint32_t i) {
    if (split_[i]) return;
    const FaceCluster& c = tree_.joined(i);  // a leaf has no children to split into
    const uint32_t f = field_[i].load(std::memory_order_relaxed);
    Receiver r;
    for (uint32_t child : c.child) {
      const uint32_t g = newField();
      if (f != kNever) {
        const FaceCluster below = node(child);
        prepareReceiver(child, below, r);
        push(fields_[f], c.box, r, below.vectorArea, fields_[g]);
        push(fields_[f + 1], c.box, r, below.vectorArea, fields_[g + 1]);
      }
      field_[child].store(g, std::memory_order_relaxed);
      since_[child].store(iterations_, std::memory_order_relaxed);
    }
    field_[i].store(kNever, std::memory_order_relaxed);
    split_[i] = 1;
    elements_ += 2, leaves_ += 1;
  }

  // A link's light as harmonics, constant over the receiver: the mean of `perPoint` over the
  // points that see the emitter, added to the field's harmonics.
  void addHarmonicLink(const Receiver& r, const Scratch& s, double seeing, const std::vector<float>& perPoint, Field& to) const {
    for (size_t p = 0; p < r.points.size(); ++p) {
      if (!s.sees[p]) continue;
      const float w = float(double(r.points[p].weight) / seeing);
      const float* from = &perPoint[p * 3 * kShCoefficients];
      for (int k = 0; k < 3 * kShCoefficients; ++k) to.sh[size_t(k)] += w * from[k];
    }
  }

  // The directions of a link whose light came as vectors: the integral of its radiance, fitted
  // in the receiver's basis as the vectors are (`projection`).
  void recordVectorLink(const Receiver& r, const Scratch& s, const std::vector<float>& projection, Field& to) const {
    const size_t np = r.points.size();
    for (size_t p = 0; p < np; ++p)
      for (int a = 0; a < s_.basis; ++a) {
        const float w = projection[size_t(a) * np + p];
        for (int ch = 0; ch < 3; ++ch) to.radiance[size_t(a * 3 + ch)] += w * s.radiance[p][ch];
      }
  }

  // TRANSPORT-LIGHT of Algorithm 1: element i with the unshot irradiance its ancestors gathered
  // (`inherited`, in i's parent's basis; null at the root) and its potential shooters.
  // `selfLinked`: an ancestor took the light its parts send each other as one link, which holds
  // this cluster's own too.
  void transportLight(uint32_t i, uint32_t parent, const Field* inheritedTotal, const Field* inheritedDirect,
                      std::vector<uint32_t> shooters, bool selfLinked = false) {
    const FaceCluster c = node(i);
    Receiver r;
    prepareReceiver(i, c, r);
    Field total, direct;
    if (inheritedTotal) {
      const OrientedBox above = tree_.joined(parent).box;  // a parent has children: never a leaf
      push(*inheritedTotal, above, r, c.vectorArea, total);
      push(*inheritedDirect, above, r, c.vectorArea, direct);
    }
    Scratch s;
    std::array<std::vector<uint32_t>, 2> childShooters;
    const double threshold = s_.error * emittedPower_;
    const size_t np = r.points.size();
    for (size_t idx = 0; idx < shooters.size(); ++idx) {
      const uint32_t j = shooters[idx];
      const Rgb unshot = emitterUnshot(j);
      const FaceCluster b = node(j);
      const bool bothLeaves = c.leaf() && b.leaf();
      // Refine the larger side that can be split.
      auto refine = [&] {
        const bool receiverSide = !c.leaf() && (b.leaf() || c.area >= b.area);
        if (receiverSide) {
          splitReceiver(i);
          for (int k = 0; k < 2; ++k)
            if (facing(node(c.child[size_t(k)]), b)) childShooters[size_t(k)].push_back(j);
        } else {
          for (uint32_t k : b.child)
            if (facing(c, node(k)) && maxChannel(emitterUnshot(k)) > 0.0f) shooters.push_back(k);
        }
      };
      // Errors are of the power arriving, not reflected: luxel's outputs include irradiance (a
      // lightmap is multiplied by its texture's albedo at display), so a dark receiver is no
      // excuse for a coarse link.
      const double scale = maxChannel(unshot);
      points_->points(j, s_.emitterSide, s.emitterPoints);
      // A cluster's points stand for it only at receivers further from it than its size: the
      // light from a wall to the floor beside it comes mostly from the wall's bottom edge, which
      // a few points miss, and what every such link misses adds up to a loss of energy.
      if (!b.leaf()) {
        const float reach = kSeparation * glm::length(b.box.half);
        bool near = false;
        for (const SurfacePoint& x : r.points) near = near || b.box.distance(x.position) < reach;
        // What a near link can carry at most: the smaller area times the emitter's radiosity
        // (A_i F_ij = A_j F_ji with F at most 1).
        const double most = maxChannel(unshot) * std::min(c.area, b.area);
        if (near && most > threshold) {
          ++refinedNear_;
          refine();
          continue;
        }
      }
      // A receiver whose faces all look at the emitter takes its light as a vector; one whose
      // faces do not is linked only when the whole transfer is below the threshold (a face that
      // sees the emitter from behind takes none of it), and takes the light as harmonics.
      const bool wholly = c.leaf() || whollyFaces(c.cone, c.box, b.box, kHorizonSlack);
      if (!bothLeaves) {
        const TransferBounds bounds = transferBounds(c, b, r, s.emitterPoints);
        if (scale * (wholly ? bounds.spread : bounds.upper) > threshold) {
          ++refinedTransfer_;
          refine();
          continue;
        }
      }
      const float blocked = couple(j, b, r, s, !wholly);
      ++links_;
      if (!bothLeaves && blocked > 0.0f && blocked < 1.0f) {
        // A shadow edge crosses the link: refine while the light it carries is above threshold.
        Rgb carried(0.0f);
        for (size_t p = 0; p < np; ++p)
          for (int ch = 0; ch < 3; ++ch)
            carried[ch] += r.points[p].weight * std::max(0.0f, glm::dot(r.points[p].normal, s.transport[p][size_t(ch)]));
        if (double(maxChannel(carried)) * c.area > threshold) {
          ++refinedShadow_;
          refine();
          continue;
        }
      }
      // A point on a side of the receiver cluster turned away from the whole emitter tells
      // nothing of the light arriving at the cluster (its rays would start into its own surface),
      // so the field is fitted to the others; counting it as dark would halve what a round
      // cluster (a statue, lit from one side) receives.
      if (wholly) {
        const std::vector<float>* projection = &r.projection;
        if (std::find(s.sees.begin(), s.sees.end(), uint8_t(0)) != s.sees.end()) {
          project(r, s.sees.data(), s.projection);
          projection = &s.projection;
        }
        for (size_t p = 0; p < np; ++p)
          for (int a = 0; a < s_.basis; ++a) {
            const float w = (*projection)[size_t(a) * np + p];
            for (int ch = 0; ch < 3; ++ch) {
              total.c[size_t(a * 3 + ch)] += w * s.transport[p][size_t(ch)];
              direct.c[size_t(a * 3 + ch)] += w * s.direct[p][size_t(ch)];
            }
          }
        if (recordSh_) recordVectorLink(r, s, *projection, total);
        continue;
      }
      // Harmonics are kept constant over the receiver (the mean over its points that see): a
      // link to a receiver that does not wholly face its emitter carries less than the
      // threshold, so how its light varies across the receiver is below it too, and a linear
      // fit over the few points on one side of a round cluster, in a plane its front and back
      // share, is noise that the clamp at zero turns into a loss.
      double seeing = 0.0;
      for (size_t p = 0; p < np; ++p) seeing += s.sees[p] ? double(r.points[p].weight) : 0.0;
      if (seeing <= 0.0) continue;
      addHarmonicLink(r, s, seeing, s.transportSh, total);
      addHarmonicLink(r, s, seeing, s.directSh, direct);
    }
    // SELF-ORACLE: the cluster's parts light each other; link them while the light that may
    // stay within is above threshold (a convex or flat cluster keeps none).
    if (!c.leaf() && !selfLinked) {
      const double self = maxChannel(emitterUnshot(i)) * c.area * c.selfFormFactorBound();
      if (self > threshold) {
        ++refinedSelf_;
        splitReceiver(i);
        const uint32_t a = c.child[0], b = c.child[1];
        const FaceCluster ca = node(a), cb = node(b);
        if (facing(ca, cb) && maxChannel(emitterUnshot(b)) > 0.0f) childShooters[0].push_back(b);
        if (facing(cb, ca) && maxChannel(emitterUnshot(a)) > 0.0f) childShooters[1].push_back(a);
      } else if (self > 0.0) {
        // Below the threshold the cluster's light to itself is still a link, taken whole as one
        // harmonics link from the cluster to itself, as a link between two clusters below the
        // threshold is taken whole; dropping it, as the paper's oracle does, lost the light a
        // concave cluster keeps at every level of the tree (a statue's own folds, a window's
        // niche: docs/algorithms.md, item 5).
        points_->points(i, s_.emitterSide, s.emitterPoints);
        couple(i, c, r, s, true);
        ++links_;
        selfLinked = true;
        double seeing = 0.0;
        for (size_t p = 0; p < np; ++p) seeing += s.sees[p] ? double(r.points[p].weight) : 0.0;
        if (seeing > 0.0) {
          addHarmonicLink(r, s, seeing, s.transportSh, total);
          addHarmonicLink(r, s, seeing, s.directSh, direct);
        }
      }
    }
    if (!split_[i]) {
      // A leaf of the element tree: keep the irradiance, and reflect what arrived this iteration
      // at each of its faces (the system's elements), with the face's own normal and reflectance
      // (the field at the centroid is the face's mean for a linear basis).
      const uint32_t f = field_[i].load(std::memory_order_relaxed);
      Field& keep = fields_[f];
      Field& keepDirect = fields_[f + 1];
      if (shootingNegative_) keep -= total, keepDirect -= direct;
      else keep += total, keepDirect += direct;
      for (uint32_t k = c.begin; k < c.begin + c.count; ++k) {
        const FaceSample& face = faces_[k];
        next_[k] = face.reflectance * irradiance(total, c.box, face.centroid, face.normal);
      }
      return;
    }
    auto visit = [&](int k) {
      transportLight(c.child[size_t(k)], i, &total, &direct, std::move(childShooters[size_t(k)]), selfLinked);
    };
    if (c.count >= kParallelFaces) tbb::parallel_invoke([&] { visit(0); }, [&] { visit(1); });
    else visit(0), visit(1);
  }

  // What a sweep reads of every face and cluster: the faces in the tree's order, and the
  // clusters bottom-up for the means. Made for the solve and again after a change of the light;
  // released when the solve is done.
  void prepareSweeps() {
    const size_t nodes = tree_.nodeCount(), ne = sys_.elementCount();
    std::vector<uint32_t> height(nodes, 0);
    for (uint32_t i = uint32_t(ne); i < nodes; ++i)
      height[i] = std::max(height[tree_.joined(i).child[0]], height[tree_.joined(i).child[1]]) + 1;
    const uint32_t levels = nodes > ne ? height[tree_.root] : 0;
    levelStart_.assign(size_t(levels) + 1, 0);
    for (uint32_t i = uint32_t(ne); i < nodes; ++i) ++levelStart_[height[i]];  // counts, shifted by one below
    for (uint32_t h = 1; h <= levels; ++h) levelStart_[h] += levelStart_[h - 1];
    mix_.resize(nodes - ne);
    std::vector<size_t> fill(levelStart_.begin(), levelStart_.end() - 1);
    for (uint32_t i = uint32_t(ne); i < nodes; ++i) {
      const FaceCluster& c = tree_.joined(i);
      const float w = c.area > 0.0f ? 1.0f / c.area : 0.0f;
      mix_[fill[height[i] - 1]++] = {i, c.child[0], c.child[1], areaOf(c.child[0]) * w, areaOf(c.child[1]) * w};
    }
    next_.assign(ne, Rgb(0.0f));
    faces_.resize(ne);
    for (size_t k = 0; k < ne; ++k) {
      const Element& el = sys_.surfaces.elements[tree_.order[k]];
      faces_[k] = {el.centroid, el.normal, el.reflectance, sys_.area[tree_.order[k]]};
    }
  }

  // Every cluster's value as the area mean of its elements' (each level one parallel pass).
  void mixClusters(std::vector<Rgb>& values) const {
    for (size_t level = 0; level + 1 < levelStart_.size(); ++level)
      tbb::parallel_for(tbb::blocked_range<size_t>(levelStart_[level], levelStart_[level + 1], 4096),
                        [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t k = range.begin(); k != range.end(); ++k) {
                            const Mix& m = mix_[k];
                            values[m.node] = m.wa * values[m.a] + m.wb * values[m.b];
                          }
                        });
  }

  // One Jacobi sweep of the series whose unshot radiosity unshot_ holds: its light shot and
  // added to the fields (subtracted, for the negative series), what the faces gathered made the
  // next unshot. Returns the power left unshot.
  double sweep() {
    transportLight(tree_.root, kNoCluster, nullptr, nullptr, {});
    // The Jacobi swap: what the faces gathered is shot next, and every cluster's mean is what it
    // shoots as a whole. In parallel, streaming through compact arrays (this pass touches every
    // face and cluster each sweep); the power is summed in fixed chunks so that the stop comes at
    // the same iteration for any thread count.
    const size_t ne = sys_.elementCount();
    constexpr size_t kChunk = 16384;
    std::vector<double> chunkPower((ne + kChunk - 1) / kChunk, 0.0);
    tbb::parallel_for(size_t(0), chunkPower.size(), [&](size_t k) {
      double power = 0.0;
      for (size_t i = k * kChunk; i < std::min(ne, (k + 1) * kChunk); ++i) {
        const uint32_t e = tree_.order[i];
        unshot_[e] = next_[i];
        next_[i] = Rgb(0.0f);
        power += double(faces_[i].area) * maxChannel(unshot_[e]);
      }
      chunkPower[k] = power;
    });
    double unshotPower = 0.0;
    for (double power : chunkPower) unshotPower += power;
    mixClusters(unshot_);
    return unshotPower;
  }

  void iterate() {
    if (faces_.empty()) throw Error("hierarchical solver: stepped after it finished");
    const Stopwatch watch;
    // After a change of the light, either series may have nothing to shoot.
    double unshotPower = maxChannel(unshot_[tree_.root]) > 0.0f || negative_.empty() ? sweep() : 0.0;
    if (!negative_.empty() && maxChannel(negative_[tree_.root]) > 0.0f) {
      // The negative series (where light left) shoots as a positive one into its own unshot and
      // next arrays, and what it gathers is taken off the fields.
      std::swap(unshot_, negative_), std::swap(next_, nextNegative_);
      shootingNegative_ = true;
      unshotPower += sweep();
      shootingNegative_ = false;
      std::swap(unshot_, negative_), std::swap(next_, nextNegative_);
    }
    ++iterations_;
    std::vector<Rgb>().swap(emission_);  // read in the first iteration only
    unshotFraction_ = emittedPower_ > 0.0 ? unshotPower / emittedPower_ : 0.0;
    done_ = unshotFraction_ < s_.unshot || iterations_ >= iterationLimit_;
    if (done_) releaseSweeps();
    seconds_ += watch.seconds();
  }

  // What only a sweep reads goes before the solution is asked for, which allocates its own
  // arrays: at millions of faces the two together were the solve's peak (docs/performance.md).
  // The fields, the tree, unshot_ (saved in checkpoints) and negative_ (its remainder, for the
  // next change) stay.
  void releaseSweeps() {
    std::vector<FaceSample>().swap(faces_);
    std::vector<Rgb>().swap(next_);
    std::vector<Mix>().swap(mix_);
    std::vector<Rgb>().swap(nextNegative_);
  }

  // A digest of the emission and reflectance the solve was made for: a change of either takes a
  // solve from scratch (sourcesChanged follows only the analytic light).
  uint64_t materialsDigest() const {
    ContentHash h;
    h.bytes(sys_.emission.data(), sys_.emission.size() * sizeof(Rgb));
    h.bytes(sys_.reflectance.data(), sys_.reflectance.size() * sizeof(Rgb));
    return h.digest();
  }

  const RadiositySystem& sys_;
  HierarchicalSettings s_;
  RayTracer* tracer_ = nullptr;
  FaceClusterTree tree_;
  std::unique_ptr<ClusterVisibility> clusterVisibility_;  // the links' rays, when not Embree's
  bool treeLoaded_ = false;             // read from the disk cache
  FaceClusterTree::Depth treeDepth_;
  std::vector<std::string> warnings_;
  std::unique_ptr<ClusterPoints> points_;
  EmitterDirectLight emitterDirect_;  // per element (solve/emitter_direct.h)
  bool exactDirect_ = false;          // emitterDirect_ holds the emitters' direct light
  static constexpr uint32_t kEmitterDirectSeed = 0xD12EC7u;
  float rayOffset_ = 0.0f;
  std::vector<Rgb> emission_;  // per cluster: area mean of its emission, for the first iteration
  std::vector<Rgb> unshot_;             // per cluster: mean radiosity shot this iteration
  // Per face in the tree's order (each leaf's faces one run, streamed every sweep): what the
  // sweep reads of it, and what it gathered this iteration, shot in the next.
  struct FaceSample {
    Vec3 centroid, normal;
    Rgb reflectance;
    float area;
  };
  std::vector<FaceSample> faces_;
  std::vector<Rgb> next_;
  std::vector<uint8_t> split_;          // per element: its children are elements
  std::unique_ptr<std::atomic<uint32_t>[]> field_;  // per element leaf: its fields in the pool
  std::unique_ptr<std::atomic<uint32_t>[]> since_;  // the iteration a cluster became an element
  tbb::concurrent_vector<Field> fields_;
  double emittedPower_ = 0.0;
  double startPower_ = 0.0;  // emittedPower_ when the solve started from nothing
  // Following changes of the analytic light (sourcesChanged): what was shot, the negative
  // series' unshot radiosity per cluster and what its faces gathered in a sweep (empty when
  // there is none), the series being swept, the digest of the materials the solve was made for,
  // the sweeps allowed, and the changes followed (after the first, emitter points carry their
  // cluster's mean: couple).
  std::vector<Rgb> analyticShot_;
  std::vector<Rgb> negative_, nextNegative_;
  bool shootingNegative_ = false;
  uint64_t materials_ = 0;
  uint32_t iterationLimit_ = 0;
  uint64_t redistributions_ = 0;
  double changeFollowed_ = 0.0;  // the changes' power since the solve started, over the power
  double unshotFraction_ = 0.0;
  uint32_t iterations_ = 0;
  std::atomic<uint64_t> links_{0};
  // Refinements over the solve, by the rule that asked for them: a near cluster emitter, the
  // transfer bound, a shadow edge across a link, the self-oracle.
  std::atomic<uint64_t> refinedNear_{0}, refinedTransfer_{0}, refinedShadow_{0}, refinedSelf_{0};
  std::atomic<size_t> leaves_{1}, elements_{1};  // the element tree: its nodes, its leaves
  // The clusters bottom-up for the swap: each as the area shares of its two children, ordered by
  // height (a level's clusters depend only on lower levels, so each level is one parallel pass).
  struct Mix {
    uint32_t node, a, b;
    float wa, wb;
  };
  std::vector<Mix> mix_;
  std::vector<size_t> levelStart_;
  bool done_ = false;
  double seconds_ = 0.0, setupSeconds_ = 0.0;
  int recordSh_ = 0;  // SH coefficients recorded for directional bakes (recordIncidentSh), 0: none
};

}  // namespace

void registerCpuHierarchical(SolverRegistry& registry) {
  SolverEntry e;
  e.description = {"hierarchical", "cpu",
                   "face-cluster hierarchical radiosity with vector irradiance (Gobbetti et al. 2003): links refined "
                   "by transfer error, never stored; Embree rays",
                   {}};
  auto& o = e.description.options;
  o.push_back(choiceOption("basis", "linear", {"constant", "linear", "bilinear", "quadratic", "cubic"},
                           "irradiance basis on each cluster (radiosity is constant)"));
  o.push_back(realOption("error", 1e-3, 1e-9, 1.0, "refine a link while its transfer error exceeds this share of the emitted power"));
  o.push_back(realOption("unshot", 1e-3, 1e-12, 0.999999, "stop when unshot power / emitted power falls below this"));
  o.push_back(integerOption("iterations", 100, 1, 100000, "at most this many iterations (bounces)"));
  o.push_back(integerOption("receiver-points", 3, 1, 8, "points on a receiver cluster: about this squared"));
  o.push_back(integerOption("emitter-points", 2, 1, 8, "points on an emitter cluster: about this squared"));
  o.push_back(flagOption("cache", true,
                         "keep the face-cluster hierarchy on disk, keyed by the surfaces' content ($LUXEL_CACHE_DIR, "
                         "else ~/.cache/luxel)"));
  o.push_back(choiceOption("emitter-light", "elements", {"elements", "links"},
                           "the emitting surfaces' direct light: per element with shadow rays, or through the "
                           "hierarchy's links as seed 002 shoots it (faster on millions of faces, coarser)"));
  o.push_back(flagOption("follow-light", true,
                         "after a light is moved or recoloured, shoot the difference from the last solution "
                         "(false: solve again from scratch)"));
  o.push_back(choiceOption("visibility", "rays", {"rays", "clusters"},
                           "the links' visibility: exact rays, or seed 002's multiresolution visibility (rays stop at "
                           "clusters whose shadow is too small to resolve and pass them by their opacity)"));
  o.push_back(realOption("visibility-stop", 1.0, 0.0, 1e6,
                         "with visibility=clusters: a cluster whose shadow on the receiver is smaller than this "
                         "times the spacing of the receiver's points stands for its faces (0: exact)"));
  for (SolverOption& a : analyticLightOptions()) o.push_back(std::move(a));
  e.make = [](const SolverResources& r, const SolverOptionValues& v) -> std::unique_ptr<Solver> {
    HierarchicalSettings s{basisSize(v.choice("basis")), v.real("error"),           v.real("unshot"),
                           v.integer("iterations"),       v.integer("receiver-points"), v.integer("emitter-points"),
                           v.flag("cache"),               v.choice("emitter-light") == "elements", v.flag("follow-light")};
    s.clusterVisibility = v.choice("visibility") == "clusters";
    s.visibilityStop = float(v.real("visibility-stop"));
    return std::make_unique<HierarchicalSolver>(r.system, r.transport, s,
                                                std::static_pointer_cast<CachedFaceClusterTree>(r.prepared));
  };
  e.prepare = [](const SurfaceSet& surfaces, const SolverOptionValues& v) -> std::shared_ptr<void> {
    return std::make_shared<CachedFaceClusterTree>(faceClusterTree(surfaces, v.flag("cache")));
  };
  e.converged.set("error", 1e-5).set("unshot", 1e-6).set("receiver-points", 3).set("emitter-points", 8);
  e.accuracy.furnace = 5e-3;  // the target for the furnace
  // The visibility of a leaf emitter is a ratio over its 8 x 8 point grid: a shadow edge falls
  // anywhere within one column, a column of the half-shadow emitter carries about a tenth of the
  // factor, so half of that.
  e.accuracy.halfShadow = 0.06;
  // Per element it takes the mean over 3 x 3 points where the reference takes the centroid: on
  // elements a block half covers or a penumbra crosses these differ by up to a third, which the
  // 0.02 of a solver of the same quadrature does not allow for (docs/algorithms.md).
  e.accuracy.cornell = 0.05;
  e.shootsFromPatches = false;  // clusters of elements shoot
  registry.add(std::move(e));
}

}  // namespace luxel
