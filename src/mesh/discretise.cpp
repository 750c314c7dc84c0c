// Cutting faces into patches and elements (Cohen, Greenberg, Immel, Brock 1986: substructuring).
// Each face is cut on a regular grid in its own parameter space, so that elements of one face tile
// it exactly and can be split again later by adaptive refinement. A face may prescribe its grid
// (Mesh::elementGrids, for scenes whose element counts are given, such as the seed papers' test
// scenes); the budget then sizes only the other faces.
#include <algorithm>
#include <cmath>
#include <numbers>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/surface.h"
#include "mesh/element_split.h"
#include "mesh/orient_faces.h"

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr size_t kMaxElements = 50'000'000;
// Samples per side when averaging a texture over an element.
constexpr int kTextureSamplesPerSide = 4;

// A face's prescribed grid, {elements along s, along t}; {0, 0} for the automatic cut.
using ElementGrid = std::array<uint16_t, 2>;

bool isFixed(const ElementGrid& g) { return g[0] > 0 && g[1] > 0; }

// Triangles are cut n x n; Scene::validate asks for g[0] == g[1], the larger one wins otherwise.
int triangleCuts(const ElementGrid& g) { return std::max(g[0], g[1]); }

size_t fixedCount(const SurfaceFace& f, const ElementGrid& g) {
  if (!isFixed(g)) return 0;
  return f.triangle ? size_t(triangleCuts(g)) * size_t(triangleCuts(g)) : size_t(g[0]) * g[1];
}

int ceilDiv(int a, int b) { return (a + b - 1) / b; }

struct GridCounts {
  int patchesU = 1, patchesV = 1;    // quads: patches along s and t; triangles: patchesU only
  int elementsU = 1, elementsV = 1;  // per patch
};

int cellsFor(float length, float size) {
  return std::max(1, int(std::ceil(length / size - 1e-3f)));
}

GridCounts gridFor(const SurfaceFace& f, float elementSize, int perPatch) {
  const float patchSize = elementSize * float(perPatch);
  GridCounts g;
  if (f.triangle) {
    float edge = std::max({glm::length(f.corners[1] - f.corners[0]),
                           glm::length(f.corners[2] - f.corners[1]),
                           glm::length(f.corners[0] - f.corners[2])});
    g.patchesU = g.patchesV = cellsFor(edge, patchSize);
    g.elementsU = g.elementsV = cellsFor(edge / float(g.patchesU), elementSize);
  } else {
    float lu = std::max(glm::length(f.corners[1] - f.corners[0]),
                        glm::length(f.corners[2] - f.corners[3]));
    float lv = std::max(glm::length(f.corners[3] - f.corners[0]),
                        glm::length(f.corners[2] - f.corners[1]));
    g.patchesU = cellsFor(lu, patchSize);
    g.patchesV = cellsFor(lv, patchSize);
    g.elementsU = cellsFor(lu / float(g.patchesU), elementSize);
    g.elementsV = cellsFor(lv / float(g.patchesV), elementSize);
  }
  return g;
}

// Elements of the faces without a prescribed grid, for a given element size.
size_t elementCount(const std::vector<SurfaceFace>& faces, const std::vector<ElementGrid>& grids,
                    float elementSize, int perPatch) {
  size_t n = 0;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (isFixed(grids[i])) continue;
    const SurfaceFace& f = faces[i];
    GridCounts g = gridFor(f, elementSize, perPatch);
    n += f.triangle ? size_t(g.patchesU) * g.patchesU * g.elementsU * g.elementsU
                    : size_t(g.patchesU) * g.patchesV * g.elementsU * g.elementsV;
  }
  return n;
}

