// Warnings about scenes that read fine but would solve to a wrong-looking answer (core/scene_checks.h),
// on a closed unit box whose faces are built here with known orientations.
#include "hrad/core/scene_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace hrad {
namespace {

bool any_contains(const std::vector<std::string>& lines, const std::string& fragment) {
  for (const std::string& l : lines)
    if (l.find(fragment) != std::string::npos) return true;
  return false;
}

Patch quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, int material, bool flip) {
  Patch p;
  p.vertices = flip ? std::vector<Vec3>{d, c, b, a} : std::vector<Vec3>{a, b, c, d};
  const Vec3 n = (p.vertices[1] - p.vertices[0]).cross(p.vertices[2] - p.vertices[0]);
  p.normal = n.normalized();
  p.area = 1.0;
  p.material = material;
  return p;
}

// The unit box [0,1]^3 with its six faces facing inwards (or all outwards when `outward`); the floor
// has material `floor_material`; a ceiling light of material 1 hangs at y = 0.99 facing down (or up).
Scene box(bool outward, bool light_up, Rgb light_emission, std::string light_name = "light") {
  Scene s;
  s.materials = {{"white", Rgb::Constant(0.5), Rgb::Zero()}, {light_name, Rgb::Constant(0.5), light_emission}};
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  // Each quad below is counter-clockwise seen from inside the box.
  s.patches = {quad(o, z, x + z, x, 0, outward),               // floor y = 0, normal +y
               quad(y, y + x, y + x + z, y + z, 0, outward),   // ceiling, normal -y
               quad(o, x, x + y, y, 0, outward),               // z = 0, normal +z
               quad(z, z + y, z + x + y, z + x, 0, outward),   // z = 1, normal -z
               quad(o, y, y + z, z, 0, outward),               // x = 0, normal +x
               quad(x, x + z, x + y + z, x + y, 0, outward)};  // x = 1, normal -x
  const double h = 0.99;
  s.patches.push_back(quad(Vec3(0.4, h, 0.4), Vec3(0.6, h, 0.4), Vec3(0.6, h, 0.6), Vec3(0.4, h, 0.6), 1, light_up));
  for (std::size_t i = 0; i < s.patches.size(); ++i) {
    s.patches[i].face = static_cast<int>(i);
    s.faces.push_back({"", s.patches[i].material, i + 1, 1.0, {static_cast<int>(i)}});
  }
  return s;
}

TEST(SceneChecks, ASoundBoxHasNoWarnings) {
  const Scene s = box(false, false, Rgb::Constant(10));
  // The inward faces: the floor's normal is +y, so the ceiling is in front of it (sanity of the fixture).
  EXPECT_GT(s.patches[0].normal.y(), 0.99);
  EXPECT_TRUE(scene_warnings(s).empty()) << scene_warnings(s)[0];
}

TEST(SceneChecks, OutwardNormalsAreFlagged) {
  // Every wall faces out: nothing lies in front of any wall (6 of 7 patches, 6 of 7 units of area).
  const std::vector<std::string> w = scene_warnings(box(true, false, Rgb::Constant(10)));
  EXPECT_TRUE(any_contains(w, "6 of 7 patches (86% of the area) have no other face in front"))
      << (w.empty() ? "" : w[0]);
  EXPECT_TRUE(any_contains(w, "flip them"));
}

TEST(SceneChecks, NoEmitterAndZeroEmissionLightsAreFlagged) {
  const std::vector<std::string> w = scene_warnings(box(false, false, Rgb::Zero(), "Emission.001"));
  EXPECT_TRUE(any_contains(w, "no face emits light"));
  EXPECT_TRUE(any_contains(w, "material 'Emission.001' looks like a light but emits nothing"));
  // A non-emitting material with an ordinary name is not a light.
  EXPECT_FALSE(any_contains(scene_warnings(box(false, false, Rgb::Zero(), "paint")), "looks like a light"));
}

TEST(SceneChecks, EmitterFacingAwayFromEverythingIsFlagged) {
  // The light 1 cm under the ceiling facing up still lights the ceiling (each is in front of the other).
  Scene s = box(false, true, Rgb::Constant(10));
  EXPECT_FALSE(any_contains(scene_warnings(s), "no light reaches"));
  // Moved into the ceiling's plane, facing up (out of the box): no face has a point above y = 1.
  for (Vec3& v : s.patches[6].vertices) v.y() = 1.0;
  EXPECT_GT(s.patches[6].normal.y(), 0.99);
  EXPECT_TRUE(any_contains(scene_warnings(s), "no light reaches any surface"));
}

// A picture on the wall z = 0 (facing +z, as the wall): flush with it, the two overlap; lifted off
// it, facing the other way, or beside it sharing only an edge, they do not.
TEST(SceneChecks, CoplanarOverlapsFacingTheSameWayAreFlagged) {
  const auto with_picture = [](double lift, bool flip, double x0) {
    Scene s = box(false, false, Rgb::Constant(10));
    s.patches.push_back(
        quad(Vec3(x0, 0.3, lift), Vec3(x0 + 0.3, 0.3, lift), Vec3(x0 + 0.3, 0.6, lift), Vec3(x0, 0.6, lift), 0, flip));
    s.patches.back().area = 0.09;
    s.patches.back().face = static_cast<int>(s.faces.size());
    s.faces.push_back({"", 0, 42, 0.09, {static_cast<int>(s.patches.size()) - 1}});
    return scene_warnings(s);
  };
  const std::vector<std::string> flush = with_picture(0.0, false, 0.2);
  EXPECT_TRUE(any_contains(flush,
                           "1 pair of patches lie in one plane, facing the same way, and overlap (first: "
                           "faces at lines 3 and 42"))
      << (flush.empty() ? "" : flush[0]);
  EXPECT_TRUE(with_picture(1e-3, false, 0.2).empty());
  EXPECT_TRUE(with_picture(0.0, true, 0.2).empty());  // back to back: each hides the other's front
  // Beside the wall's edge x = 1 in its plane: touching along the edge x = 1 only.
  EXPECT_TRUE(with_picture(0.0, false, 1.0).empty());
}

