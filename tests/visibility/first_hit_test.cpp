// Visibility::first_hit(): the nearest patch along a ray and its side, checked by the shares of
// cosine-distributed rays that reach each face of a unit cube (the view factors of Howell's
// catalogue, C-11 opposite and C-14 adjacent), by a cube with a face missing or turned outwards,
// and by the back-to-back twin of the ray's own patch.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "../formfactor/howell.h"
#include "hrad/visibility/visibility.h"
#include "test_scenes.h"

namespace hrad {
namespace {

using test::add_patch;
using test::empty_scene;
using test::howell_c11;
using test::howell_c14;
using test::square_z;

// The unit cube's six faces facing in: floor 0, ceiling 1, then four walls. `ceiling`: 1 facing
// in, -1 facing out, 0 left out.
Scene cube(int ceiling) {
  Scene s = empty_scene();
  add_patch(s, square_z(0, 1, 0, 1, 0, true));
  if (ceiling != 0) add_patch(s, square_z(0, 1, 0, 1, 1, ceiling < 0));
  add_patch(s, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});  // y = 0, facing +y
  add_patch(s, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}});  // y = 1, facing -y
  add_patch(s, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});  // x = 0, facing +x
  add_patch(s, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}});  // x = 1, facing -x
  return s;
}

struct Shares {
  int rays = 0, ceiling = 0, walls = 0, nothing = 0, backs = 0, own = 0;
};

// Cosine-distributed rays from uniform points of the floor (patch 0).
Shares cast_from_floor(const Scene& s, int rays, int ceiling_patch) {
  const auto v = make_visibility(s);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Shares out;
  for (int k = 0; k < rays; ++k) {
    const Vec3 x{u(rng), u(rng), 0.0};
    const double r2 = u(rng), phi = 2.0 * std::numbers::pi * u(rng), r = std::sqrt(r2);
    const Vec3 d{r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - r2)};
    const RayHit hit = v->first_hit(x, 0, d);
    ++out.rays;
    if (hit.patch < 0) {
      ++out.nothing;
      continue;
    }
    if (hit.patch == 0) ++out.own;
    if (!hit.front) ++out.backs;
    (hit.patch == ceiling_patch ? out.ceiling : out.walls)++;
  }
  EXPECT_EQ(v->counters().segment_queries.load(), static_cast<std::uint64_t>(rays));
  return out;
}

// Within 4 standard errors of a binomial share.
void expect_share(int count, int rays, double share) {
  const double se = std::sqrt(share * (1.0 - share) / rays);
  EXPECT_NEAR(static_cast<double>(count) / rays, share, 4.0 * se) << count << " of " << rays;
}

constexpr int kRays = 40000;

TEST(FirstHit, RaysFromACubesFloorReachItsFacesByTheirViewFactors) {
  const Shares s = cast_from_floor(cube(1), kRays, 1);
  EXPECT_EQ(s.nothing, 0);
  EXPECT_EQ(s.backs, 0);
  EXPECT_EQ(s.own, 0);
  expect_share(s.ceiling, kRays, howell_c11(1, 1, 1));
  expect_share(s.walls, kRays, 4.0 * howell_c14(1, 1, 1));
}

TEST(FirstHit, AMissingFaceLetsItsViewFactorLeave) {
  const Shares s = cast_from_floor(cube(0), kRays, -2);
  EXPECT_EQ(s.backs, 0);
  expect_share(s.nothing, kRays, howell_c11(1, 1, 1));
  EXPECT_EQ(s.nothing + s.walls, kRays);
}

TEST(FirstHit, AFaceTurnedOutwardsIsMetFromBehind) {
  const Shares s = cast_from_floor(cube(-1), kRays, 1);
  EXPECT_EQ(s.nothing, 0);
  EXPECT_EQ(s.backs, s.ceiling);
  expect_share(s.ceiling, kRays, howell_c11(1, 1, 1));
}

TEST(FirstHit, TheNearestOfStackedPatchesAndNeverTheOwnPatchsTwin) {
  Scene s = empty_scene();
  const int floor = add_patch(s, square_z(0, 1, 0, 1, 0, true));
  const int twin = add_patch(s, square_z(0, 1, 0, 1, 0, false));  // back to back with the floor
  const int high = add_patch(s, square_z(-1, 2, -1, 2, 2, false));
  const int low = add_patch(s, square_z(0.25, 0.75, 0.25, 0.75, 1, false));
  const auto v = make_visibility(s);
  const Vec3 up{0, 0, 1};
  RayHit hit = v->first_hit({0.5, 0.5, 0}, floor, up);
  EXPECT_EQ(hit.patch, low);
  EXPECT_TRUE(hit.front);
  hit = v->first_hit({0.1, 0.1, 0}, floor, up);
  EXPECT_EQ(hit.patch, high);
  EXPECT_TRUE(hit.front);
  // Grazing and steep rays from the floor pass its twin, which lies in the plane they leave.
  for (const Vec3& d : {Vec3{1, 0, 1e-9}, Vec3{0.6, 0.8, 1e-6}, Vec3{0, 0, 1}}) {
    hit = v->first_hit({0.5, 0.5, 0}, floor, d.normalized());
    EXPECT_NE(hit.patch, twin);
  }
  // Downwards from the top plate's underside: the low plate's back, and where the floor and its
  // twin lie at one distance, the floor's front.
  hit = v->first_hit({0.5, 0.5, 2}, high, -up);
  EXPECT_EQ(hit.patch, low);
  EXPECT_FALSE(hit.front);
  hit = v->first_hit({0.1, 0.1, 2}, high, -up);
  EXPECT_EQ(hit.patch, floor);
  EXPECT_TRUE(hit.front);
  hit = v->first_hit({5, 5, 2}, high, -up);
  EXPECT_EQ(hit.patch, -1);
}

}  // namespace
}  // namespace hrad
