// The one-sided limit of the point-to-polygon factor (point_to_polygon_limit()): equal to
// point_to_polygon() in front of the polygon, and to the factor approached from inside the
// element where the point lies in the polygon's plane (a shared edge, a shared vertex, a contact).
#include "hrad/formfactor/point_to_polygon_limit.h"

#include <gtest/gtest.h>

#include <vector>

#include "hrad/formfactor/point_to_polygon.h"

namespace hrad {
namespace {

// The unit square in the plane z = 0 (front +z) and the wall x = 0 over it (front +x): they share
// the edge from (0, 0, 0) to (0, 1, 0).
const std::vector<Vec3> kWall = {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}};
const Vec3 kFloorNormal(0, 0, 1);

TEST(PointToPolygonLimit, OnASharedEdgeThePerpendicularWallFillsHalfTheHemisphere) {
  // From a point inside the shared edge, approached from the floor (d = +x), the wall's plane
  // cuts the hemisphere in half and the wall, seen edge-on, fills that half in the limit: 1/2
  // whatever its size (Lambert's sum: only the edge through x counts, with the angle pi and the
  // plane spanned by the edge and d).
  for (const double y : {0.1, 0.5, 0.9}) {
    const Vec3 x(0, y, 0);
    EXPECT_NEAR(point_to_polygon_limit(x, kFloorNormal, Vec3(1, 0, 0), kWall), 0.5, 1e-14) << y;
    EXPECT_EQ(point_to_polygon(x, kFloorNormal, kWall), 0.0);  // in the wall's plane: 0 by convention
  }
}

TEST(PointToPolygonLimit, IsTheLimitOfTheFactorApproachedFromInside) {
  // The limit agrees with the factor at points approaching it from inside the floor: at distance
  // t the factor differs from its limit by O(t log t) on an edge (the wall's near field), so 1e-9
  // away it is within 1e-7.
  const Vec3 d = Vec3(1, 0.3, 0).normalized();
  for (const Vec3& x : {Vec3(0, 0.5, 0), Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1.5, 0), Vec3(0, -0.2, 0)}) {
    const double limit = point_to_polygon_limit(x, kFloorNormal, d, kWall);
    const double near = point_to_polygon(x + 1e-9 * d, kFloorNormal, kWall);
    EXPECT_NEAR(limit, near, 1e-7) << x.transpose();
  }
}

TEST(PointToPolygonLimit, InFrontOfThePolygonItIsThePointFactor) {
  // Away from the polygon's plane nothing changes (bit for bit).
  const Vec3 x(0.4, 0.3, 0.0), d(1, 0, 0);
  const std::vector<Vec3> tilted = {{0, 0, 0.2}, {0, 1, 0.2}, {-0.2, 1, 1}, {-0.2, 0, 1}};
  EXPECT_EQ(point_to_polygon_limit(x, kFloorNormal, d, tilted), point_to_polygon(x, kFloorNormal, tilted));
}

TEST(PointToPolygonLimit, ApproachedFromBehindThePolygonsPlaneItIsZero) {
  // d pointing to the wall's back side: the points x + t d never see the wall's front.
  EXPECT_EQ(point_to_polygon_limit(Vec3(0, 0.5, 0), kFloorNormal, Vec3(-1, 0, 0), kWall), 0.0);
}

}  // namespace
}  // namespace hrad
