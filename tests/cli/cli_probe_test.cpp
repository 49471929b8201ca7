// `hrad probe` as a user runs it: solve, then light at points by final gather, against closed forms
// (Howell's point-to-rectangle factors, the furnace room's E / (1 - rho)) and against the
// independent Monte Carlo reference (`hrad reference`, its own ray casting) where an occluder makes
// visibility matter. Each scene is chosen so that the solution's leaves are exact (emitters that
// reflect nothing, or a closed room of uniform emission), so the probes' only error is the gather's.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../formfactor/howell.h"
#include "hrad/io/png_writer.h"
#include "run_hrad.h"

namespace hrad::test {
namespace {

// One row of a probe or reference CSV, by column name.
using Row = std::map<std::string, std::string>;

std::vector<Row> read_rows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = csv_cells(line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = csv_cells(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    Row r;
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k) r[header[k]] = cells[k];
    rows.push_back(r);
  }
  return rows;
}

double num(const Row& r, const std::string& column) { return std::stod(r.at(column)); }

// A square light [0, a]^2 (in x, z) at height c facing down (Ke 3 6 1.5), over a floor [-3, 5]^2 at
// y = 0 (face 0) that emits 0.1: neither reflects, so the leaves carry exactly their emission.
constexpr double kA = 2.0, kC = 0.75;
const double kE[3] = {3.0, 6.0, 1.5};

void write_light_over_floor(const TempDir& dir) {
  dir.write("lit.mtl", "newmtl floor\nKd 0 0 0\nKe 0.1 0.1 0.1\nnewmtl light\nKd 0 0 0\nKe 3 6 1.5\n");
  dir.write("lit.obj",
            "mtllib lit.mtl\nusemtl floor\nv -3 0 -3\nv 5 0 -3\nv 5 0 5\nv -3 0 5\nf 1 4 3 2\n"
            "usemtl light\nv 0 0.75 0\nv 2 0.75 0\nv 2 0.75 2\nv 0 0.75 2\nf 5 6 7 8\n");
}

// Howell B-3 summed over the four rectangles meeting at the foot (u, v) of a point at depth h
// under the light, facing it: the point-to-square factor.
double under_light(double u, double v, double h) {
  return howell_b3(u, v, h) + howell_b3(kA - u, v, h) + howell_b3(u, kA - v, h) + howell_b3(kA - u, kA - v, h);
}

// Points on the floor (face 0, facing up: its radiosity is its emission), in space facing up, in
// space facing sideways (+x, on the plane x = 0 of the light's edge: Howell's perpendicular element,
// two rectangles either side of the point, for the light above and the floor below), beside the
// light's footprint, and a grid on the floor: each irradiance channel is sum E * F to 1e-9, F from
// Howell's closed forms in quad precision.
TEST(CliProbe, PointsUnderASquareLightGetHowellsFactor) {
  TempDir dir;
  write_light_over_floor(dir);
  ASSERT_EQ(
      run_hrad("solve " + dir.path("lit.obj") + " --method full --quiet --out " + dir.path("s.ply"), dir).exit_code, 0);
  dir.write("p.csv",
            "x,y,z,nx,ny,nz\n1,0,1,0,1,0\n0.3,0,1.7,0,2,0\n1.9,0.25,0.05,0,1,0\n0,0.5,0.6,1,0,0\n3,0,-1,0,1,0\n");
  const RunResult r = run_hrad("probe " + dir.path("s.ply") + " --scene " + dir.path("lit.obj") + " --points " +
                                   dir.path("p.csv") + " --quiet --out " + dir.path("r.csv"),
                               dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("5 points in"), std::string::npos) << r.out;
  const std::vector<Row> rows = read_rows(dir.path("r.csv"));
  ASSERT_EQ(rows.size(), 5u);
  // (3, 0, -1): the light spans x - 3 in [-3, -1] and z + 1 in [1, 3] from the foot.
  const double f[5] = {
      under_light(1, 1, kC), under_light(0.3, 1.7, kC), under_light(1.9, 0.05, kC - 0.25),
      howell_perpendicular_element(0.6, kA, kC - 0.5) + howell_perpendicular_element(kA - 0.6, kA, kC - 0.5),
      howell_b3(3, 3, kC) - howell_b3(1, 3, kC) - howell_b3(3, 1, kC) + howell_b3(1, 1, kC)};
  // The sideways point also sees the floor's half x > 0 (x in [0, 5], z in [-3, 5]) 0.5 below it.
  const double floor_sideways = howell_perpendicular_element(3.6, 5, 0.5) + howell_perpendicular_element(4.4, 5, 0.5);
  const bool on_floor[5] = {true, true, false, false, true};
  const char* channel[3] = {"r", "g", "b"};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(rows[i].at("face"), on_floor[i] ? "0" : "") << i;
    EXPECT_EQ(num(rows[i], "ny"), i == 3 ? 0.0 : 1.0) << i;  // the normal as a unit vector
    for (int c = 0; c < 3; ++c) {
      const double h = num(rows[i], std::string("irradiance_") + channel[c]);
      const double exact = kE[c] * f[i] + (i == 3 ? 0.1 * floor_sideways : 0.0);
      EXPECT_LT(relative_error(h, exact), 1e-9) << "point " << i << " channel " << channel[c];
      if (on_floor[i])
        EXPECT_EQ(num(rows[i], std::string("radiosity_") + channel[c]), 0.1);
      else
        EXPECT_EQ(rows[i].at(std::string("radiosity_") + channel[c]), "");
    }
  }

