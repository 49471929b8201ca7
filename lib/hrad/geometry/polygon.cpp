#include "hrad/geometry/polygon.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hrad {

Vec3 newell_normal(std::span<const Vec3> p) {
  Vec3 n = Vec3::Zero();
  const std::size_t k = p.size();
  // Relative to the first vertex, so that far-from-origin polygons keep their precision.
  for (std::size_t i = 1; i + 1 < k; ++i) n += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return n;
}

double polygon_area(std::span<const Vec3> p) { return 0.5 * newell_normal(p).norm(); }

Vec3 polygon_centroid(std::span<const Vec3> p) {
  const Vec3 n = newell_normal(p);
  const double nn = n.squaredNorm();
  Vec3 c = Vec3::Zero();
  double w_sum = 0.0;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const double w = (p[i] - p[0]).cross(p[i + 1] - p[0]).dot(n);  // signed, for non-convex input
    c += w * (p[0] + p[i] + p[i + 1]) / 3.0;
    w_sum += w;
  }
  if (nn == 0.0 || w_sum == 0.0) {
    return std::accumulate(p.begin(), p.end(), Vec3(Vec3::Zero())) / double(p.size());
  }
  return c / w_sum;
}

double planarity_deviation(std::span<const Vec3> p, const Vec3& n) {
  const Vec3 mean = std::accumulate(p.begin(), p.end(), Vec3(Vec3::Zero())) / double(p.size());
  double d = 0.0;
  for (const Vec3& v : p) d = std::max(d, std::abs((v - mean).dot(n)));
  return d;
}

double polygon_diameter(std::span<const Vec3> p) {
  double d = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) d = std::max(d, (p[i] - p[j]).norm());
  return d;
}

std::pair<Vec3, double> vertex_sphere(std::span<const Vec3> p) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : p) c += v;
  c /= static_cast<double>(p.size());
  double r2 = 0.0;
  for (const Vec3& v : p) r2 = std::max(r2, (v - c).squaredNorm());
  return {c, std::sqrt(r2)};
}

bool is_convex(std::span<const Vec3> p, const Vec3& n) {
  const std::size_t k = p.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = p[(i + k - 1) % k];
    const Vec3& b = p[i];
    const Vec3& c = p[(i + 1) % k];
    if ((b - a).cross(c - b).dot(n) < 0.0) return false;
  }
  return true;
}

std::array<Vec3, 2> plane_basis(const Vec3& n) {
  // Frisvad-style choice of a helper axis away from n.
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = helper.cross(n).normalized();
  return {u, n.cross(u)};
}

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

bool point_in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross2(b - a, p - a) >= 0.0 && cross2(c - b, p - b) >= 0.0 && cross2(a - c, p - c) >= 0.0;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate(std::span<const Vec3> p, const Vec3& n) {
  const auto [u, v] = plane_basis(n);
  std::vector<Vec2> q;
  for (const Vec3& x : p) q.emplace_back((x - p[0]).dot(u), (x - p[0]).dot(v));
  std::vector<int> ring(p.size());
  std::iota(ring.begin(), ring.end(), 0);
  std::vector<std::array<int, 3>> triangles;
  while (ring.size() > 3) {
    const std::size_t k = ring.size();
    bool clipped = false;
    for (std::size_t i = 0; i < k && !clipped; ++i) {
      const int ia = ring[(i + k - 1) % k], ib = ring[i], ic = ring[(i + 1) % k];
      if (cross2(q[ib] - q[ia], q[ic] - q[ib]) <= 0.0) continue;  // reflex or flat: not an ear
      bool empty = true;
      for (int j : ring) {
        if (j == ia || j == ib || j == ic) continue;
        if (point_in_triangle(q[j], q[ia], q[ib], q[ic])) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      triangles.push_back({ia, ib, ic});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) {  // only (near-)collinear runs are left: drop the flattest vertex
      std::size_t flattest = 0;
      double least = INFINITY;
      for (std::size_t i = 0; i < k; ++i) {
        const double turn = std::abs(cross2(q[ring[i]] - q[ring[(i + k - 1) % k]], q[ring[(i + 1) % k]] - q[ring[i]]));
        if (turn < least) {
          least = turn;
          flattest = i;
        }
      }
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(flattest));
    }
  }
  if (cross2(q[ring[1]] - q[ring[0]], q[ring[2]] - q[ring[1]]) > 0.0) triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

}  // namespace hrad
