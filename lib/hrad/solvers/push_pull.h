// Push-pull (Hanrahan, Salzman & Aupperle 1991, "PushPullRad"), written once for every solver: the
// irradiance gathered at an element is pushed down to the leaves below it (what clusters receive
// reaches the patches' roots in the gather, hsa_links.h), each leaf gets B = E + rho H with H the
// mean of the irradiance field over it, and the radiosity is pulled back up as the area mean, into
// the clusters too. The irradiance gathered at an element is a field given
// by its values at the element's points (link_operator.h PointValues); it is pushed to a child by
// evaluating the parent's polynomial at the child's points, which is exact. The radiosity's moments
// against the same basis (link_operator.h NodeField::radiosity_moments) are pulled up by the
// transpose of that restriction, so that what a link sends and what it delivers are adjoint
// (Gortler, Schroeder, Cohen & Hanrahan 1993's two-scale relations, for this basis). With the
// linear basis (linear_basis.h) a leaf's radiosity is the L2 projection of E + rho H onto its
// linear space, and its moments are those of that linear field.
#pragma once

#include <algorithm>
#include <utility>

#include "hrad/core/scene.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/linear_basis.h"
#include "hrad/solvers/link_operator.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// The leaves' change of radiosity in one iteration and their reflected radiosity |B - E| (the
/// largest over the computed channels), as their largest values and integrated over the leaves'
/// areas (the reflected power, up to pi).
struct LeafChange {
  double change = 0.0;
  double reflected = 0.0;
  double power_change = 0.0;
  double reflected_power = 0.0;
  /// One leaf (or one point of it, with its share of the leaf's area): how far it moved and what it
  /// reflects.
  void add_leaf(double area, double moved, double reflects) {
    change = std::max(change, moved);
    reflected = std::max(reflected, reflects);
    power_change += area * moved;
    reflected_power += area * reflects;
  }
  void add(const LeafChange& o) {
    change = std::max(change, o.change);
    reflected = std::max(reflected, o.reflected);
    power_change += o.power_change;
    reflected_power += o.reflected_power;
  }
};

/// A linear leaf's field (values at its points, linear_basis.h) scaled towards its mean, per channel,
/// just enough that no corner is below 0 (Zhang & Shu 2010, "On maximum-principle-satisfying high
/// order schemes for scalar conservation laws": the scaling keeps the mean, so power, and leaves
/// fields >= 0 untouched); flat where the mean itself is below 0. The L2 projection of a field >= 0
/// can dip below 0 at a corner (a leaf lit along one edge), and a corner below 0 then sends negative
/// light on. A mean below 0 comes from links that deliver negative light (refinement_oracle.cpp
/// shape_of(): a link's send shape, moved to its exact mean, is below 0 where the factor peaks at
/// another point of the sender); setting it to 0 would add power (a long corridor's far end, 16%).
void limit_positivity(PointValues& b, const std::array<double, 9>& mean_weights, int vertex_count, int channels);

/// What a part below aeps sends through the links between elements (send_closure.h), per unit of
/// its radiosity's moments m: sum_i coefficients_i m_i; per unit radiosity and area, sigma (0: the
/// part sends as its moments say); and what that should be, `closed`.
struct SendClosure {
  std::array<double, 9> coefficients{};
  double sigma = 0.0;
  double closed = 0.0;
};

/// A PointValues field over an element of `vertex_count` vertices, split as `kind`, restricted to
/// its child `child` (0..3, ElementHierarchy::split() order): the child's values are the parent's
/// polynomial at the child's points, exactly (the two-scale relation the push uses).
std::array<double, 9> restrict_to_child(const std::array<double, 9>& parent, int vertex_count, SplitKind kind,
                                        int child);

class PushPull {
 public:
  /// `tree` may be null (no clusters). Keeps references.
  PushPull(const Scene& scene, const ElementHierarchy& hierarchy, const ClusterTree* tree, int channels,
           Basis basis = Basis::kConstant);

  /// A field sized for the hierarchy and the tree, with the leaves' radiosity from the hierarchy's
  /// nodes (their emission before any solve; with the linear basis also at the leaves' points) and
  /// everything above pulled from it.
  NodeField make_field() const;
  /// Pushes field.irradiance down, sets every leaf's radiosity to E + rho H and
  /// pulls; returns the leaves' largest change. Parallel over patches, deterministic.
  LeafChange push_pull(NodeField& field) const;
  /// Sets interior elements' and clusters' radiosity from the leaves'.
  void pull(NodeField& field) const;
  /// Copies the field's element radiosity into the hierarchy's nodes (for output and the B*F test),
  /// the leaves' irradiance into ElementNode::gathered,
  /// and the clusters' mean radiosity into `cluster_radiosity` (when not null).
  void store(const NodeField& field, ElementHierarchy& hierarchy, std::vector<Rgb>* cluster_radiosity) const;

  /// Per element (by node id; empty: none): the closure of what a part below aeps sends through the
  /// links between elements (send_closure.h); its radiosity's moments are moved along a uniform
  /// field's so that it sends `closed` times its power through them. Its radiosity, and what it
  /// sends through cluster links, stay as they are.
  void set_send_closure(std::vector<SendClosure> closure) { send_closure_ = std::move(closure); }
  /// An element's simpson_points() weights over its area: the mean of a PointValues field is
  /// sum_k w_k v_k.
  const std::array<double, 9>& mean_weights(NodeId id) const { return mean_weights_[static_cast<std::size_t>(id)]; }
  /// The integrals over an element of its basis functions (link_operator.h NodeField::radiosity_moments).
  const std::array<double, 9>& basis_integrals_of(NodeId id) const {
    return basis_integrals_[static_cast<std::size_t>(id)];
  }

 private:
  Rgb push_pull_element(NodeField& field, NodeId id, const PointValues& down, LeafChange* change) const;
  Rgb pull_element(NodeField& field, NodeId id) const;
  void pull_moments(NodeField& field, NodeId id) const;
  void leaf_moments(NodeField& field, NodeId id) const;
  void pull_clusters(NodeField& field) const;

  const Scene& scene_;
  const ElementHierarchy& h_;
  const ClusterTree* tree_;
  int channels_;
  Basis basis_;
  /// Linear basis, per leaf: its simpson_points() weights and the projection onto its linear space.
  std::vector<std::array<double, 9>> point_weights_;
  std::vector<LinearProjection> projections_;
  /// Per element: its simpson_points() weights over its area (the mean of a PointValues field).
  std::vector<std::array<double, 9>> mean_weights_;
  /// Per element: the integrals of its basis functions (the Simpson weights of a quad; for a
  /// triangle's quadratic basis, 0 at the vertices and a third of the area at the midpoints).
  std::vector<std::array<double, 9>> basis_integrals_;
  std::vector<SendClosure> send_closure_;
};

}  // namespace hrad
