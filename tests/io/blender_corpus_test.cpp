// One scene exported by Blender twice (tests/io/corpus/blender: OBJ + MTL, and glTF): a sphere light,
// n-gons, an applied Bevel modifier and smoothing groups. Both files must load as the same geometry
// and materials (tests/cli/cli_corpus_test.cpp solves both).
#include <gtest/gtest.h>

#include <map>

#include "hrad/core/scene_checks.h"
#include "hrad/io/input_file.h"
#include "hrad/io/scene_reader.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

const std::string kDir = test::source_dir() + "/tests/io/corpus/blender/";

std::map<std::string, double> area_by_group(const Scene& s) {
  std::map<std::string, double> g;
  for (const Patch& p : s.patches) g[p.group] += p.area;
  return g;
}

TEST(BlenderCorpus, ObjAndGltfLoadAsTheSameSceneWithWhatBlenderWrote) {
  std::vector<std::string> obj_warnings, gltf_warnings;
  const Scene obj = read_scene(kDir + "room.obj", &obj_warnings);
  const Scene gltf = read_scene(kDir + "room.gltf", &gltf_warnings);
  // The exporter's 6 decimals are within the planarity tolerance: no face is reported bent.
  EXPECT_TRUE(obj_warnings.empty()) << obj_warnings[0];
  EXPECT_TRUE(gltf_warnings.empty()) << gltf_warnings[0];
  EXPECT_TRUE(scene_warnings(obj).empty()) << scene_warnings(obj)[0];
  // What the file holds: smoothing groups, and n-gons (the cylinder's two 8-gon caps, triangulated
  // into 6 patches each: 114 faces, 124 patches). The glTF exporter triangulated the same polygons:
  // a k-gon is k - 2 triangles, so its triangles are the OBJ patches' sum of (vertices - 2).
  const std::string text = read_input_file(kDir + "room.obj");
  EXPECT_NE(text.find("\ns 1\n"), std::string::npos);
  EXPECT_EQ(obj.faces.size(), 114u);
  EXPECT_EQ(obj.patches.size(), 114u + 2u * 5u);
  std::size_t triangles = 0;
  for (const Patch& p : obj.patches) triangles += p.vertices.size() - 2;
  EXPECT_EQ(gltf.faces.size(), triangles);
  // The sphere light: 12 segments x 6 rings = 72 faces (24 triangles, 48 quads).
  int sphere_faces = 0;
  for (const InputFace& f : obj.faces) sphere_faces += f.group == "SphereLight" ? 1 : 0;
  EXPECT_EQ(sphere_faces, 72);

  // The same surfaces: per object, areas agree to the OBJ's 6 decimals (each vertex moved by up to
  // 5e-7 m; on the sphere's ~0.13 m facets an area changes by up to ~1e-5 relative; float32 in the
  // glTF is ~1e-7).
  const auto a = area_by_group(obj), b = area_by_group(gltf);
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  for (const auto& [name, area] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    EXPECT_NEAR(b.at(name), area, 1e-5 * area) << name;
  }
  // Room 4 x 4 x 3 m: 2 x 16 + 4 x 12 = 80 m^2.
  EXPECT_NEAR(a.at("Room"), 80.0, 1e-9);
  // The same materials: base colours 0.6 / 0.1 (float32 in glTF), the light's emission colour 1 x strength 5.
  for (const Material& m : obj.materials) {
    bool found = false;
    for (const Material& n : gltf.materials)
      if (n.name == m.name) {
        found = true;
        EXPECT_LT((n.reflectance - m.reflectance).abs().maxCoeff(), 1e-7) << m.name;
        EXPECT_EQ((n.emission - m.emission).abs().maxCoeff(), 0.0) << m.name;
      }
    EXPECT_TRUE(found) << m.name;
  }
  EXPECT_EQ(obj.materials.size(), 4u);
  for (const Material& m : obj.materials)
    if (m.name == "Light") EXPECT_EQ(m.emission[0], 5.0);
}

}  // namespace
}  // namespace hrad