// Regular subdivision of a parameter-space polygon into n x n cells (quads) or n^2 triangles.
std::vector<std::array<Vec2, 4>> subdivideParams(const std::array<Vec2, 4>& p, bool triangle,
                                                 int nu, int nv) {
  std::vector<std::array<Vec2, 4>> cells;
  if (triangle) {
    const int n = nu;
    auto at = [&](int i, int j) {
      return p[0] + (float(i) / n) * (p[1] - p[0]) + (float(j) / n) * (p[2] - p[0]);
    };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + j < n; ++i) {
        Vec2 a = at(i, j), b = at(i + 1, j), c = at(i, j + 1);
        cells.push_back({a, b, c, c});
        if (i + j + 1 < n) {
          Vec2 d = at(i + 1, j + 1);
          cells.push_back({b, d, c, c});
        }
      }
  } else {
    auto at = [&](float s, float t) {
      return (1 - s) * (1 - t) * p[0] + s * (1 - t) * p[1] + s * t * p[2] + (1 - s) * t * p[3];
    };
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        float s0 = float(i) / nu, s1 = float(i + 1) / nu, t0 = float(j) / nv, t1 = float(j + 1) / nv;
        cells.push_back({at(s0, t0), at(s1, t0), at(s1, t1), at(s0, t1)});
      }
  }
  return cells;
}

Polygon polygonFromParams(const SurfaceFace& f, const std::array<Vec2, 4>& param) {
  Polygon poly;
  poly.count = f.triangle ? 3 : 4;
  for (int i = 0; i < 4; ++i) poly.v[i] = f.position(param[i]);
  return poly;
}

// Mean of a texture over the element, by a regular grid of samples in parameter space.
Rgb textureMean(const Texture& tex, const SurfaceFace& f, const std::array<Vec2, 4>& param) {
  Rgb sum(0.0f);
  int n = 0;
  const int k = kTextureSamplesPerSide;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      float s = (i + 0.5f) / k, t = (j + 0.5f) / k;
      Vec2 st;
      if (f.triangle) {
        if (s + t > 1.0f) continue;  // keep the samples inside the triangle
        st = param[0] + s * (param[1] - param[0]) + t * (param[2] - param[0]);
      } else {
        st = (1 - s) * (1 - t) * param[0] + s * (1 - t) * param[1] + s * t * param[2] +
             (1 - s) * t * param[3];
      }
      sum += tex.sample(f.uv(st));
      ++n;
    }
  return n > 0 ? sum / float(n) : tex.sample(f.uv(param[0]));
}

// Cuts a quad whose fourth corner is off the plane of the other three into two triangles, so
// that elements are planar and coincide with the triangles the ray tracer sees.
std::vector<SurfaceFace> splitIfNonPlanar(const SurfaceFace& f, bool triangle, size_t& splitCount) {
  SurfaceFace a = f;
  a.triangle = triangle;
  if (triangle) {
    a.corners[3] = a.corners[2], a.uvs[3] = a.uvs[2];
    return {a};
  }
  const auto& c = f.corners;
  Vec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
  float len = glm::length(n);
  float size = std::max({glm::length(c[1] - c[0]), glm::length(c[2] - c[1]), glm::length(c[3] - c[2]),
                         glm::length(c[0] - c[3])});
  bool planar = len > 0.0f && std::abs(glm::dot(n / len, c[3] - c[0])) <= 1e-5f * size;
  // A concave or bow-tie quad cannot be cut on a bilinear grid either: every corner must turn
  // the same way.
  bool convex = true;
  for (int i = 0; i < 4; ++i) {
    Vec3 e0 = c[(i + 1) % 4] - c[i], e1 = c[(i + 2) % 4] - c[(i + 1) % 4];
    convex &= glm::dot(glm::cross(e0, e1), n) > 0.0f;
  }
  if (planar && convex) return {a};
  ++splitCount;
  SurfaceFace t0 = f, t1 = f;
  t0.triangle = t1.triangle = true;
  t0.corners = {c[0], c[1], c[2], c[2]};
  t0.uvs = {f.uvs[0], f.uvs[1], f.uvs[2], f.uvs[2]};
  t1.corners = {c[0], c[2], c[3], c[3]};
  t1.uvs = {f.uvs[0], f.uvs[2], f.uvs[3], f.uvs[3]};
  return {t0, t1};
}

// Swapping corners 1 and 3 of a quad (turning it round) swaps its s and t: the prescribed grid
// follows, so that the same elements cover the same places.
ElementGrid turnedRound(const SurfaceFace& f, const ElementGrid& g) {
  return f.triangle ? g : ElementGrid{g[1], g[0]};
}

