// Clusters above the input polygons for hierarchical radiosity: Smits, Arvo & Greenberg 1994, "A
// clustering algorithm for radiosity in complex environments" (SIGGRAPH '94), and Sillion 1995,
// "A unified hierarchical algorithm for global illumination with scattering volumes and object
// clusters" (IEEE TVCG 1(3)). A binary volume hierarchy over the patches, built by median splits
// of their centroids along the longest axis, except that patches as large as much of their cluster
// form a child of their own (kLargePatchFraction); its leaves are the patches' quadtree roots, so
// the whole scene hangs below one root and can be linked from a single root self-link.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/visibility/sampling.h"

namespace hrad {

/// A node of the clustered hierarchy: an element (>= 0: an ElementHierarchy NodeId) or a cluster
/// (<= -2: cluster index -2 - ref). -1 stays "none" (kNoNode).
using NodeRef = std::int32_t;
inline constexpr bool is_cluster(NodeRef r) { return r <= -2; }
inline constexpr int cluster_index(NodeRef r) { return -2 - r; }
inline constexpr NodeRef cluster_ref(int index) { return -2 - index; }

/// The cosine by which a patch of unit normal n faces the unit direction d in a cluster link's
/// shares (hsa_links.h): 0 when it faces away or grazes d within rounding, where the sign of n.d is
/// noise and a share divided by a projected area of that size would be too. Written out so that
/// every sum of shares adds the same bits.
inline constexpr double kGrazingCosine = 1e-12;
/// Patches whose box diagonals pass this fraction of their cluster's box diagonal form a child of
/// their own in ClusterTree, the cluster's other patches the other child.
inline constexpr double kLargePatchFraction = 0.5;
inline double facing_cosine(const Vec3& n, const Vec3& d) {
  const double c = n.x() * d.x() + n.y() * d.y() + n.z() * d.z();
  return c > kGrazingCosine ? c : 0.0;
}

struct Cluster {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  ///< bounding box of the contents
  Vec3 centre = Vec3::Zero();                 ///< of the bounding box
  double radius = 0.0;                        ///< half the box diagonal: a bounding sphere
  double area = 0.0;                          ///< total area of the patches below
  /// Largest projected area of the contents over all directions, bounded through the six axis
  /// sums P_k^+- = sum_i A_i max(0, +-n_ik): sum_i A_i max(0, n_i.d) <= sum_k |d_k| P_k^sign(d_k)
  /// <= |(max(P_k^+, P_k^-))_k| (Cauchy-Schwarz); never above `area`.
  double max_projected_area = 0.0;
  /// P_k^+ and P_k^-: the contents' areas times max(0, +-n_k) per axis k (oriented cluster
  /// transfer: exact projected areas for axis-aligned contents).
  Eigen::Array3d axis_plus = Eigen::Array3d::Zero(), axis_minus = Eigen::Array3d::Zero();
  NodeRef children[2] = {kNoNode, kNoNode};  ///< clusters or patch roots
  int parent = -1;                           ///< cluster index, -1 for the root
  int begin = 0, end = 0;                    ///< its patches are patch_order()[begin, end)
};

class ClusterTree {
 public:
  /// Builds the tree over all patches of `scene` (a scene of one patch has no cluster: root() is
  /// that patch's element). Children always have larger cluster indices than their parent.
  explicit ClusterTree(const Scene& scene);

  NodeRef root() const { return root_; }
  std::size_t size() const { return clusters_.size(); }
  const Cluster& cluster(int index) const { return clusters_[static_cast<std::size_t>(index)]; }
  const std::vector<Cluster>& clusters() const { return clusters_; }
  /// The patches below cluster `index`.
  std::span<const int> patches(int index) const;
  /// The cluster whose child patch `patch`'s root is (-1 when there is no cluster).
  int parent_of_patch(int patch) const { return patch_parent_[static_cast<std::size_t>(patch)]; }
  /// Exact projected area of cluster `index`'s patches towards the unit direction `d`:
  /// sum_i A_i max(0, n_i.d) (self-occlusion inside the cluster is not counted).
  double projected_area(int index, const Vec3& d) const;
  /// A point uniform by area on the patches of cluster `index` from three numbers in [0, 1);
  /// returns the patch it lies on.
  int sample(int index, double w, double u, double v, Vec3* point) const;
  /// A point uniform by area on patch `patch` from two numbers in [0, 1); returns `patch`.
  int sample_patch(int patch, double u, double v, Vec3* point) const {
    *point = samplers_[static_cast<std::size_t>(position_[static_cast<std::size_t>(patch)])].point(u, v);
    return patch;
  }

 private:
  NodeRef build(int begin, int end, int parent, const std::vector<Vec3>& centroids,
                const std::vector<double>& diagonals);

  const Scene& scene_;
  std::vector<Cluster> clusters_;
  std::vector<int> order_;               ///< patches, grouped by cluster ranges
  std::vector<double> cumulative_area_;  ///< prefix sums of area along order_ (size + 1)
  std::vector<int> patch_parent_;
  std::vector<int> position_;  ///< each patch's position in order_
  /// One per patch, in order_'s order, so that a cluster's samplers lie together: sample() draws
  /// millions of points, and a sampler far from the last one read costs a cache miss.
  std::vector<detail::PolygonSampler> samplers_;
  NodeRef root_ = kNoNode;
};

}  // namespace hrad
