// The interfaces other checks read (issues 3 and 5), exercised through the real executable: the
// form-factor JSON against Howell's closed forms, the solve report's fields and invariants, and
// determinism (issue 7): the same command gives the same bytes, whatever the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "../formfactor/howell.h"
#include "run_hrad.h"

namespace hrad::test {
namespace {

TEST(CliFormFactor, PrintsBothDirectionsMatchingHowell) {
  TempDir dir;
  // Opposed 2 x 1 rectangles 0.5 apart (Howell C-11), a point under a corner of a parallel
  // 1.5 x 2 rectangle 3 away (B-3), and a pair whose receiver faces away.
  const std::string path = dir.write("pairs.json", R"({"pairs": [
      {"name": "opposed", "from": [[0,0,0],[2,0,0],[2,1,0],[0,1,0]], "to": [[0,0,0.5],[0,1,0.5],[2,1,0.5],[2,0,0.5]]},
      {"name": "corner", "from_point": [0,0,0], "from_normal": [0,0,1], "to": [[0,0,3],[0,2,3],[1.5,2,3],[1.5,0,3]]},
      {"name": "away", "from": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "to": [[0,0,1],[1,0,1],[1,1,1],[0,1,1]]}]})");
  const RunResult r = run_hrad("formfactor --json " + path, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("pairs").size(), 3u);
  const auto& opposed = j["pairs"][0];
  EXPECT_EQ(opposed.at("name"), "opposed");
  const double f = howell_c11(2.0, 1.0, 0.5);
  EXPECT_NEAR(opposed.at("F_from_to").get<double>(), f, 1e-11 * f);
  EXPECT_NEAR(opposed.at("F_to_from").get<double>(), f, 1e-11 * f);  // equal areas
  const auto& corner = j["pairs"][1];
  const double g = howell_b3(1.5, 2.0, 3.0);
  EXPECT_NEAR(corner.at("F_from_to").get<double>(), g, 1e-11 * g);
  EXPECT_TRUE(corner.at("F_to_from").is_null());
  // The second square's front faces +z, away from the first: exactly zero both ways.
  EXPECT_EQ(j["pairs"][2].at("F_from_to").get<double>(), 0.0);
  EXPECT_EQ(j["pairs"][2].at("F_to_from").get<double>(), 0.0);
}

TEST(CliSolve, ReportHoldsTheInterfaceFieldsAndFullMatrixCountsNSquared) {
  TempDir dir;
  const RunResult r = run_hrad("solve notebooks_data/scenes/two_far_surfaces.obj --method full --max-area 1 --quiet "
                               "--report " + dir.path("r.json") + " --out " + dir.path("s.ply"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "--quiet printed: " << r.err;
  const auto j = nlohmann::json::parse(slurp(dir.path("r.json")));
  EXPECT_EQ(j.at("method"), "full");
  const long n = j.at("elements").get<long>();
  EXPECT_EQ(n, 32);  // two 4 x 4 squares in elements of area <= 1
  EXPECT_EQ(j.at("links").get<long>(), n * n);
  EXPECT_GT(j.at("form_factor_evaluations").get<long>(), 0);
  EXPECT_EQ(j.at("visibility_queries").get<long>(), 0);  // nothing can block: visibility is off
  EXPECT_FALSE(j.at("effects").at("visibility").get<bool>());
  EXPECT_EQ(j.at("effects").at("color_channels").get<int>(), 1);
  EXPECT_GE(j.at("iterations").get<int>(), 0);
  EXPECT_GE(j.at("seconds").at("total").get<double>(), 0.0);
  const auto& patches = j.at("patches");
  ASSERT_EQ(patches.size(), 2u);
  EXPECT_EQ(patches[0].at("group"), "emitter");
  EXPECT_EQ(patches[1].at("group"), "receiver");
  EXPECT_DOUBLE_EQ(patches[0].at("area").get<double>(), 16.0);
  // The receiver gathers E F rho from the emitter (plus a little back): positive, well below E.
  const double e = patches[0].at("emission")[0].get<double>();
  const double b = patches[1].at("radiosity")[0].get<double>();
  const double rho = patches[1].at("reflectance")[0].get<double>();
  EXPECT_GT(b, 0.0);
  EXPECT_LT(b, rho * e * 0.05);  // F between 4 x 4 squares 20 apart is about 0.013
  EXPECT_TRUE(std::filesystem::exists(dir.path("s.ply")));
  EXPECT_EQ(dir.entries(), 2u);  // the two outputs and no temporary file
}

TEST(CliSolve, SameBytesRunAfterRunAndWhateverTheThreadCount) {
  TempDir dir;
  const std::string base = "solve notebooks_data/scenes/cornell_box.obj --quiet --method ";
  for (const std::string method : {"hierarchical", "substructure"}) {
    const std::string extra = method == "substructure" ? " --max-area 20000" : "";
    ASSERT_EQ(run_hrad(base + method + extra + " --threads 1 --out " + dir.path("a.ply"), dir).exit_code, 0);
    ASSERT_EQ(run_hrad(base + method + extra + " --threads 2 --out " + dir.path("b.ply"), dir).exit_code, 0);
    ASSERT_EQ(run_hrad(base + method + extra + " --threads 2 --out " + dir.path("c.ply"), dir).exit_code, 0);
    const std::string a = slurp(dir.path("a.ply"));
    EXPECT_GT(a.size(), 1000u);
    EXPECT_TRUE(a == slurp(dir.path("b.ply"))) << method << ": 1 and 2 threads differ";
    EXPECT_TRUE(a == slurp(dir.path("c.ply"))) << method << ": two runs differ";
  }
}

}  // namespace
}  // namespace hrad::test
