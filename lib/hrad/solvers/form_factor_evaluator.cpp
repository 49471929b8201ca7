#include "hrad/solvers/form_factor_evaluator.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "hrad/formfactor/clip_polygon.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/point_to_polygon_limit.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/geometry/polygon.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/solid_angle_sampler.h"
#include "hrad/visibility/visibility.h"

#include <tbb/parallel_for.h>

namespace hrad {
namespace {

// True when every vertex of `b` lies on or behind the plane of `a` (front = Newell normal): the
// factor between them is then exactly 0 (only fronts emit and receive).
bool behind(std::span<const Vec3> a, std::span<const Vec3> b) {
  const Vec3 n = newell_normal(a);
  for (const Vec3& v : b)
    if ((v - a[0]).dot(n) > 0.0) return false;
  return true;
}

// The part of the convex polygon `poly` in front of the plane of `other` (Sutherland-Hodgman).
void front_part(std::span<const Vec3> poly, std::span<const Vec3> other, std::vector<Vec3>& out) {
  const Vec3 n = newell_normal(other);
  thread_local std::vector<double> height;
  height.clear();
  for (const Vec3& v : poly) height.push_back((v - other[0]).dot(n));
  detail::clip_to_half_space(poly, height, out);
}

}  // namespace

bool FormFactorEvaluator::separated(std::span<const Vec3> receiver, std::span<const Vec3> source, double ratio) {
  const auto [rc, rr] = vertex_sphere(receiver);
  const auto [sc, sr] = vertex_sphere(source);
  const double gap = (rc - sc).norm() - rr - sr;
  return gap > 0.0 && 2.0 * rr <= ratio * gap;
}

FormFactorEvaluator::FormFactorEvaluator(const Scene& scene, const Effects& effects, const Visibility* visibility,
                                         int visibility_samples, FormFactorKernel kernel, std::uint64_t seed)
    : scene_(scene),
      effects_(effects),
      visibility_(visibility),
      visibility_samples_(visibility_samples),
      kernel_(kernel),
      seed_(seed) {
  assert(visibility_ != nullptr || !effects_.visibility);
  assert(visibility_samples_ > 0);
}

FormFactorEstimate FormFactorEvaluator::estimate(std::span<const Vec3> receiver, int receiver_patch,
                                                 std::span<const Vec3> source, int source_patch,
                                                 bool with_reverse) const {
  FormFactorEstimate e;
  // Two elements of one planar patch never exchange light.
  if (receiver_patch == source_patch) return e;
  if (faces_away(receiver, source)) {
    e.facing_away = true;
    return e;
  }
  if (effects_.visibility) {
    // Classify first: a fully hidden pair needs no kernel call, a fully visible one no samples.
    const PairClass c = classify(receiver, receiver_patch, source, source_patch, nullptr, nullptr);
    if (c == PairClass::kFacingAway) {
      e.facing_away = true;
      e.visibility = 0.0;
      return e;
    }
    if (c == PairClass::kFullyHidden) {
      e.visibility = 0.0;
      return e;
    }
    if (c == PairClass::kPartial) {
      const PairVisibility v = pair_visibility(receiver, receiver_patch, source, source_patch);
      e.partial = true;
      e.visibility = v.fraction;
      e.error = v.error;
    }
    const PairFormFactor f = unoccluded(receiver, receiver_patch, source, source_patch, with_reverse);
    e.unoccluded = f.from_to;
    e.value = f.from_to * e.visibility;
    e.reverse = f.to_from * e.visibility;
    e.error *= f.from_to;
    return e;
  }
  const PairFormFactor f = unoccluded(receiver, receiver_patch, source, source_patch, with_reverse);
  e.unoccluded = e.value = f.from_to;
  e.reverse = f.to_from;
  return e;
}

PairVisibility FormFactorEvaluator::pair_visibility(std::span<const Vec3> receiver, int receiver_patch,
                                                    std::span<const Vec3> source, int source_patch,
                                                    const std::vector<int>* occluders, int samples,
                                                    std::uint64_t stream, bool halves,
                                                    std::vector<VisibilityPair>* pairs) const {
  if (pairs != nullptr) pairs->clear();
  // Ray-traced form factors (Wallace, Elmquist & Haines 1989): the visible fraction weighted by the
  // point-to-point kernel, so that the near parts of a pair count as much as they contribute to F.
  // The kernel is symmetric, so the fraction is the same in both directions and reciprocity is kept.
  // n point pairs with one ray each, stratified on both polygons and paired in random order (as
  // sampled() pairs them), rather than a few receiver points with many rays each: where a shadow
  // boundary crosses the receiver, what varies most is which receiver points see the source, and n
  // receiver points halve the spread of the estimate that sqrt(n) points leave (the generated
  // offices' power balance, from independent samples of every link: spread 2.4e-3 -> 8e-4 at 1k
  // polygons).
  const std::uint64_t pair = pair_seed(receiver, receiver_patch, source, source_patch);
  const std::uint64_t seed = stream == 0 ? pair : detail::mix_seed(pair, stream);
  const int n = samples > 0 ? samples : visibility_samples_;
  // Points only on the parts of each polygon in front of the other's plane: elsewhere no ray
  // carries weight.
  thread_local std::vector<Vec3> facing_receiver, facing_source;
  front_part(receiver, source, facing_receiver);
  front_part(source, receiver, facing_source);
  PairVisibility v;
  if (facing_receiver.size() < 3 || facing_source.size() < 3) {
    v.error = detail::fraction_error(0, 0);
    return v;
  }
  const detail::PolygonSampler sx(facing_receiver), sy(facing_source);
  const Vec3 nx = newell_normal(receiver).normalized();
  const Vec3& ny = scene_.patches[static_cast<std::size_t>(source_patch)].normal;
  thread_local std::vector<Vec2> ux, uy, second;
  detail::Rng rx(detail::mix_seed(seed, 1)), ry(detail::mix_seed(seed, 2));
  // stratified_unit_square() returns its cells in random order: ux[i] and uy[i] are a random pairing.
  const int first = halves && n >= 2 ? n / 2 : n;
  detail::stratified_unit_square(first, rx, &ux);
  detail::stratified_unit_square(first, ry, &uy);
  if (first < n) {
    // The second half from streams of its own: independent of the first.
    detail::Rng rx2(detail::mix_seed(seed, 3)), ry2(detail::mix_seed(seed, 4));
    detail::stratified_unit_square(n - first, rx2, &second);
    ux.insert(ux.end(), second.begin(), second.end());
    detail::stratified_unit_square(n - first, ry2, &second);
    uy.insert(uy.end(), second.begin(), second.end());
  }
  // Polygons closer than their size (a shelf board 5 mm from its upright, a lamp at a wall): the
  // kernel peaks where they come close, area-uniform pairs seldom land there, and the ratio of
  // sums then mostly weighs the far parts: biased, and to one side where the near parts see each
  // other and the far ones are shaded (a generated warehouse loses 0.4% of its power so, at any
  // sample count up to 1024). There each receiver point's source point follows the solid angle
  // (Arvo 1995): weight Omega(x) cos(theta_x) <= 2 pi, the kernel's integral over the source.
  const bool near = !separated(receiver, source, 1.0);
  double visible = 0.0, weight = 0.0;
  v.halves[0].pairs = first;
  v.halves[1].pairs = n - first;
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    const Vec3 x = sx.point(ux[k].x(), ux[k].y());
    Vec3 y;
    double w = 0.0;
    if (near) {
      const detail::SolidAngleSampler towards(x, facing_source);
      Vec3 direction;
      if (!towards.sample(uy[k].x(), uy[k].y(), &direction, &y)) continue;
      w = towards.solid_angle() * std::max(0.0, nx.dot(direction));
    } else {
      y = sy.point(uy[k].x(), uy[k].y());
    }
    // Facing and occlusion decided exactly on the points of the patches that x and y stand for
    // (Visibility::sight()), as in visibility_from_point().
    const Sight sight = occluders != nullptr ? visibility_->sight_among(x, receiver_patch, y, source_patch, *occluders)
                                             : visibility_->sight(x, receiver_patch, y, source_patch);
    if (sight == Sight::kFacingAway) continue;
    if (!near) w = detail::point_pair_kernel(nx, ny, y - x);
    ++v.rays;
    weight += w;
    PairVisibility::Half& half = v.halves[i < first ? 0 : 1];
    half.weight += w;
    if (sight == Sight::kVisible) ++v.visible_rays, visible += w, half.visible += w;
    if (pairs != nullptr) pairs->push_back({x, y, w, sight == Sight::kVisible});
  }
  v.error = detail::fraction_error(v.visible_rays, v.rays);
  // E[w]: near pairs take x uniform on the front part A'x and w integrates the kernel over the
  // source, so E[w] = pi A F / A'x; far pairs take both points uniform, E[w] = pi A F / (A'x A'y).
  v.mean_weight_per_exchange =
      std::numbers::pi / (polygon_area(facing_receiver) * (near ? 1.0 : polygon_area(facing_source)));
  // No ray passed, or none carried weight: nothing is known to be seen. (A fraction over rays that
  // carry no weight is no estimate: it gave closed boxes their light.)
  if (v.visible_rays > 0 && visible > 0.0) v.fraction = visible / weight;
  return v;
}

