// `hrad compare` as a user runs it: a solve of two plates scored against the ruler (the solver's
// constant element is exact there: Howell C-11, so what remains is the ruler's noise, which the
// command must account for), against a reference scaled by hand (the relative error and bias
// worked out), and against itself.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "plates_scene.h"
#include "run_hrad.h"

namespace hrad::test {
namespace {

nlohmann::json compare(const TempDir& dir, const std::string& against, const std::string& extra = "") {
  const RunResult r = run_hrad(
      "compare " + dir.path("r.json") + " --against " + dir.path(against) + " --out " + dir.path("c.json") + extra,
      dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("relative L2"), std::string::npos) << r.out;
  return nlohmann::json::parse(slurp(dir.path("c.json")));
}

TEST(CliCompare, ExactPlatesAgainstTheRulerLeaveOnlyItsNoise) {
  TempDir dir;
  write_plates(dir);
  ASSERT_EQ(run_hrad("solve " + dir.path("plates.obj") + " --quiet --report " + dir.path("r.json"), dir).exit_code, 0);
  ASSERT_EQ(
      run_hrad("reference " + dir.path("plates.obj") + " --faces --samples 16384 --quiet --out " + dir.path("f.csv"),
               dir)
          .exit_code,
      0);
  const nlohmann::json c = compare(dir, "f.csv");
  const double l2 = c["relative_l2"], noise = c["reference_noise"];
  // The emitter reflects nothing (black): scored by B - E, it adds nothing; its emission counted
  // as error would dominate. The receiver is exact up to the ruler's noise.
  EXPECT_GT(noise, 0.0);
  EXPECT_LT(noise, 0.01);
  EXPECT_LT(l2, 4.0 * noise);
  EXPECT_EQ(c["faces"], 2);
}

TEST(CliCompare, ScaledReferenceGivesTheWorkedError) {
  TempDir dir;
  write_plates(dir);
  ASSERT_EQ(run_hrad("solve " + dir.path("plates.obj") + " --quiet --report " + dir.path("r.json"), dir).exit_code, 0);
  const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("r.json")));
  // A ruler CSV whose receiver is 10% brighter than the solve, with standard errors of 1% of its values.
  std::string csv =
      "face,group,area,radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se\n"
      "0,light,1,2,1,0.5,0,0,0\n";
  const auto& b = report["patches"][1]["radiosity"];
  csv += fmt::format("1,receiver,1,{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", 1.1 * b[0].get<double>(),
                     1.1 * b[1].get<double>(), 1.1 * b[2].get<double>(), 0.011 * b[0].get<double>(),
                     0.011 * b[1].get<double>(), 0.011 * b[2].get<double>());
  dir.write("scaled.csv", csv);
  const nlohmann::json c = compare(dir, "scaled.csv", " --by group");
  EXPECT_NEAR(c["relative_l2"].get<double>(), 0.1 / 1.1, 1e-12);
  EXPECT_NEAR(c["bias"].get<double>(), -0.1 / 1.1, 1e-12);
  EXPECT_NEAR(c["reference_noise"].get<double>(), 0.01, 1e-12);  // 1% of the reference
  EXPECT_EQ(c["largest_face"]["face"], 1);
  EXPECT_EQ(c["largest_face"]["group"], "receiver");
  ASSERT_EQ(c["groups"].size(), 2u);
  EXPECT_EQ(c["groups"][0]["key"], "receiver");
  EXPECT_NEAR(c["groups"][0]["share"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(c["groups"][1]["share"].get<double>(), 0.0);

  // Face by face: the receiver errs by 0.1 / 1.1 and carries all of the squared error; the black
  // emitter reflects nothing in the reference, so it has no relative error.
  ASSERT_EQ(run_hrad("compare " + dir.path("r.json") + " --against " + dir.path("scaled.csv") + " --faces-out " +
                         dir.path("f.csv"),
                     dir)
                .exit_code,
            0);
  std::istringstream rows(slurp(dir.path("f.csv")));
  std::string header, light, receiver, extra;
  std::getline(rows, header);
  std::getline(rows, light);
  std::getline(rows, receiver);
  EXPECT_FALSE(std::getline(rows, extra));
  EXPECT_EQ(header,
            "face,line,group,material,area,reflected_r,reflected_g,reflected_b,reference_r,reference_g,reference_b,"
            "reference_se_r,reference_se_g,reference_se_b,error,share");
  const std::vector<std::string> l = csv_cells(light), r = csv_cells(receiver);
  ASSERT_EQ(l.size(), 16u);
  ASSERT_EQ(r.size(), 16u);
  EXPECT_EQ(l[2], "light");
  EXPECT_EQ(l[14], "");
  EXPECT_EQ(std::stod(l[15]), 0.0);
  EXPECT_EQ(r[2], "receiver");
  EXPECT_NEAR(std::stod(r[14]), 0.1 / 1.1, 1e-12);
  EXPECT_NEAR(std::stod(r[15]), 1.0, 1e-12);

  // A report against itself: no error, no noise.
  const nlohmann::json self = compare(dir, "r.json");
  EXPECT_EQ(self["relative_l2"].get<double>(), 0.0);
  EXPECT_EQ(self["reference_noise"].get<double>(), 0.0);
}

}  // namespace
}  // namespace hrad::test