// Two-sided materials get a second, reversed face: the back side, with its own radiosity, and the
// front's element grid.
void addTwinFaces(const Scene& scene, std::vector<SurfaceFace>& faces,
                  std::vector<ElementGrid>& grids) {
  const size_t n = faces.size();
  for (size_t i = 0; i < n; ++i) {
    if (!scene.materials[faces[i].material].twoSided) continue;
    SurfaceFace back = faces[i];
    std::swap(back.corners[1], back.corners[back.triangle ? 2 : 3]);
    std::swap(back.uvs[1], back.uvs[back.triangle ? 2 : 3]);
    if (back.triangle) back.corners[3] = back.corners[2], back.uvs[3] = back.uvs[2];
    back.normal = -faces[i].normal;
    back.twin = int32_t(i);
    faces[i].twin = int32_t(faces.size());
    faces.push_back(back);
    grids.push_back(turnedRound(back, grids[i]));
  }
}

Patch makePatch(const SurfaceFace& f, uint32_t faceIndex, const std::array<Vec2, 4>& param) {
  Patch patch;
  patch.polygon = polygonFromParams(f, param);
  patch.centroid = patch.polygon.centroid();
  patch.normal = f.normal;
  patch.area = patch.polygon.area();
  patch.face = faceIndex;
  return patch;
}

// An element's reflectance and exitance: its face's material, textures averaged over the element.
void readMaterial(const Scene& scene, const SurfaceFace& f, Element& e) {
  const Material& m = scene.materials[f.material];
  e.reflectance = m.reflectance;
  if (m.reflectanceTexture >= 0)
    e.reflectance *= textureMean(scene.textures[size_t(m.reflectanceTexture)], f, e.param);
  e.exitance = kPi * m.emission;
  if (m.emissionTexture >= 0)
    e.exitance *= textureMean(scene.textures[size_t(m.emissionTexture)], f, e.param);
}

Element makeElement(const Scene& scene, const SurfaceSet& set, uint32_t faceIndex,
                    uint32_t patchIndex, const std::array<Vec2, 4>& param, uint8_t depth) {
  const SurfaceFace& f = set.faces[faceIndex];
  Element e;
  e.polygon = polygonFromParams(f, param);
  e.param = param;
  e.centroid = e.polygon.centroid();
  e.normal = f.normal;
  e.area = e.polygon.area();
  e.face = faceIndex;
  e.patch = patchIndex;
  e.material = f.material;
  readMaterial(scene, f, e);
  e.depth = depth;
  return e;
}

// Cuts a face with a prescribed grid. Quads: nu x nv elements, in patches of blocks of about
// perPatch x perPatch elements (block edges at round(k nu / patchesU), so block sizes differ by at
// most one); each patch is the parameter rectangle of its block. Triangles: n^2 elements; one
// patch when n <= perPatch, else P^2 triangular patches of (n/P)^2 elements each, P the smallest
// divisor of n with n/P <= perPatch (so the patches' grids line up with the n x n grid exactly).
void cutPrescribed(const Scene& scene, SurfaceSet& set, uint32_t fi, const ElementGrid& g,
                   int perPatch) {
  const SurfaceFace& f = set.faces[fi];
  if (f.triangle) {
    const int n = triangleCuts(g);
    int p = ceilDiv(n, perPatch);
    while (n % p != 0) ++p;
    const std::array<Vec2, 4> whole{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(0, 1)};
    for (const auto& patchParam : subdivideParams(whole, true, p, p)) {
      Patch patch = makePatch(f, fi, patchParam);
      const auto patchIndex = uint32_t(set.patches.size());
      for (const auto& param : subdivideParams(patchParam, true, n / p, n / p)) {
        patch.elements.push_back(uint32_t(set.elements.size()));
        set.elements.push_back(makeElement(scene, set, fi, patchIndex, param, 0));
      }
      set.patches.push_back(std::move(patch));
    }
    return;
  }
  const int nu = g[0], nv = g[1];
  const int pu = ceilDiv(nu, perPatch), pv = ceilDiv(nv, perPatch);
  // round(k n / parts), halves up, in integers.
  auto edge = [](int n, int parts, int k) { return (2 * k * n + parts) / (2 * parts); };
  auto at = [&](int i, int j) { return Vec2(float(i) / float(nu), float(j) / float(nv)); };
  for (int pj = 0; pj < pv; ++pj)
    for (int pi = 0; pi < pu; ++pi) {
      const int i0 = edge(nu, pu, pi), i1 = edge(nu, pu, pi + 1);
      const int j0 = edge(nv, pv, pj), j1 = edge(nv, pv, pj + 1);
      Patch patch = makePatch(f, fi, {at(i0, j0), at(i1, j0), at(i1, j1), at(i0, j1)});
      const auto patchIndex = uint32_t(set.patches.size());
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
          const std::array<Vec2, 4> cell{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
          patch.elements.push_back(uint32_t(set.elements.size()));
          set.elements.push_back(makeElement(scene, set, fi, patchIndex, cell, 0));
        }
      set.patches.push_back(std::move(patch));
    }
}

}  // namespace