KernelVisibility FormFactorEvaluator::visibility_from_point(const Vec3& x, const Vec3& nx, int patch_x,
                                                            std::span<const Vec3> source, int source_patch,
                                                            const std::vector<int>* occluders, int rays,
                                                            std::uint64_t seed) const {
  KernelVisibility k;
  if (rays <= 0) return k;
  detail::Rng rng(seed);
  thread_local std::vector<Vec2> uv;
  detail::stratified_unit_square(rays, rng, &uv);
  // Rays only to the part of the source in front of x's tangent plane, where they carry weight.
  thread_local std::vector<Vec3> facing;
  thread_local std::vector<double> height;
  height.clear();
  for (const Vec3& v : source) height.push_back((v - x).dot(nx));
  detail::clip_to_half_space(source, height, facing);
  if (facing.size() < 3) return k;
  // The refinement oracle asks one ray per point: then building the sampler costs more than the ray.
  std::optional<detail::PolygonSampler> sampler;
  if (uv.size() > 2) sampler.emplace(facing);
  const Vec3 ny = scene_.patches[static_cast<std::size_t>(source_patch)].normal;
  for (const Vec2& s : uv) {
    const Vec3 y = sampler ? sampler->point(s.x(), s.y()) : detail::polygon_point(facing, s.x(), s.y());
    // Facing and occlusion decided exactly on the points of the patches that x and y stand for
    // (Visibility::sight()): a pair whose rounded doubles merely seem to face each other is not
    // a ray, and no ray passes through a closed surface.
    const Sight sight = occluders != nullptr ? visibility_->sight_among(x, patch_x, y, source_patch, *occluders)
                                             : visibility_->sight(x, patch_x, y, source_patch);
    if (sight == Sight::kFacingAway) continue;
    const double w = detail::point_pair_kernel(nx, ny, y - x);
    ++k.rays;
    k.weight += w;
    if (sight == Sight::kVisible) {
      ++k.visible_rays;
      k.visible += w;
    }
  }
  return k;
}

