#include "hrad/solvers/cluster_transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "hrad/geometry/polygon.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

ClusterTransfer::ClusterTransfer(const Scene& scene, const ElementHierarchy& hierarchy, const ClusterTree& tree,
                                 const Visibility* visibility, bool use_visibility, int visibility_samples)
    : scene_(scene),
      h_(hierarchy),
      tree_(tree),
      visibility_(visibility),
      use_visibility_(use_visibility && visibility != nullptr),
      samples_(std::max(1, visibility_samples)) {}

NodeShape ClusterTransfer::shape(NodeRef r) const {
  NodeShape s;
  if (is_cluster(r)) {
    const Cluster& c = tree_.cluster(cluster_index(r));
    s.centre = c.centre;
    s.radius = c.radius;
    s.area = c.area;
    s.max_projected_area = c.max_projected_area;
    return s;
  }
  const ElementNode& e = h_.node(r);
  s.centre = polygon_centroid(e.polygon());
  for (const Vec3& v : e.polygon()) s.radius = std::max(s.radius, (v - s.centre).norm());
  s.area = e.area;
  s.max_projected_area = e.area;
  return s;
}

TransferBound ClusterTransfer::bound(const NodeShape& p, const NodeShape& q) const {
  const double d = (q.centre - p.centre).norm() - p.radius - q.radius;
  if (!(d > 0.0)) return {INFINITY, INFINITY};
  const double solid = std::numbers::pi * d * d;
  return {std::min(1.0, q.max_projected_area / solid), std::min(1.0, p.max_projected_area / solid)};
}

bool ClusterTransfer::facing_away(NodeRef p, NodeRef q) const {
  auto behind = [&](NodeRef element, NodeRef other) {
    const ElementNode& e = h_.node(element);
    const Vec3& n = scene_.patches[static_cast<std::size_t>(e.patch)].normal;
    const Vec3& o = e.vertices[0];
    if (is_cluster(other)) {
      const Cluster& c = tree_.cluster(cluster_index(other));
      for (int k = 0; k < 8; ++k) {
        const Vec3 corner((k & 1) ? c.hi.x() : c.lo.x(), (k & 2) ? c.hi.y() : c.lo.y(), (k & 4) ? c.hi.z() : c.lo.z());
        if ((corner - o).dot(n) > 0.0) return false;
      }
      return true;
    }
    for (const Vec3& v : h_.node(other).polygon())
      if ((v - o).dot(n) > 0.0) return false;
    return true;
  };
  if (!is_cluster(p) && behind(p, q)) return true;
  if (!is_cluster(q) && behind(q, p)) return true;
  return false;
}

double ClusterTransfer::projected_area(NodeRef r, const Vec3& d) const {
  if (is_cluster(r)) return tree_.projected_area(cluster_index(r), d);
  const ElementNode& e = h_.node(r);
  return e.area * std::max(0.0, scene_.patches[static_cast<std::size_t>(e.patch)].normal.dot(d));
}

int ClusterTransfer::sample(NodeRef r, double w, double u, double v, Vec3* point) const {
  if (is_cluster(r)) return tree_.sample(cluster_index(r), w, u, v, point);
  const ElementNode& e = h_.node(r);
  *point = detail::PolygonSampler(e.polygon()).point(u, v);
  return e.patch;
}

FormFactorEstimate ClusterTransfer::far_field(NodeRef p, const NodeShape& sp, NodeRef q, const NodeShape& sq) const {
  FormFactorEstimate e;
  Vec3 d = sq.centre - sp.centre;
  const double r = d.norm();
  if (!(r > 0.0)) return e;
  d /= r;
  const double g = projected_area(p, d) * projected_area(q, -d) / (std::numbers::pi * r * r);
  if (!(g > 0.0)) {
    e.facing_away = true;
    return e;
  }
  e.unoccluded = e.value = g / sp.area;
  e.reverse = g / sq.area;
  return e;
}

