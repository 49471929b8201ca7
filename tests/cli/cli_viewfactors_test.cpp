// `hrad viewfactors` as a user runs it: every output format carries the same factors (checked
// against Howell's closed forms for a unit cube), the report's invariants, and one-line errors.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../formfactor/howell.h"
#include "run_hrad.h"
#include "support/source_tree.h"

namespace hrad::test {
namespace {

const char* kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "o floor\nf 1 2 3 4\no ceiling\nf 5 8 7 6\no w1\nf 1 5 6 2\no w2\nf 2 6 7 3\no w3\nf 3 7 8 4\no w4\nf 4 8 5 1\n";

// Radiant exchange in the cube: floor 600 K, ceiling 300 K, two walls reradiating, two at 400 K and 350 K.
const char* kCubeConditions = "surface,temperature,heat_flux\n0,600,\n1,300,\n2,,0\n3,,0\n4,400,\n5,350,\n";

// Dense rows of numbers split by `separator`.
std::vector<std::vector<double>> numbers(const std::string& text, char separator, std::size_t skip_lines = 0) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) {
    if (n++ < skip_lines) continue;
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, separator);)
      if (!cell.empty()) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// The cube's matrix: 0 on the diagonal, C-11 (1,1,1) = 0.199825 opposite, C-14 = 0.200044 adjacent
// (faces 0/1, 2/4 and 3/5 are opposite).
double cube_factor(int i, int j) {
  if (i == j) return 0.0;
  const int opposite[6] = {1, 0, 4, 5, 2, 3};
  return opposite[i] == j ? howell_c11(1, 1, 1) : howell_c14(1, 1, 1);
}

