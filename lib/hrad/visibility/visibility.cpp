// The parts of the visibility interface that need no CGAL: the default from-point estimate.
#include "hrad/visibility/visibility.h"

#include "hrad/visibility/sampling.h"

namespace hrad {

VisibilityEstimate Visibility::estimate_from_point(const Vec3& x, int patch_x, std::span<const Vec3> b, int patch_b,
                                                   int samples, std::uint64_t seed) const {
  counters_.point_queries.add();
  VisibilityEstimate e;
  detail::Rng rng(seed);
  std::vector<Vec2> uv;
  detail::stratified_unit_square(samples, rng, &uv);
  const detail::PolygonSampler sampler(b);
  int visible = 0;
  for (const Vec2& s : uv) visible += segment_blocked(x, patch_x, sampler.point(s.x(), s.y()), patch_b) ? 0 : 1;
  e.fraction = samples > 0 ? double(visible) / samples : 1.0;
  e.error = detail::fraction_error(visible, samples);
  e.pair_class = PairClass::kPartial;
  return e;
}

}  // namespace hrad
