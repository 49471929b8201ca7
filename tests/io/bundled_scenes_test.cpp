// The bundled scenes load cleanly and their fronts face where the scene means them to.
#include <gtest/gtest.h>

#include "hrad/io/obj_reader.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

Scene load(const std::string& name) {
  std::vector<std::string> warnings;
  Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/" + name, &warnings);
  EXPECT_TRUE(warnings.empty()) << name << ": " << (warnings.empty() ? "" : warnings[0]);
  return s;
}

Vec3 mean_vertex(const Patch& p) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : p.vertices) c += v;
  return c / double(p.vertices.size());
}

TEST(BundledScenes, SimpleRoomWallsFaceInTableFacesOut) {
  const Scene s = load("simple_room.obj");
  ASSERT_EQ(s.faces.size(), 12u);
  EXPECT_EQ(s.emitter_count(), 1);
  EXPECT_NEAR(s.total_area(), 2 * 20.0 + 2 * 10.0 + 2 * 12.5 + 1.0 + 1.2 * 0.8 + 2 * 1.2 * 0.75 + 2 * 0.8 * 0.75,
              1e-12);
  const Vec3 room_centre(2.0, 1.25, 2.5), table_centre(2.0, 0.375, 2.3);
  for (const Patch& p : s.patches) {
    const Vec3 inside = p.group == "table" ? table_centre : room_centre;
    const double side = (inside - mean_vertex(p)).dot(p.normal);
    if (p.group == "table")
      EXPECT_LT(side, 0.0) << "table faces point out";
    else
      EXPECT_GT(side, 0.0) << p.group << " faces into the room";
  }
}

TEST(BundledScenes, LectureSurfacesFaceEachOther) {
  for (const char* name : {"two_far_surfaces.obj", "two_surfaces_edge.obj"}) {
    const Scene s = load(name);
    ASSERT_EQ(s.patches.size(), 2u);
    const Patch& a = s.patches[0];
    const Patch& b = s.patches[1];
    EXPECT_GT((mean_vertex(b) - mean_vertex(a)).dot(a.normal), 0.0) << name;
    EXPECT_GT((mean_vertex(a) - mean_vertex(b)).dot(b.normal), 0.0) << name;
    EXPECT_NEAR(a.area, 16.0, 1e-12);
    EXPECT_NEAR(b.area, 16.0, 1e-12);
  }
}

}  // namespace
}  // namespace hrad
