// Inputs the fuzzers found (tests/fuzz/), kept as regression tests.
#include <gtest/gtest.h>

#include <vector>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/quadrature_form_factor.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

// polygon_pair_fuzzer, corpus file regression_partly_shared_edge.bin: a unit square and a tilted
// parallelogram whose edges overlap along part of y = 1, x in [0, 1]. A Gauss order computed as
// ceil(inf) was cast to int (undefined behaviour reported by UBSan).
TEST(FuzzRegression, PartlySharedCollinearEdge) {
  const std::vector<Vec3> from = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<Vec3> to = {{0, 1, 0}, {2, 1, 0}, {6, 2, 1}, {4, 2, 1}};
  const PairFormFactor f = polygon_to_polygon(from, to);
  ASSERT_TRUE(std::isfinite(f.from_to));
  ASSERT_TRUE(std::isfinite(f.to_from));
  EXPECT_GE(f.from_to, 0.0);
  EXPECT_LE(f.from_to, 1.0);
  EXPECT_NEAR(polygon_area(from) * f.from_to, polygon_area(to) * f.to_from, 1e-14);
  const QuadratureFormFactor q = quadrature_form_factor(from, to, 1e-8);
  EXPECT_NEAR(f.from_to, q.value, 1e-6 + 10 * q.error_estimate);
}

// formfactor_json_fuzzer, corpus file regression_huge_quad.json: a unit right triangle
// (with a repeated vertex) under a quad 1 wide and 1.1e12 long, 1 above. The contour sum is rounding
// noise at that aspect ratio and the refinement ran out of pieces; the noise (F = 4.8e6) was returned.
// The part of the quad beyond y = 1e3 adds less than 1e-3 to the factor: compare with the quad cut there.
TEST(FuzzRegression, HugeQuadAboveATriangle) {
  const std::vector<Vec3> from = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vec3> to = {{0, 0, 1}, {0, 1112244074723.0, 1}, {1, 1, 1}, {1, 0, 1}};
  const std::vector<Vec3> cut = {{0, 0, 1}, {0, 1e3, 1}, {1, 1, 1}, {1, 0, 1}};
  const PairFormFactor f = polygon_to_polygon(from, to), g = polygon_to_polygon(from, cut);
  ASSERT_TRUE(std::isfinite(f.from_to) && std::isfinite(f.to_from));
  EXPECT_GE(f.from_to, 0.0);
  EXPECT_LE(f.from_to, 1.0);
  EXPECT_NEAR(f.from_to, g.from_to, 1e-3);
}

}  // namespace
}  // namespace hrad
