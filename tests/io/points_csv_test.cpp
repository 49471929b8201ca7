#include "hrad/io/points_csv.h"

#include <gtest/gtest.h>

#include <string>

#include "../support/temp_dir.h"
#include "hrad/core/error.h"

namespace hrad {
namespace {

// Values parsed exactly (correct rounding: 0.1 is the double nearest 0.1), normals made unit,
// lines counted with blank lines, CRLF endings, spaces around cells and a '+' sign accepted, and
// the columns found by their header names in any order.
TEST(PointsCsv, ReadsPositionsAndUnitNormalsWithTheirLines) {
  test::TempDir dir;
  const std::string path = dir.write("p.csv", "x,y,z,nx,ny,nz\r\n0.1, 2.5 ,-3e-2,0,0,2\r\n\r\n+1,2,3,3,0,-4\r\n");
  const std::vector<ProbePoint> p = read_points_csv(path);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].position, Vec3(0.1, 2.5, -3e-2));
  EXPECT_EQ(p[0].normal, Vec3(0, 0, 1));
  EXPECT_EQ(p[0].line, 2u);
  EXPECT_EQ(p[1].position, Vec3(1, 2, 3));
  EXPECT_NEAR((p[1].normal - Vec3(0.6, 0, -0.8)).norm(), 0.0, 1e-16);
  EXPECT_EQ(p[1].line, 4u);

  const std::string reordered = dir.write("q.csv", "nx,ny,nz,x,y,z\n0,1,0,7,8,9\n");
  const std::vector<ProbePoint> q = read_points_csv(reordered);
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0].position, Vec3(7, 8, 9));
  EXPECT_EQ(q[0].normal, Vec3(0, 1, 0));

  EXPECT_TRUE(read_points_csv(dir.write("h.csv", "x,y,z,nx,ny,nz\n")).empty());  // a header alone: no points
}

struct BadCsv {
  std::string name, text, expected;  ///< expected: must appear in the message (file:line and what)
};

class PointsCsvBad : public ::testing::TestWithParam<BadCsv> {};

TEST_P(PointsCsvBad, OneLineErrorNamingFileAndLine) {
  const BadCsv& c = GetParam();
  test::TempDir dir;
  const std::string path = dir.write("bad.csv", c.text);
  try {
    read_points_csv(path);
    FAIL() << "no error for " << c.name;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("bad.csv" + c.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Defects, PointsCsvBad,
    ::testing::Values(
        BadCsv{"empty", "", ": empty file"}, BadCsv{"blank_lines_only", "\n  \n", ": empty file"},
        BadCsv{"missing_column", "x,y,z,nx,ny\n1,2,3,0,0\n", ":1: expected the header x,y,z,nx,ny,nz: no column 'nz'"},
        BadCsv{"extra_column", "x,y,z,nx,ny,nz,w\n", ":1: expected the header x,y,z,nx,ny,nz: unexpected column 'w'"},
        BadCsv{"misspelt_column", "\nx,y,z,nx,ny,nzz\n",
               ":2: expected the header x,y,z,nx,ny,nz: unexpected column 'nzz'"},
        BadCsv{"twice", "x,y,z,nx,ny,x\n", ":1: expected the header x,y,z,nx,ny,nz: column 'x' twice"},
        BadCsv{"too_few_cells", "x,y,z,nx,ny,nz\n1,2,3,0,0,1\n1,2,3,0,0\n", ":3: too few cells"},
        BadCsv{"too_many_cells", "x,y,z,nx,ny,nz\n1,2,3,0,0,1,5\n", ":2: too many cells"},
        BadCsv{"not_a_number", "x,y,z,nx,ny,nz\n1,2,3,0,abc,1\n", ":2: column ny: 'abc' is not a number"},
        BadCsv{"trailing_garbage", "x,y,z,nx,ny,nz\n1,2,3x,0,0,1\n", ":2: column z: '3x'"},
        BadCsv{"empty_cell", "x,y,z,nx,ny,nz\n1,,3,0,0,1\n", ":2: column y: empty cell"},
        BadCsv{"nan", "x,y,z,nx,ny,nz\nnan,2,3,0,0,1\n", ":2: column x: 'nan' is not finite"},
        BadCsv{"infinity", "x,y,z,nx,ny,nz\n1,2,3,0,0,-inf\n", ":2: column nz: '-inf' is not finite"},
        BadCsv{"overflow", "x,y,z,nx,ny,nz\n1e999,2,3,0,0,1\n", ":2: column x: '1e999' is out of the range"},
        BadCsv{"zero_normal", "x,y,z,nx,ny,nz\n1,2,3,0,0,1\n\n1,2,3,0,0,0\n", ":4: zero normal"},
        BadCsv{"underflowing_normal", "x,y,z,nx,ny,nz\n1,2,3,0,0,1e-400\n", ":2: "}),
    [](const auto& info) { return info.param.name; });

TEST(PointsCsv, MissingFileAndFolderAreNamed) {
  test::TempDir dir;
  for (const std::string& path : {dir.path("missing.csv"), dir.root().string()}) {
    try {
      read_points_csv(path);
      FAIL() << path;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace hrad
