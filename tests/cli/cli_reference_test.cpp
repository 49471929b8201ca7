// `hrad reference` as a user runs it: the CSV columns it promises, values against closed forms
// within 4 standard errors, and the same bytes at 1 and 2 threads.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "../formfactor/howell.h"
#include "plates_scene.h"
#include "run_hrad.h"

namespace hrad::test {
namespace {

std::vector<std::vector<std::string>> read_rows(const std::string& text, std::string* header) {
  std::istringstream in(text);
  std::getline(in, *header);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) rows.push_back(csv_cells(line));
  return rows;
}

TEST(CliReference, PointsCsvMatchesHowellWithinFourStandardErrors) {
  TempDir dir;
  write_plates(dir);
  const std::string common =
      "reference " + dir.path("plates.obj") + " --points " + dir.path("points.csv") + " --samples 4096";
  const RunResult r = run_hrad(common + " --out " + dir.path("r.csv"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rays"), std::string::npos) << r.out;
  std::string header;
  const auto rows = read_rows(slurp(dir.path("r.csv")), &header);
  EXPECT_EQ(
      header,
      "x,y,z,nx,ny,nz,face,irradiance_r,irradiance_g,irradiance_b,irradiance_r_se,irradiance_g_se,irradiance_b_se,"
      "radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se");
  ASSERT_EQ(rows.size(), 2u);
  const double e[3] = {2.0, 1.0, 0.5};
  // Centre of the receiver: four corner rectangles 0.5 x 0.5 at distance 1.
  const double f_centre = 4 * howell_b3(0.5, 0.5, 1.0), f_corner = howell_b3(1.0, 1.0, 0.5);
  ASSERT_EQ(rows[0].size(), 19u);
  EXPECT_EQ(rows[0][6], "1");  // on the receiver, input face 1
  for (int c = 0; c < 3; ++c) {
    const double h = std::stod(rows[0][7 + c]), se = std::stod(rows[0][10 + c]);
    EXPECT_NEAR(h, e[c] * f_centre, 4 * se) << c;
    EXPECT_LT(se, 0.01 * e[c] * f_centre);
    const double b = std::stod(rows[0][13 + c]), b_se = std::stod(rows[0][16 + c]);
    EXPECT_NEAR(b, 0.5 * e[c] * f_centre, 4 * b_se) << c;
  }
  // In space: irradiance only, empty face and radiosity cells.
  ASSERT_EQ(rows[1].size(), 19u);
  EXPECT_EQ(rows[1][6], "");
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(std::stod(rows[1][7 + c]), e[c] * f_corner, 4 * std::stod(rows[1][10 + c])) << c;
    EXPECT_EQ(rows[1][13 + c], "");
  }

  // The same bytes with 1 and 2 threads.
  ASSERT_EQ(run_hrad(common + " --threads 1 --out " + dir.path("a.csv"), dir).exit_code, 0);
  ASSERT_EQ(run_hrad(common + " --threads 2 --out " + dir.path("b.csv"), dir).exit_code, 0);
  EXPECT_TRUE(slurp(dir.path("a.csv")) == slurp(dir.path("b.csv")));
  EXPECT_TRUE(slurp(dir.path("a.csv")) == slurp(dir.path("r.csv")));
}

TEST(CliReference, FacesCsvMatchesHowellC11) {
  TempDir dir;
  write_plates(dir);
  const RunResult r = run_hrad(
      "reference " + dir.path("plates.obj") + " --faces --samples 16384 --quiet --out " + dir.path("f.csv"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  std::string header;
  const auto rows = read_rows(slurp(dir.path("f.csv")), &header);
  EXPECT_EQ(header, "face,group,area,radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0][1], "light");
  EXPECT_EQ(rows[0][3], "2");  // black emitter: its emission, exactly
  EXPECT_EQ(rows[0][6], "0");
  EXPECT_EQ(rows[1][1], "receiver");
  EXPECT_EQ(std::stod(rows[1][2]), 1.0);
  const double e[3] = {2.0, 1.0, 0.5}, f = howell_c11(1.0, 1.0, 1.0);
  for (int c = 0; c < 3; ++c) {
    const double se = std::stod(rows[1][6 + c]);
    EXPECT_NEAR(std::stod(rows[1][3 + c]), 0.5 * e[c] * f, 4 * se) << c;
    EXPECT_LT(se, 0.01 * 0.5 * e[c] * f);
  }
}

}  // namespace
}  // namespace hrad::test
