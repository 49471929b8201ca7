#include "hrad/viewfactors/pair_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

// The most and the least height of b's vertices above a's plane.
std::pair<double, double> heights(const PatchBoundShape& a, const PatchBoundShape& b) {
  double most = -std::numeric_limits<double>::infinity(), least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < b.count; ++k) {
    const double h = a.normal.dot(b.vertices[static_cast<std::size_t>(k)]) - a.offset;
    most = std::max(most, h);
    least = std::min(least, h);
  }
  return {most, least};
}

}  // namespace

std::vector<PatchBoundShape> patch_bound_shapes(const Scene& scene) {
  std::vector<PatchBoundShape> shapes(scene.patches.size());
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const Patch& patch = scene.patches[i];
    PatchBoundShape& s = shapes[i];
    if (patch.vertices.size() > s.vertices.size())
      throw Error(fmt::format("patch {} has {} vertices (at most 4)", i, patch.vertices.size()));
    s.count = static_cast<int>(patch.vertices.size());
    s.lo = s.hi = patch.vertices.front();
    for (int k = 0; k < s.count; ++k) {
      const Vec3& v = patch.vertices[static_cast<std::size_t>(k)];
      s.vertices[static_cast<std::size_t>(k)] = v;
      s.centre += v / s.count;
      s.lo = s.lo.cwiseMin(v);
      s.hi = s.hi.cwiseMax(v);
    }
    for (int k = 0; k < s.count; ++k)
      s.radius = std::max(s.radius, (s.vertices[static_cast<std::size_t>(k)] - s.centre).norm());
    s.normal = patch.normal;
    s.offset = patch.normal.dot(s.centre);
    s.area = patch.area;
  }
  return shapes;
}

FactorBound factor_bound(const PatchBoundShape& p, const PatchBoundShape& q) {
  const auto [hp, lp] = heights(p, q);
  const auto [hq, lq] = heights(q, p);
  if (!(hp > 0.0) || !(hq > 0.0)) return {};
  const Vec3 box_gap = (p.lo - q.hi).cwiseMax(q.lo - p.hi).cwiseMax(0.0);
  const double d = std::max({(p.centre - q.centre).norm() - p.radius - q.radius, box_gap.norm(), lp, lq});
  if (!(d > 0.0)) {
    constexpr double kNone = std::numeric_limits<double>::infinity();
    return {kNone, kNone};
  }
  // Rounding of the few operations above is far below this margin.
  constexpr double kMargin = 1.0 + 1e-9;
  const double g = kMargin * std::min(1.0, hp / d) * std::min(1.0, hq / d) / (std::numbers::pi * d * d);
  return {q.area * g, p.area * g};
}

}  // namespace hrad