  // A 4 x 2 grid on the floor: cell centres, u = x fastest, every point on face 0 facing up.
  const RunResult g = run_hrad("probe " + dir.path("s.ply") + " --scene " + dir.path("lit.obj") +
                                   " --grid y,0,0,0,2,1,4,2 --quiet --out " + dir.path("g.csv"),
                               dir);
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const std::vector<Row> grid = read_rows(dir.path("g.csv"));
  ASSERT_EQ(grid.size(), 8u);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      const Row& row = grid[static_cast<std::size_t>(i + 4 * j)];
      const double x = 0.25 + 0.5 * i, z = 0.25 + 0.5 * j;
      EXPECT_EQ(num(row, "x"), x);
      EXPECT_EQ(num(row, "z"), z);
      EXPECT_EQ(row.at("face"), "0");
      EXPECT_LT(relative_error(num(row, "irradiance_b"), kE[2] * under_light(x, z, kC)), 1e-9) << i << "," << j;
    }
}

// Lux (gather/photometry.h): the same grid with the emission declared in lm/m2 and in W/m2 gains
// illuminance_lux = efficacy * (0.265074126 R + 0.670114631 G + 0.064811243 B) of Howell's
// irradiance, to 1e-9 (efficacy 1 and 179 lm/W); stdout gives the grid's least, mean and greatest
// lux and the uniformity; --isolux writes the plot, 512 pixels along the grid's longer side (u, 2 m)
// and 256 along v (1 m), plus its colour bar.
TEST(CliProbe, DeclaredUnitsGiveLuxAndAnIsoluxPlot) {
  TempDir dir;
  write_light_over_floor(dir);
  ASSERT_EQ(
      run_hrad("solve " + dir.path("lit.obj") + " --method full --quiet --out " + dir.path("s.ply"), dir).exit_code, 0);
  const double weighted = 0.265074126 * kE[0] + 0.670114631 * kE[1] + 0.064811243 * kE[2];
  for (const auto& [units, efficacy] : {std::pair<std::string, double>{"lm/m2", 1.0}, {"W/m2", 179.0}}) {
    const RunResult g = run_hrad("probe " + dir.path("s.ply") + " --scene " + dir.path("lit.obj") +
                                     " --grid y,0,0,0,2,1,4,2 --emission-units " + units + " --isolux " +
                                     dir.path("plan.png") + " --quiet --out " + dir.path("g.csv"),
                                 dir);
    ASSERT_EQ(g.exit_code, 0) << g.err;
    const std::vector<Row> grid = read_rows(dir.path("g.csv"));
    ASSERT_EQ(grid.size(), 8u);
    double least = 1e300, greatest = 0.0;
    for (const Row& row : grid) {
      const double exact = efficacy * weighted * under_light(num(row, "x"), num(row, "z"), kC);
      EXPECT_LT(relative_error(num(row, "illuminance_lux"), exact), 1e-9) << units;
      least = std::min(least, exact);
      greatest = std::max(greatest, exact);
    }
    // The summary's least and greatest, printed to 6 digits.
    const std::size_t at = g.out.find("illuminance (lux): least ");
    ASSERT_NE(at, std::string::npos) << g.out;
    EXPECT_LT(relative_error(std::stod(g.out.substr(at + 25)), least), 1e-5) << g.out;
    const std::size_t top = g.out.find("greatest ", at);
    ASSERT_NE(top, std::string::npos) << g.out;
    EXPECT_LT(relative_error(std::stod(g.out.substr(top + 9)), greatest), 1e-5) << g.out;
    const Image plan = read_png(dir.path("plan.png"));
    EXPECT_EQ(plan.height, 256) << units;
    EXPECT_GT(plan.width, 512) << units;
  }
  // Without declared units there is no lux column.
  ASSERT_EQ(run_hrad("probe " + dir.path("s.ply") + " --scene " + dir.path("lit.obj") +
                         " --grid y,0,0,0,2,1,4,2 --quiet --out " + dir.path("g.csv"),
                     dir)
                .exit_code,
            0);
  EXPECT_EQ(read_rows(dir.path("g.csv"))[0].count("illuminance_lux"), 0u);
}

