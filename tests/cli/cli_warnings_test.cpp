// Scenes that read fine but would solve to a wrong-looking answer: `hrad info` and `hrad solve` say so
// on stderr and the solve report lists the warnings (core/scene_checks.h); scenes in other formats
// and files that are not scenes.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "run_hrad.h"

namespace hrad::test {
namespace {

// The box [0,2] x [0,1] x [0,1] as Blender exports it, 6 decimals; `flip` reverses every face (the
// normals then point out of the room); the light is a small quad under the ceiling facing down.
std::string box_obj(bool flip, const std::string& light_material) {
  std::string obj =
      "# Blender v3.4.1 OBJ File: ''\nmtllib box.mtl\no Room\n"
      "v 0.000000 0.000000 0.000000\nv 2.000000 0.000000 0.000000\nv 2.000000 0.000000 1.000000\n"
      "v 0.000000 0.000000 1.000000\nv 0.000000 1.000000 0.000000\nv 2.000000 1.000000 0.000000\n"
      "v 2.000000 1.000000 1.000000\nv 0.000000 1.000000 1.000000\n"
      "v 0.900000 0.990000 0.400000\nv 1.100000 0.990000 0.400000\nv 1.100000 0.990000 0.600000\n"
      "v 0.900000 0.990000 0.600000\nusemtl Wall\ns 1\n";
  const char* faces[] = {"1 4 3 2", "5 6 7 8", "1 2 6 5", "4 8 7 3", "1 5 8 4", "2 3 7 6"};
  for (const char* f : faces) {
    std::string face = f;
    if (flip) face = std::string{face[6], ' ', face[4], ' ', face[2], ' ', face[0]};
    obj += "f " + face + "\n";
  }
  obj += "usemtl " + light_material + "\nf 9 10 11 12\n";
  return obj;
}

const std::string kMtl =
    "# Blender MTL File: 'None'\nnewmtl Wall\nNs 250.000000\nKa 1.000000 1.000000 1.000000\n"
    "Kd 0.500000 0.500000 0.500000\nKs 0.500000 0.500000 0.500000\nKe 0.000000 0.000000 0.000000\nNi 1.450000\n"
    "d 1.000000\nillum 2\nnewmtl Lamp\nKd 0.800000 0.800000 0.800000\nKe 10.000000 10.000000 10.000000\nillum 2\n"
    "newmtl Emission\nKd 0.800000 0.800000 0.800000\nKe 0.000000 0.000000 0.000000\nillum 2\n";

TEST(CliWarnings, SoundBoxIsQuiet) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  const std::string obj = dir.write("box.obj", box_obj(false, "Lamp"));
  const RunResult r = run_hrad("info " + obj, dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliWarnings, OutwardNormalsEmitterlessAndZeroEmissionExports) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  // Normals out of the room: solves to black without a word before.
  const std::string flipped = dir.write("flipped.obj", box_obj(true, "Lamp"));
  const RunResult info = run_hrad("info " + flipped, dir);
  EXPECT_EQ(info.exit_code, 0);
  EXPECT_NE(info.err.find("6 of 7 patches"), std::string::npos) << info.err;
  EXPECT_NE(info.err.find("flip them"), std::string::npos) << info.err;
  // Blender's Emission shader exported as Ke 0: no emitter, and a light-named material that emits nothing.
  const std::string dark = dir.write("dark.obj", box_obj(false, "Emission"));
  const RunResult solve = run_hrad("solve " + dark + " --quiet --report " + dir.path("r.json"), dir);
  EXPECT_EQ(solve.exit_code, 0) << solve.err;
  EXPECT_NE(solve.err.find("no face emits light"), std::string::npos) << solve.err;
  EXPECT_NE(solve.err.find("material 'Emission' looks like a light but emits nothing"), std::string::npos) << solve.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("r.json")));
  ASSERT_TRUE(report.contains("warnings"));
  EXPECT_EQ(report["warnings"].size(), 2u) << report["warnings"].dump();
}