TEST(CliViewFactors, EveryFormatCarriesTheClosedForms) {
  TempDir dir;
  const std::string scene = dir.write("cube.obj", kCube);
  const RunResult r = run_hrad(
      "viewfactors " + scene + " --out " + dir.path("F.csv") + " --report " + dir.path("R.json") + " --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto dense = numbers(slurp(dir.path("F.csv")), ',');
  ASSERT_EQ(dense.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    ASSERT_EQ(dense[i].size(), 6u);
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(dense[i][j], cube_factor(i, j), 1e-10);
  }
  const nlohmann::json report = nlohmann::json::parse(slurp(dir.path("R.json")));
  EXPECT_LE(report["max_reciprocity_error"].get<double>(), 1e-12);
  EXPECT_LE(report["max_closure_error"].get<double>(), 1e-9);
  EXPECT_EQ(report["per_surface"].size(), 6u);

  ASSERT_EQ(run_hrad("viewfactors " + scene + " --out " + dir.path("F.mtx") + " --quiet", dir).exit_code, 0);
  ASSERT_EQ(
      run_hrad("viewfactors " + scene + " --format triplets --out " + dir.path("T.csv") + " --quiet", dir).exit_code,
      0);
  ASSERT_EQ(run_hrad("viewfactors " + scene + " --out " + dir.path("V.txt") + " --quiet", dir).exit_code, 0);
  const std::string mtx = slurp(dir.path("F.mtx"));
  EXPECT_EQ(mtx.rfind("%%MatrixMarket matrix coordinate real general\n", 0), 0u);
  const auto mm = numbers(mtx, ' ', 2);
  ASSERT_EQ(mm[0].size(), 3u);
  EXPECT_EQ(mm[0][2], 30.0);  // nonzeros: every off-diagonal pair
  for (std::size_t k = 1; k < mm.size(); ++k) EXPECT_EQ(mm[k][2], dense[int(mm[k][0]) - 1][int(mm[k][1]) - 1]);
  const auto triplets = numbers(slurp(dir.path("T.csv")), ',', 1);
  ASSERT_EQ(triplets.size(), 30u);
  for (const auto& t : triplets) EXPECT_EQ(t[2], dense[int(t[0])][int(t[1])]);
  // View3D layout: header, areas, rows, emissivities (1 - the default reflectance 0.5).
  const auto v3 = numbers(slurp(dir.path("V.txt")), ' ', 1);
  ASSERT_EQ(v3.size(), 8u);
  for (double a : v3[0]) EXPECT_EQ(a, 1.0);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(v3[1 + i], dense[i]);
  for (double e : v3[7]) EXPECT_EQ(e, 0.5);
}

TEST(CliViewFactors, BadOptionsAreOneLineErrorsWithNothingWritten) {
  TempDir dir;
  const std::string scene = dir.write("cube.obj", kCube);
  const std::string out = dir.path("F.csv");
  for (const std::string& bad :
       {std::string("--by zone"), std::string("--threshold 2"), std::string("--visibility-error 0"),
        std::string("--format xml"), std::string("--max-rays 3"), std::string("--sample-below 1"),
        std::string("--far-rays 2")}) {
    const RunResult r = run_hrad("viewfactors " + scene + " --out " + out + " " + bad, dir);
    EXPECT_NE(r.exit_code, 0) << bad;
    ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
    EXPECT_NE(r.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad;
  }
  const RunResult ext = run_hrad("viewfactors " + scene + " --out " + dir.path("F.xlsx"), dir);
  EXPECT_NE(ext.exit_code, 0);
  EXPECT_NE(ext.err.find("--out"), std::string::npos) << ext.err;
}

// A closed box of 3,456 quads (all pairs on different walls see each other: about 5 M pairs to
// store, ~240 MB) in a process limited to 250 MB: refused before any pair is computed, in one line
// naming --threshold and the estimate, with nothing written.
TEST(CliViewFactors, WorkBeyondMemoryIsRefusedWithAnEstimate) {
  TempDir dir;
  std::ostringstream obj;
  const int k = 24;
  int vertex = 0;
  // Wall w: the plane axis a = side, quads over the other two axes, wound to face inwards.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
          const double c[4][2] = {
              {double(i), double(j)}, {i + 1.0, double(j)}, {i + 1.0, j + 1.0}, {double(i), j + 1.0}};
          for (int v = 0; v < 4; ++v) {
            const int o = side == 0 ? v : 3 - v;
            double p[3];
            p[axis] = side * k;
            p[(axis + 1) % 3] = c[o][0];
            p[(axis + 2) % 3] = c[o][1];
            obj << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
          }
          obj << "f " << vertex + 1 << " " << vertex + 2 << " " << vertex + 3 << " " << vertex + 4 << "\n";
          vertex += 4;
        }
  const std::string scene = dir.write("box.obj", obj.str());
  const std::string out = dir.path("F.mtx");
  const RunResult r = run_hrad("--version >/dev/null; ulimit -v 250000; '" + test::hrad_executable() +
                                   "' viewfactors " + scene + " --out " + out + " --quiet",
                               dir);
  EXPECT_NE(r.exit_code, 0);
  // One error line (after the reader's warning that the faces have no material).
  int errors = 0;
  for (const std::string& line : r.err_lines()) errors += line.find("error") != std::string::npos ? 1 : 0;
  EXPECT_EQ(errors, 1) << r.err;
  EXPECT_NE(r.err.find("--threshold"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("MB of memory"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}


}  // namespace
}  // namespace hrad::test

namespace hrad::test {
namespace {

// A .vs3 model in, the matrix out, and the same matrix (same bytes) from the equivalent OBJ
// (written by --write-vs3 from it); radiant exchange on the cube at fixed temperatures closes its
// energy balance (sum of heat rates 0 in a closed enclosure).
TEST(CliViewFactors, Vs3AndObjGiveTheSameMatrixAndExchangeBalances) {
  TempDir dir;
  const std::string scene = dir.write("cube.obj", kCube);
  ASSERT_EQ(run_hrad("viewfactors " + scene + " --write-vs3 " + dir.path("cube.vs3") + " --quiet", dir).exit_code, 0);
  const RunResult a = run_hrad("viewfactors " + scene + " --out " + dir.path("obj.txt") + " --quiet", dir);
  const RunResult b =
      run_hrad("viewfactors " + dir.path("cube.vs3") + " --out " + dir.path("vs3.txt") + " --quiet", dir);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(slurp(dir.path("obj.txt")), slurp(dir.path("vs3.txt")));

  const std::string bc =
      dir.write("bc.csv", kCubeConditions);
  const RunResult x = run_hrad("viewfactors " + scene + " --out " + dir.path("F.csv") + " --boundary " + bc +
                                   " --heat " + dir.path("Q.csv") + " --quiet",
                               dir);
  ASSERT_EQ(x.exit_code, 0) << x.err;
  // surface,name,area,emissivity,temperature,heat_flux,heat_rate,radiosity
  std::istringstream q(slurp(dir.path("Q.csv")));
  std::string line;
  std::getline(q, line);
  EXPECT_EQ(line, "surface,name,area,emissivity,temperature,heat_flux,heat_rate,radiosity");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(q, line)) rows.push_back(csv_cells(line));
  ASSERT_EQ(rows.size(), 6u);
  double total = 0.0, scale = 0.0;
  for (const auto& r : rows) total += std::stod(r[6]), scale += std::abs(std::stod(r[6]));
  EXPECT_LT(std::abs(total), 1e-9 * scale);
  EXPECT_NEAR(std::stod(rows[2][5]), 0.0, 1e-9 * scale);  // reradiating: net flux 0
  EXPECT_EQ(std::stod(rows[0][4]), 600.0);

  const std::string bad = dir.write("bad.csv", "surface,temperature,heat_flux\n0,600,\n0,300,\n");
  const RunResult e = run_hrad(
      "viewfactors " + scene + " --out " + dir.path("G.csv") + " --boundary " + bad + " --heat " + dir.path("R.csv"),
      dir);
  EXPECT_NE(e.exit_code, 0);
  EXPECT_NE(e.err.find("bad.csv:3: surface 0 was given on line 2"), std::string::npos) << e.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("G.csv")));
}


// Net heat per surface (W) from a --heat file, in surface order.
std::vector<double> heat_rates(const std::string& path) {
  std::istringstream q(slurp(path));
  std::string line;
  std::getline(q, line);
  std::vector<double> rates;
  while (std::getline(q, line)) rates.push_back(std::stod(csv_cells(line)[6]));
  return rates;
}

// The cube's exchange by each radiosity solver at one element per face (the options that stop
// subdivision) is the net radiation method on the faces: the matrix method's heat to 1e-9 of the
// largest (full, substructure: factors exact to 1e-9) and 1e-7 (hierarchical: links' factors are
// asked for 1e-7), and the closed cube balances to the same (the iterative methods stopped at
// 1e-12, below the factors' error). Refined, the radiosity varies over the
// faces and the heat moves by a few percent at most (the reradiating walls' share).
TEST(CliViewFactors, ExchangeByEachSolverMatchesTheMatrixMethodOnFaces) {
  TempDir dir;
  const std::string scene = dir.write("cube.obj", kCube);
  const std::string bc =
      dir.write("bc.csv", kCubeConditions);
  const RunResult m = run_hrad("viewfactors " + scene + " --out " + dir.path("F.csv") + " --boundary " + bc +
                                   " --heat " + dir.path("matrix.csv") + " --quiet",
                               dir);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const std::vector<double> reference = heat_rates(dir.path("matrix.csv"));
  double largest = 0.0;
  for (double q : reference) largest = std::max(largest, std::abs(q));
  const std::pair<std::string, double> coarse[] = {{"full --max-area 10", 1e-9},
                                                   {"substructure --max-area 10 --patch-area 10 --tolerance 1e-12", 1e-9},
                                                   {"hierarchical --aeps 10 --tolerance 1e-12", 1e-7}};
  for (const auto& [method, tolerance] : coarse) {
    const std::string out = dir.path("q.csv");
    std::filesystem::remove(out);
    const RunResult r =
        run_hrad("viewfactors " + scene + " --boundary " + bc + " --heat " + out + " --quiet --method " + method, dir);
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
    EXPECT_NE(r.out.find("6 elements"), std::string::npos) << r.out;
    const std::vector<double> q = heat_rates(out);
    ASSERT_EQ(q.size(), reference.size());
    double total = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      EXPECT_NEAR(q[i], reference[i], tolerance * largest) << method << " surface " << i;
      total += q[i];
    }
    EXPECT_NEAR(total, 0.0, tolerance * largest) << method;
  }
  for (const std::string method : {"full", "substructure", "hierarchical"}) {
    const RunResult r = run_hrad(
        "viewfactors " + scene + " --boundary " + bc + " --heat " + dir.path("fine.csv") + " --quiet --method " + method,
        dir);
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
    const std::vector<double> q = heat_rates(dir.path("fine.csv"));
    for (std::size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(q[i], reference[i], 0.05 * largest) << method << " " << i;
    std::filesystem::remove(dir.path("fine.csv"));
  }
}

TEST(CliViewFactors, ExchangeMethodOptionsThatDoNotApplyAreOneLineErrors) {
  TempDir dir;
  const std::string scene = dir.write("cube.obj", kCube);
  const std::string bc =
      dir.write("bc.csv", kCubeConditions);
  const std::string heat = dir.path("Q.csv");
  const std::string exchange = " --boundary " + bc + " --heat " + heat;
  const std::pair<std::string, std::string> bad[] = {
      {"--method full --out " + dir.path("F.csv") + exchange, "--out"},
      {"--method hierarchical --sky-temperature 280" + exchange, "--sky-temperature"},
      {"--method substructure --exact" + exchange, "--exact"},
      {"--method full --feps 0.1" + exchange, "--feps"},
      {"--method hierarchical --max-area 0.1" + exchange, "--max-area"},
      {"--method full --patch-area 0.1" + exchange, "--patch-area"},
      {"--out " + dir.path("F.csv") + " --aeps 0.1" + exchange, "--aeps"},
      {"--method full", "--boundary"},
      {"--method radiosity" + exchange, "--method"},
      {"--method hierarchical --feps -1" + exchange, "--feps"},
  };
  for (const auto& [options, named] : bad) {
    const RunResult r = run_hrad("viewfactors " + scene + " " + options + " --quiet", dir);
    EXPECT_NE(r.exit_code, 0) << options;
    ASSERT_EQ(r.err_lines().size(), 1u) << options << ": " << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << options << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(heat)) << options;
    EXPECT_FALSE(std::filesystem::exists(dir.path("F.csv"))) << options;
  }
}

}  // namespace
}  // namespace hrad::test
