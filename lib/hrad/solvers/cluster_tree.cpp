#include "hrad/solvers/cluster_tree.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "hrad/geometry/polygon.h"
#include "hrad/visibility/sampling.h"

namespace hrad {

ClusterTree::ClusterTree(const Scene& scene) : scene_(scene) {
  const int n = static_cast<int>(scene.patches.size());
  assert(n >= 1);
  std::vector<Vec3> centroids(static_cast<std::size_t>(n));
  std::vector<double> diagonals(static_cast<std::size_t>(n));
  order_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto& v = scene.patches[static_cast<std::size_t>(i)].vertices;
    centroids[static_cast<std::size_t>(i)] = polygon_centroid(v);
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const Vec3& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    diagonals[static_cast<std::size_t>(i)] = v.empty() ? 0.0 : (hi - lo).norm();
    order_[static_cast<std::size_t>(i)] = i;
  }
  patch_parent_.assign(static_cast<std::size_t>(n), -1);
  clusters_.reserve(static_cast<std::size_t>(std::max(0, n - 1)));
  root_ = build(0, n, -1, centroids, diagonals);
  samplers_.reserve(static_cast<std::size_t>(n));
  position_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int patch = order_[static_cast<std::size_t>(i)];
    samplers_.emplace_back(scene.patches[static_cast<std::size_t>(patch)].vertices);
    position_[static_cast<std::size_t>(patch)] = i;
  }
  cumulative_area_.resize(static_cast<std::size_t>(n) + 1, 0.0);
  for (int i = 0; i < n; ++i)
    cumulative_area_[static_cast<std::size_t>(i) + 1] =
        cumulative_area_[static_cast<std::size_t>(i)] +
        scene.patches[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])].area;
}

NodeRef ClusterTree::build(int begin, int end, int parent, const std::vector<Vec3>& centroids,
                           const std::vector<double>& diagonals) {
  if (end - begin == 1) {
    const int patch = order_[static_cast<std::size_t>(begin)];
    patch_parent_[static_cast<std::size_t>(patch)] = parent;
    return static_cast<NodeRef>(patch);  // the patch's root element (root(patch) == patch)
  }
  const int index = static_cast<int>(clusters_.size());
  clusters_.emplace_back();
  Cluster c;
  c.parent = parent;
  c.begin = begin;
  c.end = end;
  c.lo = Vec3::Constant(INFINITY);
  c.hi = Vec3::Constant(-INFINITY);
  Vec3 clo = c.lo, chi = c.hi;
  Eigen::Array3d plus = Eigen::Array3d::Zero(), minus = Eigen::Array3d::Zero();
  for (int i = begin; i < end; ++i) {
    const int patch = order_[static_cast<std::size_t>(i)];
    const Patch& p = scene_.patches[static_cast<std::size_t>(patch)];
    for (const Vec3& v : p.vertices) {
      c.lo = c.lo.cwiseMin(v);
      c.hi = c.hi.cwiseMax(v);
    }
    clo = clo.cwiseMin(centroids[static_cast<std::size_t>(patch)]);
    chi = chi.cwiseMax(centroids[static_cast<std::size_t>(patch)]);
    c.area += p.area;
    plus += p.area * p.normal.array().max(0.0);
    minus += p.area * (-p.normal.array()).max(0.0);
  }
  c.centre = 0.5 * (c.lo + c.hi);
  c.radius = 0.5 * (c.hi - c.lo).norm();
  c.max_projected_area = std::min(c.area, plus.max(minus).matrix().norm());
  c.axis_plus = plus;
  c.axis_minus = minus;
  clusters_[static_cast<std::size_t>(index)] = c;
  // Patches as large as much of the cluster (a city's ground, sky or enclosing walls among its
  // buildings) would make every cluster above them as large, so that none of them is ever far from
  // anything: they go together as one child, the rest as the other (kept in order, so the tree is
  // the same on every platform). A group made only of such patches is median-split.
  const double large = kLargePatchFraction * 2.0 * c.radius;
  const auto rest = std::stable_partition(order_.begin() + begin, order_.begin() + end, [&](int patch) {
    return diagonals[static_cast<std::size_t>(patch)] > large;
  });
  if (const int split = static_cast<int>(rest - order_.begin()); split > begin && split < end) {
    const NodeRef large_ones = build(begin, split, index, centroids, diagonals);
    const NodeRef others = build(split, end, index, centroids, diagonals);
    clusters_[static_cast<std::size_t>(index)].children[0] = large_ones;
    clusters_[static_cast<std::size_t>(index)].children[1] = others;
    return cluster_ref(index);
  }
  // Median split of the centroids along the longest axis of their box (ties by patch index, so
  // the tree is the same on every platform).
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  auto first = order_.begin() + begin, middle = order_.begin() + mid, last = order_.begin() + end;
  std::nth_element(first, middle, last, [&](int a, int b) {
    const double ca = centroids[static_cast<std::size_t>(a)][axis], cb = centroids[static_cast<std::size_t>(b)][axis];
    return ca < cb || (ca == cb && a < b);
  });
  const NodeRef left = build(begin, mid, index, centroids, diagonals);
  const NodeRef right = build(mid, end, index, centroids, diagonals);
  clusters_[static_cast<std::size_t>(index)].children[0] = left;
  clusters_[static_cast<std::size_t>(index)].children[1] = right;
  return cluster_ref(index);
}

std::span<const int> ClusterTree::patches(int index) const {
  const Cluster& c = cluster(index);
  return {order_.data() + c.begin, static_cast<std::size_t>(c.end - c.begin)};
}

double ClusterTree::projected_area(int index, const Vec3& d) const {
  double sum = 0.0;
  for (const int patch : patches(index)) {
    const Patch& p = scene_.patches[static_cast<std::size_t>(patch)];
    sum += p.area * facing_cosine(p.normal, d);
  }
  return sum;
}

int ClusterTree::sample(int index, double w, double u, double v, Vec3* point) const {
  const Cluster& c = cluster(index);
  const double lo = cumulative_area_[static_cast<std::size_t>(c.begin)];
  const double target = lo + w * (cumulative_area_[static_cast<std::size_t>(c.end)] - lo);
  // First position whose prefix sum passes the target: the patch covering it.
  auto it = std::upper_bound(cumulative_area_.begin() + c.begin + 1, cumulative_area_.begin() + c.end + 1, target);
  int i = static_cast<int>(it - cumulative_area_.begin()) - 1;
  i = std::clamp(i, c.begin, c.end - 1);
  *point = samplers_[static_cast<std::size_t>(i)].point(u, v);
  return order_[static_cast<std::size_t>(i)];
}

}  // namespace hrad
