// A scene file declares the unit of its emission where other programs ignore it (README "Scene
// format"): each format's place is read, a bad or contradictory declaration is an error naming the
// file and line, and comments that are not addressed to hrad change nothing.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "../support/temp_dir.h"
#include "hrad/core/error.h"
#include "hrad/io/scene_reader.h"

namespace hrad {
namespace {

const std::string kQuad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

// The error `read_scene(path)` throws, or "" when it reads.
std::string error_of(const std::string& path) {
  try {
    read_scene(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneDirectives, ObjAndMtlCommentsDeclareTheUnit) {
  test::TempDir dir;
  dir.write("m.mtl", "#@hrad emission-units W/m2\nnewmtl w\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  const Scene from_mtl = read_scene(dir.write("a.obj", "mtllib m.mtl\nusemtl w\n" + kQuad));
  ASSERT_TRUE(from_mtl.emission_units.has_value());
  EXPECT_EQ(from_mtl.emission_units->units, EmissionUnits::watts_per_m2);
  EXPECT_EQ(from_mtl.emission_units->where, dir.path("m.mtl") + ":1");

  // In the OBJ, after statements, with tabs; the same unit again in the MTL agrees with it.
  const Scene from_obj =
      read_scene(dir.write("b.obj", "mtllib m.mtl\nusemtl w\n" + kQuad + "#@hrad\t emission-units  W/m^2\n"));
  ASSERT_TRUE(from_obj.emission_units.has_value());
  EXPECT_EQ(from_obj.emission_units->units, EmissionUnits::watts_per_m2);
  EXPECT_EQ(from_obj.emission_units->where, dir.path("b.obj") + ":8");

  // Comments not addressed to hrad declare nothing.
  dir.write("n.mtl", "# exported for @hrad emission-units lm/m2\nnewmtl w\nKd 0.5 0.5 0.5\n");
  EXPECT_FALSE(
      read_scene(dir.write("c.obj", "# hrad: a note\n#@hradx emission-units W/m2\nmtllib n.mtl\nusemtl w\n" + kQuad))
          .emission_units);
}

TEST(SceneDirectives, BadOrContradictoryDeclarationsNameTheirLines) {
  test::TempDir dir;
  dir.write("m.mtl", "newmtl w\n#@hrad emission-units W/m2\nKd 0.5 0.5 0.5\n");
  const std::string contradiction =
      error_of(dir.write("a.obj", "#@hrad emission-units lm/m2\nmtllib m.mtl\nusemtl w\n" + kQuad));
  EXPECT_NE(contradiction.find(dir.path("m.mtl") + ":2: emission-units W/m2 contradicts lm/m2 declared at " +
                               dir.path("a.obj") + ":1"),
            std::string::npos)
      << contradiction;
  const std::string unit = error_of(dir.write("b.obj", kQuad + "\n#@hrad emission-units cd/m2\n"));
  EXPECT_NE(unit.find(dir.path("b.obj") + ":7: emission-units 'cd/m2' is not lm/m2 or W/m2"), std::string::npos)
      << unit;
  const std::string unknown = error_of(dir.write("c.obj", "#@hrad emission-unit lm/m2\n" + kQuad));
  EXPECT_NE(unknown.find(dir.path("c.obj") + ":1: unknown hrad declaration 'emission-unit'"), std::string::npos)
      << unknown;
  const std::string two = error_of(dir.write("d.obj", "#@hrad emission-units lm/m2 W/m2\n" + kQuad));
  EXPECT_NE(two.find(dir.path("d.obj") + ":1: '@hrad emission-units' takes one unit"), std::string::npos) << two;
}

TEST(SceneDirectives, PlyHeaderCommentDeclaresTheUnit) {
  test::TempDir dir;
  const std::string header =
      "ply\nformat ascii 1.0\ncomment made by a modeller\ncomment @hrad emission-units {}\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const Scene s = read_scene(dir.write("s.ply", fmt::format(fmt::runtime(header), "lm/m2")));
  ASSERT_TRUE(s.emission_units.has_value());
  EXPECT_EQ(s.emission_units->units, EmissionUnits::lumens_per_m2);
  EXPECT_EQ(s.emission_units->where, dir.path("s.ply") + ":4");
  const std::string bad = error_of(dir.write("t.ply", fmt::format(fmt::runtime(header), "lux")));
  EXPECT_NE(bad.find(dir.path("t.ply") + ":4: emission-units 'lux' is not lm/m2 or W/m2"), std::string::npos) << bad;
}

TEST(SceneDirectives, GltfAssetExtrasDeclareTheUnit) {
  test::TempDir dir;
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  {
    std::ofstream bin(dir.path("s.bin"), std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
  }
  const auto gltf = [&](const std::string& name, const std::string& extras) {
    return dir.write(name, R"({"asset": {"version": "2.0", "extras": )" + extras + R"(},
      "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"uri": "s.bin", "byteLength": 36}]})");
  };
  const Scene s = read_scene(gltf("a.gltf", R"({"hrad": {"emission-units": "W/m2"}})"));
  ASSERT_TRUE(s.emission_units.has_value());
  EXPECT_EQ(s.emission_units->units, EmissionUnits::watts_per_m2);
  EXPECT_FALSE(read_scene(gltf("b.gltf", R"({"author": "someone"})")).emission_units);
  const std::string bad = error_of(gltf("c.gltf", R"({"hrad": {"emission-units": 3}})"));
  EXPECT_NE(bad.find("c.gltf: /asset/extras/hrad/emission-units: not a string"), std::string::npos) << bad;
  const std::string unknown = error_of(gltf("d.gltf", R"({"hrad": {"units": "W/m2"}})"));
  EXPECT_NE(unknown.find("d.gltf: /asset/extras/hrad: unknown hrad declaration 'units'"), std::string::npos)
      << unknown;
}

}  // namespace
}  // namespace hrad
