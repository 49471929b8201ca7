// A baseboard standing on a floor, with linear elements at a coarse --aeps (RenderPark's office2 has
// one along each wall): the floor's elements touch it along the contact, where the kernel between
// them is singular, so the quadrature over a floor element's points overshoots the link's exact
// mean many times. Moved by the whole difference, the floor element's send shape went negative over
// its far side, the link weighed the floor's radiosity there negatively, and office2's baseboard
// came out 36% dark. Such links send by their point factors scaled to the link's mean
// (refinement_oracle.cpp, kSendScaleRatio).
// The judge is the Monte Carlo ruler (reference.h), which shares no kernel with the solver.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/reference.h"
#include "hrad/solvers/solve.h"
#include "support/ruler_error.h"

namespace hrad {
namespace {

constexpr double kLength = 5.5, kHeight = 0.08;

struct Room {
  Scene scene;
  int baseboard = -1;  ///< its face (one patch)
};

// A room [0, 4] x [0, 2.8] x [0, 5.5] (y up, reflectance 0.6) whose x = 0 wall is a 5.5 m x 8 cm
// baseboard (reflectance 0.65) under the wall, lit by a 60 cm square lamp facing down 20 cm under
// the ceiling at (x, z) = `lamp`: the floor beside the baseboard is bright near the lamp and dim
// along the rest of it.
Room baseboard_room(Vec3 lamp) {
  Room r;
  Scene& s = r.scene;
  s.materials = {test::material(Rgb::Constant(0.6), Rgb::Zero(), "wall"),
                 test::material(Rgb::Constant(0.65), Rgb::Zero(), "baseboard"),
                 test::material(Rgb::Zero(), Rgb::Constant(40.0), "light")};
  const double a = 4.0, b = 2.8, c = kLength;
  const Vec3 centre(a / 2, b / 2, c / 2);
  auto wall = [&](std::vector<Vec3> v, int m) { test::add_polygon(s, v, centre - polygon_centroid(v), m); };
  wall({{0, 0, 0}, {a, 0, 0}, {a, 0, c}, {0, 0, c}}, 0);
  wall({{0, b, 0}, {a, b, 0}, {a, b, c}, {0, b, c}}, 0);
  r.baseboard = static_cast<int>(s.faces.size());
  wall({{0, 0, 0}, {0, kHeight, 0}, {0, kHeight, c}, {0, 0, c}}, 1);
  wall({{0, kHeight, 0}, {0, b, 0}, {0, b, c}, {0, kHeight, c}}, 0);
  wall({{a, 0, 0}, {a, b, 0}, {a, b, c}, {a, 0, c}}, 0);
  wall({{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}}, 0);
  wall({{0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}}, 0);
  const double y = b - 0.2, h = 0.3;
  test::add_polygon(s,
                    {{lamp.x() - h, y, lamp.z() - h},
                     {lamp.x() + h, y, lamp.z() - h},
                     {lamp.x() + h, y, lamp.z() + h},
                     {lamp.x() - h, y, lamp.z() + h}},
                    Vec3(0, -1, 0), 2);
  return r;
}

// The ruler's mean radiosity of the baseboard: point estimates at the midpoints of a 64 x 2 grid
// over it (4096 paths each), with its standard error.
std::pair<double, double> ruler_baseboard(const Room& r) {
  std::vector<ProbePoint> points;
  for (int i = 0; i < 64; ++i)
    for (int k = 0; k < 2; ++k)
      points.push_back({Vec3(0.0, (k + 0.5) / 2 * kHeight, (i + 0.5) / 64 * kLength), Vec3(1, 0, 0)});
  return test::ruler_mean(r.scene, points, r.baseboard, 4096);
}

// Guarantee: with linear elements at --aeps total/50, where the floor's elements (5.5 m^2) touch the
// baseboard whole, the baseboard's mean radiosity is within 4 of the ruler's standard errors plus
// 6% of it, for lamps at two places along the room.
TEST(ContactSend, BaseboardOnACoarseLinearFloorMatchesTheRuler) {
  for (const Vec3& lamp : {Vec3(0.8, 0.0, 1.2), Vec3(2.0, 0.0, 3.5)}) {
    const Room r = baseboard_room(lamp);
    SCOPED_TRACE(::testing::Message() << "lamp at x " << lamp.x() << ", z " << lamp.z());
    const auto [truth, se] = ruler_baseboard(r);
    ASSERT_GT(truth, 0.0);
    SolveOptions o;
    o.method = Method::kHierarchical;
    o.basis = Basis::kLinear;
    o.aeps = r.scene.total_area() / 50.0;
    Solution sol;
    const SolveSummary sum = solve(r.scene, o, &sol);
    ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
    const double b = sol.patch_radiosity[static_cast<std::size_t>(r.baseboard)][0];
    EXPECT_NEAR(b, truth, 4.0 * se + 0.06 * truth);
    std::printf("lamp at x %g, z %g: baseboard %.4f +- %.4f (ruler), linear at total/50 %+.1f%%\n", lamp.x(), lamp.z(),
                truth, se, 100 * (b / truth - 1));
  }
}

}  // namespace
}  // namespace hrad
