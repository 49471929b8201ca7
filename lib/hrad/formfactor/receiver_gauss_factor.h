// Element-to-polygon form factor by fixed Gauss points on the receiving element and Lambert's
// exact point-to-polygon formula at each: the solvers' cheap kernel.
#pragma once

#include <span>
#include <vector>

#include "hrad/core/types.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_quadrature.h"

namespace hrad {

/// Most cells along one side of an elongated quad in receiver_gauss_points(): strips up to about
/// 1400 : 1 keep cells of aspect 2 or less, at a cost linear in the aspect. Fewer cells put the
/// points of a corridor's wall strips far from where the end wall's light arrives, and closed
/// corridors then lose power (tests/hard/long_room_test.cpp).
inline constexpr long kMaxReceiverCells = 1024;

/// The receiver's points: the 3 x 3 product Gauss-Legendre rule on a quad's bilinear map (degree 5
/// in (u, v)), on each of k cells of aspect below ~2 along an elongated quad (k its sides' length
/// ratio over sqrt(2), rounded, at most kMaxReceiverCells); the order-2 rule of polygon_quadrature() (12 points) on any
/// other polygon. The
/// weights sum to the area to rounding. They do not depend on the source, so each point's factors
/// to the polygons of a closed surface sum to 1 and so do the element's (closure, to rounding).
void receiver_gauss_points(std::span<const Vec3> receiver, const Vec3& unit_normal,
                           std::vector<detail::WeightedPoint>& out);

/// Deepest level of graded cells below a cell of the plain rule (1/4096 of its size).
inline constexpr int kMaxNearDepth = 12;

/// Depth of the graded cells along an edge that an emitter has in the receiver's plane (a corridor's
/// end wall beside its side walls: the point factor rises to 1/2 at the edge, log-like, and all of
/// the emitter's light that reaches the wall crosses the row of cells along it), at about
/// 2^(depth + 1) cells along each such edge. Closed 1 x 1 x 1000 corridor, full matrix at the
/// defaults: one 3 x 3 rule on the elements beside the end wall lost 4.1e-3 of the power, depth 3
/// 7.9e-5, depth 4 2.9e-5 (tests/hard/long_room_test.cpp).
inline constexpr int kCreaseDepth = 4;

/// An edge of a polygon that floats in front of the receiver, close to it (a lamp a millimetre
/// from a wall): the point factor to that polygon rises from 0 to its full value across a band
/// around the edge as wide as the edge's distance, which a cell of the rule larger than that
/// distance cannot follow. Or an edge an emitter has in the receiver's plane, graded to kCreaseDepth.
struct NearEdge {
  Vec3 a, b;
  /// Cells through whose sphere this edge passes are cut to this depth at most.
  int max_depth = kMaxNearDepth;
  /// Distance from x to the segment.
  double distance(const Vec3& x) const;
};

/// receiver_gauss_points() graded towards `near`: a cell that a near edge passes through (its
/// bounding sphere) is cut into four (a quad's cell in its parameter square, a triangle at its edge
/// midpoints), to the edge's max_depth levels; every cell keeps the plain rule. The cells along a lamp's
/// edge end about twice as large as its distance: a lamp 1 mm or 0.3 mm from a wall then balances
/// power within 1e-3 (lamp_near_wall_test; cells half that size change the balance by 1e-6 at four
/// times the points, cells twice as large miss it by 10%). The points still do not depend on the
/// source: one receiver's factors to a closed surface sum to 1. Empty `near`: exactly the plain rule.
void receiver_gauss_points(std::span<const Vec3> receiver, const Vec3& unit_normal, std::span<const NearEdge> near,
                           std::vector<detail::WeightedPoint>& out);

/// F(receiver -> source) = (1/A) sum_k w_k F(dA_k -> source) over receiver_gauss_points(), with
/// point_to_polygon() (Cohen & Wallace 1993, eq. 4.16) at each point and `rel_tol` passed to it.
/// The default is the plain contour sum: a solver needs far less than 1e-13 where the sum cancels,
/// and the plain sum keeps closure to rounding. Unoccluded; the receiver's normal from its vertex
/// order. The error is the rule's: ~1e-4 relative for unit squares 1 apart (Howell C-11), larger
/// for a source close to the receiver against the receiver's size.
/// `point_count`, when not null, receives the number of point factors evaluated.
double receiver_gauss_factor(std::span<const Vec3> receiver, std::span<const Vec3> source,
                             double rel_tol = kLambertSumOnly, int* point_count = nullptr);
/// The same on the points graded towards `near` (receiver_gauss_points() with near edges).
double receiver_gauss_factor(std::span<const Vec3> receiver, std::span<const Vec3> source,
                             std::span<const NearEdge> near, double rel_tol = kLambertSumOnly,
                             int* point_count = nullptr);

/// The same factor by one point, the receiver's centroid, where the receiver is small against its
/// distance to the source: diameter(receiver) <= `centroid_ratio` x the gap between the two
/// polygons' bounding spheres; receiver_gauss_factor() otherwise. The midpoint rule's relative
/// error for a point factor ~ cos cos / (pi r^2) is about (diameter / distance)^2 / 4 (its second
/// derivative over the receiver), so ratio 0.1 keeps it near 0.25%: enough where the factors are
/// only a distribution of an exactly known total (hierarchical_leaf_factors.h), at 1/9 the cost.
double receiver_factor_by_distance(std::span<const Vec3> receiver, std::span<const Vec3> source, double centroid_ratio,
                                   int* point_count = nullptr);

}  // namespace hrad