bool FormFactorEvaluator::faces_away(std::span<const Vec3> a, std::span<const Vec3> b) const {
  if (!effects_.cull_facing_away || !(behind(a, b) || behind(b, a))) return false;
  culled_.add();
  return true;
}

double FormFactorEvaluator::point_factor(const Vec3& x, const Vec3& n, std::span<const Vec3> source) const {
  point_factors_.add();
  return point_to_polygon(x, n, source, kLambertSumOnly);
}

double FormFactorEvaluator::point_factor(const Vec3& x, const Vec3& n, const Vec3& inward,
                                         std::span<const Vec3> source) const {
  point_factors_.add();
  return point_to_polygon_limit(x, n, inward, source, kLambertSumOnly);
}

PairFormFactor FormFactorEvaluator::gauss(std::span<const Vec3> receiver, std::span<const Vec3> source) const {
  evaluations_.add();
  int points_r = 0, points_s = 0;
  const double f_rs = receiver_gauss_factor(receiver, source, kLambertSumOnly, &points_r);
  const double f_sr = receiver_gauss_factor(source, receiver, kLambertSumOnly, &points_s);
  point_factors_.add(static_cast<std::uint64_t>(points_r + points_s));
  const double exchange = 0.5 * (polygon_area(receiver) * f_rs + polygon_area(source) * f_sr);
  return {exchange / polygon_area(receiver), exchange / polygon_area(source)};
}

