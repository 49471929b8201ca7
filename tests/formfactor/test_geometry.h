// Small geometry helpers for the form-factor tests: rectangles, rigid motions, a seeded generator.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "hrad/core/types.h"

namespace hrad::test {

using Polygon = std::vector<Vec3>;

/// The rectangle origin, origin + u, origin + u + v, origin + v: counter-clockwise about u x v.
inline Polygon rectangle(const Vec3& origin, const Vec3& u, const Vec3& v) {
  return {origin, origin + u, origin + u + v, origin + v};
}

inline Polygon reversed(Polygon p) { return Polygon(p.rbegin(), p.rend()); }

/// x -> scale * R x + t for every vertex.
inline Polygon moved(const Polygon& p, const Eigen::Matrix3d& rotation, const Vec3& shift, double scale = 1.0) {
  Polygon out;
  for (const Vec3& v : p) out.push_back(scale * (rotation * v) + shift);
  return out;
}

inline Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

}  // namespace hrad::test
