// Deterministic stratified sampling of convex planar polygons, shared by the visibility
// estimators. No CGAL here.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "hrad/core/rng.h"
#include "hrad/core/types.h"

namespace hrad::detail {

/// Maps the unit square onto a convex planar polygon, uniformly by area: u picks a triangle of
/// the fan from vertex 0 (by area) and both coordinates are remapped into it with the
/// square-root warp (Turk 1990, "Generating random points in triangles"). Points are formed as
/// v0 + s (vi - v0) + t (vi+1 - v0), so a coordinate that is constant over the polygon (an
/// axis-aligned wall) is reproduced exactly. A triangle's or a quad's data is held in the sampler
/// itself: an array of samplers (ClusterTree) then reads one place per point, and building one
/// allocates nothing.
class PolygonSampler {
 public:
  explicit PolygonSampler(std::span<const Vec3> polygon);
  Vec3 point(double u, double v) const;
  double area() const { return area_; }

 private:
  boost::container::small_vector<Vec3, 4> vertices_;
  boost::container::small_vector<double, 2> cdf_;  ///< cumulative fan-triangle area, normalised to end at 1
  double area_ = 0.0;
};

/// PolygonSampler(polygon).point(u, v), the same bits, without building the sampler: for one point
/// per polygon (a cluster's surfaces sampled by area), where the sampler's two allocations cost
/// more than the point.
Vec3 polygon_point(std::span<const Vec3> polygon, double u, double v);

/// `n` points in [0, 1)^2, stratified: n distinct cells of a ceil(sqrt n)^2 grid chosen at random,
/// one uniform point in each. Every point is uniform on the square, so estimates stay unbiased.
void stratified_unit_square(int n, Rng& rng, std::vector<Vec2>* out);

/// Error estimate of a visible fraction k/n from n stratified Bernoulli samples: the half-width of
/// the Wilson score interval at one standard deviation (Wilson 1927). Unlike sqrt(p(1-p)/n) it is
/// not zero when all samples agree (about 1/(2n) then), so a refinement oracle still sees doubt.
double fraction_error(int visible, int n);

/// Deterministic seed for one sampled query from the caller's seed and a stream index.
/// The point-to-point form-factor kernel without its 1/pi, cos(theta_x) cos(theta_y) / r^2 =
/// (n_x . d)(-n_y . d) / r^4 for d = y - x and unit normals, 0 when either point is behind the
/// other: the weight of kernel-weighted visibility (Wallace, Elmquist & Haines 1989).
inline double point_pair_kernel(const Vec3& nx, const Vec3& ny, const Vec3& d) {
  const double r2 = d.squaredNorm();
  return r2 > 0.0 ? std::max(0.0, nx.dot(d)) * std::max(0.0, -ny.dot(d)) / (r2 * r2) : 0.0;
}

inline std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  Rng r(seed ^ (stream * 0xd1b54a32d192ed03ULL));
  return r.next();
}

}  // namespace hrad::detail