// Guarantee: patches_facing_nothing() finds the patches with no vertex of another patch in front of
// their plane, as the scan of every pair does, on random scenes: tessellated floors, boxes facing in
// or out, and quads of random orientation (whose planes the extreme vertices and the scene's box do
// not settle, so the scan runs too), with blind patches among them.
TEST(SceneChecks, PatchesFacingNothingAgreeWithTheScanOfEveryPair) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t blind_total = 0, checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Scene s;
    s.materials = {{"white", Rgb::Constant(0.5), Rgb::Zero()}};
    const int tiles = 1 + trial % 6;
    for (int i = 0; i < tiles; ++i)
      for (int j = 0; j < tiles; ++j) {
        const Vec3 a(i, 0, j), b(i, 0, j + 1), c(i + 1, 0, j + 1), d(i + 1, 0, j);
        s.patches.push_back(quad(a, b, c, d, 0, trial % 7 == 0));
      }
    for (int k = 0; k < 3 + trial % 5; ++k) {
      // A quad of random orientation about a random centre.
      const Vec3 centre(u(rng) * tiles, u(rng) * 3.0, u(rng) * tiles);
      Vec3 e1 = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
      Vec3 e2 = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).cross(e1).normalized();
      e1 *= 0.1 + u(rng);
      e2 *= 0.1 + u(rng);
      s.patches.push_back(quad(centre - e1 - e2, centre + e1 - e2, centre + e1 + e2, centre - e1 + e2, 0, false));
    }
    if (trial % 3 == 0) {
      // A box standing on the floor, facing in or out.
      const Scene b = box(trial % 2 == 0, false, Rgb::Zero());
      for (std::size_t i = 0; i + 1 < b.patches.size(); ++i) s.patches.push_back(b.patches[i]);
    }
    const auto [lo, hi] = s.bounds();
    const double tol = 1e-9 * (hi - lo).norm();
    const std::vector<char> found = patches_facing_nothing(s);
    ASSERT_EQ(found.size(), s.patches.size());
    for (std::size_t i = 0; i < s.patches.size(); ++i) {
      const Patch& p = s.patches[i];
      bool sees = false;
      for (std::size_t j = 0; j < s.patches.size() && !sees; ++j)
        if (j != i)
          for (const Vec3& v : s.patches[j].vertices)
            if ((v - p.vertices[0]).dot(p.normal) > tol) sees = true;
      EXPECT_EQ(found[i] != 0, !sees) << "trial " << trial << ", patch " << i;
      blind_total += sees ? 0 : 1;
      ++checked;
    }
  }
  // Both answers occur (the fixture is not all one kind).
  EXPECT_GT(blind_total, 10u);
  EXPECT_LT(blind_total, checked / 2);
}

// Guarantee: a patch whose only vertex in front is extreme along none of the 26 directions that
// patches_facing_nothing() looks along first is still found to face something (its scan). p faces
// (1, 2, 0) from x + 2y = 19; of the small quads about A (10, 0), B (0, 9), C (6, 6) and D (3, 8.5),
// only D's (x + 2y about 20) lie in front, and A, B or C is the farthest along every one of the 26.
TEST(SceneChecks, AVertexInFrontThatNoDirectionFavoursIsFound) {
  Scene s;
  s.materials = {{"white", Rgb::Constant(0.5), Rgb::Zero()}};
  const auto square = [](double x, double y) {  // a tilted quad about (x, y), z from 0 to 1
    return quad(Vec3(x - 0.2, y - 0.2, 0), Vec3(x + 0.2, y - 0.2, 0), Vec3(x + 0.2, y + 0.2, 1),
                Vec3(x - 0.2, y + 0.2, 1), 0, false);
  };
  s.patches = {square(10, 0), square(0, 9), square(6, 6)};
  const Vec3 n = Vec3(1, 2, 0).normalized(), along = Vec3(2, -1, 0).normalized() * 0.5, up(0, 0, 0.5);
  const Vec3 o(1, 9, 0.5);  // x + 2y = 19
  Patch p = quad(o - along - up, o + along - up, o + along + up, o - along + up, 0, false);
  if (p.normal.dot(n) < 0.0) p = quad(o - along - up, o + along - up, o + along + up, o - along + up, 0, true);
  ASSERT_NEAR(p.normal.dot(n), 1.0, 1e-12);
  s.patches.push_back(p);
  const std::vector<char> without_d = patches_facing_nothing(s);
  EXPECT_EQ(without_d[3], 1);  // nothing in front of p yet
  s.patches.push_back(square(3, 8.5));
  const std::vector<char> with_d = patches_facing_nothing(s);
  EXPECT_EQ(with_d[3], 0);
}

}  // namespace
}  // namespace hrad
