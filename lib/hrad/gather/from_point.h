// What the final gathers (leaf_gather.h, link_gather.h) compute from one point: its random stream,
// bounds of the point-to-area kernel over a polygon (for grouping a source's leaves), and the
// kernel-weighted visible fraction of a polygon.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "hrad/core/types.h"
#include "hrad/gather/final_gather.h"
#include "hrad/visibility/visibility.h"

namespace hrad::detail {

/// A point's random stream: its coordinates and normal, hashed with `seed`, so that a point gets
/// the same samples in any batch, order and thread count.
std::uint64_t point_seed(const GatherPoint& p, std::uint64_t seed);

/// Bounds k_min <= k(y) <= k_max of the point-to-area kernel k(y) = (n . d)+ h / |d|^4, d = y - x,
/// over a planar convex polygon at height h > 0 above x along the polygon's normal (so -n_y . d =
/// h for every y): (n . d)+ is linear in y, extreme at the vertices; |d| lies between a lower
/// bound on the distance to the polygon (the larger of h and the distance to the vertices'
/// bounding sphere) and the largest vertex distance.
std::pair<double, double> kernel_bounds(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon, double h);

/// The kernel-weighted visible fraction of `polygon` (on patch `patch_y`, normal `ny`) from x (on
/// patch `patch_x`, normal `nx`) over `samples` stratified points (Wallace, Elmquist & Haines 1989):
/// F(x -> polygon) times it estimates the occluded factor. Only `occluders` can block when given
/// (a classification's list); `uv` is scratch.
double weighted_fraction(const Visibility& visibility, const Vec3& x, const Vec3& nx, int patch_x,
                         std::span<const Vec3> polygon, const Vec3& ny, int patch_y, const std::vector<int>* occluders,
                         int samples, std::uint64_t seed, std::vector<Vec2>& uv);

/// Systematic sampling of `m` rays over entries of importance w_i >= 0 (W their sum): with an offset
/// u uniform in [0, 1) drawn from `seed`, entry i gets ceil(S_i m / W - u) - ceil(S_{i-1} m / W - u)
/// rays (S_i the partial sums), the integer part of its expected count m w_i / W or one more, the
/// counts summing to m (Madow 1949). Returns W / m, what one ray stands for; W = 0: every count 0.
double systematic_counts(std::span<const double> importance, int m, std::uint64_t seed, std::vector<int>* counts);

}  // namespace hrad::detail
