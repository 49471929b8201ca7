// The Blender corpus scene (tests/io/corpus/blender) solved from its OBJ and from its glTF by the real
// executable: the same answer from both exporters' files.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <nlohmann/json.hpp>

#include "run_hrad.h"

namespace hrad::test {
namespace {

struct Group {
  double area = 0.0;
  double power[3] = {0, 0, 0};  ///< sum of area x radiosity per channel
};

std::map<std::string, Group> groups_of(const std::string& report_path) {
  const nlohmann::json report = nlohmann::json::parse(slurp(report_path));
  std::map<std::string, Group> g;
  for (const auto& p : report["patches"]) {
    Group& group = g[p["group"].get<std::string>()];
    const double a = p["area"].get<double>();
    group.area += a;
    for (int c = 0; c < 3; ++c) group.power[c] += a * p["radiosity"][c].get<double>();
  }
  return g;
}

// Solved by plain HSA at the defaults, each file's own mesh (quads and n-gons against triangles: 517
// against 960 elements): per object, the area-mean radiosity agrees within 1% of the object's
// brightest channel. The bound: HR at the defaults is within a few percent per face of a converged
// answer (README, clustered against plain HSA: worst face 3% at the defaults), and the two meshes'
// errors are independent; an object's mean averages them (measured: at most 0.4%, the cylinder). The
// light's emitted power (area x 5) agrees as the areas do: to 1e-5, the OBJ's 6 decimals on the
// sphere's ~0.13 m facets.
TEST(CliCorpus, BlenderObjAndGltfSolveToTheSameAnswer) {
  TempDir dir;
  const std::string corpus = "tests/io/corpus/blender/";
  for (const char* f : {"room.obj", "room.gltf"}) {
    const RunResult r = run_hrad("solve " + corpus + f + " --quiet --clustering off --report " + dir.path(std::string(f) + ".json"), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;  // no warning on either file
  }
  const auto a = groups_of(dir.path("room.obj.json")), b = groups_of(dir.path("room.gltf.json"));
  ASSERT_EQ(a.size(), 4u);
  ASSERT_EQ(b.size(), 4u);
  for (const auto& [name, g] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    double brightest = 0.0;
    for (double p : g.power) brightest = std::max(brightest, p / g.area);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(b.at(name).power[c] / b.at(name).area, g.power[c] / g.area, 0.01 * brightest) << name << " " << c;
  }
  EXPECT_NEAR(b.at("SphereLight").power[0], a.at("SphereLight").power[0], 1e-5 * a.at("SphereLight").power[0]);
  EXPECT_NEAR(a.at("SphereLight").power[0] / a.at("SphereLight").area, 5.0, 1e-12);  // B = E: black light
}

// Closed unit cubes written by hand in 3ds Max's and SketchUp's habits (tests/io/corpus/hand,
// make_furnaces.py: byte order marks, CRLF, tab-indented MTL statements, "mtllib ./NAME", names with
// '#' and spaces; inches and triangles). Walls Kd 0.5 Ke 2, floor Kd 0.75 Ke 1: E / (1 - rho) = 4 for
// both, so B = 4 on every face is the exact answer of B = E + rho F B whenever every row of F sums to 1.
// The full matrix's contour kernel makes each row of a closed room sum to 1 (README, "Kernels"; the
// hard cases hold such boxes to 1e-8 with LU), so 1e-9 relative here, where the geometry is exact.
// Each face keeps the material its usemtl names: 3ds Max's "Material #25" and "Material #26" are two
// materials, not one "Material" with the last definition's values.
TEST(CliCorpus, HandWrittenExporterFurnacesKeepTheirMaterialsAndSolveToTheClosedForm) {
  struct Case {
    std::string file, floor, walls;
    std::size_t floor_patches, patches;
  };
  const Case cases[] = {{"tests/io/corpus/hand/3dsmax/furnace box.obj", "Material #26", "Material #25", 1, 6},
                        {"tests/io/corpus/hand/sketchup/furnace.obj", "Light Wood Floor", "Beige Wall", 2, 12}};
  for (const Case& c : cases) {
    TempDir dir;
    const RunResult r = run_hrad("solve '" + c.file + "' --method full --quiet --report " + dir.path("r.json"), dir);
    ASSERT_EQ(r.exit_code, 0) << c.file << "\n" << r.err;
    EXPECT_TRUE(r.err.empty()) << c.file << "\n" << r.err;
    const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("r.json")));
    ASSERT_EQ(report["patches"].size(), c.patches) << c.file;
    std::size_t floor_patches = 0;
    for (const auto& p : report["patches"]) {
      const std::string material = p["material"].get<std::string>();
      ASSERT_TRUE(material == c.floor || material == c.walls) << c.file << ": " << material;
      const bool floor = material == c.floor;
      floor_patches += floor ? 1 : 0;
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(p["reflectance"][k].get<double>(), floor ? 0.75 : 0.5) << c.file << " " << material;
        EXPECT_EQ(p["emission"][k].get<double>(), floor ? 1.0 : 2.0) << c.file << " " << material;
        EXPECT_NEAR(p["radiosity"][k].get<double>(), 4.0, 4e-9) << c.file << " patch " << p["face"];
      }
    }
    EXPECT_EQ(floor_patches, c.floor_patches) << c.file;
  }
}

// The same furnace as MeshLab writes PLY (make_furnaces.py: binary little endian, per-face uchar colour
// with alpha, per-face custom float attributes emission_r/g/b). Byte colours make the reflectances
// 128/255 and 191/255 and float emissions make E / (1 - rho) 4 only to float precision, so each
// patch's radiosity must lie between the least and the greatest of the patches' E / (1 - rho) (B =
// sum_k (rho F)^k E is monotone in E), and all of them within float precision of 4.
TEST(CliCorpus, MeshLabPlyFurnaceSolvesToTheClosedForm) {
  TempDir dir;
  const std::string file = "tests/io/corpus/hand/meshlab/furnace.ply";
  const RunResult r = run_hrad("solve " + file + " --method full --quiet --report " + dir.path("r.json"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("r.json")));
  ASSERT_EQ(report["patches"].size(), 6u);
  double least = 1e300, greatest = 0.0;
  for (const auto& p : report["patches"])
    for (int k = 0; k < 3; ++k) {
      const double ratio = p["emission"][k].get<double>() / (1.0 - p["reflectance"][k].get<double>());
      least = std::min(least, ratio);
      greatest = std::max(greatest, ratio);
    }
  EXPECT_NEAR(least, 4.0, 1e-6);
  EXPECT_NEAR(greatest, 4.0, 1e-6);
  for (const auto& p : report["patches"]) {
    EXPECT_DOUBLE_EQ(p["reflectance"][0].get<double>(), p["face"].get<int>() == 0 ? 191.0 / 255.0 : 128.0 / 255.0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(p["radiosity"][k].get<double>(), least * (1 - 1e-9)) << "face " << p["face"];
      EXPECT_LE(p["radiosity"][k].get<double>(), greatest * (1 + 1e-9)) << "face " << p["face"];
    }
  }
}

}  // namespace
}  // namespace hrad::test
