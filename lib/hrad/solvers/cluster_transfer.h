// Geometry of the nodes of the clustered hierarchy (elements and clusters) for the refinement
// oracle (Smits, Arvo & Greenberg 1994, sec. 3-4; Sillion 1995, sec. 4, "oriented" clusters):
// bounding spheres, projected areas, facing tests, a cheap far-field factor, and the surfaces below
// a node as a SurfaceSampler for the sampled factor (FormFactorEvaluator::sampled()).
//
// Bound: every point of p sees q within the solid angle of q's bounding sphere, at distance
// >= d_min = |c_p - c_q| - r_p - r_q, so F(p -> q) <= Aproj_max(q) / (pi d_min^2) (the point-to-
// disc factor with cos <= 1 at both ends); unbounded (must refine) when the spheres overlap.
// Far field: the factor between the two centres with the exact projected areas of the contents
// towards each other (oriented clusters, Sillion 1995 eq. 9), F(p -> q) = Aproj_p(d) Aproj_q(-d) /
// (pi r^2 A_p): no visibility, the 1/r^2 of the centres (an underestimate of the mean of 1/r^2 over
// the two volumes), used only to decide whether a pair may be linked.
#pragma once

#include <cstdint>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/form_factor_evaluator.h"

namespace hrad {

/// Which of a cluster link end's weights (ClusterTransfer::link_weights()).
enum class LinkWeights { kGets, kSends };

struct NodeShape {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;  ///< bounding sphere about centre
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
  /// `tree` may be null (no clusters). Keeps references.
  ClusterTransfer(const Scene& scene, const ElementHierarchy& hierarchy, const ClusterTree* tree);

  const Scene& scene() const { return scene_; }
  NodeShape shape(NodeRef r) const;
  TransferBound bound(const NodeShape& p, const NodeShape& q) const;
  /// True when nothing of q lies strictly in front of element p's plane or the other way round
  /// (exactly zero transfer); only decided when one of them is an element.
  bool facing_away(NodeRef p, NodeRef q) const;
  /// True when every patch of p has all of q's bounding box on or behind its plane, or every patch
  /// of q all of p's (exactly zero transfer, for clusters too; costs a test per patch).
  bool patches_face_away(NodeRef p, NodeRef q) const;
  /// The far-field factors without visibility (value F(p -> q), reverse F(q -> p); facing_away
  /// when either side shows no surface to the other).
  FormFactorEstimate far_field(NodeRef p, const NodeShape& sp, NodeRef q, const NodeShape& sq) const;
  /// Exact projected area of r's surfaces towards the unit direction d (facing_cosine()).
  double projected_area(NodeRef r, const Vec3& d) const;
  /// A cluster link's weights at its end r (hsa_links.h), per patch j of r (in tree order),
  /// appended to `per_area`; returns W = sum A_j q_j. kGets: q_j = F(dA at j's centroid -> the other
  /// end's bounding sphere) (point_to_sphere()) times the other end's projected area towards j over
  /// its largest (its axis sums, Cluster::axis_plus: exact for axis-aligned contents) times the part
  /// of the other end j sees (ShadedPatch::visible in `shaded`): a deterministic estimate of j's
  /// factor, by which the refinement bounds a patch's share and an end gets what the link brings
  /// where none of its own rays reached the other end. Unlike projected areas towards the other
  /// end's centre, this follows each patch's own position, the other end's extent and which way the
  /// other end faces: a ceiling lamp level with a far cluster's centre still sees its lower half. kSends: q_j = j's sampled factor to the
  /// other end (ShadedPatch::factor; 0 when not listed), what j sends per unit radiosity over A_j,
  /// and by reciprocity the weight by which j gets a share of what the link brings.
  double link_weights(NodeRef r, NodeRef other, const ShadedPatches* shaded, std::vector<float>* per_area,
                      LinkWeights kind = LinkWeights::kGets) const;
  /// Removes from `shaded` the patches of r whose q_j above is 0 whatever they see (facing wholly
  /// away from the other end's bounding sphere): they take no part in the link anyway.
  void drop_idle(NodeRef r, NodeRef other, ShadedPatches* shaded) const;
  /// The largest share per unit area that a link gives a patch of r: the largest q_j over W (kGets)
  /// (+infinity when W is 0). Times the link's exchange A_r F, the largest factor a patch of r
  /// receives through it.
  double largest_share(NodeRef r, NodeRef other, const ShadedPatches* shaded) const;
  /// A point uniform by area on r's surfaces; returns its patch.
  int sample(NodeRef r, double w, double u, double v, Vec3* point) const;
  /// The number of patches below r (1 for an element).
  int patch_count(NodeRef r) const;
  /// A point uniform on r's k-th patch (on the element itself for an element); returns the patch.
  int sample_patch(NodeRef r, int k, double u, double v, Vec3* point) const;

 private:
  const Scene& scene_;
  const ElementHierarchy& h_;
  const ClusterTree* tree_;
  /// q_j of link_weights() without visibility, for patch `patch` of area `area` at `at`.
  double facing_weight(const Patch& patch, const Vec3& at, NodeRef other_end, const NodeShape& other) const;

  std::vector<Vec3> centroids_;  ///< per patch
};

/// The surfaces below one node, for FormFactorEvaluator::sampled().
class NodeSurfaces final : public SurfaceSampler {
 public:
  NodeSurfaces(const ClusterTransfer& geometry, NodeRef node, double area)
      : geometry_(geometry), node_(node), area_(area) {}
  double area() const override { return area_; }
  int sample(double w, double u, double v, Vec3* point) const override {
    return geometry_.sample(node_, w, u, v, point);
  }
  int patch_count() const override { return geometry_.patch_count(node_); }
  int sample_patch(int k, double u, double v, Vec3* point) const override {
    return geometry_.sample_patch(node_, k, u, v, point);
  }

 private:
  const ClusterTransfer& geometry_;
  NodeRef node_;
  double area_;
};

}  // namespace hrad