PairFormFactor FormFactorEvaluator::analytic(std::span<const Vec3> receiver, std::span<const Vec3> source,
                                             double rel_tol, double abs_tol) const {
  evaluations_.add();
  return polygon_to_polygon(receiver, source, rel_tol, abs_tol);
}

double FormFactorEvaluator::receiver_factor(std::span<const Vec3> receiver, std::span<const Vec3> source,
                                            double centroid_ratio) const {
  // Within a receiver's size of the source a fixed Gauss rule cannot follow the factor's rise
  // towards it (~1e-3 off next to a shared edge): the closed form there.
  if (!separated(receiver, source, 1.0)) return analytic(receiver, source).from_to;
  int points = 0;
  const double f = receiver_factor_by_distance(receiver, source, centroid_ratio, &points);
  point_factors_.add(static_cast<std::uint64_t>(points));
  return f;
}

PairClass FormFactorEvaluator::classify(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                                        const std::vector<int>* candidates, std::vector<int>* occluders) const {
  if (!effects_.visibility) return PairClass::kFullyVisible;
  shaft_queries_.add();
  return visibility_->classify_among(a, patch_a, b, patch_b, candidates, occluders);
}

FormFactorEstimate FormFactorEvaluator::sampled(const SurfaceSampler& p, const SurfaceSampler& q, int samples,
                                                std::uint64_t seed, std::vector<int>* seen_p,
                                                std::vector<int>* seen_q) const {
  evaluations_.add();
  FormFactorEstimate e;
  const int n = std::max(1, samples);
  detail::Rng rng(seed);
  // Stratified on both sides: the i-th pair takes the i-th stratum of each side, the strata of q
  // permuted so that the pairs do not line up.
  thread_local std::vector<int> order;
  order.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
  for (int i = n - 1; i > 0; --i)
    std::swap(order[static_cast<std::size_t>(i)], order[rng.below(static_cast<std::uint64_t>(i + 1))]);
  double sum = 0.0, sum2 = 0.0, weight = 0.0, visible_weight = 0.0;
  int visible = 0, counted = 0;
  for (int i = 0; i < n; ++i) {
    Vec3 x, y;
    const int px = p.sample((i + rng.uniform()) / n, rng.uniform(), rng.uniform(), &x);
    const int py = q.sample((order[static_cast<std::size_t>(i)] + rng.uniform()) / n, rng.uniform(), rng.uniform(), &y);
    double k = 0.0;
    if (px != py) {
      const Vec3& nx = scene_.patches[static_cast<std::size_t>(px)].normal;
      const Vec3& ny = scene_.patches[static_cast<std::size_t>(py)].normal;
      k = detail::point_pair_kernel(nx, ny, y - x) / std::numbers::pi;
    }
    // With visibility, facing and occlusion are decided exactly (Visibility::sight()).
    const Sight sight = k > 0.0 && effects_.visibility && px != py ? visibility_->sight(x, px, y, py) : Sight::kVisible;
    if (sight == Sight::kFacingAway) k = 0.0;
    double kv = k;
    if (k > 0.0) {
      ++counted;
      weight += k;
      if (sight == Sight::kBlocked)
        kv = 0.0;
      else {
        ++visible, visible_weight += k;
        if (seen_p != nullptr) seen_p->push_back(px);
        if (seen_q != nullptr) seen_q->push_back(py);
      }
    }
    sum += kv;
    sum2 += kv * kv;
  }
  const double mean = sum / n;
  const double variance = std::max(0.0, sum2 / n - mean * mean);
  const double exchange = p.area() * q.area() * mean;  // A_p F(p -> q)
  e.value = exchange / p.area();
  e.reverse = exchange / q.area();
  e.unoccluded = weight > 0.0 ? p.area() * q.area() * (weight / n) / p.area() : 0.0;
  e.visibility = weight > 0.0 ? visible_weight / weight : 0.0;
  e.partial = counted > 0 && visible < counted && visible > 0;
  e.error = q.area() * std::sqrt(variance / n);
  e.facing_away = counted == 0;
  return e;
}

