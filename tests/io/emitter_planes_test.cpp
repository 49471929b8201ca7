#include "hrad/io/emitter_planes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "../support/temp_dir.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/scene_reader.h"

namespace hrad {
namespace {

// Materials: 0 reflects, 1 emits 50 (far above the mean radiosity of any scene here), 2 emits 0.01.
Scene empty_scene() {
  Scene s;
  s.materials = {test::material(Rgb::Constant(0.5), Rgb::Zero(), "wall"),
                 test::material(Rgb::Constant(0.4), Rgb::Constant(50.0), "lamp"),
                 test::material(Rgb::Constant(0.5), Rgb::Constant(0.01), "glow")};
  return s;
}

// A lamp strip 1 x 0.04 at height y = 0 facing down (-y), centred on the origin along x.
void add_lamp(Scene& s, int material = 1) {
  test::add_polygon(s, {{-0.5, 0, -0.02}, {0.5, 0, -0.02}, {0.5, 0, 0.02}, {-0.5, 0, 0.02}}, Vec3(0, -1, 0), material);
}

// A vertical side 1 long along x at z, from y0 to y1, facing the lamp (towards z = 0).
void add_side(Scene& s, double z, double y0, double y1) {
  test::add_polygon(s, {{-0.5, y0, z}, {0.5, y0, z}, {0.5, y1, z}, {-0.5, y1, z}}, Vec3(0, 0, -z), 0);
}

double face_area(const Scene& s, int face) {
  double a = 0.0;
  for (const int p : s.faces[static_cast<std::size_t>(face)].patches) a += s.patches[static_cast<std::size_t>(p)].area;
  return a;
}

// The extreme heights of each patch of `face`, sorted by the lowest.
std::vector<std::pair<double, double>> heights(const Scene& s, int face) {
  std::vector<std::pair<double, double>> out;
  for (const int p : s.faces[static_cast<std::size_t>(face)].patches) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Vec3& v : s.patches[static_cast<std::size_t>(p)].vertices)
      lo = std::min(lo, v.y()), hi = std::max(hi, v.y());
    out.emplace_back(lo, hi);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Guarantee: a reflector side crossing the lamp's plane is cut exactly along it (one patch below,
// one above, meeting at y = 0), keeps its area, and its patches keep its face, material and facing.
TEST(EmitterPlanes, ASideCrossingTheLampsPlaneIsCutAlongIt) {
  Scene s = empty_scene();
  add_lamp(s);
  add_side(s, 0.05, -0.06, 0.02);
  const Patch before = s.patches[1];
  const EmitterPlaneCuts cuts = cut_emitter_planes(s);
  EXPECT_EQ(cuts.pairs, 1u);
  EXPECT_EQ(cuts.patches_added, 1u);
  ASSERT_EQ(s.faces[1].patches.size(), 2u);
  EXPECT_NEAR(face_area(s, 1), before.area, 1e-15);
  const auto h = heights(s, 1);
  EXPECT_NEAR(h[0].first, -0.06, 1e-15);
  EXPECT_NEAR(h[0].second, 0.0, 1e-15);
  EXPECT_NEAR(h[1].first, 0.0, 1e-15);
  EXPECT_NEAR(h[1].second, 0.02, 1e-15);
  for (const int p : s.faces[1].patches) {
    const Patch& q = s.patches[static_cast<std::size_t>(p)];
    EXPECT_EQ(q.face, 1);
    EXPECT_EQ(q.material, before.material);
    EXPECT_GT(q.normal.dot(before.normal), 1.0 - 1e-12);
    EXPECT_GT(newell_normal(q.vertices).normalized().dot(before.normal), 1.0 - 1e-12);
    EXPECT_TRUE(is_convex(q.vertices, q.normal));
  }
  ASSERT_EQ(s.faces[0].patches.size(), 1u);  // the lamp itself stays whole
}

// Guarantee: faces are cut only where they cross the plane of a bright emitter within its reach, and
// the pieces on either side are more than slivers. Each control differs from the cut side above in
// one thing.
TEST(EmitterPlanes, OnlyNearFacesThatCrossABrightEmittersPlaneAreCut) {
  struct Case {
    const char* what;
    double z, y0, y1;
    int lamp_material;
    std::size_t patches;
  };
  for (const Case& c :
       {Case{"crossing, near", 0.05, -0.06, 0.02, 1, 2},
        Case{"crossing, beyond the lamp's diameter", 1.2, -0.06, 0.02, 1, 1},
        Case{"crossing, just within it", 0.95, -0.06, 0.02, 1, 2}, Case{"ending on the plane", 0.05, -0.06, 0.0, 1, 1},
        Case{"wholly above it", 0.05, 0.01, 0.08, 1, 1}, Case{"crossing by a sliver (1%)", 0.05, -0.099, 0.001, 1, 1},
        Case{"crossing by 3%", 0.05, -0.097, 0.003, 1, 2},
        Case{"crossing a dim emitter's plane", 0.05, -0.06, 0.02, 2, 1}}) {
    SCOPED_TRACE(c.what);
    Scene s = empty_scene();
    add_lamp(s, c.lamp_material);
    add_side(s, c.z, c.y0, c.y1);
    // A large floor far below, emitting 50 in the dim emitter's case (which then is far below the
    // mean radiosity), dark otherwise.
    test::add_polygon(s, {{-5, -3, -5}, {5, -3, -5}, {5, -3, 5}, {-5, -3, 5}}, Vec3(0, 1, 0),
                      c.lamp_material == 2 ? 1 : 0);
    cut_emitter_planes(s);
    EXPECT_EQ(s.faces[1].patches.size(), c.patches);
    EXPECT_EQ(s.faces[2].patches.size(), 1u);  // parallel to the lamp
  }
}

// Guarantee: in a furnace (every face emits alike) no emitter stands out and nothing is cut, while
// the same room with one lamp much brighter than the rest is cut where it crosses that lamp's plane.
TEST(EmitterPlanes, AFurnaceIsLeftWhole) {
  for (const double lamp : {1.0, 100.0}) {
    Scene s = test::make_box(2.0, 2.0, 2.0,
                             {test::material(Rgb::Constant(0.6), Rgb::Constant(1.0), "wall"),
                              test::material(Rgb::Constant(0.6), Rgb::Constant(lamp), "lamp")},
                             {0, 0, 0, 0, 0, 0});
    test::add_polygon(s, {{0.5, 1.5, 0.5}, {1.5, 1.5, 0.5}, {1.5, 1.5, 1.5}, {0.5, 1.5, 1.5}}, Vec3(0, -1, 0), 1);
    const std::size_t before = s.patches.size();
    cut_emitter_planes(s);
    // The four walls cross the lamp's plane y = 1.5 within its diameter (1.41) of its box.
    EXPECT_EQ(s.patches.size(), lamp > 1.0 ? before + 4 : before) << "lamp " << lamp;
  }
}

// The area of the convex polygon `poly` in front of the plane through `o` with normal `n`.
double area_in_front(const std::vector<Vec3>& poly, const Vec3& o, const Vec3& n) {
  std::vector<Vec3> kept;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % poly.size()];
    const double da = (a - o).dot(n), db = (b - o).dot(n);
    if (da >= 0.0) kept.push_back(a);
    if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) kept.push_back(a + (b - a) * (da / (da - db)));
  }
  return kept.size() >= 3 ? polygon_area(kept) : 0.0;
}