void SurfaceSet::refreshMaterials(const Scene& scene) {
  for (Element& e : elements) readMaterial(scene, faces[e.face], e);
}

float SurfaceSet::totalArea() const {
  double a = 0.0;
  for (const Element& e : elements) a += e.area;
  return float(a);
}

void SurfaceSet::dropPatches() {
  std::vector<Patch>().swap(patches);
  for (Element& e : elements) e.patch = kNoPatch;
#if defined(__GLIBC__)
  // The patches' element lists are millions of small blocks in the heap's middle, which free()
  // keeps mapped for reuse: give their pages back now, so that the drop is memory the process
  // no longer holds whatever it allocates next.
  malloc_trim(0);
#endif
}

void SurfaceSet::splitElement(uint32_t index, const Scene& scene) {
  const Element parent = elements[index];
  const auto children = splitCorners(parent.param, faces[parent.face].triangle);
  const auto depth = uint8_t(parent.depth + 1);
  elements[index] = makeElement(scene, *this, parent.face, parent.patch, children[0], depth);
  for (int c = 1; c < 4; ++c) {
    if (parent.patch != kNoPatch) patches[parent.patch].elements.push_back(uint32_t(elements.size()));
    elements.push_back(makeElement(scene, *this, parent.face, parent.patch, children[c], depth));
  }
}