ShadedPatches FormFactorEvaluator::shaded_surfaces(const SurfaceSampler& from, const SurfaceSampler& to, int rays,
                                                   std::uint64_t seed, std::vector<int>* reached) const {
  ShadedPatches shaded;
  detail::Rng rng(seed);
  for (int k = 0; k < from.patch_count(); ++k) {
    Vec3 x, y;
    int px = from.sample_patch(k, 0.5, 0.5, &x);
    const Vec3& nx = scene_.patches[static_cast<std::size_t>(px)].normal;
    double weight = 0.0, seen = 0.0;
    for (int r = 0; r < rays; ++r) {
      px = from.sample_patch(k, rng.uniform(), rng.uniform(), &x);
      // Stratified over `to`'s area: each ray its own share of the other end's patches.
      const int py = to.sample((r + rng.uniform()) / rays, rng.uniform(), rng.uniform(), &y);
      if (px == py) continue;
      const Vec3& ny = scene_.patches[static_cast<std::size_t>(py)].normal;
      const double kernel = detail::point_pair_kernel(nx, ny, y - x);
      if (!(kernel > 0.0)) continue;
      weight += kernel;
      if (!effects_.visibility || visibility_->sight(x, px, y, py) == Sight::kVisible) {
        seen += kernel;
        if (reached != nullptr) reached->push_back(py);
      }
    }
    shaded.push_back({px, weight > 0.0 ? static_cast<float>(seen / weight) : 0.0f,
                      static_cast<float>(to.area() * seen / (std::numbers::pi * rays))});
  }
  std::sort(shaded.begin(), shaded.end());
  return shaded;
}

std::uint64_t FormFactorEvaluator::pair_seed(std::span<const Vec3> a, int pa, std::span<const Vec3> b, int pb) const {
  // splitmix-style mixing of the vertices relative to their patch's first vertex and diameter,
  // quantized, so that a scaled scene draws the same samples, in any thread and any order.
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(pa) << 32) ^ static_cast<std::uint32_t>(pb);
  auto mix = [&h](std::uint64_t x) {
    h ^= x + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    h ^= h >> 31;
  };
  auto add = [&](std::span<const Vec3> poly, int patch) {
    const Patch& p = scene_.patches[static_cast<std::size_t>(patch)];
    const double size = polygon_diameter(p.vertices);
    for (const Vec3& v : poly)
      for (int k = 0; k < 3; ++k)
        mix(static_cast<std::uint64_t>(std::llround((v[k] - p.vertices[0][k]) / size * 0x1p30)));
  };
  add(a, pa);
  add(b, pb);
  return stream_seed(h);
}

std::uint64_t FormFactorEvaluator::stream_seed(std::uint64_t seed) const {
  return seed_ == 0 ? seed : detail::mix_seed(seed, seed_);
}

Work FormFactorEvaluator::work() const {
  Work w;
  w.point_factor_evaluations = point_factors_.load();
  w.form_factor_evaluations = evaluations_.load();
  w.shaft_queries = shaft_queries_.load();
  if (visibility_ != nullptr) w.segment_queries = visibility_->counters().segment_queries.load();
  return w;
}

void FormFactorEvaluator::set_sources(std::span<const std::span<const Vec3>> polygons, std::span<const int> patches) {
  if (floating_built_.load(std::memory_order_acquire))
    throw std::logic_error("FormFactorEvaluator::set_sources after the first factor: the receivers' points are fixed");
  sources_by_patch_.assign(scene_.patches.size(), {});
  for (std::size_t k = 0; k < polygons.size(); ++k)
    sources_by_patch_[static_cast<std::size_t>(patches[k])].emplace_back(polygons[k].begin(), polygons[k].end());
}

