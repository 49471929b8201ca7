// The shaft predicates (hrad/visibility/shaft_hull.h's Ops) on CGAL's Epick points, for the tests
// and benchmarks that compare the shaft's facets with CGAL's convex_hull_3. Header only: its users
// link CGAL::CGAL themselves (hrad_test_support does not).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace hrad::test {

struct EpickShaftOps {
  using P = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  static CGAL::Orientation orient(const P& a, const P& b, const P& c, const P& d) {
    return CGAL::orientation(a, b, c, d);
  }
  static bool collinear(const P& a, const P& b, const P& c) { return CGAL::collinear(a, b, c); }
};

}  // namespace hrad::test
