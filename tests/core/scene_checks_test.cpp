// Warnings about scenes that read fine but would solve to a wrong-looking answer (core/scene_checks.h),
// on a closed unit box whose faces are built here with known orientations.
#include "hrad/core/scene_checks.h"

#include <gtest/gtest.h>

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
    s.patches.push_back(quad(Vec3(x0, 0.3, lift), Vec3(x0 + 0.3, 0.3, lift), Vec3(x0 + 0.3, 0.6, lift),
                             Vec3(x0, 0.6, lift), 0, flip));
    s.patches.back().area = 0.09;
    s.patches.back().face = static_cast<int>(s.faces.size());
    s.faces.push_back({"", 0, 42, 0.09, {static_cast<int>(s.patches.size()) - 1}});
    return scene_warnings(s);
  };
  const std::vector<std::string> flush = with_picture(0.0, false, 0.2);
  EXPECT_TRUE(any_contains(flush, "1 pair of patches lie in one plane, facing the same way, and overlap (first: "
                                  "faces at lines 3 and 42"))
      << (flush.empty() ? "" : flush[0]);
  EXPECT_TRUE(with_picture(1e-3, false, 0.2).empty());
  EXPECT_TRUE(with_picture(0.0, true, 0.2).empty());  // back to back: each hides the other's front
  // Beside the wall's edge x = 1 in its plane: touching along the edge x = 1 only.
  EXPECT_TRUE(with_picture(0.0, false, 1.0).empty());
}

}  // namespace
}  // namespace hrad
