#include "hrad/reference/area_sampler.h"

#include <algorithm>
#include <cmath>

#include "hrad/geometry/patch_plane.h"

namespace hrad::detail {

AreaSampler::AreaSampler(const Scene& scene, std::span<const int> patches, std::span<const double> weight_per_area)
    : weight_per_area_(weight_per_area.begin(), weight_per_area.end()) {
  normal_.resize(scene.patches.size(), Vec3::Zero());
  offset_.resize(scene.patches.size(), 0.0);
  for (int pi : patches) {
    const auto p = static_cast<std::size_t>(pi);
    const double w = weight_per_area_[p];
    if (!(w > 0.0)) continue;
    const std::vector<Vec3>& v = scene.patches[p].vertices;
    normal_[p] = scene.patches[p].normal;
    offset_[p] = plane_offset(scene.patches[p]);
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      const Vec3 ab = v[k] - v[0], ac = v[k + 1] - v[0];
      const double area = ab.cross(ac).norm() / 2;
      if (!(area > 0.0)) continue;
      triangles_.push_back({v[0], ab, ac, pi});
      total_ += w * area;
      cdf_.push_back(total_);
    }
  }
}

SurfacePoint AreaSampler::sample(double u, double v) const {
  const double target = u * total_;
  const std::size_t i = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin()), cdf_.size() - 1);
  const double below = i == 0 ? 0.0 : cdf_[i - 1];
  const double stretched = std::clamp((target - below) / (cdf_[i] - below), 0.0, 1.0);
  const double r = std::sqrt(stretched);
  const Triangle& t = triangles_[i];
  Vec3 x = t.a + (r * (1.0 - v)) * t.ab + (r * v) * t.ac;
  // The fan of a patch planar to 1e-7 of its size (io/obj_reader.h) may leave its plane by as
  // much; the ray caster's planes are the patches' (embree_scene.h), so the point goes there.
  const auto p = static_cast<std::size_t>(t.patch);
  x -= normal_[p] * (normal_[p].dot(x) - offset_[p]);
  return {x, t.patch};
}

}  // namespace hrad::detail
