// A cheap upper bound of the unobstructed factors of a pair of planar patches, both directions,
// for dropping pairs below a threshold without a closed form or a shaft test.
//
// For x on p and y on q at distance r, cos(theta_x) = n_p.(y - x) / r <= h_p / r, where h_p is
// the most any vertex of q rises above p's plane (q lies in the hull of its vertices), and
// likewise cos(theta_y) <= h_q / r; both are at most 1. With d <= r for every such x, y (the gap
// between the patches' bounding spheres, between their bounding boxes, or the least height of one
// above the other's plane, whichever is largest), the kernel cos cos / (pi r^2) is at most
// g(d) = min(1, h_p / d) min(1, h_q / d) / (pi d^2), so
//   F_pq <= A_q g(d),   F_qp <= A_p g(d)
// (h_p <= 0 or h_q <= 0: the pair faces away, both 0). No bound (infinity) when d <= 0.
// Independent of the unit of length.
#pragma once

#include <array>
#include <vector>

#include "hrad/core/scene.h"

namespace hrad {

/// What the bound needs of one patch, gathered once.
struct PatchBoundShape {
  std::array<Vec3, 4> vertices;
  int count = 0;  ///< vertices used (3 or 4)
  Vec3 normal = Vec3::Zero(), centre = Vec3::Zero(), lo = Vec3::Zero(), hi = Vec3::Zero();
  double offset = 0.0;  ///< normal . (any point of the patch)
  double radius = 0.0;  ///< of a sphere about `centre` holding the patch
  double area = 0.0;
};

struct FactorBound {
  double pq = 0.0, qp = 0.0;  ///< upper bounds of F_pq and F_qp (unobstructed, hence obstructed too)
};

/// The shapes of every patch of `scene` (hrad::Error for a patch of more than 4 vertices).
std::vector<PatchBoundShape> patch_bound_shapes(const Scene& scene);

FactorBound factor_bound(const PatchBoundShape& p, const PatchBoundShape& q);

}  // namespace hrad