SurfaceSet discretise(const Scene& scene, const DiscretiseOptions& options) {
  if (!(options.elementSize >= 0.0f) || !std::isfinite(options.elementSize))
    throw Error(fmt::format("element size {} must be a finite length >= 0", options.elementSize));
  if (options.elementSize == 0.0f && (options.elementBudget == 0 || options.elementBudget > kMaxElements))
    throw Error(fmt::format("element budget {} must be between 1 and {}", options.elementBudget,
                            kMaxElements));
  if (options.elementsPerPatchSide < 1 || options.elementsPerPatchSide > 64)
    throw Error(fmt::format("elements per patch side {} must be between 1 and 64",
                            options.elementsPerPatchSide));

  SurfaceSet set;
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Mesh& mesh : scene.meshes)
    for (const Vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  set.sceneExtent = glm::length(hi - lo);
  for (const Object& o : scene.objects) set.objectTransforms.push_back(o.transform);

  std::vector<ElementGrid> grids;  // one per entry of set.faces
  for (uint32_t mi = 0; mi < scene.meshes.size(); ++mi) {
    const Mesh& mesh = scene.meshes[mi];
    if (!mesh.elementGrids.empty() && mesh.elementGrids.size() != mesh.faces.size())
      throw Error(fmt::format("scene '{}': mesh '{}': {} element grids for {} faces", scene.name,
                              mesh.name, mesh.elementGrids.size(), mesh.faces.size()));
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      const Face& face = mesh.faces[fi];
      SurfaceFace f;
      f.mesh = mi;
      f.meshFace = uint32_t(fi);
      f.material = mesh.material;
      for (int i = 0; i < 4; ++i) {
        f.corners[i] = mesh.positions[face.v[i]];
        f.uvs[i] = mesh.uvs.empty() ? Vec2(0.0f) : mesh.uvs[face.v[i]];
      }
      ElementGrid grid = mesh.elementGrids.empty() ? ElementGrid{0, 0} : mesh.elementGrids[fi];
      if (!isFixed(grid)) grid = {0, 0};
      auto pieces = splitIfNonPlanar(f, face.isTriangle(), set.splitQuads);
      // A quad cut in two has no grid of its own any more: its halves are cut automatically.
      if (pieces.size() > 1) grid = {0, 0};
      for (SurfaceFace& piece : pieces) {
        Polygon poly{piece.corners, piece.triangle ? 3 : 4};
        if (!poly.hasArea()) continue;  // degenerate faces carry no light
        piece.normal = poly.normal();
        set.faces.push_back(piece);
        grids.push_back(grid);
      }
    }
  }
  if (options.orientByLight) {
    set.flippedFaces = orientFacesByLight(scene, set.faces, set.sceneExtent);
    for (size_t i = 0; i < set.faces.size(); ++i)
      if (set.faces[i].flipped) grids[i] = turnedRound(set.faces[i], grids[i]);
  }
  addTwinFaces(scene, set.faces, grids);
  if (set.faces.empty()) {
    // Coordinates past the limit overflow every area to infinity: say that, not its symptom.
    scene.validate();
    throw Error(fmt::format("scene '{}': no face has a positive area", scene.name));
  }
  // Faces with a prescribed grid are fixed; the budget search sizes the others only.
  double freeArea = 0.0, fixedArea = 0.0;
  size_t fixedElements = 0, freeFaces = 0;
  for (size_t i = 0; i < set.faces.size(); ++i) {
    const SurfaceFace& f = set.faces[i];
    const double area = Polygon{f.corners, f.triangle ? 3 : 4}.area();
    if (isFixed(grids[i])) {
      fixedArea += area;
      fixedElements += fixedCount(f, grids[i]);
    } else {
      freeArea += area;
      ++freeFaces;
    }
  }

  const int perPatch = options.elementsPerPatchSide;
  float size = options.elementSize;
  if (size == 0.0f && freeFaces > 0) {
    // What the fixed faces leave of the budget; when they take it all, one element per free face.
    const size_t left =
        options.elementBudget > fixedElements ? options.elementBudget - fixedElements : 0;
    const double budget = double(left > 0 ? left : freeFaces);
    // Rounding each face up to whole cells overshoots the budget; correct the size a few times.
    size = float(std::sqrt(freeArea / budget));
    for (int i = 0; i < 4; ++i) {
      size_t n = elementCount(set.faces, grids, size, perPatch);
      size *= float(std::sqrt(double(n) / budget));
    }
  } else if (size == 0.0f) {
    size = float(std::sqrt(fixedArea / double(std::max<size_t>(fixedElements, 1))));  // for show
  }
  const size_t expected = elementCount(set.faces, grids, size, perPatch) + fixedElements;
  if (expected > kMaxElements)
    throw Error(fmt::format("element size {} gives {} elements, over the limit of {}", size,
                            expected, kMaxElements));
  set.elementSize = size;
  set.elements.reserve(expected);

  for (uint32_t fi = 0; fi < set.faces.size(); ++fi) {
    if (isFixed(grids[fi])) {
      cutPrescribed(scene, set, fi, grids[fi], perPatch);
      continue;
    }
    const SurfaceFace& f = set.faces[fi];
    GridCounts g = gridFor(f, size, perPatch);
    std::array<Vec2, 4> whole = f.triangle
                                    ? std::array<Vec2, 4>{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(0, 1)}
                                    : std::array<Vec2, 4>{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
    for (const auto& patchParam : subdivideParams(whole, f.triangle, g.patchesU, g.patchesV)) {
      Patch patch = makePatch(f, fi, patchParam);
      const auto patchIndex = uint32_t(set.patches.size());
      for (const auto& param : subdivideParams(patchParam, f.triangle, g.elementsU, g.elementsV)) {
        patch.elements.push_back(uint32_t(set.elements.size()));
        set.elements.push_back(makeElement(scene, set, fi, patchIndex, param, 0));
      }
      set.patches.push_back(std::move(patch));
    }
  }
  return set;
}

}  // namespace luxel