// A scene that declares its unit ("#@hrad emission-units", here in its MTL) gets lux without the
// option, the same values as with it; the option overrides a declaration, with a warning.
TEST(CliProbe, SceneDeclaredUnitsGiveLuxWithoutTheOption) {
  TempDir dir;
  write_light_over_floor(dir);
  const std::string mtl = "newmtl floor\nKd 0 0 0\nKe 0.1 0.1 0.1\nnewmtl light\nKd 0 0 0\nKe 3 6 1.5\n";
  dir.write("lit.mtl", "#@hrad emission-units W/m2\n" + mtl);
  ASSERT_EQ(
      run_hrad("solve " + dir.path("lit.obj") + " --method full --quiet --out " + dir.path("s.ply"), dir).exit_code, 0);
  const std::string probe =
      "probe " + dir.path("s.ply") + " --scene " + dir.path("lit.obj") + " --grid y,0,0,0,2,1,4,2 --quiet --out ";
  const RunResult declared = run_hrad(probe + dir.path("d.csv"), dir);
  ASSERT_EQ(declared.exit_code, 0) << declared.err;
  EXPECT_EQ(declared.err.find("warning"), std::string::npos) << declared.err;
  const RunResult option = run_hrad(probe + dir.path("o.csv") + " --emission-units W/m2", dir);
  ASSERT_EQ(option.exit_code, 0) << option.err;
  const RunResult other = run_hrad(probe + dir.path("l.csv") + " --emission-units lm/m2", dir);
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_NE(other.err.find("--emission-units lm/m2 overrides W/m2 declared at " + dir.path("lit.mtl") + ":1"),
            std::string::npos)
      << other.err;
  const std::vector<Row> d = read_rows(dir.path("d.csv")), o = read_rows(dir.path("o.csv")),
                         l = read_rows(dir.path("l.csv"));
  ASSERT_EQ(d.size(), 8u);
  ASSERT_EQ(o.size(), 8u);
  ASSERT_EQ(l.size(), 8u);
  const double weighted = 0.265074126 * kE[0] + 0.670114631 * kE[1] + 0.064811243 * kE[2];
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double exact = 179.0 * weighted * under_light(num(d[i], "x"), num(d[i], "z"), kC);
    EXPECT_LT(relative_error(num(d[i], "illuminance_lux"), exact), 1e-9);
    EXPECT_EQ(d[i].at("illuminance_lux"), o[i].at("illuminance_lux"));
    EXPECT_LT(relative_error(num(l[i], "illuminance_lux"), exact / 179.0), 1e-9);
  }
  // `hrad info` says where the unit was declared.
  const RunResult info = run_hrad("info " + dir.path("lit.obj"), dir);
  EXPECT_NE(info.out.find("emission in W/m2 (declared at " + dir.path("lit.mtl") + ":1)"), std::string::npos)
      << info.out;
}

