// Curved charts: least squares conformal maps.
//
// Levy, Petitjean, Ray and Maillot, "Least Squares Conformal Maps for Automatic Texture Atlas
// Generation", SIGGRAPH 2002. Each triangle contributes |sum_j W_j U_j|^2 / d_T, the squared
// violation of the Cauchy-Riemann equations integrated over it (d_T twice its area, W_j the
// complex edge opposite corner j in the triangle's own orthonormal frame, U_j = u_j + i v_j).
// Two vertices, the farthest pair found by two sweeps, are pinned; the rest minimise the sum,
// solved through the normal equations with a sparse LDL^T factorisation (Eigen).
#include <Eigen/Sparse>
#include <cmath>
#include <unordered_map>

#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {
namespace {

uint32_t farthestFrom(const std::vector<Vec3>& p, uint32_t from) {
  uint32_t best = from;
  float bestD = -1.0f;
  for (uint32_t i = 0; i < p.size(); ++i) {
    float d = glm::dot(p[i] - p[from], p[i] - p[from]);
    if (d > bestD) bestD = d, best = i;
  }
  return best;
}

}  // namespace

bool lscm(const WeldedMesh& w, Chart& chart) {
  // Local numbering of the chart's vertices.
  std::unordered_map<uint32_t, uint32_t> local;
  std::vector<Vec3> pos;
  std::vector<std::array<uint32_t, 4>> corner(chart.faces.size());
  for (size_t i = 0; i < chart.faces.size(); ++i) {
    uint32_t f = chart.faces[i];
    for (int k = 0; k < 4; ++k) {
      auto [it, fresh] = local.try_emplace(w.v[f][size_t(k)], uint32_t(pos.size()));
      if (fresh) pos.push_back(w.positions[w.v[f][size_t(k)]]);
      corner[i][size_t(k)] = it->second;
    }
  }
  const uint32_t n = uint32_t(pos.size());
  if (n < 3) return false;
  const uint32_t pin0 = farthestFrom(pos, farthestFrom(pos, 0));
  const uint32_t pin1 = farthestFrom(pos, pin0);
  if (pin0 == pin1) return false;
  const Eigen::Vector2d pinned[2] = {{0.0, 0.0}, {double(glm::length(pos[pin1] - pos[pin0])), 0.0}};
  // Free vertex k -> columns 2 col[k] (u) and 2 col[k] + 1 (v); pinned ones -> -1 / -2.
  std::vector<int64_t> col(n);
  int64_t free = 0;
  for (uint32_t k = 0; k < n; ++k) col[k] = k == pin0 ? -1 : k == pin1 ? -2 : free++;

  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rhs;
  auto addTriangle = [&](uint32_t i0, uint32_t i1, uint32_t i2) {
    glm::dvec3 p0 = pos[i0], p1 = pos[i1], p2 = pos[i2];
    glm::dvec3 e = p1 - p0, c = glm::cross(p1 - p0, p2 - p0);
    double d = glm::length(c);  // twice the area
    double len = glm::length(e);
    if (!(d > 1e-14 * len * len) || len <= 0.0) return;  // degenerate: no energy
    glm::dvec3 ex = e / len, ey = glm::cross(c / d, ex);
    double x[3] = {0.0, len, glm::dot(p2 - p0, ex)}, y[3] = {0.0, 0.0, glm::dot(p2 - p0, ey)};
    const uint32_t id[3] = {i0, i1, i2};
    const double s = 1.0 / std::sqrt(d);
    const int64_t row = int64_t(rhs.size());
    rhs.push_back(0.0), rhs.push_back(0.0);
    for (int j = 0; j < 3; ++j) {
      int a = (j + 1) % 3, b = (j + 2) % 3;  // W_j = p_b - p_a (the edge opposite j)
      double wr = (x[b] - x[a]) * s, wi = (y[b] - y[a]) * s;
      // Real part: wr u - wi v; imaginary part: wi u + wr v.
      int64_t k = col[id[j]];
      if (k >= 0) {
        triplets.emplace_back(row, 2 * k, wr), triplets.emplace_back(row, 2 * k + 1, -wi);
        triplets.emplace_back(row + 1, 2 * k, wi), triplets.emplace_back(row + 1, 2 * k + 1, wr);
      } else {
        const Eigen::Vector2d& u = pinned[-k - 1];
        rhs[size_t(row)] -= wr * u.x() - wi * u.y();
        rhs[size_t(row + 1)] -= wi * u.x() + wr * u.y();
      }
    }
  };
  for (size_t i = 0; i < chart.faces.size(); ++i) {
    const auto& v = corner[i];
    addTriangle(v[0], v[1], v[2]);
    if (w.corners[chart.faces[i]] == 4) addTriangle(v[0], v[2], v[3]);
  }
  if (free == 0) return false;
  Eigen::SparseMatrix<double> A(Eigen::Index(rhs.size()), Eigen::Index(2 * free));
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::Map<const Eigen::VectorXd> b(rhs.data(), Eigen::Index(rhs.size()));
  Eigen::SparseMatrix<double> normal = A.transpose() * A;
  Eigen::VectorXd atb = A.transpose() * b;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) return false;
  Eigen::VectorXd x = solver.solve(atb);
  if (solver.info() != Eigen::Success || !x.allFinite()) return false;

  std::vector<Vec2> uv(n);
  for (uint32_t k = 0; k < n; ++k)
    uv[k] = col[k] >= 0 ? Vec2(float(x[2 * col[k]]), float(x[2 * col[k] + 1]))
                        : Vec2(float(pinned[-col[k] - 1].x()), float(pinned[-col[k] - 1].y()));
  chart.uv.assign(chart.faces.size(), {});
  chart.planar = false;
  for (size_t i = 0; i < chart.faces.size(); ++i) {
    uint32_t f = chart.faces[i];
    for (int k = 0; k < 4; ++k) chart.uv[i][size_t(k)] = uv[corner[i][size_t(k)]];
    if (w.area[f] <= 0.0f) continue;
    const auto& t = chart.uv[i];
    if (!(signedArea(t[0], t[1], t[2]) > 0.0f)) return false;
    if (w.corners[f] == 4 && !(signedArea(t[0], t[2], t[3]) > 0.0f)) return false;
  }
  return true;
}

}  // namespace luxel::lightmap
