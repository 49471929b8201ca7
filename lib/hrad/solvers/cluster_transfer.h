// Transfer between nodes of the clustered hierarchy when at least one is a cluster: a bound for
// the refinement oracle and an estimate for the link (Smits, Arvo & Greenberg 1994, sec. 3-4;
// Sillion 1995, sec. 4, "oriented" clusters).
//
// Bound (for tests and a conservative oracle): every point of p sees q within the solid angle of q's bounding sphere, at distance
// >= d_min = |c_p - c_q| - r_p - r_q, so F(p -> q) <= Aproj_max(q) / (pi d_min^2) (the point-to-
// disc factor with cos <= 1 at both ends); unbounded (must refine) when the spheres overlap.
// Estimate: the far-field factor between the two centres with the exact projected areas of the
// contents towards each other (oriented clusters, Sillion 1995 eq. 9: a cluster's contribution is
// its projected area in the direction of transfer), F(p -> q) = Aproj_p(d) Aproj_q(-d) /
// (pi r^2 A_p), times the kernel-weighted visible fraction of sampled point pairs (Wallace,
// Elmquist & Haines 1989). It is reciprocal by construction: A_p F(p -> q) = A_q F(q -> p).
#pragma once

#include <atomic>
#include <cstdint>

#include "hrad/core/scene.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/form_factor_evaluator.h"

namespace hrad {

class Visibility;

struct NodeShape {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;              ///< bounding sphere about centre
  double area = 0.0;
  double max_projected_area = 0.0;  ///< bound of the projected area over all directions
};

/// Upper bounds of F(p -> q) and F(q -> p); +infinity when the bounding spheres overlap.
struct TransferBound {
  double pq = 0.0;
  double qp = 0.0;
};

class ClusterTransfer {
 public:
  /// `visibility` may be null when `use_visibility` is false. Keeps references.
  ClusterTransfer(const Scene& scene, const ElementHierarchy& hierarchy, const ClusterTree& tree,
                  const Visibility* visibility, bool use_visibility, int visibility_samples);

  NodeShape shape(NodeRef r) const;
  TransferBound bound(const NodeShape& p, const NodeShape& q) const;
  /// True when nothing of q lies strictly in front of element p's plane or the other way round
  /// (exactly zero transfer); only decided when one of them is an element.
  bool facing_away(NodeRef p, NodeRef q) const;
  /// The estimate for a link p <-> q (p != q, at least one a cluster): value F(p -> q), reverse
  /// F(q -> p), visibility the weighted visible fraction, unoccluded the factor without it.
  /// Deterministic: the samples' seed comes from p and q.
  FormFactorEstimate estimate(NodeRef p, const NodeShape& sp, NodeRef q, const NodeShape& sq) const;

  /// The far-field factors without visibility (value F(p -> q), reverse F(q -> p); facing_away
  /// when either side shows no surface to the other). Cheap: no visibility query.
  FormFactorEstimate far_field(NodeRef p, const NodeShape& sp, NodeRef q, const NodeShape& sq) const;

  /// Exact projected area of r's surfaces towards the unit direction d.
  double projected_area(NodeRef r, const Vec3& d) const;

  std::uint64_t estimates() const { return estimates_.load(std::memory_order_relaxed); }

 private:
  // A point uniform by area on r's surfaces; returns its patch.
  int sample(NodeRef r, double w, double u, double v, Vec3* point) const;

  const Scene& scene_;
  const ElementHierarchy& h_;
  const ClusterTree& tree_;
  const Visibility* visibility_;
  bool use_visibility_;
  int samples_;
  mutable std::atomic<std::uint64_t> estimates_{0};
};

}  // namespace hrad
