// Convex polygons in a plane, cut by other convex polygons: the pieces a face keeps when another
// lies flush on it or a hair in front of it (io/flush_faces.h, io/near_faces.h).
#pragma once

#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

using Point2 = Eigen::Vector2d;
using Polygon2 = std::vector<Point2>;

/// The area of `p`, positive when counter-clockwise (the shoelace formula).
double signed_area(const Polygon2& p);

/// The part of the convex polygon `poly` to the left of the directed line a -> b (`left`) or to its
/// right (Sutherland & Hodgman 1974, one clipping plane).
Polygon2 clip(const Polygon2& poly, const Point2& a, const Point2& b, bool left);

/// `poly` less the convex polygon `cutter` (counter-clockwise), as disjoint convex pieces: the k-th
/// lies outside cutter's k-th edge and inside its edges before k.
std::vector<Polygon2> subtract(const Polygon2& poly, const Polygon2& cutter);

/// `poly`'s part inside the convex polygon `cutter` (counter-clockwise).
Polygon2 intersect(const Polygon2& poly, const Polygon2& cutter);

/// Cutters that tile a convex polygon between them (a picture's two triangles) merged into it, so
/// that a face is cut by that polygon's edges only, into fewer and fatter pieces: two convex
/// polygons that do not overlap tile their hull exactly when their areas add up to its (within `tol`).
std::vector<Polygon2> merged(std::vector<Polygon2> cutters, double tol);

/// A patch's plane with 2D coordinates: origin at its first vertex, axes e1 along its first edge and
/// e2 = n x e1 (counter-clockwise seen from the front stays counter-clockwise).
struct PatchFrame {
  explicit PatchFrame(const Patch& p);
  Point2 to2(const Vec3& x) const { return {(x - origin).dot(e1), (x - origin).dot(e2)}; }
  Vec3 to3(const Point2& u) const { return origin + u.x() * e1 + u.y() * e2; }
  /// A polygon's vertices in this frame, counter-clockwise.
  Polygon2 counter_clockwise(const std::vector<Vec3>& vertices) const;
  Vec3 origin, e1, e2;
};

/// Appends the convex `pieces` of patch `p` (in `frame`) to `out` as patches of p's face and material:
/// triangles and convex quadrilaterals (a piece of more corners as a fan of triangles); repeated and
/// collinear corners (within 1e-9 of `size`) are dropped, and so are pieces thinner than 1e-6 of
/// `size`. Returns the area appended.
double append_pieces(const Patch& p, const PatchFrame& frame, const std::vector<Polygon2>& pieces, double size,
                     std::vector<Patch>* out);

/// Appends patch `p` to `out` cut along the outlines of the patches `cutters` (lying in p's plane or
/// projected onto it; cutters that tile a convex polygon merged first): without `keep_inside` what
/// they cover is dropped (io/flush_faces.h), with it kept as pieces of its own (io/near_faces.h). The
/// pieces are patches of p's face and material: triangles and convex quadrilaterals (a piece of more
/// corners as a fan of triangles); repeated and collinear corners (within 1e-9 of `size`) are
/// dropped, and so are pieces thinner than 1e-6 of `size` (a cutter's edge along one of p's, up to
/// rounding). Returns the area appended.
double append_cut(const Patch& p, const std::vector<const Patch*>& cutters, bool keep_inside, double size,
                  std::vector<Patch>* out);

/// `patches` with each patch i cut by append_cut() along the patches `cutters[i]` (indices into
/// `patches`), a patch without cutters as it is; `removed` (when not null) gets the area dropped.
std::vector<Patch> cut_patches(const std::vector<Patch>& patches, const std::vector<std::vector<int>>& cutters,
                               bool keep_inside, double size, double* removed = nullptr);

}  // namespace hrad
