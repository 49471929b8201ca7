// Pair classification (shaft culling with exact predicates) and sampled pair visibility.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hrad/visibility/visibility.h"
#include "test_scenes.h"

namespace hrad {
namespace {

using test::add_patch;
using test::empty_scene;
using test::square_z;

const std::vector<Vec3> kFloor = square_z(0, 1, 0, 1, 0, true);
const std::vector<Vec3> kCeiling = square_z(0, 1, 0, 1, 1, false);

TEST(Classify, FacingPairsWithoutOccluderAreFullyVisible) {
  Scene s = empty_scene();
  const int a = add_patch(s, kFloor), b = add_patch(s, kCeiling);
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(kFloor, a, kCeiling, b), PairClass::kFullyVisible);
  const VisibilityEstimate e = v->estimate(kFloor, a, kCeiling, b, 16, 1);
  EXPECT_EQ(e.fraction, 1.0);
  EXPECT_EQ(e.error, 0.0);
  EXPECT_EQ(v->counters().segment_queries.load(), 0u);  // settled without rays
  EXPECT_EQ(v->counters().pairs_visible.load(), 2u);
  EXPECT_EQ(v->counters().pair_queries.load(), 2u);
}

TEST(Classify, FacingAway) {
  Scene s = empty_scene();
  const auto up_at_1 = square_z(0, 1, 0, 1, 1, true);  // B's back toward the floor
  const auto up_at_2 = square_z(0, 1, 0, 1, 2, true);
  const auto side = std::vector<Vec3>{{2, 0, 0}, {2, 1, 0}, {2, 1, 1}, {2, 0, 1}};  // x = 2, front +x: away
  const auto coplanar = square_z(2, 3, 0, 1, 0, true);
  add_patch(s, kFloor);
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(kFloor, 0, up_at_1, -1), PairClass::kFacingAway);
  EXPECT_EQ(v->classify(up_at_2, -1, kCeiling, -1), PairClass::kFacingAway);  // the floor is behind up_at_2
  EXPECT_EQ(v->classify(kFloor, 0, side, -1), PairClass::kFacingAway);
  EXPECT_EQ(v->classify(kFloor, 0, coplanar, -1), PairClass::kFacingAway);
  EXPECT_EQ(v->estimate(kFloor, 0, up_at_1, -1, 16, 1).fraction, 0.0);
  EXPECT_EQ(v->counters().pairs_facing_away.load(), 5u);
}

TEST(Classify, LargeOccluderHidesFully) {
  Scene s = empty_scene();
  const int a = add_patch(s, kFloor), b = add_patch(s, kCeiling);
  add_patch(s, square_z(-1, 2, -1, 2, 0.5, true));  // one planar quad patch (two triangles inside)
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(kFloor, a, kCeiling, b), PairClass::kFullyHidden);
  const VisibilityEstimate e = v->estimate(kFloor, a, kCeiling, b, 16, 1);
  EXPECT_EQ(e.fraction, 0.0);
  EXPECT_EQ(e.error, 0.0);
}

TEST(Classify, OccluderMadeOfTwoPatchesIsPartialButSamplesAllBlocked) {
  // Two triangle patches together cover the pair's shaft; neither alone does, so the pair is
  // partial for the classifier and sampling must find every ray blocked (the shared diagonal
  // included).
  Scene s = empty_scene();
  const int a = add_patch(s, kFloor), b = add_patch(s, kCeiling);
  add_patch(s, {{-1, -1, 0.5}, {2, -1, 0.5}, {2, 2, 0.5}});
  add_patch(s, {{-1, -1, 0.5}, {2, 2, 0.5}, {-1, 2, 0.5}});
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(kFloor, a, kCeiling, b), PairClass::kPartial);
  const VisibilityEstimate e = v->estimate(kFloor, a, kCeiling, b, 256, 3);
  EXPECT_EQ(e.fraction, 0.0);
  EXPECT_GT(e.error, 0.0);  // sampled: some doubt remains
  EXPECT_LT(e.error, 0.01);
}

