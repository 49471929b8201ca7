// The interfaces other checks read, exercised through the real executable: the form-factor JSON
// against Howell's closed forms, the solve report's fields and invariants, and determinism: the same
// command gives the same bytes, whatever the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

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
  const RunResult r = run_hrad(
      "solve notebooks_data/scenes/two_far_surfaces.obj --method full --max-area 1 --quiet "
      "--report " +
          dir.path("r.json") + " --out " + dir.path("s.ply"),
      dir);
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

TEST(CliSolve, LinearElementsOfTheFullMatrixIterateByDefaultAndKeepThePatchMeans) {
  // --basis linear with --method full and no --linear-solver iterates by Jacobi; the receiver's mean
  // is the constant elements' up to the two quadratures (1 x 1 elements 20 apart: far below 1e-4),
  // since the projection keeps each element's mean. Asking for LU with it is one line naming the option.
  TempDir dir;
  double mean[2] = {0.0, 0.0};
  for (const int linear : {0, 1}) {
    const std::string report = dir.path(linear ? "l.json" : "c.json");
    const RunResult r =
        run_hrad(std::string("solve notebooks_data/scenes/two_far_surfaces.obj --method full --max-area 1 "
                             "--tolerance 1e-10 --quiet --basis ") +
                     (linear ? "linear" : "constant") + " --report " + report,
                 dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(report));
    EXPECT_EQ(j.at("options").at("basis"), linear ? "linear" : "constant");
    EXPECT_EQ(j.at("options").at("linear_solver"), linear ? "jacobi" : "lu");
    EXPECT_EQ(j.at("termination"), linear ? "converged" : "direct");
    EXPECT_FALSE(j.at("options").at("balance").get<bool>());
    mean[linear] = j.at("patches")[1].at("radiosity")[0].get<double>();
  }
  EXPECT_GT(mean[0], 0.0);
  EXPECT_NEAR(mean[1], mean[0], 1e-4 * mean[0]);
  const RunResult lu = run_hrad(
      "solve notebooks_data/scenes/two_far_surfaces.obj --method full --basis linear "
      "--linear-solver lu --quiet",
      dir);
  EXPECT_NE(lu.exit_code, 0);
  EXPECT_NE(lu.err.find("--linear-solver"), std::string::npos) << lu.err;
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

TEST(CliSweep, CutsAlongNearFacesUnlessToldAndThenNamesThem) {
  // The bundled lamp 1 mm in front of its wall: by default the sweep cuts the wall along the lamp, silently,
  // as hrad solve does; with --no-cut-near-faces it names the pair, says so in command.txt, and keeps the
  // wall whole (fewer patches), so that the cut sweep's reference samples are refused as another scene's.
  TempDir dir;
  const std::string base =
      "sweep notebooks_data/scenes/lamp_near_wall.obj --quick --elements 64 --patches 12 --feps 0.3 --aeps 0.001 "
      "--no-gather --basis constant --samples 64 --out ";
  const RunResult cut = run_hrad(base + dir.path("cut"), dir);
  ASSERT_EQ(cut.exit_code, 0) << cut.err;
  EXPECT_EQ(cut.err.find("from nearby"), std::string::npos) << cut.err;
  EXPECT_EQ(slurp(dir.path("cut") + "/command.txt").find("near-faces"), std::string::npos);
  const RunResult whole = run_hrad(base + dir.path("whole") + " --no-cut-near-faces", dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_NE(whole.err.find("lamp_near_wall.obj:53: warning: 1 pair of faces face each other from nearby"),
            std::string::npos)
      << whole.err;
  EXPECT_NE(slurp(dir.path("whole") + "/command.txt").find("--no-cut-near-faces"), std::string::npos);
  const RunResult mixed =
      run_hrad(base + dir.path("mixed") + " --no-cut-near-faces --reference-from " + dir.path("cut"), dir);
  EXPECT_NE(mixed.exit_code, 0);
  EXPECT_NE(mixed.err.find("reference_samples.json: 1024 samples, this scene has 768"), std::string::npos) << mixed.err;
}

TEST(CliSweep, WritesEveryOutputAndFinerRunsAreMoreAccurate) {
  // A small sweep end to end on the simple room (a table shadows the floor): every file of the
  // interface, one CSV row per setting, and error that falls as each method's mesh gets finer.
  TempDir dir;
  const std::string out = dir.path("sweep");
  // The sweep's default 256 error samples per patch (--samples), not fewer: 16 alias with this
  // room's element grid, and the full matrix's measured error can then rise with refinement.
  const RunResult r = run_hrad(
      "sweep notebooks_data/scenes/simple_room.obj --elements 32,64,128 --patches 12,24,48 --feps 0.3,0.1,0.03 "
      "--aeps 0.01,0.003,0.001 --out " +
          out,
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("reference"), std::string::npos) << r.err;  // progress on stderr

  std::istringstream csv(slurp(out + "/sweep.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(
      line,
      "method,parameter,value,elements,links,form_factor_evaluations,visibility_queries,seconds,error_l2,error_linf,"
      "iterations,termination,error_l2_smooth,error_linf_smooth,error_l2_gathered,error_linf_gathered,"
      "gather_seconds,gather_work");
  struct Row {
    std::string method, parameter;
    double elements, links, error_l2, error_l2_smooth, error_l2_gathered;
  };
  std::vector<Row> rows;
  while (std::getline(csv, line)) {
    const std::vector<std::string> cells = csv_cells(line);
    ASSERT_EQ(cells.size(), 18u) << line;
    rows.push_back({cells[0], cells[1], std::stod(cells[3]), std::stod(cells[4]), std::stod(cells[8]),
                    std::stod(cells[12]), std::stod(cells[14])});
    EXPECT_GT(rows.back().error_l2_gathered, 0.0) << line;  // measured (not nan) for every run
    EXPECT_LT(rows.back().error_l2_gathered, 1.0) << line;
    EXPECT_GT(std::stod(cells[17]), 0.0) << line;  // the gather's work
    EXPECT_GT(rows.back().error_l2, 0.0) << line;
    EXPECT_LT(rows.back().error_l2, 1.0) << line;
  }
  // 3 element counts for full and substructuring, 3 patch counts, 3 feps and 3 aeps, each once per
  // basis (constant, linear).
  ASSERT_EQ(rows.size(), 30u);
  auto runs = [&](const std::string& method, const std::string& parameter) {
    std::vector<Row> v;
    for (const Row& row : rows)
      if (row.method == method && row.parameter == parameter) v.push_back(row);
    return v;
  };
  const auto full = runs("full", "max_area"), aeps = runs("hierarchical", "aeps");
  ASSERT_EQ(full.size(), 3u);
  ASSERT_EQ(aeps.size(), 3u);
  EXPECT_EQ(runs("substructure", "max_area").size(), 3u);
  EXPECT_EQ(runs("substructure", "patch_area").size(), 3u);
  EXPECT_EQ(runs("hierarchical", "feps").size(), 3u);
  EXPECT_EQ(runs("hierarchical_linear", "feps").size(), 3u);
  const auto linear_aeps = runs("hierarchical_linear", "aeps");
  ASSERT_EQ(linear_aeps.size(), 3u);
  EXPECT_LT(linear_aeps.back().error_l2, linear_aeps.front().error_l2);
  const auto full_linear = runs("full_linear", "max_area");
  ASSERT_EQ(full_linear.size(), 3u);
  EXPECT_EQ(runs("substructure_linear", "max_area").size(), 3u);
  EXPECT_EQ(runs("substructure_linear", "patch_area").size(), 3u);
  for (std::size_t k = 0; k < full.size(); ++k) {
    // The same meshes with each basis: linear elements must do better on each.
    EXPECT_EQ(full_linear[k].elements, full[k].elements);
    EXPECT_LT(full_linear[k].error_l2, full[k].error_l2);
  }
  EXPECT_LT(full.front().elements, full.back().elements);
  EXPECT_LT(full.back().error_l2, full.front().error_l2);
  EXPECT_LT(full.back().error_l2_smooth, full.front().error_l2_smooth);
  EXPECT_LT(aeps.back().error_l2, aeps.front().error_l2);

  const auto ref = nlohmann::json::parse(slurp(out + "/reference.json"));
  EXPECT_TRUE(ref.at("final_gather").get<bool>());
  EXPECT_EQ(ref.at("elements_aimed_at").get<double>(), 4 * 128.0);  // 4 x the finest full run
  EXPECT_GT(ref.at("elements").get<double>(), full.back().elements);
  EXPECT_EQ(ref.at("scene"), "notebooks_data/scenes/simple_room.obj");

  const auto fit = nlohmann::json::parse(slurp(out + "/fit.json"));
  for (const char* method :
       {"full", "substructure", "hierarchical", "full_linear", "substructure_linear", "hierarchical_linear"})
    EXPECT_TRUE(fit.at("methods").at(method).at("time_to_target_error").contains("reached")) << method;
  // (substructuring's element counts collide here, 102 twice: fewer than 3 distinct, no fit)
  for (const char* method : {"full", "hierarchical"})
    EXPECT_TRUE(fit["methods"][method].at("time_vs_elements").contains("b")) << method;
  EXPECT_TRUE(fit["methods"]["hierarchical"].at("error_vs_feps").contains("b"));
  EXPECT_TRUE(fit.contains("speedup"));

  EXPECT_EQ(slurp(out + "/pareto.png").substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_NE(slurp(out + "/command.txt").find("--aeps 0.01,0.003,0.001"), std::string::npos);

  // --reference-from: a second sweep with one setting per parameter reads the reference back
  // instead of solving it, and judges the same runs to the same digits.
  const std::string again = dir.path("again");
  const RunResult r2 = run_hrad(
      "sweep notebooks_data/scenes/simple_room.obj --elements 128 --patches 20 "
      "--feps 0.3 --aeps 0.001 --basis constant --reference-from " +
          out + " --out " + again,
      dir);
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_NE(r2.err.find("reference from"), std::string::npos) << r2.err;
  EXPECT_EQ(r2.err.find("LU"), std::string::npos) << r2.err;
  auto row_of = [](const std::string& csv_text, const std::string& prefix) {
    std::istringstream in(csv_text);
    for (std::string l; std::getline(in, l);)
      if (l.rfind(prefix, 0) == 0) return l;
    return std::string();
  };
  const std::string first = slurp(out + "/sweep.csv"), second = slurp(again + "/sweep.csv");
  for (const std::string prefix : {"full,max_area,", "hierarchical,feps,0.3,", "hierarchical,aeps,"}) {
    const std::string a = row_of(second, prefix);
    ASSERT_FALSE(a.empty()) << prefix;
    // The same setting in the first sweep: the same value, hence the same row but for the seconds
    // (the solve's and the gather's).
    const std::string value = a.substr(0, a.find(',', prefix.size()));
    const std::string b = row_of(first, value + ",");
    ASSERT_FALSE(b.empty()) << value;
    auto without_seconds = [](const std::string& line) {
      std::vector<std::string> cells = csv_cells(line);
      cells.erase(cells.begin() + 16);  // gather_seconds
      cells.erase(cells.begin() + 7);   // seconds
      return cells;
    };
    EXPECT_EQ(without_seconds(a), without_seconds(b)) << a << "\n" << b;
  }
  EXPECT_EQ(nlohmann::json::parse(slurp(again + "/reference.json")).at("reused_from"), out);
  // command.txt reruns the sweep: every option given is in it.
  const std::string command = slurp(again + "/command.txt");
  for (const char* given :
       {"--elements 128", "--patches 20", "--feps 0.3", "--aeps 0.001", "--basis constant", "--reference-from"})
    EXPECT_NE(command.find(given), std::string::npos) << given << " missing from " << command;
  // Another scene's samples are refused before anything runs, naming the file.
  const RunResult wrong = run_hrad(
      "sweep notebooks_data/scenes/cornell_box.obj --quick --reference-from " + out + " --out " + dir.path("wrong"),
      dir);
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.err.find(out + "/reference_samples.json: "), std::string::npos) << wrong.err;
  EXPECT_NE(wrong.err.find("another scene"), std::string::npos) << wrong.err;
}

}  // namespace
}  // namespace hrad::test
