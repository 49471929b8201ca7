// The exact last word of shaft culling, for occluders that touch the shaft in a way the plane
// tests cannot settle. Exact constructions live in shaft_exact.cpp (slow to compile).
#pragma once

#include <array>
#include <span>

#include "hrad/core/types.h"

namespace hrad::detail {

/// Does the closed triangle `t` meet the interior of the convex polytope
/// {x : orientation(p, q, r, x) >= 0 for every plane (p, q, r) of `planes`}? The polytope must
/// have an interior. Exact: the triangle is clipped to the polytope in rational arithmetic; the
/// clipped convex set P misses the interior iff it lies in one bounding plane (P meets a plane
/// in a face of P, and a union of proper faces never covers P's relative interior).
bool triangle_meets_interior(const std::array<Vec3, 3>& t, std::span<const std::array<Vec3, 3>> planes);

}  // namespace hrad::detail