TEST(Classify, WallsTouchingTheShaftDoNotMakeItPartial) {
  // A closed unit room: four walls touch the floor and the ceiling along their edges.
  Scene s = empty_scene();
  const int floor = add_patch(s, kFloor), ceiling = add_patch(s, kCeiling);
  add_patch(s, {{1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}});  // x = 1, front -x
  add_patch(s, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});  // x = 0, front +x
  add_patch(s, {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}});  // y = 0, front +y
  add_patch(s, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}});  // y = 1, front -y
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(kFloor, floor, kCeiling, ceiling), PairClass::kFullyVisible);
  // Corner elements: the floor element touches two walls, the ceiling element the other two.
  const auto fa = square_z(0.75, 1, 0, 0.25, 0, true), cb = square_z(0, 0.25, 0.75, 1, 1, false);
  EXPECT_EQ(v->classify(fa, floor, cb, ceiling), PairClass::kFullyVisible);
  // Floor element against a wall element that shares its edge (perpendicular neighbours). An
  // element is a part of its patch and faces the way the patch does.
  const std::vector<Vec3> wall_el{{1, 0.25, 0}, {1, 0.25, 0.25}, {1, 0.5, 0.25}, {1, 0.5, 0}};  // front -x
  EXPECT_EQ(v->classify(square_z(0.75, 1, 0.25, 0.5, 0, true), floor, wall_el, 2), PairClass::kFullyVisible);
}

TEST(Classify, OccludersBehindEitherPlaneAreIgnored) {
  // A block's side face (x = 1, front +x) and a ceiling reaching over the block: the block's top
  // lies in the hull of the pair but only behind the side face's plane, where no facing pair is.
  Scene s = empty_scene();
  const std::vector<Vec3> side{{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}};
  const auto ceiling = square_z(-2, 4, -2, 3, 3, false);
  const int is = add_patch(s, side), ic = add_patch(s, ceiling);
  add_patch(s, square_z(0, 1, 0, 1, 1, true));  // the block's top, sharing the side's top edge
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(side, is, ceiling, ic), PairClass::kFullyVisible);
  // Moved in front of the side face, the same occluder matters.
  Scene t = empty_scene();
  add_patch(t, side);
  add_patch(t, ceiling);
  add_patch(t, square_z(1.5, 2.5, 0, 1, 1.5, true));
  EXPECT_EQ(make_visibility(t)->classify(side, 0, ceiling, 1), PairClass::kPartial);
}

TEST(Classify, OccluderTouchingAShaftEdgeIsDecidedExactly) {
  // Floor and ceiling unit squares: the shaft is the unit cube. A triangle whose edge touches the
  // cube's vertical edge x = y = 1 at one point, and otherwise stays outside, straddles every
  // facet plane and its own plane separates nothing: the exact clipping settles it as visible.
  // Shifted by 2^-30 the edge cuts a sliver of the cube: partial.
  for (const double shift : {0.0, std::ldexp(1.0, -30)}) {
    Scene s = empty_scene();
    const int a = add_patch(s, kFloor), b = add_patch(s, kCeiling);
    add_patch(s, {{1.5 - shift, 0.5, 0.5}, {0.5 - shift, 1.5, 0.5}, {1.5, 1.5, 0.2}});
    VisibilityOptions exact;
    exact.exact_shaft_contacts = true;
    EXPECT_EQ(make_visibility(s, exact)->classify(kFloor, a, kCeiling, b),
              shift == 0.0 ? PairClass::kFullyVisible : PairClass::kPartial);
    // By default the contact is left to sampling.
    EXPECT_EQ(make_visibility(s)->classify(kFloor, a, kCeiling, b), PairClass::kPartial);
  }
}

TEST(Classify, OccluderInTheBoxButOutsideTheShaftIsIgnored) {
  Scene s = empty_scene();
  const auto b = square_z(2, 3, 0, 1, 1, false);
  const int ia = add_patch(s, kFloor), ib = add_patch(s, b);
  add_patch(s, {{2.4, 0.4, 0.2}, {2.6, 0.4, 0.2}, {2.5, 0.6, 0.2}});
  const auto v = make_visibility(s);
  EXPECT_EQ(v->classify(kFloor, ia, b, ib), PairClass::kFullyVisible);
}

