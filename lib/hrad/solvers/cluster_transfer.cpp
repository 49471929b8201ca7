#include "hrad/solvers/cluster_transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "hrad/formfactor/point_to_sphere.h"
#include "hrad/geometry/polygon.h"
#include "hrad/visibility/sampling.h"

namespace hrad {

ClusterTransfer::ClusterTransfer(const Scene& scene, const ElementHierarchy& hierarchy, const ClusterTree* tree)
    : scene_(scene), h_(hierarchy), tree_(tree) {
  centroids_.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) centroids_.push_back(polygon_centroid(p.vertices));
}

NodeShape ClusterTransfer::shape(NodeRef r) const {
  NodeShape s;
  if (is_cluster(r)) {
    const Cluster& c = tree_->cluster(cluster_index(r));
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
      const Cluster& c = tree_->cluster(cluster_index(other));
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

bool ClusterTransfer::patches_face_away(NodeRef p, NodeRef q) const {
  auto box = [&](NodeRef r) {
    Eigen::AlignedBox3d b;
    if (is_cluster(r)) {
      const Cluster& c = tree_->cluster(cluster_index(r));
      b.extend(c.lo).extend(c.hi);
    } else {
      for (const Vec3& v : h_.node(r).polygon()) b.extend(v);
    }
    return b;
  };
  auto all_behind = [&](NodeRef from, NodeRef to) {
    const Eigen::AlignedBox3d b = box(to);
    for (int k = 0, n = patch_count(from); k < n; ++k) {
      const int patch =
          is_cluster(from) ? tree_->patches(cluster_index(from))[static_cast<std::size_t>(k)] : h_.node(from).patch;
      const Patch& s = scene_.patches[static_cast<std::size_t>(patch)];
      for (int corner = 0; corner < 8; ++corner)
        if ((b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)) - s.vertices[0]).dot(s.normal) > 0.0)
          return false;
    }
    return true;
  };
  return all_behind(p, q) || all_behind(q, p);
}

double ClusterTransfer::projected_area(NodeRef r, const Vec3& d) const {
  if (is_cluster(r)) return tree_->projected_area(cluster_index(r), d);
  const ElementNode& e = h_.node(r);
  return e.area * facing_cosine(scene_.patches[static_cast<std::size_t>(e.patch)].normal, d);
}

double ClusterTransfer::facing_weight(const Patch& patch, const Vec3& at, NodeRef other_end,
                                      const NodeShape& other) const {
  const double f = point_to_sphere(at, patch.normal, other.centre, other.radius);
  if (!(f > 0.0)) return 0.0;
  // The other end's projected area towards the patch over its largest: its axis sums for a cluster.
  const Vec3 u = (at - other.centre).normalized();
  double shows = 0.0;
  if (is_cluster(other_end)) {
    const Cluster& c = tree_->cluster(cluster_index(other_end));
    for (int k = 0; k < 3; ++k) shows += std::abs(u[k]) * (u[k] > 0.0 ? c.axis_plus[k] : c.axis_minus[k]);
  } else {
    shows = projected_area(other_end, u);
  }
  return other.max_projected_area > 0.0 ? f * shows / other.max_projected_area : 0.0;
}

double ClusterTransfer::link_weights(NodeRef r, NodeRef other_end, const ShadedPatches* shaded,
                                     std::vector<float>* per_area, LinkWeights kind) const {
  const NodeShape other = shape(other_end);
  double total = 0.0;
  for (int k = 0, n = patch_count(r); k < n; ++k) {
    const int patch = is_cluster(r) ? tree_->patches(cluster_index(r))[static_cast<std::size_t>(k)] : h_.node(r).patch;
    const Patch& s = scene_.patches[static_cast<std::size_t>(patch)];
    const double area = is_cluster(r) ? s.area : h_.node(r).area;
    const Vec3 at =
        is_cluster(r) ? centroids_[static_cast<std::size_t>(patch)] : polygon_centroid(h_.node(r).polygon());
    float q = 0.0f;
    if (kind == LinkWeights::kSends) {
      if (shaded != nullptr) {
        const auto it = std::lower_bound(shaded->begin(), shaded->end(), ShadedPatch{patch, 0.0f, 0.0f});
        if (it != shaded->end() && it->patch == patch) q = it->factor;
      }
    } else {
      q = static_cast<float>(facing_weight(s, at, other_end, other) * visible_share(shaded, patch));
    }
    per_area->push_back(q);
    total += area * static_cast<double>(q);
  }
  return total;
}

void ClusterTransfer::drop_idle(NodeRef r, NodeRef other_end, ShadedPatches* shaded) const {
  if (!is_cluster(r)) return;
  const NodeShape other = shape(other_end);
  std::erase_if(*shaded, [&](const ShadedPatch& p) {
    return !(facing_weight(scene_.patches[static_cast<std::size_t>(p.patch)],
                           centroids_[static_cast<std::size_t>(p.patch)], other_end, other) > 0.0);
  });
}

double ClusterTransfer::largest_share(NodeRef r, NodeRef other, const ShadedPatches* shaded) const {
  thread_local std::vector<float> q;
  q.clear();
  const double total = link_weights(r, other, shaded, &q);
  const float most = q.empty() ? 0.0f : *std::max_element(q.begin(), q.end());
  return total > 0.0 ? static_cast<double>(most) / total : INFINITY;
}

int ClusterTransfer::sample(NodeRef r, double w, double u, double v, Vec3* point) const {
  if (is_cluster(r)) return tree_->sample(cluster_index(r), w, u, v, point);
  const ElementNode& e = h_.node(r);
  *point = detail::polygon_point(e.polygon(), u, v);
  return e.patch;
}

int ClusterTransfer::patch_count(NodeRef r) const {
  return is_cluster(r) ? static_cast<int>(tree_->patches(cluster_index(r)).size()) : 1;
}

int ClusterTransfer::sample_patch(NodeRef r, int k, double u, double v, Vec3* point) const {
  if (is_cluster(r))
    return tree_->sample_patch(tree_->patches(cluster_index(r))[static_cast<std::size_t>(k)], u, v, point);
  return sample(r, 0.0, u, v, point);
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

}  // namespace hrad
