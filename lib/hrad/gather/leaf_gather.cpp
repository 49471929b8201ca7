#include "hrad/gather/leaf_gather.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/core/error.h"
#include "hrad/core/rng.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/gather/from_point.h"
#include "hrad/geometry/polygon.h"
#include "hrad/visibility/occluded_form_factor.h"
#include "hrad/visibility/sampling.h"

namespace hrad {

void validate_leaf_gather_options(const LeafGatherOptions& o) {
  if (!(o.tolerance >= 0.0 && std::isfinite(o.tolerance)))
    throw Error(fmt::format("--gather-tolerance: {} is not a finite number >= 0", o.tolerance));
  if (o.visibility_samples < 1 || o.visibility_samples > 1 << 20)
    throw Error(fmt::format("--visibility-samples: {} is not in [1, 1048576]", o.visibility_samples));
}

struct LeafGather::Pair {
  PairClass cls = PairClass::kFullyVisible;
  std::vector<int> occluders;  ///< sorted; complete for every point of the receiver and part of the source
};

namespace {

// Each point factor is the plain contour sum (point_to_polygon.h, kLambertSumOnly): its error is
// absolute, ~1e-16 times the sum of its terms (each at most pi), so ~1e-15 a leaf, and what a
// gather adds up is absolute too. A relative accuracy would refine the sums that cancel (small
// leaves seen almost edge-on, whose factors of ~1e-9 change nothing) at a cost the gather need
// not pay (final_gather_benchmark, BM_LeafFactors).
constexpr double kFactorTolerance = kLambertSumOnly;

}  // namespace

struct LeafGather::Scratch {
  // One list per depth of the walk, never reallocated (the walk holds pointers to them): a tree is
  // at most detail::kLeafQuadtreeMaxDepth + 1 nodes deep.
  std::vector<std::vector<int>> occluders = std::vector<std::vector<int>>(detail::kLeafQuadtreeMaxDepth + 2);
  std::vector<Vec2> uv;
  // PartialSampling::shared: the partly visible nodes gathered at this point.
  struct Partial {
    int node = -1, patch = -1;
    double factor = 0.0, importance = 0.0;
    std::size_t first_occluder = 0, occluder_count = 0;
  };
  std::vector<Partial> partial;
  std::vector<int> partial_occluders;
  std::vector<double> importance;
  std::vector<int> counts;
  std::vector<int>& occluders_at(std::size_t depth) { return occluders.at(depth); }
};

LeafGather::LeafGather(const Scene& scene, const Solution& solution, const LeafGatherOptions& options)
    : scene_(scene), solution_(solution), options_(options), trees_(scene, solution) {
  validate_leaf_gather_options(options);
  visibility_ = make_visibility(scene);
  occlusion_ = visibility_->scene_has_occlusion();
  Rgb weighted = Rgb::Zero();
  double area = 0.0;
  for (int p = 0; p < static_cast<int>(scene.patches.size()); ++p) {
    const int root = trees_.root(p);
    if (root < 0) continue;
    weighted += trees_.node(root).area * trees_.node(root).mean;
    area += trees_.node(root).area;
  }
  mean_radiosity_ = area > 0.0 ? (weighted / area).maxCoeff() : 0.0;
  for (const Patch& p : scene.patches) {
    patch_normal_.push_back(p.normal);
    plane_tolerance_.push_back(1e-9 * polygon_diameter(p.vertices));
  }
  pairs_.resize(scene.patches.size());
  row_once_ = std::make_unique<std::once_flag[]>(scene.patches.size());
}

LeafGather::~LeafGather() = default;

const LeafGather::Pair& LeafGather::pair(int receiver, int source) const {
  std::call_once(row_once_[static_cast<std::size_t>(receiver)], [&] {
    const Patch& r = scene_.patches[static_cast<std::size_t>(receiver)];
    std::vector<Pair> row(scene_.patches.size());
    for (std::size_t q = 0; q < row.size(); ++q) {
      if (static_cast<int>(q) == receiver) continue;
      row[q].cls = visibility_->classify_among(r.vertices, receiver, scene_.patches[q].vertices, static_cast<int>(q),
                                               nullptr, &row[q].occluders);
    }
    pairs_[static_cast<std::size_t>(receiver)] = std::move(row);
  });
  return pairs_[static_cast<std::size_t>(receiver)][static_cast<std::size_t>(source)];
}

Rgb LeafGather::gather_point(const GatherPoint& p, Scratch& s, GatherWork& w, double* bound) const {
  const Vec3& x = p.position;
  const Vec3& n = p.normal;
  const std::uint64_t seed = detail::point_seed(p, options_.seed);
  const bool sampled = options_.visibility == VisibilityMode::sampled;
  const bool shared = sampled && options_.partial == PartialSampling::shared;
  const double tolerance = options_.tolerance * mean_radiosity_;
  Rgb h = Rgb::Zero();
  s.partial.clear();
  s.partial_occluders.clear();
  ++w.points;

  for (int q = 0; q < static_cast<int>(scene_.patches.size()); ++q) {
    if (q == p.patch) continue;  // a planar patch does not see itself
    const int root = trees_.root(q);
    if (root < 0) continue;
    const Patch& source = scene_.patches[static_cast<std::size_t>(q)];
    // No factor unless x is in front of q's plane and q reaches above x's tangent plane. A point
    // in q's plane up to rounding (on a coplanar neighbour, a hit point computed in floating
    // point) sees q edge-on: its factor is 0 in the limit, and the contour sum, all cancellation,
    // would cost the kernel its most expensive refinement to find ~1e-13.
    if (!(source.normal.dot(x - source.vertices[0]) > plane_tolerance_[static_cast<std::size_t>(q)])) continue;
    bool above = false;
    for (const Vec3& v : source.vertices) above |= n.dot(v - x) > 0.0;
    if (!above) continue;
    ++w.patch_visits;

    PairClass cls = PairClass::kFullyVisible;
    const std::vector<int>* occluders = nullptr;
    if (occlusion_) {
      const Pair* pr = p.patch >= 0 ? &pair(p.patch, q) : nullptr;
      if (pr) {
        cls = pr->cls;
        occluders = &pr->occluders;
      }
      if (is_blocking(cls)) continue;
      // A point in space has no pair: it is always classified (exactly where the shaft settles).
      if (!pr || (sampled && cls == PairClass::kPartial && options_.classify_points)) {
        std::vector<int>& out = s.occluders_at(0);
        cls = visibility_->classify_among(std::span<const Vec3>(&x, 1), p.patch, source.vertices, q, occluders, &out);
        ++w.classifications;
        occluders = &out;
        if (is_blocking(cls)) continue;
      }
    }

    // The walk down q's tree (recursive: depth is the tree's, at most ~40).
    auto walk = [&](auto&& self, int id, PairClass c, const std::vector<int>* occ, std::size_t depth) -> void {
      const std::span<const Vec3> polygon = trees_.polygon(id);
      const detail::LeafQuadtreeNode& node = trees_.node(id);
      // Nothing of it above x's tangent plane: no factor, here or below (x is in front of its plane).
      bool above = false;
      for (const Vec3& v : polygon) above |= n.dot(v - x) > 0.0;
      if (!above) return;
      if (c == PairClass::kPartial && sampled && options_.classify_points && depth > 0) {
        std::vector<int>& out = s.occluders_at(depth);
        c = visibility_->classify_among(std::span<const Vec3>(&x, 1), p.patch, polygon, q, occ, &out);
        ++w.classifications;
        occ = &out;
        if (is_blocking(c)) return;
      }
      double factor = -1.0, node_bound = 0.0;
      bool whole = node.is_leaf();
      if (!whole && node.tiled && tolerance > 0.0) {
        const double deviation = node.mean_deviation.maxCoeff();
        if (deviation == 0.0) {
          whole = true;  // one radiosity over the node: gathering it whole is exact
        } else {
          auto [k_min, k_max] = detail::kernel_bounds(x, n, polygon, source.normal.dot(x - polygon[0]));
          if (c == PairClass::kPartial) k_min = 0.0;
          // The factor is at most A k_max / pi: where even that fails the test, skip evaluating it.
          if ((k_max - k_min) * deviation <= tolerance * k_max) {
            factor = point_to_polygon(x, n, polygon, kFactorTolerance);
            ++w.node_visits;
            node_bound = node.area / std::numbers::pi * (k_max - k_min) * deviation;
            whole = node_bound <= tolerance * factor;
          }
        }
      }
      // Sampled per node, a partly visible node is opened down to its leaves (see the header).
      if (whole && c == PairClass::kPartial && sampled && !shared && !node.is_leaf()) whole = false;
      if (!whole) {
        for (int child : trees_.children(id)) self(self, child, c, occ, depth + 1);
        return;
      }
      if (factor < 0.0) {
        factor = point_to_polygon(x, n, polygon, kFactorTolerance);
        ++w.node_visits;
      }
      if (!(factor > 0.0)) return;
      ++w.nodes_gathered;
      w.leaves_covered += node.leaves;
      if (bound) *bound += node_bound;
      if (c != PairClass::kPartial) {
        h += factor * node.mean;
      } else if (!sampled) {
        ++w.exact_regions;
        h += occluded_point_to_polygon(scene_, x, n, p.patch, polygon, q) * node.mean;
      } else if (!shared) {
        const int k = options_.visibility_samples;
        w.rays += static_cast<std::uint64_t>(k);
        h += factor * node.mean *
             detail::weighted_fraction(*visibility_, x, n, p.patch, polygon, source.normal, q, occ, k,
                                       detail::mix_seed(seed, static_cast<std::uint64_t>(id)), s.uv);
      } else {
        const double importance = factor * node.mean.sum();
        if (!(importance > 0.0)) return;
        Scratch::Partial e{id, q, factor, importance, s.partial_occluders.size(), occ ? occ->size() : 0};
        if (occ) s.partial_occluders.insert(s.partial_occluders.end(), occ->begin(), occ->end());
        s.partial.push_back(e);
      }
    };
    walk(walk, root, cls, occluders, 0);
  }

  if (!s.partial.empty()) {
    // Systematic sampling of m rays over the cumulative importance C (see the header).
    s.importance.clear();
    for (const Scratch::Partial& e : s.partial) s.importance.push_back(e.importance);
    const double per_ray =
        detail::systematic_counts(s.importance, options_.visibility_samples, detail::mix_seed(seed, 0xfeed), &s.counts);
    for (std::size_t i = 0; i < s.partial.size(); ++i) {
      const Scratch::Partial& e = s.partial[i];
      const int count = s.counts[i];
      if (count <= 0) continue;
      const std::span<const Vec3> polygon = trees_.polygon(e.node);
      const detail::LeafQuadtreeNode& node = trees_.node(e.node);
      const Vec3& ny = patch_normal_[static_cast<std::size_t>(e.patch)];
      const detail::PolygonSampler sampler(polygon);
      detail::Rng node_rng(detail::mix_seed(seed, static_cast<std::uint64_t>(e.node)));
      detail::stratified_unit_square(count, node_rng, &s.uv);
      const std::span<const int> occ(s.partial_occluders.data() + e.first_occluder, e.occluder_count);
      double weight = 0.0, visible = 0.0;
      for (const Vec2& u : s.uv) {
        const Vec3 y = sampler.point(u.x(), u.y());
        const double k = detail::point_pair_kernel(n, ny, y - x);
        weight += k;
        if (!visibility_->segment_blocked_among(x, p.patch, y, e.patch, occ)) visible += k;
      }
      w.rays += static_cast<std::uint64_t>(count);
      const double fraction = weight > 0.0 ? visible / weight : 0.0;
      h += per_ray * count * fraction * (node.mean / node.mean.sum());
    }
  }
  return h;
}

std::vector<Rgb> LeafGather::gather_with_bounds(std::span<const GatherPoint> points, std::vector<double>* bounds,
                                                ProgressReporter* progress) const {
  std::vector<Rgb> out(points.size(), Rgb::Zero());
  if (bounds) bounds->assign(points.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      Scratch scratch;
                      GatherWork local;
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        out[i] = gather_point(points[i], scratch, local, bounds ? &(*bounds)[i] : nullptr);
                      {
                        const std::lock_guard<std::mutex> lock(work_mutex_);
                        work_ += local;
                      }
                      if (progress) progress->advance(r.size());
                    });
  return out;
}

std::vector<Rgb> LeafGather::gather(std::span<const GatherPoint> points, ProgressReporter* progress) const {
  return gather_with_bounds(points, nullptr, progress);
}

GatherWork LeafGather::work() const {
  const std::lock_guard<std::mutex> lock(work_mutex_);
  return work_;
}

}  // namespace hrad
