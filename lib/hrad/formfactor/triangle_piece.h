// Triangles that the refinement of the kernels bisects (longest edge first).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "hrad/core/types.h"

namespace hrad::detail {

struct TrianglePiece {
  std::array<Vec3, 3> v;  // counter-clockwise about the polygon's normal
  Vec3 centre;            // vertex mean
  double radius;          // largest vertex distance from the centre
  double area;
};

TrianglePiece make_triangle_piece(const Vec3& a, const Vec3& b, const Vec3& c);

/// Longest-edge bisection (Rivara 1984), keeping the vertex order.
std::array<TrianglePiece, 2> bisect(const TrianglePiece& t);

/// Fan triangulation of a convex polygon, ear clipping otherwise.
std::vector<TrianglePiece> triangle_pieces(std::span<const Vec3> polygon, const Vec3& unit_normal);

}  // namespace hrad::detail
