#include "hrad/io/near_faces.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../support/temp_dir.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/scene_reader.h"

namespace hrad {
namespace {

// A 4 x 4 floor (facing up) and a 1 x 1 quad `height` above it facing `down` or up, at x, z in
// [1.5, 2.5].
Scene floor_and_quad(const test::TempDir& dir, double height, bool down, bool cut) {
  dir.write("m.mtl", "newmtl w\nKd 0.5 0.5 0.5\n");
  std::string obj = "mtllib m.mtl\nusemtl w\no floor\nv 0 0 4\nv 4 0 4\nv 4 0 0\nv 0 0 0\nf 1 2 3 4\no box\n";
  obj += "v 1.5 " + std::to_string(height) + " 1.5\nv 2.5 " + std::to_string(height) + " 1.5\nv 2.5 " +
         std::to_string(height) + " 2.5\nv 1.5 " + std::to_string(height) + " 2.5\n";
  obj += down ? "f 5 6 7 8\n" : "f 8 7 6 5\n";
  ObjReadOptions options;
  options.cut_near_faces = cut;
  return read_scene(dir.write("s.obj", obj), nullptr, options);
}

TEST(NearFaces, TheFloorIsCutAlongTheOutlineOfAFaceJustAboveIt) {
  test::TempDir dir;
  const Scene s = floor_and_quad(dir, 0.01, true, true);
  ASSERT_EQ(s.faces.size(), 2u);
  EXPECT_NEAR(s.faces[0].area, 16.0, 1e-12);  // the floor keeps its area
  EXPECT_EQ(s.faces[1].patches.size(), 1u);   // the smaller face is not cut
  ASSERT_GT(s.faces[0].patches.size(), 1u);
  // One piece is the footprint; the others lie outside it; none overlap.
  int footprints = 0;
  for (const int i : s.faces[0].patches) {
    const Patch& p = s.patches[static_cast<std::size_t>(i)];
    EXPECT_TRUE(is_convex(p.vertices, p.normal));
    for (const Vec3& v : p.vertices) EXPECT_EQ(v.y(), 0.0);
    const Vec3 c = polygon_centroid(p.vertices);
    const bool under = c.x() > 1.5 && c.x() < 2.5 && c.z() > 1.5 && c.z() < 2.5;
    if (under) {
      ++footprints;
      EXPECT_NEAR(p.area, 1.0, 1e-12);
    }
  }
  EXPECT_EQ(footprints, 1);
  // The reader cuts by default: read_scene() with default options gives the same patches.
  EXPECT_EQ(read_scene(dir.path("s.obj"), nullptr, {}).patches.size(), s.patches.size());
  // Without the option, or with the quad too far above (0.2 > 0.1 x its diameter 1.41) or facing
  // away from the floor, nothing is cut.
  EXPECT_EQ(floor_and_quad(dir, 0.01, true, false).patches.size(), 2u);
  EXPECT_EQ(floor_and_quad(dir, 0.2, true, true).patches.size(), 2u);
  EXPECT_EQ(floor_and_quad(dir, 0.01, false, true).patches.size(), 2u);
  EXPECT_GT(floor_and_quad(dir, 0.1, true, true).patches.size(), 2u);  // 0.1 <= 0.141
}

TEST(NearFaces, FindingNamesThePairsThatWouldSplitAFaceNotThoseThatEncloseIt) {
  test::TempDir dir;
  // The box's bottom 1 cm above the floor: two pairs (each within a tenth of the other's diameter),
  // of which only the bottom's outline splits (the floor's encloses the bottom): the floor (face 0)
  // behind, the box in front.
  const NearCuts box = find_near_faces(floor_and_quad(dir, 0.01, true, false));
  EXPECT_EQ(box.pairs, 2u);
  EXPECT_EQ(box.splitting_pairs, 1u);
  EXPECT_EQ(box.first_behind, 0);
  EXPECT_EQ(box.first_front, 1);
  EXPECT_NEAR(box.first_gap, 0.01, 1e-12);
  // 0.2 above: too far for the bottom's outline (0.1 x 1.41), near enough for the floor's, which
  // encloses the bottom.
  const NearCuts far = find_near_faces(floor_and_quad(dir, 0.2, true, false));
  EXPECT_EQ(far.pairs, 1u);
  EXPECT_EQ(far.splitting_pairs, 0u);
  EXPECT_EQ(find_near_faces(floor_and_quad(dir, 0.01, false, false)).pairs, 0u);  // facing away
  // A long corridor's floor and ceiling, 1 apart and 20 long, face each other "from nearby" by the
  // rule, but each one's outline encloses the other: a cut would split nothing, so nothing is named.
  dir.write("m.mtl", "newmtl w\nKd 0.5 0.5 0.5\n");
  ObjReadOptions whole;  // read as they are, not cut (the default)
  whole.cut_near_faces = false;
  const std::string obj =
      "mtllib m.mtl\nusemtl w\nv 0 0 0\nv 0 0 20\nv 1 0 20\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 1 1 20\nv 0 1 20\n"
      "f 1 2 3 4\nf 5 6 7 8\n";
  const NearCuts corridor = find_near_faces(read_scene(dir.write("c.obj", obj), nullptr, whole));
  EXPECT_EQ(corridor.pairs, 2u);
  EXPECT_EQ(corridor.splitting_pairs, 0u);
  EXPECT_EQ(corridor.first_behind, -1);
  // Shifted along the corridor by half its length, each splits the other.
  const std::string shifted =
      "mtllib m.mtl\nusemtl w\nv 0 0 0\nv 0 0 20\nv 1 0 20\nv 1 0 0\nv 0 1 10\nv 1 1 10\nv 1 1 30\nv 0 1 30\n"
      "f 1 2 3 4\nf 5 6 7 8\n";
  EXPECT_EQ(find_near_faces(read_scene(dir.write("d.obj", shifted), nullptr, whole)).splitting_pairs, 2u);
}

}  // namespace
}  // namespace hrad