// The cube [0, 2]^3 facing inwards, every face emitting 2 with reflectance 0.6; the floor cut in
// two along x = 1 (faces 0 and 1; then the ceiling 2, the walls z = 0, z = 2, x = 0, x = 2).
void write_furnace_cube(const TempDir& dir) {
  dir.write("cube.mtl", "newmtl wall\nKd 0.6 0.6 0.6\nKe 2 2 2\n");
  dir.write("cube.obj",
            "mtllib cube.mtl\nusemtl wall\n"
            "v 0 0 0\nv 2 0 0\nv 2 0 2\nv 0 0 2\nv 0 2 0\nv 2 2 0\nv 2 2 2\nv 0 2 2\nv 1 0 0\nv 1 0 2\n"
            "f 1 4 10 9\nf 9 10 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
}

// The furnace: a closed cube of uniform emission E and reflectance rho has B = E / (1 - rho)
// everywhere, solved exactly by the full matrix (LU; its rows sum to 1 in a closed room). Every point
// inside, facing any way, gathers H = B (its factors to the closed surface sum to 1); a point on a
// wall has radiosity E + rho B = B. To 1e-9, with the default grouping and leaf by leaf.
TEST(CliProbe, ClosedRoomGivesTheFurnaceClosedFormAnywhere) {
  TempDir dir;
  const double rho = 0.6, e = 2.0, b = e / (1.0 - rho);
  write_furnace_cube(dir);
  ASSERT_EQ(run_hrad("solve " + dir.path("cube.obj") +
                         " --method full --linear-solver lu --max-area 0.3 --quiet --out " + dir.path("s.ply"),
                     dir)
                .exit_code,
            0);
  // In space facing six ways and obliquely (one near a wall, one near a corner), on the floor's two
  // patches, on the ceiling, on a wall.
  dir.write("p.csv",
            "x,y,z,nx,ny,nz\n1,1,1,0,1,0\n1,1,1,0,-1,0\n0.3,1.2,1.7,1,0,0\n1.9,0.1,0.2,-1,-1,2\n0.01,1.99,0.02,3,-2,1\n"
            "0.5,0,1.5,0,1,0\n1.5,0,0.5,0,1,0\n1.2,2,0.7,0,-1,0\n2,1.3,0.4,-1,0,0\n");
  for (const std::string tolerance : {"", " --gather-tolerance 0"}) {
    const RunResult r = run_hrad("probe " + dir.path("s.ply") + " --scene " + dir.path("cube.obj") + " --points " +
                                     dir.path("p.csv") + " --quiet --out " + dir.path("r.csv") + tolerance,
                                 dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<Row> rows = read_rows(dir.path("r.csv"));
    ASSERT_EQ(rows.size(), 9u);
    const char* face[9] = {"", "", "", "", "", "0", "1", "2", "6"};
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(rows[i].at("face"), face[i]) << tolerance << " point " << i;
      EXPECT_LT(relative_error(num(rows[i], "irradiance_g"), b), 1e-9) << tolerance << " point " << i;
      if (*face[i]) EXPECT_LT(relative_error(num(rows[i], "radiosity_g"), b), 1e-9) << tolerance << " point " << i;
    }
  }
}

// The furnace with a closed box floating 1 cm above the floor, solved cut along the box's bottom (the
// default) and kept whole (--no-cut-near-faces): the solution PLY says which, and probe reads the scene
// alike (read the other way, its patches would not be the solution's). Cut, every point gathers
// B = E / (1 - rho) to the closed scenes' power tolerance (the box's partly visible pairs are sampled);
// whole, the floor's elements average the box's shadow with the light around it (the defect the cut
// removes: 1.5e-3 at the point facing down), so within 1e-2.
TEST(CliProbe, ASolutionIsProbedThroughTheSceneCutAsTheSolveCutIt) {
  TempDir dir;
  const double rho = 0.6, e = 2.0, b = e / (1.0 - rho);
  write_furnace_cube(dir);
  std::string box = slurp(dir.path("cube.obj"));
  std::size_t faces_before = 0;
  for (std::size_t at = box.find("\nf "); at != std::string::npos; at = box.find("\nf ", at + 1)) ++faces_before;
  // The box [0.6, 1.4] x [0.01, 0.5] x [0.6, 1.4], faces outwards (vertices 11-18).
  box +=
      "v 0.6 0.01 0.6\nv 1.4 0.01 0.6\nv 1.4 0.01 1.4\nv 0.6 0.01 1.4\n"
      "v 0.6 0.5 0.6\nv 1.4 0.5 0.6\nv 1.4 0.5 1.4\nv 0.6 0.5 1.4\n"
      "f 11 12 13 14\nf 15 18 17 16\nf 11 15 16 12\nf 14 13 17 18\nf 11 14 18 15\nf 12 16 17 13\n";
  dir.write("cube.obj", box);
  // Beside the box, under it (on the floor's piece in its shadow), on its top, in space.
  dir.write("p.csv", "x,y,z,nx,ny,nz\n0.3,0,0.3,0,1,0\n1,0,1,0,1,0\n1,0.5,1,0,1,0\n1,1.5,1,0,-1,0\n");
  int patches[2] = {0, 0};
  for (const bool whole : {false, true}) {
    const std::string tag = whole ? "whole" : "cut";
    const RunResult solved = run_hrad(
        "solve " + dir.path("cube.obj") + " --method full --linear-solver lu --max-area 0.3 --quiet --out " +
            dir.path(tag + ".ply") + " --report " + dir.path(tag + ".json") + (whole ? " --no-cut-near-faces" : ""),
        dir);
    ASSERT_EQ(solved.exit_code, 0) << solved.err;
    EXPECT_EQ(
        slurp(dir.path(tag + ".ply")).find("comment hrad scene: faces not cut along near faces") != std::string::npos,
        whole)
        << tag;
    const nlohmann::json report = nlohmann::json::parse(slurp(dir.path(tag + ".json")));
    EXPECT_EQ(report["options"]["cut_near_faces"].get<bool>(), !whole) << tag;
    patches[whole] = report["patch_count"].get<int>();
    const RunResult r = run_hrad("probe " + dir.path(tag + ".ply") + " --scene " + dir.path("cube.obj") + " --points " +
                                     dir.path("p.csv") + " --quiet --out " + dir.path(tag + ".csv"),
                                 dir);
    ASSERT_EQ(r.exit_code, 0) << tag << ": " << r.err;
    const std::vector<Row> rows = read_rows(dir.path(tag + ".csv"));
    ASSERT_EQ(rows.size(), 4u);
    for (std::size_t i = 0; i < rows.size(); ++i)
      EXPECT_LT(relative_error(num(rows[i], "irradiance_g"), b), whole ? 1e-2 : 1e-3) << tag << " point " << i;
  }
  // Whole, one patch a face; cut, the floor beneath the box in pieces.
  EXPECT_EQ(static_cast<std::size_t>(patches[1]), faces_before + 6);
  EXPECT_GT(patches[0], patches[1]);
  // The whole solve's PLY without its comment: probe reads the scene cut, whose patches the leaves do not lie on.
  std::string ply = slurp(dir.path("whole.ply"));
  const std::string comment = "comment hrad scene: faces not cut along near faces (hrad solve --no-cut-near-faces)\n";
  ASSERT_NE(ply.find(comment), std::string::npos);
  ply.erase(ply.find(comment), comment.size());
  dir.write("unmarked.ply", ply);
  const RunResult r = run_hrad("probe " + dir.path("unmarked.ply") + " --scene " + dir.path("cube.obj") + " --points " +
                                   dir.path("p.csv") + " --quiet --out " + dir.path("u.csv"),
                               dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("unmarked.ply: leaf "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a solution of another scene, or of this one read otherwise"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("u.csv")));
}

// Visibility decided from the point, against the independent ruler: a black rectangular occluder
// between the light and a black floor (nothing reflects, so the leaves are exact and H = E F_visible).
// The probes with exact visible regions and with the default sampled visibility agree with
// `hrad reference` (Monte Carlo on Embree, no shared kernel) within 4 of its standard errors, at
// points fully lit and in the penumbra. Where the occluder's shadow on the light's plane lies inside
// the light (the central projection from the point, scale c / 0.4), the exact probe is Howell's
// factor of the light minus that of the shadow rectangle, to 1e-9.
TEST(CliProbe, OccludedPointsAgreeWithTheMonteCarloReference) {
  TempDir dir;
  dir.write("occ.mtl", "newmtl black\nKd 0 0 0\nnewmtl light\nKd 0 0 0\nKe 3 6 1.5\n");
  dir.write("occ.obj",
            "mtllib occ.mtl\nusemtl black\nv -3 0 -3\nv 5 0 -3\nv 5 0 5\nv -3 0 5\nf 1 4 3 2\n"
            "v 0.5 0.4 0.5\nv 1.1 0.4 0.5\nv 1.1 0.4 1.2\nv 0.5 0.4 1.2\nf 5 8 7 6\n"
            "usemtl light\nv 0 0.75 0\nv 2 0.75 0\nv 2 0.75 2\nv 0 0.75 2\nf 9 10 11 12\n");
  ASSERT_EQ(
      run_hrad("solve " + dir.path("occ.obj") + " --method full --quiet --out " + dir.path("s.ply"), dir).exit_code, 0);
  dir.write("p.csv",
            "x,y,z,nx,ny,nz\n0.8,0,0.85,0,1,0\n0.45,0,0.8,0,1,0\n1.6,0,1.6,0,1,0\n1.2,0,0.3,0,1,0\n"
            "0.8,0.2,1.3,0,1,0\n");
  const RunResult ref = run_hrad("reference " + dir.path("occ.obj") + " --points " + dir.path("p.csv") +
                                     " --samples 16384 --quiet --out " + dir.path("ref.csv"),
                                 dir);
  ASSERT_EQ(ref.exit_code, 0) << ref.err;
  const std::vector<Row> mc = read_rows(dir.path("ref.csv"));
  ASSERT_EQ(mc.size(), 5u);
  for (const std::string visibility : {" --exact-visibility", ""}) {
    const RunResult r = run_hrad("probe " + dir.path("s.ply") + " --scene " + dir.path("occ.obj") + " --points " +
                                     dir.path("p.csv") + " --quiet --out " + dir.path("r.csv") + visibility,
                                 dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<Row> rows = read_rows(dir.path("r.csv"));
    ASSERT_EQ(rows.size(), 5u);
    if (!visibility.empty()) {
      // From (0.8, 0, 0.85) the occluder [0.5, 1.1] x [0.5, 1.2] projects to 0.8 +- 0.3 * 1.875 in x
      // and 0.85 +- 0.35 * 1.875 in z: inside the light, centred on the foot.
      const double shadow = 4.0 * howell_b3(0.3 * 1.875, 0.35 * 1.875, kC);
      EXPECT_LT(relative_error(num(rows[0], "irradiance_g"), kE[1] * (under_light(0.8, 0.85, kC) - shadow)), 1e-9);
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double h = num(rows[i], "irradiance_g"), m = num(mc[i], "irradiance_g"), se = num(mc[i], "irradiance_g_se");
      EXPECT_LT(std::abs(h - m), 4.0 * se + 1e-12)
          << visibility << " point " << i << ": " << h << " vs " << m << " +- " << se;
    }
  }
}

// A solution of another scene (the cube's, 7 patches, against a scene of 2) is refused,
// naming the solution file, and nothing is written.
TEST(CliProbe, SolutionOfAnotherSceneIsRefused) {
  TempDir dir;
  write_furnace_cube(dir);
  ASSERT_EQ(
      run_hrad("solve " + dir.path("cube.obj") + " --method full --quiet --out " + dir.path("s.ply"), dir).exit_code,
      0);
  const RunResult r = run_hrad("probe " + dir.path("s.ply") +
                                   " --scene notebooks_data/scenes/two_far_surfaces.obj "
                                   "--grid y,0,0,0,1,1,2,2 --quiet --out " +
                                   dir.path("r.csv"),
                               dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find(dir.path("s.ply") + ": patch id"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("r.csv")));
}

}  // namespace
}  // namespace hrad::test
