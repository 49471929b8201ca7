// The reference's ray caster: first hits, fronts and backs, rays leaving a surface, walls of zero
// thickness, blocked segments; and rays counted as cast.
#include <gtest/gtest.h>

#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/embree_scene.h"

namespace hrad::test {
namespace {

Scene unit_box() { return make_box(1.0, 1.0, 1.0, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}); }

// make_box's walls: 0 floor (y = 0), 1 ceiling, 2 x = 0, 3 x = 1, 4 z = 0, 5 z = 1, all facing in.
TEST(ReferenceEmbreeScene, FirstHitIsTheWallAheadOnItsPlane) {
  const Scene scene = unit_box();
  const EmbreeScene rays(scene);
  RayCounts counts;
  const RayHit hit = rays.closest_hit(Vec3(0.5, 0.3, 0.2), Vec3(1, 0.1, 0.05).normalized(), counts);
  EXPECT_EQ(hit.patch, 3);
  EXPECT_TRUE(hit.front);
  EXPECT_NEAR(hit.point.x(), 1.0, 1e-15);  // projected onto the plane in double precision
  const Vec3 expected = Vec3(0.5, 0.3, 0.2) + 0.5 * Vec3(1, 0.1, 0.05);
  EXPECT_NEAR((hit.point - expected).norm(), 0.0, 1e-6);  // Embree's single-precision distance
  EXPECT_EQ(counts.closest_hit, 1u);
  EXPECT_EQ(counts.shadow, 0u);
}

TEST(ReferenceEmbreeScene, RaysLeavingAWallIgnoreItsPlane) {
  const Scene scene = unit_box();
  const EmbreeScene rays(scene);
  RayCounts counts;
  // From the floor, straight up and at a grazing angle: the ceiling and the x = 1 wall, not the floor.
  EXPECT_EQ(rays.closest_hit(Vec3(0.5, 0.0, 0.5), Vec3::UnitY(), counts).patch, 1);
  EXPECT_EQ(rays.closest_hit(Vec3(0.5, 0.0, 0.5), Vec3(1, 1e-9, 0).normalized(), counts).patch, 3);
  // A segment from the floor to the ceiling is not blocked by either end's wall.
  EXPECT_FALSE(rays.blocked(Vec3(0.2, 0.0, 0.3), Vec3(0.8, 1.0, 0.6), counts));
  EXPECT_EQ(counts.shadow, 1u);
}

TEST(ReferenceEmbreeScene, BlocksAndBacks) {
  Scene scene = unit_box();
  add_block(scene, 0.4, 0.6, 0.0, 0.5, 0.4, 0.6, 0);  // a block on the floor, faces outward
  const EmbreeScene rays(scene);
  RayCounts counts;
  EXPECT_TRUE(rays.blocked(Vec3(0.1, 0.0, 0.5), Vec3(0.9, 0.0, 0.5), counts));  // along the floor through the block
  EXPECT_FALSE(rays.blocked(Vec3(0.1, 0.0, 0.5), Vec3(0.1, 1.0, 0.5), counts));
  // From inside the block, the block's faces are backs.
  const RayHit inside = rays.closest_hit(Vec3(0.5, 0.25, 0.5), Vec3::UnitX(), counts);
  EXPECT_GE(inside.patch, 6);
  EXPECT_FALSE(inside.front);
}

// A wall of zero thickness: two coincident patches back to back, each tessellated differently.
// From either side the ray meets the patch that faces it, whichever Embree reports first.
TEST(ReferenceEmbreeScene, ZeroThicknessWallShowsTheFrontFacingTheRay) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, Vec3::UnitZ(), 0);  // faces +z
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, -Vec3::UnitZ(), 0);            // faces -z, half
  add_polygon(s, {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, -Vec3::UnitZ(), 0);            // faces -z, other half
  const EmbreeScene rays(s);
  RayCounts counts;
  for (const Vec3& target : {Vec3(0.3, 0.2, 0), Vec3(0.8, 0.7, 0), Vec3(0.5, 0.5, 0)}) {
    const RayHit from_above = rays.closest_hit(target + Vec3(0.1, 0, 1), Vec3(-0.1, 0, -1).normalized(), counts);
    EXPECT_EQ(from_above.patch, 0);
    EXPECT_TRUE(from_above.front);
    const RayHit from_below = rays.closest_hit(target + Vec3(0, 0.1, -1), Vec3(0, -0.1, 1).normalized(), counts);
    EXPECT_GE(from_below.patch, 1);
    EXPECT_TRUE(from_below.front);
    // Leaving the wall upward from a point on it: nothing above.
    EXPECT_EQ(rays.closest_hit(target, Vec3::UnitZ(), counts).patch, -1);
  }
}

}  // namespace
}  // namespace hrad::test