// Classification agrees with rays: fully visible pairs have no blocked ray, fully hidden pairs no
// free one, and a pair with both kinds of rays is partial. Random triangles, random occluders.
TEST(Classify, AgreesWithSampledRaysOnRandomScenes) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int counts[4] = {0, 0, 0, 0};
  for (int scene_id = 0; scene_id < 40; ++scene_id) {
    Scene s = empty_scene();
    auto rv = [&](double lo, double hi) {
      return Vec3(lo + (hi - lo) * u(rng), lo + (hi - lo) * u(rng), lo + (hi - lo) * u(rng));
    };
    // A: triangle near z = 0 facing up; B: triangle near z = 1 facing down; occluders between.
    std::vector<Vec3> a{rv(0, 1), rv(0, 1), rv(0, 1)}, b{rv(0, 1), rv(0, 1), rv(0, 1)};
    for (Vec3& p : a) p.z() *= 0.1;
    for (Vec3& p : b) p.z() = 1.0 - 0.1 * p.z();
    if ((a[1] - a[0]).cross(a[2] - a[0]).z() < 0) std::swap(a[1], a[2]);
    if ((b[1] - b[0]).cross(b[2] - b[0]).z() > 0) std::swap(b[1], b[2]);
    const int ia = add_patch(s, a), ib = add_patch(s, b);
    const int occluders = 1 + scene_id % 4;
    for (int k = 0; k < occluders; ++k) {
      const Vec3 c = rv(0, 1);
      const double r = 0.1 + 1.4 * u(rng);
      add_patch(
          s, {Vec3(c.x() - r, c.y() - r, 0.2 + 0.6 * c.z()),
              Vec3(c.x() + r, c.y() - r, 0.2 + 0.6 * c.z() + 0.1 * u(rng)), Vec3(c.x(), c.y() + r, 0.2 + 0.6 * c.z())});
    }
    const auto v = make_visibility(s);
    const PairClass c = v->classify(a, ia, b, ib);
    counts[static_cast<int>(c)]++;
    int free_rays = 0, blocked_rays = 0;
    for (int i = 0; i < 2000; ++i) {
      double s1 = u(rng), s2 = u(rng);
      if (s1 + s2 > 1) {
        s1 = 1 - s1;
        s2 = 1 - s2;
      }
      double t1 = u(rng), t2 = u(rng);
      if (t1 + t2 > 1) {
        t1 = 1 - t1;
        t2 = 1 - t2;
      }
      const Vec3 pa = a[0] + s1 * (a[1] - a[0]) + s2 * (a[2] - a[0]);
      const Vec3 pb = b[0] + t1 * (b[1] - b[0]) + t2 * (b[2] - b[0]);
      // Classification speaks for mutually facing pairs only.
      if (s.patches[ia].normal.dot(pb - pa) <= 0 || s.patches[ib].normal.dot(pa - pb) <= 0) continue;
      (v->segment_blocked(pa, ia, pb, ib) ? blocked_rays : free_rays)++;
    }
    if (c == PairClass::kFullyVisible) EXPECT_EQ(blocked_rays, 0) << scene_id;
    if (c == PairClass::kFullyHidden) EXPECT_EQ(free_rays, 0) << scene_id;
    if (free_rays > 0 && blocked_rays > 0) EXPECT_EQ(c, PairClass::kPartial) << scene_id;
  }
  EXPECT_EQ(counts[static_cast<int>(PairClass::kFacingAway)], 0);
  EXPECT_GT(counts[static_cast<int>(PairClass::kFullyVisible)], 0);
  EXPECT_GT(counts[static_cast<int>(PairClass::kFullyHidden)], 0);
  EXPECT_GT(counts[static_cast<int>(PairClass::kPartial)], 0);
}

TEST(Estimate, IsRepeatableForASeed) {
  Scene s = empty_scene();
  const int a = add_patch(s, kFloor), b = add_patch(s, kCeiling);
  add_patch(s, square_z(0.25, 0.75, 0.25, 0.75, 0.5, true));
  const auto v = make_visibility(s);
  const VisibilityEstimate e1 = v->estimate(kFloor, a, kCeiling, b, 100, 42);
  const VisibilityEstimate e2 = v->estimate(kFloor, a, kCeiling, b, 100, 42);
  EXPECT_EQ(e1.pair_class, PairClass::kPartial);
  EXPECT_EQ(e1.fraction, e2.fraction);
  EXPECT_EQ(e1.error, e2.error);
}

}  // namespace
}  // namespace hrad