TEST(CliWarnings, FaceWithoutMaterialSolvesWithTheDefault) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  std::string obj = box_obj(false, "Lamp");
  obj.replace(obj.find("usemtl Wall\n"), 12, "");  // the walls before any usemtl
  const RunResult r = run_hrad("solve " + dir.write("nomat.obj", obj) + " --quiet", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("nomat.obj:17: warning: this face and 5 more have no material"), std::string::npos) << r.err;
}

TEST(CliWarnings, SolutionGivenAsASceneSaysWhatItIs) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  const std::string obj = dir.write("box.obj", box_obj(false, "Lamp"));
  ASSERT_EQ(run_hrad("solve " + obj + " --quiet --out " + dir.path("s.ply"), dir).exit_code, 0);
  const RunResult r = run_hrad("solve " + dir.path("s.ply"), dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("this is a solution written by 'hrad solve'"), std::string::npos) << r.err;
}

// Every solve prints and reports where the power went (reference/power_balance.h). The closed box
// solved by the full matrix with the analytic kernel balances (no warning, the report's residual
// within the allowance); the same box solved hierarchically and stopped after one iteration has absorbed only the first
// bounces, and the lost power is a warning on stderr and in the report that names the iteration limit.
TEST(CliWarnings, PowerThatDoesNotBalanceIsAWarning) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  const std::string obj = dir.write("box.obj", box_obj(false, "Lamp"));
  RunResult r =
      run_hrad("solve " + obj + " --method full --kernel analytic --quiet --report " + dir.path("ok.json"), dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("power: emitted 0.4;"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("does not balance power"), std::string::npos) << r.err;
  nlohmann::json report = nlohmann::json::parse(slurp(dir.path("ok.json")));
  EXPECT_TRUE(report["power_balance"]["balanced"].get<bool>()) << report["power_balance"].dump();
  EXPECT_NEAR(report["power_balance"]["emitted"].get<double>(), 10 * 0.2 * 0.2, 1e-9);
  EXPECT_EQ(report["power_balance"]["escaped"].get<double>(), 0.0);  // closed
  r = run_hrad("solve " + obj + " --quiet --max-iterations 1 --report " + dir.path("short.json"), dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("does not balance power"), std::string::npos) << r.err;
  // and says why: the iterations stopped, not the mesh
  EXPECT_NE(r.err.find("stopped at --max-iterations before converging"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("refine"), std::string::npos) << r.err;
  report = nlohmann::json::parse(slurp(dir.path("short.json")));
  EXPECT_FALSE(report["power_balance"]["balanced"].get<bool>());
  EXPECT_GT(report["power_balance"]["relative_residual"].get<double>(), 0.1);
  ASSERT_EQ(report["warnings"].size(), 1u);
  EXPECT_NE(report["warnings"][0].get<std::string>().find("does not balance power"), std::string::npos);
}

// A rug modelled flush with the floor (same plane, facing up): light reaching it would land on the rug
// and on the floor beneath, and the solution would absorb more than the box emits (19% more at
// --method full). The reader takes the rug, the smaller object, to lie on top, cuts what it covers
// out of the floor and says so; the power then balances with every method, as it does with the rug
// lifted a tenth of a millimetre (where visibility hides the floor beneath it and nothing is cut).
TEST(CliWarnings, FlushRugIsCutOutOfTheFloorAndPowerBalances) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  for (const std::string height : {"0.000000", "0.000100"}) {
    const std::string obj =
        dir.write("rug.obj", box_obj(false, "Lamp") + "o Rug\nusemtl Wall\nv 0.500000 " + height +
                                 " 0.250000\nv 0.500000 " + height + " 0.750000\nv 1.500000 " + height +
                                 " 0.750000\nv 1.500000 " + height + " 0.250000\nf 13 14 15 16\n");
    for (const std::string method : {"full --kernel analytic", "substructure", "hierarchical"}) {
      const RunResult r =
          run_hrad("solve " + obj + " --method " + method + " --quiet --report " + dir.path("r.json"), dir);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("r.json")));
      const nlohmann::json& balance = report["power_balance"];
      // Absorbed (on the faces' fronts and on the lamp's back) against emitted.
      EXPECT_TRUE(balance["balanced"].get<bool>()) << method << " " << height << " " << balance.dump();
      EXPECT_LT(std::abs(balance["relative_residual"].get<double>()), 1e-3)
          << method << " " << height << " " << balance.dump();
      EXPECT_EQ(r.err.find("does not balance power"), std::string::npos) << r.err;
      // The floor (the first face) shows 2 - 0.5 when the rug lies on it, all of itself when lifted.
      const double floor = report["patches"][0]["area"].get<double>();
      if (height == "0.000000") {
        EXPECT_NE(r.err.find("rug.obj:32: warning: 1 pair of faces lie flush on each other"), std::string::npos)
            << r.err;
        EXPECT_NE(r.err.find("first: line 32 on line 18"), std::string::npos) << r.err;
        EXPECT_NEAR(floor, 1.5, 1e-12);
      } else {
        EXPECT_EQ(r.err.find("flush"), std::string::npos) << r.err;
        EXPECT_NEAR(floor, 2.0, 1e-12);
      }
    }
  }
}

