// The link operator: one interface for every way a solver stores its interactions (the full
// matrix's dense F, substructuring's element-to-patch factors, hierarchical links at any level,
// links resolved to leaves, cluster links). Each gathers into a field on the nodes of the element
// hierarchy (and of the cluster tree above it); one push-pull (push_pull.h) and one iteration loop
// (iteration.h) drive them all, and each reports the work a gather does.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

/// A field over one element by its values at the element's simpson_points() (formfactor/
/// simpson_rule.h): biquadratic on a quad's bilinear map (9 values), quadratic on a triangle (the
/// values at the vertices and edge midpoints; the 7th, at the centroid, is the quadratic's value
/// there; the 8th and 9th are unused). Restricted to a child of a 1-to-4 split it is again such a
/// field, exactly (push_pull.h).
using PointValues = std::array<Rgb, 9>;

inline void add_constant(PointValues& v, const Rgb& c) {
  for (Rgb& x : v) x += c;
}

/// Radiosity and gathered irradiance on the nodes, by dense index: elements (ElementHierarchy node
/// ids) first, then clusters (hierarchy size + cluster index).
struct NodeField {
  std::size_t elements = 0;
  std::vector<Rgb> radiosity;  ///< leaves: B; interior elements and clusters: their area mean
  /// Per element: the moments of its radiosity against the basis of PointValues fields, m_i =
  /// integral over the element of phi_i B (phi_i: the biquadratic or quadratic Lagrange function of
  /// point i). A field's integral against B is then sum_i field_i m_i. Leaves: B times the integral
  /// of phi_i; interior: pulled from the children's by the transpose of the push's restriction.
  std::vector<PointValues> radiosity_moments;
  /// Per element: a leaf's radiosity at its points, E + rho H there (for display; interior: unset).
  std::vector<PointValues> point_radiosity;
  std::vector<PointValues> irradiance;  ///< per element: gathered at this node, to be pushed to its leaves
  /// Per element: a leaf's mean irradiance H after the last push (what B = E + rho H used; interior: unset).
  std::vector<Rgb> leaf_irradiance;

  void resize(std::size_t element_count, std::size_t cluster_count) {
    elements = element_count;
    radiosity.assign(element_count + cluster_count, Rgb::Zero());
    PointValues zero;
    zero.fill(Rgb::Zero());
    irradiance.assign(element_count, zero);
    leaf_irradiance.assign(element_count, Rgb::Zero());
    radiosity_moments.assign(element_count, zero);
    point_radiosity.assign(element_count, zero);
  }
  void clear_gathered() {
    for (PointValues& v : irradiance) v.fill(Rgb::Zero());
  }
};

class LinkOperator {
 public:
  virtual ~LinkOperator() = default;
  /// Adds what each receiver gathers through its links (factor times the radiosity its source
  /// shows towards it) to field.irradiance (a cluster's share of its patches at their roots).
  /// Reads field.radiosity. Deterministic: the same bits at any thread count.
  virtual void gather(NodeField& field) const = 0;
  /// Terms one gather touches (one factor times one radiosity each).
  virtual std::uint64_t terms() const = 0;
  /// Bytes the operator holds.
  virtual std::uint64_t bytes() const = 0;
};

}  // namespace hrad