const std::vector<NearEdge>& FormFactorEvaluator::floating_edges(int patch) const {
  std::call_once(floating_once_, [this] {
    const std::size_t n = scene_.patches.size();
    if (sources_by_patch_.size() != n) {  // no mesh given: the patches themselves
      sources_by_patch_.assign(n, {});
      for (std::size_t i = 0; i < n; ++i) sources_by_patch_[i].push_back(scene_.patches[i].vertices);
    }
    // A cell is never larger than the largest polygon on its patch.
    std::vector<std::pair<Vec3, double>> spheres(n);
    std::vector<double> largest(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      spheres[i] = vertex_sphere(scene_.patches[i].vertices);
      for (const auto& poly : sources_by_patch_[i]) largest[i] = std::max(largest[i], vertex_sphere(poly).second);
    }
    floating_edges_.assign(n, {});
    // Patch Q floats in front of patch P when every vertex of Q lies strictly in front of P's plane
    // and P is not wholly behind Q's (they can exchange light). A cell on P lies within P's bounding
    // sphere and is cut only by an edge through its own: an edge higher over P's plane than P's
    // largest polygon, or farther from P's centre than 3 of P's radii, never cuts one.
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      const Patch& p = scene_.patches[i];
      const auto [cp, rp] = spheres[i];
      const double contact = kContactTolerance * 2.0 * rp;
      auto height = [&](const Vec3& v) { return (v - p.vertices[0]).dot(p.normal); };
      for (std::size_t j = 0; j < n; ++j) {
        const auto [cq, rq] = spheres[j];
        if (j == i || (cp - cq).norm() - rq > 3.0 * rp) continue;
        const Patch& q = scene_.patches[j];
        bool floats = true, sees = false, front = true, above = false;
        for (const Vec3& v : q.vertices) {
          floats = floats && height(v) > contact;
          front = front && height(v) > -contact;
          above = above || height(v) > contact;
        }
        for (const Vec3& v : p.vertices) sees = sees || (v - q.vertices[0]).dot(q.normal) > contact;
        if (!sees) continue;
        if (!floats) {
          // An emitter standing on P's plane (a corridor's end wall beside its side walls): the
          // edges its elements have in that plane, graded to kCreaseDepth.
          if (!front || !above || !(scene_.material_of(q).emission.maxCoeff() > 0.0)) continue;
          for (const auto& poly : sources_by_patch_[j])
            for (std::size_t k = 0; k < poly.size(); ++k) {
              const NearEdge e{poly[k], poly[(k + 1) % poly.size()], kCreaseDepth};
              if (std::abs(height(e.a)) <= contact && std::abs(height(e.b)) <= contact && e.distance(cp) < 3.0 * rp)
                floating_edges_[i].push_back(e);
            }
          continue;
        }
        for (const auto& poly : sources_by_patch_[j])
          for (std::size_t k = 0; k < poly.size(); ++k) {
            const NearEdge e{poly[k], poly[(k + 1) % poly.size()]};
            if (std::min(height(e.a), height(e.b)) < largest[i] && e.distance(cp) < 3.0 * rp)
              floating_edges_[i].push_back(e);
          }
      }
    });
    floating_built_.store(true, std::memory_order_release);
  });
  return floating_edges_[static_cast<std::size_t>(patch)];
}

double FormFactorEvaluator::contour_factor(std::span<const Vec3> receiver, int receiver_patch,
                                           std::span<const Vec3> source, int* points) const {
  // The floating edges near enough to this receiver to cut one of its cells (a cell lies within the
  // receiver, is no larger, and is cut only by an edge through its own sphere).
  thread_local std::vector<NearEdge> near;
  near.clear();
  if (const std::vector<NearEdge>& floating = floating_edges(receiver_patch); !floating.empty()) {
    const auto [c, r] = vertex_sphere(receiver);
    for (const NearEdge& e : floating)
      if (e.distance(c) < 3.0 * r) near.push_back(e);
  }
  return receiver_gauss_factor(receiver, source, near, kLambertSumOnly, points);
}

PairFormFactor FormFactorEvaluator::unoccluded(std::span<const Vec3> receiver, int receiver_patch,
                                               std::span<const Vec3> source, int source_patch,
                                               bool with_reverse) const {
  if (kernel_ == FormFactorKernel::kAnalytic) return analytic(receiver, source);
  evaluations_.add();
  int points_r = 0, points_s = 0;
  const PairFormFactor f{contour_factor(receiver, receiver_patch, source, &points_r),
                         with_reverse ? contour_factor(source, source_patch, receiver, &points_s) : 0.0};
  point_factors_.add(static_cast<std::uint64_t>(points_r + points_s));
  return f;
}

}  // namespace hrad