FormFactorEstimate ClusterTransfer::estimate(NodeRef p, const NodeShape& sp, NodeRef q, const NodeShape& sq) const {
  estimates_.fetch_add(1, std::memory_order_relaxed);
  FormFactorEstimate e;
  Vec3 d = sq.centre - sp.centre;
  const double r = d.norm();
  if (!(r > 0.0)) return e;
  d /= r;
  const double ap = projected_area(p, d), aq = projected_area(q, -d);
  const double g = ap * aq / (std::numbers::pi * r * r);  // A_p F(p -> q), far field
  if (!(g > 0.0)) {
    e.facing_away = true;
    return e;
  }
  e.unoccluded = g / sp.area;
  if (use_visibility_) {
    // Kernel-weighted visible fraction over kx x ky point pairs (as FormFactorEvaluator does for
    // partly visible element pairs), seeded by the pair so that any thread draws the same samples.
    const int kx = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples_)))));
    const int ky = std::max(1, (samples_ + kx - 1) / kx);
    detail::Rng rng(detail::mix_seed((static_cast<std::uint64_t>(static_cast<std::uint32_t>(p)) << 32) |
                                         static_cast<std::uint32_t>(q),
                                     7));
    thread_local std::vector<Vec3> xs, ys;
    thread_local std::vector<int> px, py;
    xs.resize(static_cast<std::size_t>(kx));
    px.resize(static_cast<std::size_t>(kx));
    ys.resize(static_cast<std::size_t>(ky));
    py.resize(static_cast<std::size_t>(ky));
    for (int i = 0; i < kx; ++i) {
      const double w = (i + rng.uniform()) / kx;  // stratified over the contents' area
      px[static_cast<std::size_t>(i)] = sample(p, w, rng.uniform(), rng.uniform(), &xs[static_cast<std::size_t>(i)]);
    }
    for (int j = 0; j < ky; ++j) {
      const double w = (j + rng.uniform()) / ky;
      py[static_cast<std::size_t>(j)] = sample(q, w, rng.uniform(), rng.uniform(), &ys[static_cast<std::size_t>(j)]);
    }
    double weight = 0.0, visible_weight = 0.0;
    int visible = 0, count = 0;
    for (int i = 0; i < kx; ++i) {
      const Vec3& x = xs[static_cast<std::size_t>(i)];
      const Vec3& nx = scene_.patches[static_cast<std::size_t>(px[static_cast<std::size_t>(i)])].normal;
      for (int j = 0; j < ky; ++j) {
        const Vec3& y = ys[static_cast<std::size_t>(j)];
        const Vec3& ny = scene_.patches[static_cast<std::size_t>(py[static_cast<std::size_t>(j)])].normal;
        const Vec3 dd = y - x;
        const double r2 = dd.squaredNorm();
        const double k = r2 > 0.0 ? std::max(0.0, nx.dot(dd)) * std::max(0.0, -ny.dot(dd)) / (r2 * r2) : 0.0;
        if (px[static_cast<std::size_t>(i)] == py[static_cast<std::size_t>(j)]) continue;  // same plane: no exchange
        const bool seen = k > 0.0 && !visibility_->segment_blocked(x, px[static_cast<std::size_t>(i)], y,
                                                                   py[static_cast<std::size_t>(j)]);
        weight += k;
        visible_weight += seen ? k : 0.0;
        visible += seen ? 1 : 0;
        ++count;
      }
    }
    // No sampled pair faces each other: the contents that do are a small part; count them as
    // half visible rather than dropping the link (its factor is small: the bound accepted it).
    e.visibility = weight > 0.0 ? visible_weight / weight : 0.5;
    e.error = e.unoccluded * detail::fraction_error(visible, std::max(1, count));
  }
  e.value = e.unoccluded * e.visibility;
  e.reverse = g * e.visibility / sq.area;
  return e;
}

}  // namespace hrad
