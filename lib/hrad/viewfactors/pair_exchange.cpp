#include "hrad/viewfactors/pair_exchange.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_quadrature.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/viewfactors/point_factors.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/visible_region.h"

namespace hrad {
namespace {

struct Fraction {
  double value = 1.0, error = 0.0;
  int rays = 0, regions = 0;
};

// The posterior standard deviation of a fraction after `visible` of `n` Bernoulli samples under a
// uniform prior, Beta(visible + 1, n - visible + 1) (Laplace's rule of succession). Unlike the
// binomial sqrt(p (1 - p) / n), or the Wilson half-width, it stays near 1 / n when every ray
// agrees, which is what a few rays can say about a pair that is in fact mostly visible.
double posterior_fraction_error(int visible, int n) {
  const double a = visible + 1.0, b = n - visible + 1.0, s = a + b;
  return std::sqrt(a * b / (s * s * (s + 1.0)));
}

// Kernel-weighted visible fraction from `rays` point pairs: sqrt(rays) stratified points on p, as
// many rays from each to stratified points of q (tested against `occluders`, or the whole scene when
// null). Its standard error is the ratio estimator's over
// the points of p (each point's rays are one group), floored by posterior_fraction_error() of the
// ray count, which is not zero when every ray agrees.
Fraction sampled_fraction(const FormFactorEvaluator& ev, const Patch& a, int p, const Patch& b, int q,
                          const std::vector<int>* occluders, int rays, std::uint64_t seed) {
  const int kx = std::max(2, static_cast<int>(std::lround(std::sqrt(double(rays)))));
  const int ky = std::max(1, (rays + kx - 1) / kx);
  detail::Rng rng(detail::mix_seed(seed, 1));
  std::vector<Vec2> ux;
  detail::stratified_unit_square(kx, rng, &ux);
  const detail::PolygonSampler sx(a.vertices);
  std::vector<double> v(ux.size()), w(ux.size());
  double sv = 0.0, sw = 0.0;
  int visible_rays = 0, cast = 0;
  for (std::size_t i = 0; i < ux.size(); ++i) {
    const KernelVisibility k = ev.visibility_from_point(sx.point(ux[i].x(), ux[i].y()), a.normal, p, b.vertices, q,
                                                        occluders, ky, detail::mix_seed(seed, 2 + i));
    v[i] = k.visible;
    w[i] = k.weight;
    sv += k.visible;
    sw += k.weight;
    visible_rays += k.visible_rays;
    cast += k.rays;
  }
  Fraction f;
  f.rays = cast;
  if (!(sw > 0.0)) return f;  // no ray carries weight: the pair exchanges (almost) nothing
  f.value = std::clamp(sv / sw, 0.0, 1.0);
  const double n = static_cast<double>(ux.size()), mean_w = sw / n;
  double s2 = 0.0;
  for (std::size_t i = 0; i < ux.size(); ++i) s2 += (v[i] - f.value * w[i]) * (v[i] - f.value * w[i]);
  const double ratio_se = std::sqrt(s2 / (n * (n - 1.0))) / mean_w;
  f.error = std::max(ratio_se, posterior_fraction_error(visible_rays, cast));
  return f;
}

Fraction region_fraction(const FormFactorEvaluator& ev, const Patch& a, int p, const Patch& b, int q, int order) {
  std::vector<detail::WeightedPoint> points;
  detail::polygon_quadrature(a.vertices, a.normal, order, points);
  double visible = 0.0, total = 0.0;
  Fraction f;
  for (const detail::WeightedPoint& x : points) {
    const double full = point_to_polygon(x.x, a.normal, b.vertices);
    if (!(full > 0.0)) continue;
    const VisibleRegion region = visible_region(ev.scene(), x.x, p, b.vertices, q);
    ++f.regions;
    total += x.weight * full;
    visible += x.weight * std::min(full, point_factor_to_region(x.x, a.normal, region));
  }
  if (total > 0.0) f.value = std::clamp(visible / total, 0.0, 1.0);
  return f;
}

void apply(const Fraction& fraction, PairExchange* r) {
  r->regions = fraction.regions;
  r->exchange = r->unoccluded * fraction.value;
  r->error = r->unoccluded * fraction.error;
}

// Classifies the pair (collecting the occluders a partly visible pair's rays must test) and
// evaluates its closed form.
PairExchange classify(const FormFactorEvaluator& ev, int p, int q, const PairExchangeOptions& options,
                      std::vector<int>* occluders) {
  PairExchange r;
  const Scene& scene = ev.scene();
  const Patch& a = scene.patches[static_cast<std::size_t>(p)];
  const Patch& b = scene.patches[static_cast<std::size_t>(q)];
  occluders->clear();
  if (ev.faces_away(a.vertices, b.vertices)) return r;
  // The closed form to what each class needs (polygon_to_polygon.h: a looser tolerance keeps more
  // contour sums and takes lower Gauss orders for far pairs): a fully visible pair's factor is the
  // answer, to 1e-10 relative; a partly visible pair's is multiplied by a fraction known to ~1e-3
  // at best, so 1e-8 is ample. With a threshold or sample_below, the closed form comes first, at
  // kScreenTolerance: a pair below the threshold both ways is dropped (the factor with its
  // tolerance as the bound), one below sample_below is sampled with it (a fraction from tens of
  // rays); the rest are classified and evaluated again to what their class needs.
  constexpr double kScreenTolerance = 1e-6;
  PairFormFactor f;
  if (options.threshold > 0.0 || options.sample_below > 0.0) {
    f = polygon_to_polygon(a.vertices, b.vertices, kScreenTolerance);
    ++r.closed_forms;
    const double margin = 1.0 + 16.0 * kScreenTolerance;
    if (f.from_to * margin < options.threshold && f.to_from * margin < options.threshold) {
      r.dropped = true;
      r.dropped_pq = f.from_to * margin;
      r.dropped_qp = f.to_from * margin;
      return r;
    }
    if (f.from_to < options.sample_below && f.to_from < options.sample_below) {
      r.pair_class = PairClass::kPartial;
      r.shaft_skipped = true;
      // The smaller of the two directions' exchange areas, lowered by the closed form's
      // tolerance: at most the exact A_p F_pq = A_q F_qp, so neither factor can exceed its
      // unobstructed value whatever fraction the rays find (the relative bias, < 2e-5, is far
      // below a fraction's sampling error).
      r.unoccluded = std::min(a.area * f.from_to, b.area * f.to_from) / margin;
      if (r.unoccluded > 0.0) {
        const Fraction fraction = sampled_fraction(ev, a, p, b, q, nullptr, std::max(kMinSampledRays, options.far_rays),
                                                   ev.pair_seed(a.vertices, p, b.vertices, q));
        r.rays = fraction.rays;
        apply(fraction, &r);
      }
      return r;
    }
  }
  r.pair_class = ev.classify(a.vertices, p, b.vertices, q, nullptr, occluders);
  if (r.pair_class == PairClass::kFacingAway || r.pair_class == PairClass::kFullyHidden) return r;
  f = polygon_to_polygon(
      a.vertices, b.vertices,
      r.pair_class == PairClass::kPartial ? options.partial_closed_form_tolerance : options.closed_form_tolerance);
  ++r.closed_forms;
  // Both directions come from one evaluation; their mean is symmetric in p and q.
  r.unoccluded = 0.5 * (a.area * f.from_to + b.area * f.to_from);
  if (r.pair_class == PairClass::kFullyVisible) r.exchange = r.unoccluded;
  return r;
}

}  // namespace

PairExchange classify_pair(const FormFactorEvaluator& ev, int p, int q, const PairExchangeOptions& options) {
  thread_local std::vector<int> occluders;
  return classify(ev, p, q, options, &occluders);
}

void sample_partial(const FormFactorEvaluator& ev, int p, int q, int rays, PairExchange* r) {
  if (r->pair_class != PairClass::kPartial || !(r->unoccluded > 0.0)) return;
  const Scene& scene = ev.scene();
  const Patch& a = scene.patches[static_cast<std::size_t>(p)];
  const Patch& b = scene.patches[static_cast<std::size_t>(q)];
  thread_local std::vector<int> occluders;
  occluders.clear();
  ev.classify(a.vertices, p, b.vertices, q, nullptr, &occluders);
  const std::uint64_t seed = ev.pair_seed(a.vertices, p, b.vertices, q);
  rays = std::max(kMinSampledRays, rays);
  const Fraction fraction =
      sampled_fraction(ev, a, p, b, q, &occluders, rays, detail::mix_seed(seed, static_cast<std::uint64_t>(rays)));
  r->rays += fraction.rays;
  apply(fraction, r);
}

PairExchange pair_exchange(const FormFactorEvaluator& ev, int p, int q, const PairExchangeOptions& options) {
  thread_local std::vector<int> occluders;
  PairExchange r = classify(ev, p, q, options, &occluders);
  if (r.pair_class != PairClass::kPartial || !(r.unoccluded > 0.0) || r.shaft_skipped) return r;
  const Scene& scene = ev.scene();
  const Patch& a = scene.patches[static_cast<std::size_t>(p)];
  const Patch& b = scene.patches[static_cast<std::size_t>(q)];
  Fraction fraction;
  if (options.partial == PartialVisibility::kExactRegion) {
    fraction = region_fraction(ev, a, p, b, q, options.region_order);
  } else {
    const std::uint64_t seed = ev.pair_seed(a.vertices, p, b.vertices, q);
    for (int rays = std::max(kMinSampledRays, options.min_rays);; rays *= 4) {
      fraction = sampled_fraction(ev, a, p, b, q, &occluders, std::min(rays, options.max_rays),
                                  detail::mix_seed(seed, static_cast<std::uint64_t>(rays)));
      r.rays += fraction.rays;
      if (fraction.error <= options.fraction_error || rays >= options.max_rays) break;
    }
  }
  apply(fraction, &r);
  return r;
}

}  // namespace hrad
