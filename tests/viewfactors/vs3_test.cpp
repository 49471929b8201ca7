// View3D input (.vs3): our own example files written from the manual's grammar (vs3_file.h), read
// into the same matrices as the equivalent geometry, and one-line file:line errors.
#include <gtest/gtest.h>

#include <sstream>

#include "../formfactor/howell.h"
#include "../support/temp_dir.h"
#include "hrad/core/error.h"
#include "hrad/viewfactors/vs3_file.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

// The unit cube's vertices and six inward surfaces (make_box order: y=0, y=1, x=0, x=1, z=0, z=1).
const char* kCubeVertices = "V 1 0 0 0\nV 2 1 0 0\nV 3 1 1 0\nV 4 0 1 0\nV 5 0 0 1\nV 6 1 0 1\nV 7 1 1 1\nV 8 0 1 1\n";

std::string header(const std::string& control = "encl=0 list=0 eps=1.0e-4 maxU=8 maxO=8 minO=0 row=0 col=0 emit=0") {
  return "T test enclosure\nC " + control + "\nF 3\n";
}

// A cube whose floor is two triangles combined (cmb) into one surface: the 6 x 6 matrix of the
// plain cube (Howell C-11 0.199825 opposite, C-14 0.200044 adjacent) to 1e-10, rows summing to 1.
TEST(Vs3, CombinedSurfacesAreOneRow) {
  TempDir dir;
  const std::string path = dir.write("cube.vs3", header() + kCubeVertices +
                                                     "! n v1 v2 v3 v4 base cmb emit name\n"
                                                     "S 1 1 5 6 0 0 0 0.9 floor\n"
                                                     "S 2 1 6 2 0 0 1 0.9 floor_b\n"
                                                     "S 3 4 3 7 8 0 0 0.8 ceiling\n"
                                                     "S 4 1 4 8 5 0 0 0.8 west\n"
                                                     "S 5 2 6 7 3 0 0 0.8 east\n"
                                                     "S 6 1 2 3 4 0 0 0.8 south\n"
                                                     "S 7 5 8 7 6 0 0 0.8 north\n"
                                                     "End\n");
  const Vs3Model model = read_vs3(path);
  ASSERT_EQ(model.units.size(), 6);
  EXPECT_EQ(model.units.names[0], "floor");
  EXPECT_DOUBLE_EQ(model.units.emissivity[0], 0.9);
  const ViewFactorMatrix m = compute_view_factors(model.scene, model.units, plain_options());
  const int opposite[6] = {1, 0, 3, 2, 5, 4};  // floor/ceiling, west/east, south/north
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(m.row_sum(i), 1.0, 1e-10);
    for (int j = 0; j < 6; ++j)
      if (j != i)
        EXPECT_NEAR(m.factor(i, j), opposite[i] == j ? howell_c11(1, 1, 1) : howell_c14(1, 1, 1), 1e-10)
            << i << " " << j;
  }
}

