// point_to_polygon() has a path of its own for quads (the normal from the diagonals, an unrolled
// contour sum); polygons of other sizes, and those above 16 vertices (on the heap), take the general
// one. A repeated vertex adds an edge of length 0, whose term is 0, so the quad given with a vertex
// repeated must give the same factor through the general path: planar and slightly non-planar quads,
// whole or clipped by the tangent plane, near, far and grazing. The plain sum must agree to rounding;
// where it is refined, the general path's triangulation has a degenerate triangle more, so the two
// agree to the refinement's accuracy (1e-13).
#include <gtest/gtest.h>

#include <random>

#include "hrad/formfactor/point_to_polygon.h"
#include "test_geometry.h"

namespace hrad::test {
namespace {

Polygon with_first_vertex_repeated(const Polygon& quad, int copies) {
  Polygon p(static_cast<std::size_t>(copies), quad[0]);
  p.insert(p.end(), quad.begin(), quad.end());
  return p;
}

TEST(PointToQuad, SameFactorsAsTheGeneralPath) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int nonzero = 0, clipped = 0, refined = 0;
  for (int i = 0; i < 4000; ++i) {
    // A random convex quad of size ~1 in a random plane at distance ~1..1e3 from the element.
    const double distance = std::pow(10.0, 1.5 * (u(rng) + 1.0));
    Polygon quad = rectangle(Vec3(-0.5, -0.5, 0), Vec3(1.0 + 0.5 * u(rng), 0.3 * u(rng), 0),
                             Vec3(0.3 * u(rng), 1.0 + 0.5 * u(rng), 0));
    quad[2] += Vec3(0.2 * u(rng), 0.2 * u(rng), 0);
    if (i % 3 == 1)  // slightly non-planar
      for (Vec3& v : quad) v.z() += 1e-9 * u(rng);
    quad = moved(quad, random_rotation(rng), distance * random_unit(rng));
    Vec3 n = random_unit(rng);
    if (i % 5 == 2) {  // grazing: the quad's centre almost in the tangent plane
      const Vec3 d = quad[0].normalized();
      n = (n - n.dot(d) * d).normalized() + 1e-4 * u(rng) * d;
      n.normalize();
    }
    const Vec3 x = Vec3::Zero();
    clipped += (quad[0].dot(n) > 0) != (quad[2].dot(n) > 0);
    const double plain_f = point_to_polygon(x, n, quad, kLambertSumOnly);
    for (double rel_tol : {kPointToPolygonTolerance, kLambertSumOnly}) {
      const double quad_f = point_to_polygon(x, n, quad, rel_tol);
      const double general_f = point_to_polygon(x, n, with_first_vertex_repeated(quad, 1), rel_tol);
      const double heap_f = point_to_polygon(x, n, with_first_vertex_repeated(quad, 17), rel_tol);
      nonzero += quad_f > 0.0;
      const bool is_refined = quad_f != plain_f;
      refined += is_refined;
      const double tol = (is_refined ? kPointToPolygonTolerance : 1e-15) * quad_f;
      ASSERT_LE(std::abs(general_f - quad_f), tol) << i << " rel_tol " << rel_tol;
      ASSERT_LE(std::abs(heap_f - quad_f), tol) << i << " rel_tol " << rel_tol;
    }
  }
  // The cases above must all occur.
  EXPECT_GT(nonzero, 2000);
  EXPECT_GT(clipped, 200);
  EXPECT_GT(refined, 100);
}

}  // namespace
}  // namespace hrad::test
