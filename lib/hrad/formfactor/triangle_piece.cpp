#include "hrad/formfactor/triangle_piece.h"

#include "hrad/geometry/polygon.h"

namespace hrad::detail {

TrianglePiece make_triangle_piece(const Vec3& a, const Vec3& b, const Vec3& c) {
  TrianglePiece t{{a, b, c}, (a + b + c) / 3.0, 0.0, 0.5 * (b - a).cross(c - a).norm()};
  for (const Vec3& v : t.v) t.radius = std::max(t.radius, (v - t.centre).norm());
  return t;
}

std::array<TrianglePiece, 2> bisect(const TrianglePiece& t) {
  int k = 0;
  double longest = -1.0;
  for (int i = 0; i < 3; ++i) {
    const double l = (t.v[(i + 1) % 3] - t.v[i]).squaredNorm();
    if (l > longest) longest = l, k = i;
  }
  const Vec3& a = t.v[k];
  const Vec3& b = t.v[(k + 1) % 3];
  const Vec3& c = t.v[(k + 2) % 3];
  const Vec3 m = 0.5 * (a + b);
  return {make_triangle_piece(a, m, c), make_triangle_piece(m, b, c)};
}

std::vector<TrianglePiece> triangle_pieces(std::span<const Vec3> p, const Vec3& normal) {
  std::vector<TrianglePiece> out;
  if (is_convex(p, normal)) {
    for (std::size_t i = 1; i + 1 < p.size(); ++i) out.push_back(make_triangle_piece(p[0], p[i], p[i + 1]));
  } else {
    for (const auto& t : triangulate(p, normal)) out.push_back(make_triangle_piece(p[t[0]], p[t[1]], p[t[2]]));
  }
  return out;
}

}  // namespace hrad::detail
