#include "hrad/formfactor/simpson_rule.h"

#include <cassert>

namespace hrad {

SimpsonPoints simpson_points(std::span<const Vec3> v) {
  SimpsonPoints s;
  auto mid = [](const Vec3& a, const Vec3& b) -> Vec3 { return (a + b) * 0.5; };  // as ElementHierarchy::split()
  if (v.size() == 4) {
    s.count = 9;
    const auto& uv = kSimpsonQuadUv;
    for (int k = 0; k < 4; ++k) s.x[k] = v[k];
    for (int k = 0; k < 4; ++k) s.x[4 + k] = mid(v[k], v[(k + 1) % 4]);
    s.x[8] = (v[0] + v[1] + v[2] + v[3]) * 0.25;
    for (int k = 0; k < 9; ++k) {
      const double u = uv[k][0], w = uv[k][1];
      const Vec3 xu = (1 - w) * (v[1] - v[0]) + w * (v[2] - v[3]);
      const Vec3 xv = (1 - u) * (v[3] - v[0]) + u * (v[2] - v[1]);
      const double su = (u == 0.5) ? 4.0 : 1.0, sv = (w == 0.5) ? 4.0 : 1.0;
      s.weight[k] = su * sv / 36.0 * xu.cross(xv).norm();
    }
    return s;
  }
  assert(v.size() == 3);
  s.count = 7;
  const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
  for (int k = 0; k < 3; ++k) {
    s.x[k] = v[k];
    s.weight[k] = area / 20.0;
    s.x[3 + k] = mid(v[k], v[(k + 1) % 3]);
    s.weight[3 + k] = area * 2.0 / 15.0;
  }
  s.x[6] = (v[0] + v[1] + v[2]) / 3.0;
  s.weight[6] = area * 9.0 / 20.0;
  return s;
}

std::array<double, 4> corner_mean_weights(const SimpsonPoints& s) {
  std::array<double, 4> w{};
  double area = 0.0;
  for (int i = 0; i < s.count; ++i) area += s.weight[i];
  if (!(area > 0.0)) return w;
  if (s.count == 9) {
    // Bilinear corner functions at the points: 1 at its own corner, 1/2 at the midpoints of its two
    // edges, 1/4 at the centre.
    for (int c = 0; c < 4; ++c)
      w[c] = (s.weight[c] + 0.5 * (s.weight[4 + c] + s.weight[4 + (c + 3) % 4]) + 0.25 * s.weight[8]) / area;
  } else {
    // Linear: 1 at its vertex, 1/2 at the midpoints of its edges, 1/3 at the centroid.
    for (int c = 0; c < 3; ++c)
      w[c] = (s.weight[c] + 0.5 * (s.weight[3 + c] + s.weight[3 + (c + 2) % 3]) + s.weight[6] / 3.0) / area;
  }
  return w;
}

std::array<int, 4> child_corner_points(int vertex_count, int child) {
  if (vertex_count == 4) return {child, 4 + child, 8, 4 + (child + 3) % 4};
  // Triangle children: {v0, m01, m20}, {v1, m12, m01}, {v2, m20, m12}, {m01, m12, m20}.
  switch (child) {
    case 0:
      return {0, 3, 5, -1};
    case 1:
      return {1, 4, 3, -1};
    case 2:
      return {2, 5, 4, -1};
    default:
      return {3, 4, 5, -1};
  }
}

}  // namespace hrad
