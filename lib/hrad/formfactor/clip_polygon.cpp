#include "hrad/formfactor/clip_polygon.h"

namespace hrad::detail {

void clip_to_half_space(std::span<const Vec3> p, std::span<const double> d, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t k = p.size();
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t j = (i + 1) % k;
    if (d[i] >= 0.0) out.push_back(p[i]);
    if ((d[i] > 0.0 && d[j] < 0.0) || (d[i] < 0.0 && d[j] > 0.0)) {
      // Interpolate from the vertex nearer the plane, so the new point is as accurate as it can be.
      const double t = d[i] / (d[i] - d[j]);
      out.push_back(t <= 0.5 ? Vec3(p[i] + t * (p[j] - p[i])) : Vec3(p[j] + (1.0 - t) * (p[i] - p[j])));
    }
  }
}

}  // namespace hrad::detail