// A mask (M, a window in the east wall) is a surface of its own taken out of its base; a null
// surface (N, a hole in the ceiling) is taken out and lets radiation leave; an obstruction-only
// surface (O) has no row. Checked by additivity against the same model without them: window +
// wall remainder = the whole wall (1e-10), and the hole's share is what the rows lost.
TEST(Vs3, MasksNullsAndObstructions) {
  TempDir dir;
  const std::string surfaces =
      "S 1 1 5 6 2 0 0 0.9 floor\nS 2 4 3 7 8 0 0 0.9 ceiling\nS 3 1 4 8 5 0 0 0.9 west\nS 4 2 6 7 3 0 0 0.9 east\n"
      "S 5 1 2 3 4 0 0 0.9 south\nS 6 5 8 7 6 0 0 0.9 north\n";
  const std::string extra_vertices =
      "V 9 1 0.25 0.25\nV 10 1 0.75 0.25\nV 11 1 0.75 0.75\nV 12 1 0.25 0.75\n"
      "V 13 0.25 1 0.25\nV 14 0.75 1 0.25\nV 15 0.75 1 0.75\nV 16 0.25 1 0.75\n";
  const Vs3Model plain =
      read_vs3(dir.write("plain.vs3", header() + kCubeVertices + extra_vertices + surfaces + "End\n"));
  const Vs3Model holed =
      read_vs3(dir.write("holed.vs3", header() + kCubeVertices + extra_vertices + surfaces +
                                          "M 7 9 12 11 10 4 0 0.5 window\nN 8 13 14 15 16 2 0 1 skylight\nEnd\n"));
  ASSERT_EQ(plain.units.size(), 6);
  ASSERT_EQ(holed.units.size(), 7);  // the null surface has no row
  EXPECT_NEAR(holed.units.area[3], 0.75, 1e-15);
  EXPECT_NEAR(holed.units.area[1], 0.75, 1e-15);
  const ViewFactorMatrix a = compute_view_factors(plain.scene, plain.units, plain_options());
  const ViewFactorMatrix b = compute_view_factors(holed.scene, holed.units, plain_options());
  for (int i : {0, 2, 4, 5}) {
    // Additivity over the east wall: F(i -> wall remainder) + F(i -> window) = F(i -> east wall).
    EXPECT_NEAR(b.factor(i, 3) + b.factor(i, 6), a.factor(i, 3), 1e-10) << i;
    // What the rows lost is the skylight's share: F(i -> ceiling) - F'(i -> ceiling remainder).
    EXPECT_NEAR(1.0 - b.row_sum(i), a.factor(i, 1) - b.factor(i, 1), 1e-10) << i;
  }
  // An obstruction-only partition at x = 0.5 across the whole box: no row, and nothing crosses it.
  const Vs3Model split = read_vs3(
      dir.write("split.vs3", header() + kCubeVertices + "V 9 0.5 0 0\nV 10 0.5 1 0\nV 11 0.5 1 1\nV 12 0.5 0 1\n" +
                                 "S 1 1 5 6 2 0 0 0.9 floor\nS 2 4 3 7 8 0 0 0.9 ceiling\nS 3 1 4 8 5 0 0 0.9 west\n"
                                 "S 4 2 6 7 3 0 0 0.9 east\nO 5 9 10 11 12 0 0 0.9 partition\nEnd\n"));
  ASSERT_EQ(split.units.size(), 4);
  const ViewFactorMatrix s = compute_view_factors(split.scene, split.units, plain_options());
  EXPECT_EQ(s.factor(2, 3), 0.0);
  EXPECT_EQ(s.factor(3, 2), 0.0);
}

// OBJ -> .vs3 -> the same patches and the same matrix, bit for bit.
TEST(Vs3, WrittenFromASceneReadsBackToTheSameMatrix) {
  Scene s = make_box(2, 1, 1.5, {material(Rgb::Constant(0.3), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 0.5, 1.2, 0.3, 0.6, 0.4, 0.9, 0);
  std::ostringstream text;
  write_vs3(text, s, face_units(s), "box");
  TempDir dir;
  const Vs3Model model = read_vs3(dir.write("box.vs3", text.str()));
  ASSERT_EQ(model.units.size(), static_cast<int>(s.faces.size()));
  EXPECT_DOUBLE_EQ(model.units.emissivity[0], 0.7);
  const ViewFactorMatrix a = compute_view_factors(s, face_units(s), plain_options());
  const ViewFactorMatrix b = compute_view_factors(model.scene, model.units, plain_options());
  EXPECT_EQ(a.column, b.column);
  EXPECT_EQ(a.exchange, b.exchange);
}

// Defects are one-line errors naming file:line.
TEST(Vs3, DefectsNameFileAndLine) {
  TempDir dir;
  const std::string head = header() + kCubeVertices;  // lines 1-11
  const std::pair<std::string, std::string> cases[] = {
      {head + "S 1 1 2 9 0 0 0 0.9 a\n", ":12: vertex 9 is not defined"},
      {head + "S 2 1 2 3 0 0 0 0.9 a\n", ":12: surface 2 out of order"},
      {head + "S 1 1 2 3 0 0 0 1.5 a\n", ":12: emissivity 1.5"},
      {head + "M 1 1 2 3 0 0 0 0.9 a\n", ":12: a mask or null surface needs its base"},
      {head + "X 1\n", ":12: unknown record 'X'"},
      {head + "S 1 1 2 3 0 0 0 abc a\n", ":12: emit: 'abc'"},
      {head + "S 1 1 2 3 0 0 1 0.9 a\n", ":12: cmb 1 is not another surface"},
      {"T t\nC encl=0 speed=3\n", ":2: unknown control 'speed'"},
      {"T t\nF 2\n", ":2: two-dimensional geometry"},
      {"T t\nV 1 0 0 0\n", ":2: vertex before the F 3 line"},
      {head + "S 1 1 2 3 4 0 0 0.9 a\nM 2 1 2 3 0 1 0 0.9 b\nS 3 1 2 3 0 0 0 0.9 c\nM 4 5 6 7 0 1 0 0.9 d\n",
       ":15: not in the plane of its base surface 1"},
  };
  for (const auto& [text, fragment] : cases) {
    const std::string path = dir.write("bad.vs3", text);
    try {
      read_vs3(path);
      ADD_FAILURE() << "accepted: " << fragment;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path + fragment), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace hrad::test
