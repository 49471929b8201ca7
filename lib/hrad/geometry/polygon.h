// Planar polygons in 3D, in plain double precision (no CGAL here: exact predicates live in
// the visibility and effects translation units).
#pragma once

#include <array>
#include <span>
#include <utility>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

/// Newell's normal: the vector area of the polygon, |n| = 2 * area for any simple polygon,
/// pointing to the side its vertex order runs counter-clockwise (right-hand rule).
/// (Sutherland, Sproull & Schumacker 1974; robust for non-planar input.)
Vec3 newell_normal(std::span<const Vec3> polygon);

/// Area of a planar polygon (half the length of the Newell vector).
double polygon_area(std::span<const Vec3> polygon);

/// Area-weighted centroid of a planar polygon.
Vec3 polygon_centroid(std::span<const Vec3> polygon);

/// Largest distance of a vertex from the plane through the vertex mean with normal `unit_normal`.
double planarity_deviation(std::span<const Vec3> polygon, const Vec3& unit_normal);

/// Largest distance between two vertices.
double polygon_diameter(std::span<const Vec3> polygon);

/// The mean of the vertices and the largest distance from it: a bounding sphere (not the smallest).
std::pair<Vec3, double> vertex_sphere(std::span<const Vec3> polygon);

/// True if the planar polygon is strictly convex (no reflex vertex) seen along `unit_normal`.
/// Collinear consecutive vertices count as convex.
bool is_convex(std::span<const Vec3> polygon, const Vec3& unit_normal);

/// Ear-clipping triangulation of a simple planar polygon (Meisters 1975), vertex indices into
/// `polygon`, each triangle counter-clockwise about `unit_normal`.
std::vector<std::array<int, 3>> triangulate(std::span<const Vec3> polygon, const Vec3& unit_normal);

/// An orthonormal basis (u, v) of the plane with normal `unit_normal`; (u, v, n) is right-handed.
std::array<Vec3, 2> plane_basis(const Vec3& unit_normal);

}  // namespace hrad