TEST(CliWarnings, AFaceJustAboveTheFloorFacingItIsCutAlongByDefaultAndNamedOtherwise) {
  TempDir dir;
  dir.write("box.mtl", kMtl);
  // A box's bottom 1 cm above the floor, facing down: the floor is dark under it and lit around it.
  const std::string obj =
      dir.write("bottom.obj", box_obj(false, "Lamp") +
                                  "o Box\nusemtl Wall\nv 0.500000 0.010000 0.250000\nv 0.500000 0.010000 0.750000\n"
                                  "v 1.500000 0.010000 0.750000\nv 1.500000 0.010000 0.250000\nf 16 15 14 13\n");
  const std::string warning =
      "bottom.obj:18: warning: 1 pair of faces face each other from nearby (first: line 32, 0.01 in front of line 18)";
  const RunResult whole = run_hrad("solve " + obj + " --quiet --no-cut-near-faces --report " + dir.path("r.json"), dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_NE(whole.err.find(warning), std::string::npos) << whole.err;
  EXPECT_NE(whole.err.find("without --no-cut-near-faces, hrad solve and hrad sweep cut along the outline"),
            std::string::npos)
      << whole.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("r.json")));
  EXPECT_NE(report["warnings"].dump().find("face each other from nearby"), std::string::npos);
  EXPECT_FALSE(report["options"]["cut_near_faces"].get<bool>());
  // hrad info names them before any solve, as a note of what the solvers cut.
  const RunResult info = run_hrad("info " + obj, dir);
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.err.find("bottom.obj:18: note: 1 pair of faces face each other from nearby (first: line 32, 0.01 in "
                          "front of line 18): hrad solve and hrad sweep cut the face behind"),
            std::string::npos)
      << info.err;
  // By default the solve cuts the floor along the bottom: nothing to warn of.
  const RunResult cut = run_hrad("solve " + obj + " --quiet --report " + dir.path("c.json"), dir);
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  EXPECT_EQ(cut.err.find("from nearby"), std::string::npos) << cut.err;
  const nlohmann::json cut_report = nlohmann::json::parse(slurp(dir.path("c.json")));
  EXPECT_TRUE(cut_report["options"]["cut_near_faces"].get<bool>());
  EXPECT_GT(cut_report["patch_count"].get<int>(), report["patch_count"].get<int>());
  // Lifted to 0.2 (more than a tenth of the bottom's diameter 1.1): nothing to name.
  std::string far = slurp(obj);
  for (std::size_t at = far.find("0.010000"); at != std::string::npos; at = far.find("0.010000"))
    far.replace(at, 8, "0.200000");
  const RunResult lifted = run_hrad("solve " + dir.write("far.obj", far) + " --quiet", dir);
  ASSERT_EQ(lifted.exit_code, 0) << lifted.err;
  EXPECT_EQ(lifted.err.find("from nearby"), std::string::npos) << lifted.err;
}

}  // namespace
}  // namespace hrad::test
