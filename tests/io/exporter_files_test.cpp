// What exporters write (Blender, 3ds Max, SketchUp, MeshLab), read with the right geometry and
// materials: each case states the exporter habit it stands for and checks areas, counts and
// reflectance against values computed by hand from the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include <fmt/format.h>
#include "../support/temp_dir.h"
#include "hrad/core/error.h"
#include "hrad/io/obj_reader.h"
#include "hrad/io/scene_reader.h"

namespace hrad {
namespace {

const Material& material_named(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

// A unit square in z = 0 facing +z (vertices 1-4) and a 2 x 1 rectangle at z = 1 facing -z (5-8).
const std::string kTwoQuads = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 0 1 1\nv 2 1 1\nv 2 0 1\n";

TEST(ExporterFiles, ByteOrderMarksOnObjAndMtl) {
  // Windows tools (3ds Max, Notepad) start files with a UTF-8 byte order mark.
  test::TempDir dir;
  dir.write("m.mtl", "\xEF\xBB\xBFnewmtl w\nKd 0.25 0.5 0.75\n");
  const Scene s =
      read_obj_scene(dir.write("s.obj", "\xEF\xBB\xBFmtllib m.mtl\nusemtl w\n" + kTwoQuads + "f 1 2 3 4\n"));
  ASSERT_EQ(s.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(s.patches[0].area, 1.0);
  EXPECT_EQ(material_named(s, "w").reflectance[2], 0.75);
}

TEST(ExporterFiles, OneValueKdMeansGrey) {
  // MTL spec: "Kd r g b" where g and b default to r.
  test::TempDir dir;
  dir.write("m.mtl", "newmtl w\nKd 0.7\nKe 2\n");
  const Scene s = read_obj_scene(dir.write("s.obj", "mtllib m.mtl\nusemtl w\n" + kTwoQuads + "f 1 2 3 4\n"));
  const Material& w = material_named(s, "w");
  EXPECT_EQ(w.reflectance[0], 0.7);
  EXPECT_EQ(w.reflectance[1], 0.7);
  EXPECT_EQ(w.reflectance[2], 0.7);
  EXPECT_EQ(w.emission[2], 2.0);
}

TEST(ExporterFiles, TwoLibrariesOnOneMtllibLineAndNamesWithSpaces) {
  // Blender: "mtllib my scene.mtl" and "newmtl Material.001"; SketchUp: names with spaces; some
  // exporters list several libraries on one line or quote names.
  test::TempDir dir;
  dir.write("a.mtl", "newmtl Red Brick\nKd 0.5 0.1 0.1\n");
  dir.write("b.mtl", "newmtl \"Glass Pane\"\nKd 0.1 0.1 0.5\n");
  dir.write("my scene.mtl", "newmtl Material.001\nKd 0.3 0.3 0.3\n");
  const Scene s = read_obj_scene(dir.write(
      "s.obj", "mtllib a.mtl b.mtl\nmtllib my scene.mtl\n" + kTwoQuads +
                   "usemtl Red Brick\nf 1 2 3 4\nusemtl Glass Pane\nf 5 6 7 8\nusemtl Material.001\nf 1 2 3\n"));
  ASSERT_EQ(s.faces.size(), 3u);
  EXPECT_EQ(s.materials[s.faces[0].material].name, "Red Brick");
  EXPECT_EQ(s.materials[s.faces[0].material].reflectance[0], 0.5);
  EXPECT_EQ(s.materials[s.faces[1].material].name, "Glass Pane");
  EXPECT_EQ(s.materials[s.faces[1].material].reflectance[2], 0.5);
  EXPECT_EQ(s.materials[s.faces[2].material].name, "Material.001");
  EXPECT_DOUBLE_EQ(s.faces[1].area, 2.0);
  EXPECT_EQ(s.files.size(), 4u);  // the OBJ and its three libraries
}

TEST(ExporterFiles, CommentsAfterStatementsAndPrincipledBsdfExtras) {
  // 3ds Max writes "f 1 2 3 4 # quad"; Blender's Principled BSDF export adds Pr, Pm, Ps, Pc, Pcr,
  // aniso, map_* beside Ke; none of them is a radiosity material's business, Kd and Ke are.
  test::TempDir dir;
  dir.write("m.mtl",
            "# Blender MTL File\nnewmtl Emitter\nNs 250.000000\nKa 1.000000 1.000000 1.000000\n"
            "Kd 0.800000 0.800000 0.800000\nKs 0.500000 0.500000 0.500000\nKe 10.000000 9.000000 8.000000\n"
            "Ni 1.450000\nd 1.000000\nillum 2\nPr 0.5\nPm 0.0\nPs 0.0\nPc 0.0\nPcr 0.03\naniso 0.0\nanisor 0.0\n"
            "map_Kd tex.png\nmap_Ke glow.png\n");
  const Scene s = read_obj_scene(
      dir.write("s.obj", "mtllib m.mtl # libraries\nusemtl Emitter\n" + kTwoQuads + "f 1 2 3 4 # quad\n"));
  ASSERT_EQ(s.patches.size(), 1u);
  const Material& m = material_named(s, "Emitter");
  EXPECT_EQ(m.reflectance[0], 0.8);
  EXPECT_EQ(m.emission[0], 10.0);
  EXPECT_EQ(m.emission[2], 8.0);
}

TEST(ExporterFiles, HashInsideMaterialNamesIsPartOfTheName) {
  // 3ds Max's default material names: "Material #25", "Material #26". Cut at '#' as a trailing comment,
  // both were one "Material" holding the last definition's values.
  test::TempDir dir;
  dir.write("m.mtl",
            "newmtl Material #25\n\tKd 0.2500 0.2500 0.2500\nnewmtl Material #26\n\tKd 0.7500 0.7500 0.7500\n");
  const Scene s =
      read_obj_scene(dir.write("s.obj", "mtllib m.mtl\n" + kTwoQuads +
                                            "usemtl Material #25\nf 1 2 3 4\nusemtl Material #26\nf 5 6 7 8 # top\n"));
  ASSERT_EQ(s.patches.size(), 2u);
  EXPECT_EQ(s.materials[s.patches[0].material].name, "Material #25");
  EXPECT_EQ(s.materials[s.patches[0].material].reflectance[0], 0.25);
  EXPECT_EQ(s.materials[s.patches[1].material].name, "Material #26");
  EXPECT_EQ(s.materials[s.patches[1].material].reflectance[0], 0.75);
  EXPECT_DOUBLE_EQ(s.patches[1].area, 2.0);  // the face's trailing comment is still a comment
}

TEST(ExporterFiles, HexFloatIsAnErrorNotADifferentNumber) {
  // strtod reads 0x1p2 as 4, tinyobjloader as 0: one number syntax for both passes.
  test::TempDir dir;
  dir.write("m.mtl", "newmtl w\nKd 0.5 0.5 0.5\n");
  const std::string obj = dir.write("s.obj", "mtllib m.mtl\nusemtl w\nv 0 0 0\nv 0x1p2 0 0\nv 0 1 0\nf 1 2 3\n");
  try {
    read_obj_scene(obj);
    FAIL() << "hex float accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(obj + ":4: '0x1p2' is not a number"), std::string::npos) << e.what();
  }
}

TEST(ExporterFiles, FaceWithoutMaterialGetsTheDefaultWithOneWarning) {
  test::TempDir dir;
  std::vector<std::string> warnings;
  const Scene s = read_obj_scene(dir.write("s.obj", kTwoQuads + "f 1 2 3 4\nf 5 6 7 8\n"), &warnings);
  ASSERT_EQ(s.faces.size(), 2u);
  const Material& m = s.materials[s.faces[0].material];
  EXPECT_EQ(m.name, kDefaultMaterialName);
  EXPECT_EQ(m.reflectance[1], kDefaultReflectance);
  EXPECT_FALSE(m.is_emitter());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("s.obj:9: warning: this face and 1 more have no material"), std::string::npos)
      << warnings[0];
}

// Blender rounds coordinates to 6 decimals: a 1 m quad rotated about an axis comes out off its plane
// by up to ~1e-6 absolute. It must read as one planar patch; a truly bent quad is still split, and
// many bent faces give one warning line.
TEST(ExporterFiles, PlanarityWithinThePrintedPrecisionAndOneLineForManyBentFaces) {
  test::TempDir dir;
  dir.write("m.mtl", "newmtl w\nKd 0.5 0.5 0.5\n");
  // A unit quad in the plane x + y + z = 1.5 through (0.5,0.5,0.5), corners printed with 6 decimals.
  const Vec3 c(0.5, 0.5, 0.5), u = Vec3(1, -1, 0).normalized(), w = Vec3(1, 1, -2).normalized();
  std::string obj = "mtllib m.mtl\nusemtl w\n";
  for (const auto& [a, b] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}) {
    const Vec3 p = c + a * u + b * w;
    obj += fmt::format("v {:.6f} {:.6f} {:.6f}\n", p.x(), p.y(), p.z());
  }
  obj += "f 1 2 3 4\n";
  std::vector<std::string> warnings;
  const Scene rounded = read_obj_scene(dir.write("r.obj", obj), &warnings);
  EXPECT_EQ(rounded.patches.size(), 1u);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  EXPECT_NEAR(rounded.total_area(), 1.0, 4e-6);  // 6 decimals on a unit square

  // Three quads bent by 0.1 (corner lifted): split, one warning naming the first.
  std::string bent = "mtllib m.mtl\nusemtl w\n";
  for (int k = 0; k < 3; ++k)
    bent += fmt::format("v {0} 0 0\nv {1} 0 0\nv {1} 1 0.1\nv {0} 1 0\nf -4 -3 -2 -1\n", 2 * k, 2 * k + 1);
  warnings.clear();
  const Scene b = read_obj_scene(dir.write("b.obj", bent), &warnings);
  EXPECT_EQ(b.patches.size(), 6u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("b.obj:7: warning: 3 faces are non-planar"), std::string::npos) << warnings[0];
}

// MeshLab-style PLY: per-vertex uchar colours; and a face-property PLY with reflectance and emission.
TEST(ExporterFiles, PlyScenesWithVertexColoursOrFaceProperties) {
  test::TempDir dir;
  const std::string vertex_colours = dir.write(
      "v.ply",
      "ply\nformat ascii 1.0\ncomment MeshLab style\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0 51 102 153\n2 0 0 51 102 153\n2 1 0 51 102 153\n"
      "0 1 0 51 102 153\n4 0 1 2 3\n");
  const Scene v = read_scene(vertex_colours);
  ASSERT_EQ(v.patches.size(), 1u);
  EXPECT_DOUBLE_EQ(v.patches[0].area, 2.0);
  EXPECT_DOUBLE_EQ(v.materials[v.patches[0].material].reflectance[0], 0.2);  // 51 / 255
  EXPECT_DOUBLE_EQ(v.materials[v.patches[0].material].reflectance[2], 0.6);  // 153 / 255

  const std::string face_props =
      dir.write("f.ply",
                "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                "element face 2\nproperty list uchar int vertex_indices\nproperty float reflectance_r\n"
                "property float reflectance_g\nproperty float reflectance_b\nproperty float emission_r\n"
                "property float emission_g\nproperty float emission_b\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                "3 0 1 2 0.5 0.25 0.125 0 0 0\n3 0 2 3 0 0 0 4 4 4\n");
  const Scene f = read_scene(face_props);
  ASSERT_EQ(f.faces.size(), 2u);
  EXPECT_EQ(f.materials[f.faces[0].material].reflectance[1], 0.25);
  EXPECT_EQ(f.emitter_count(), 1);
  EXPECT_EQ(f.materials[f.faces[1].material].emission[0], 4.0);
  EXPECT_DOUBLE_EQ(f.total_area(), 1.0);
}

TEST(ExporterFiles, SolutionPlyGivenAsASceneSaysWhatItIs) {
  test::TempDir dir;
  const std::string sol = dir.write(
      "s.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
      "element face 1\nproperty list uchar int vertex_indices\nproperty double radiosity_r\nproperty int patch\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 0\n");
  try {
    read_scene(sol);
    FAIL() << "a solution read as a scene";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("this is a solution written by 'hrad solve'"), std::string::npos) << e.what();
  }
}

// glTF 2.0 as Blender exports it: a mesh with a node transform, base colour and an emissive
// material with KHR_materials_emissive_strength; the buffer in a .bin file beside it.
TEST(ExporterFiles, GltfWithTransformsBaseColourAndEmissiveStrength) {
  test::TempDir dir;
  // One unit square (two triangles) in z = 0 facing +z.
  const float positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  {
    std::ofstream bin(dir.path("s.bin"), std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
    bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
  }
  const std::string gltf = dir.write("s.gltf", R"({
    "asset": {"version": "2.0", "generator": "hand-written in the style of Khronos glTF Blender I/O"},
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0, "translation": [0, 0, 3], "scale": [2, 3, 1]},
              {"mesh": 1, "rotation": [1, 0, 0, 0]}],
    "meshes": [{"name": "Floor", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
               {"name": "Lamp", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 1}]}],
    "materials": [{"name": "Wall", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.4, 0.3, 1.0]}},
                  {"name": "Light", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.2, 1.0]},
                   "emissiveFactor": [1.0, 0.5, 0.25],
                   "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8.0}}}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "buffers": [{"uri": "s.bin", "byteLength": 60}]})");
  const Scene s = read_scene(gltf);
  ASSERT_EQ(s.faces.size(), 4u);  // two triangles per square
  double floor_area = 0.0, lamp_area = 0.0;
  for (const Patch& p : s.patches) {
    if (p.group == "Floor") {
      floor_area += p.area;
      EXPECT_DOUBLE_EQ(p.vertices[0].z(), 3.0);  // translated
      EXPECT_NEAR(p.normal.z(), 1.0, 1e-15);
    } else {
      lamp_area += p.area;
      EXPECT_NEAR(p.normal.z(), -1.0, 1e-15);  // 180 degrees about x turns +z to -z
    }
  }
  EXPECT_DOUBLE_EQ(floor_area, 6.0);  // scaled 2 x 3
  EXPECT_DOUBLE_EQ(lamp_area, 1.0);
  EXPECT_DOUBLE_EQ(material_named(s, "Wall").reflectance[1], 0.4);
  EXPECT_DOUBLE_EQ(material_named(s, "Light").emission[0], 8.0);
  EXPECT_DOUBLE_EQ(material_named(s, "Light").emission[2], 2.0);
  EXPECT_EQ(s.files.size(), 2u);  // the .gltf and its .bin
}

}  // namespace
}  // namespace hrad
