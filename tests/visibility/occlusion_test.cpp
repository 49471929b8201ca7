// scene_has_occlusion(): exact decision whether any patch can block a pair of others; and
// thread safety of the const queries.
#include <gtest/gtest.h>

#include <thread>

#include "hrad/io/obj_reader.h"
#include "hrad/visibility/visibility.h"
#include "support/source_tree.h"
#include "test_scenes.h"

namespace hrad {
namespace {

using test::add_patch;
using test::empty_scene;
using test::square_z;

/// The six walls of [0, sx] x [0, sy] x [0, sz], fronts inside; each wall split into k x k quads.
void add_box(Scene& s, double sx, double sy, double sz, int k = 1) {
  const double size[3] = {sx, sy, sz};
  for (int axis = 0; axis < 3; ++axis)
    for (int high = 0; high < 2; ++high) {
      const int au = (axis + 1) % 3, av = (axis + 2) % 3;
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
          auto at = [&](int di, int dj) {
            Vec3 p;
            p[axis] = high ? size[axis] : 0.0;
            p[au] = size[au] * (i + di) / k;
            p[av] = size[av] * (j + dj) / k;
            return p;
          };
          // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
          if (high)
            add_patch(s, {at(0, 0), at(0, 1), at(1, 1), at(1, 0)});
          else
            add_patch(s, {at(0, 0), at(1, 0), at(1, 1), at(0, 1)});
        }
    }
}

TEST(SceneHasOcclusion, EmptyConvexRoomHasNone) {
  Scene s = empty_scene();
  add_box(s, 1.0, 2.0, 0.7);
  EXPECT_FALSE(make_visibility(s)->scene_has_occlusion());
  Scene tessellated = empty_scene();
  add_box(tessellated, 1.0, 2.0, 0.7, 3);
  EXPECT_FALSE(make_visibility(tessellated)->scene_has_occlusion());
}

TEST(SceneHasOcclusion, ABlockInsideOccludes) {
  Scene s = empty_scene();
  add_box(s, 1.0, 1.0, 1.0);
  add_patch(s, square_z(0.4, 0.6, 0.4, 0.6, 0.3, true));
  EXPECT_TRUE(make_visibility(s)->scene_has_occlusion());
}

TEST(SceneHasOcclusion, AWallFacingOutOccludes) {
  Scene s = empty_scene();
  add_box(s, 1.0, 1.0, 1.0);
  std::reverse(s.patches[0].vertices.begin(), s.patches[0].vertices.end());
  EXPECT_TRUE(make_visibility(s)->scene_has_occlusion());
}

TEST(SceneHasOcclusion, NonConvexRoomOccludes) {
  // An L-shaped floor plan: two boxes side by side without the wall between them would still be
  // convex; cut a corner instead with a re-entrant pair of walls.
  Scene s = empty_scene();
  add_patch(s, {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}});  // floor, front +z
  add_patch(s, {{0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}});
  add_patch(s, {{1, 1, 0}, {1, 1, 1}, {1, 2, 1}, {1, 2, 0}});  // re-entrant wall x = 1, front +x
  add_patch(s, {{1, 1, 0}, {2, 1, 0}, {2, 1, 1}, {1, 1, 1}});  // re-entrant wall y = 1, front +y
  EXPECT_TRUE(make_visibility(s)->scene_has_occlusion());
}

TEST(SceneHasOcclusion, DecidedExactlyForAPatchOffTheHullByOneTinyStep) {
  // A triangle lying on the floor (coplanar, facing in) occludes nothing; lifted by 1e-300 it
  // stands inside the room and could block grazing rays: the exact predicate sees the difference.
  for (const double lift : {0.0, 1e-300}) {
    Scene s = empty_scene();
    add_box(s, 1.0, 1.0, 1.0);
    add_patch(s, {{0.2, 0.2, lift}, {0.6, 0.2, lift}, {0.2, 0.6, lift}});
    EXPECT_EQ(make_visibility(s)->scene_has_occlusion(), lift != 0.0) << lift;
  }
}

TEST(SceneHasOcclusion, CornellBoxHasOcclusion) {
  const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  EXPECT_TRUE(make_visibility(s)->scene_has_occlusion());
}

TEST(Visibility, ConstQueriesAreThreadSafeAndCountersAddUp) {
  Scene s = empty_scene();
  add_box(s, 1.0, 1.0, 1.0, 2);
  add_patch(s, square_z(0.3, 0.7, 0.3, 0.7, 0.5, true));
  add_patch(s, square_z(0.3, 0.7, 0.3, 0.7, 0.5, false));
  const auto v = make_visibility(s);
  const int n = static_cast<int>(s.patches.size());
  auto run = [&](std::vector<double>* out) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        out->push_back(v->estimate(s.patches[i].vertices, i, s.patches[j].vertices, j, 32, i * 1000 + j).fraction);
  };
  std::vector<double> serial, t1, t2;
  run(&serial);
  const auto rays_serial = v->counters().segment_queries.load();
  std::thread a(run, &t1), b(run, &t2);
  a.join();
  b.join();
  EXPECT_EQ(t1, serial);
  EXPECT_EQ(t2, serial);
  EXPECT_EQ(v->counters().segment_queries.load(), 3 * rays_serial);
  EXPECT_EQ(v->counters().pair_queries.load(), 3u * n * n);
  EXPECT_GT(rays_serial, 0u);
  const auto& c = v->counters();
  EXPECT_EQ(c.pairs_facing_away.load() + c.pairs_visible.load() + c.pairs_hidden.load() + c.pairs_partial.load(),
            c.pair_queries.load());
}

}  // namespace
}  // namespace hrad