// Guarantee (property): in random scenes of lamps and faces, cutting keeps every face's area (to
// 1e-12), gives convex patches of 3 or 4 corners in their face's plane, leaves faces that cross no
// near bright lamp's plane exactly as they were, and leaves no patch of a face crossing one lamp's
// plane (by more than 10% each side, with no other lamp near) straddling that plane.
TEST(EmitterPlanes, RandomScenesKeepAreaAndCutAlongThePlanes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;  // faces crossing one lamp's plane well inside, whose pieces were checked
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    Scene s = empty_scene();
    const int lamps = 1 + trial % 3;
    for (int l = 0; l < lamps; ++l) {
      const Vec3 c(u(rng), u(rng), u(rng)), n = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 a = n.unitOrthogonal() * 0.3, b = n.cross(a).normalized() * 0.1;
      test::add_polygon(s, {c - a - b, c + a - b, c + a + b, c - a + b}, n, 1);
    }
    for (int f = 0; f < 12; ++f) {
      const Vec3 c(u(rng), u(rng), u(rng)), n = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 a = n.unitOrthogonal() * (0.2 + 0.3 * std::abs(u(rng))), b = n.cross(a).normalized() * 0.25;
      if (f % 3 == 0)
        test::add_polygon(s, {c - a - b, c + a - b, c + b}, n, 0);
      else
        test::add_polygon(s, {c - a - b, c + a - b, c + a + b, c - a + b}, n, 0);
    }
    const Scene before = s;
    cut_emitter_planes(s);
    ASSERT_EQ(s.faces.size(), before.faces.size());
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      const Patch& original = before.patches[f];
      EXPECT_NEAR(face_area(s, static_cast<int>(f)), original.area, 1e-12 * original.area);
      for (const int p : s.faces[f].patches) {
        const Patch& q = s.patches[static_cast<std::size_t>(p)];
        ASSERT_GE(q.vertices.size(), 3u);
        ASSERT_LE(q.vertices.size(), 4u);
        EXPECT_TRUE(is_convex(q.vertices, q.normal));
        for (const Vec3& v : q.vertices) EXPECT_NEAR((v - original.vertices[0]).dot(original.normal), 0.0, 1e-12);
      }
      // Which lamps' planes this face crosses within reach (boxes grown by the lamp's diameter).
      std::vector<int> crossing;
      for (int l = 0; l < lamps; ++l) {
        const Patch& lamp = before.patches[static_cast<std::size_t>(l)];
        if (static_cast<int>(f) == l) continue;
        Vec3 lo = lamp.vertices[0], hi = lo, flo = original.vertices[0], fhi = flo;
        for (const Vec3& v : lamp.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        for (const Vec3& v : original.vertices) flo = flo.cwiseMin(v), fhi = fhi.cwiseMax(v);
        const double reach = polygon_diameter(lamp.vertices);
        if (((flo.array() > hi.array() + reach) || (fhi.array() < lo.array() - reach)).any()) continue;
        double below = 0.0, above = 0.0;
        for (const Vec3& v : original.vertices) {
          const double d = (v - lamp.vertices[0]).dot(lamp.normal);
          below = std::min(below, d), above = std::max(above, d);
        }
        if (below < -1e-9 && above > 1e-9) crossing.push_back(l);
      }
      if (crossing.empty()) {
        ASSERT_EQ(s.faces[f].patches.size(), 1u);
        EXPECT_EQ(s.patches[static_cast<std::size_t>(s.faces[f].patches[0])].vertices, original.vertices);
        continue;
      }
      if (crossing.size() != 1) continue;
      const Patch& lamp = before.patches[static_cast<std::size_t>(crossing[0])];
      double side = 0.0;  // the face's patches' area in front of the lamp's plane
      for (const int p : s.faces[f].patches) {
        const Patch& q = s.patches[static_cast<std::size_t>(p)];
        double lo = INFINITY, hi = -INFINITY;
        for (const Vec3& v : q.vertices) {
          const double d = (v - lamp.vertices[0]).dot(lamp.normal);
          lo = std::min(lo, d), hi = std::max(hi, d);
        }
        if (lo > -1e-12) side += q.area;
      }
      const double fraction = area_in_front(original.vertices, lamp.vertices[0], lamp.normal) / original.area;
      if (fraction > 0.1 && fraction < 0.9) {
        EXPECT_GE(s.faces[f].patches.size(), 2u);
        EXPECT_NEAR(side, fraction * original.area, 1e-12 * original.area) << "a patch straddles the plane";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);  // the scenes exercise the cut
}

// Guarantee: read_scene() cuts what it reads (here an OBJ lamp in a trough), and keeps the faces.
TEST(EmitterPlanes, ReadScenesAreCut) {
  test::TempDir dir;
  dir.write("m.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.4 0.4 0.4\nKe 50 50 50\n");
  const std::string path =
      dir.write("s.obj",
                "mtllib m.mtl\nusemtl lamp\n"
                "v -0.5 0 -0.02\nv -0.5 0 0.02\nv 0.5 0 0.02\nv 0.5 0 -0.02\nf 1 2 3 4\n"
                "usemtl wall\n"
                "v -0.5 -0.06 0.05\nv 0.5 -0.06 0.05\nv 0.5 0.02 0.05\nv -0.5 0.02 0.05\nf 5 6 7 8\n");
  const Scene s = read_scene(path);
  ASSERT_EQ(s.faces.size(), 2u);
  EXPECT_EQ(s.patches.size(), 3u);
  EXPECT_EQ(s.faces[1].patches.size(), 2u);
  ObjReadOptions whole;
  whole.cut_emitter_planes = false;
  EXPECT_EQ(read_scene(path, nullptr, whole).patches.size(), 2u);
}

}  // namespace
}  // namespace hrad
