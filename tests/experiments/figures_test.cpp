// The lecture's figures (experiments/figures.h) at small settings: each CSV has the columns the plot
// scripts and notebooks read, and the counts someone could get wrong hold exactly.
#include "hrad/experiments/figures.h"

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hrad/io/obj_reader.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

Scene bundled(const std::string& name) { return read_obj_scene(test::source_dir() + "/notebooks_data/scenes/" + name); }

// A CSV as a header and rows of cells (no quoting: hrad's CSVs have none).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  double num(std::size_t row, const std::string& column) const { return std::stod(rows.at(row).at(column)); }
  const std::string& str(std::size_t row, const std::string& column) const { return rows.at(row).at(column); }
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

Csv parse(const std::string& text, const std::vector<std::string>& expected_header) {
  Csv csv;
  std::stringstream in(text);
  std::string line;
  std::getline(in, line);
  csv.header = split(line);
  EXPECT_EQ(csv.header, expected_header);
  while (std::getline(in, line)) {
    const auto cells = split(line);
    EXPECT_EQ(cells.size(), csv.header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size() && i < csv.header.size(); ++i) row[csv.header[i]] = cells[i];
    csv.rows.push_back(row);
  }
  return csv;
}

TEST(Figures, CostIsTheWorkTheSolvesCounted) {
  // Figure 1 plots what the solves counted (solvers/work.h), not n^2 or n N by definition. Bounds from
  // the loops that do the work: the full matrix evaluates each unordered pair of elements at most once
  // (full_matrix.cpp: pairs i < j, both directions from one evaluation), substructuring each element
  // against each shooter at most once (here the N input polygons shoot); and the lecture's growth:
  // substructuring's factors ~ n N with N fixed (slope within 0.2 of 1: the share of pairs culled for
  // facing away still changes at these sizes), the full matrix's (~ n^2) growing faster by more than
  // half a power, hierarchical radiosity's gather terms more slowly than the full matrix's factors.
  // Both from 64 elements: on coarser meshes the rows graded towards the blocks' faces (floating in
  // front of the walls and the ceiling, receiver_gauss_points()) add points to every pair, which
  // flattens the fits.
  const Scene scene = bundled("cornell_box.obj");
  CostOptions o;
  o.element_counts = {64, 256, 512};
  o.substructure_counts = {64, 256, 1024};
  o.aeps_fractions = {3e-2, 1e-2, 3e-3};
  const std::vector<CostRow> rows = cost_rows(scene, o);
  const Csv csv = parse(cost_csv(rows),
                        {"method", "parameter", "value", "patches", "elements", "links", "element_factor_evaluations",
                         "point_factor_evaluations", "gather_terms", "segment_queries", "seconds"});
  ASSERT_EQ(csv.rows.size(), 9u);
  const double patches = double(scene.patches.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const CostRow& r = rows[i];
    const double n = double(r.elements);
    EXPECT_EQ(csv.num(i, "element_factor_evaluations"), double(r.work.form_factor_evaluations));
    EXPECT_EQ(csv.num(i, "gather_terms"), double(r.work.gather_terms));
    EXPECT_GT(r.work.form_factor_evaluations, 0u) << r.method;
    EXPECT_GT(r.work.gather_terms, 0u) << r.method;
    EXPECT_GT(r.work.segment_queries, 0u) << r.method;  // the blocks shadow the room
    if (r.method == "full") EXPECT_LE(double(r.work.form_factor_evaluations), n * (n - 1) / 2);
    if (r.method == "substructure") EXPECT_LE(double(r.work.form_factor_evaluations), n * patches);
  }
  const nlohmann::json fits = cost_fits(rows);
  const auto slope = [&](const char* method, const char* measure) {
    const nlohmann::json& f = fits.at("methods").at(method).at(measure);
    EXPECT_FALSE(f.is_null()) << method << " " << measure;
    return f.is_null() ? 0.0 : f.at("b").get<double>();
  };
  EXPECT_NEAR(slope("substructure", "factor_evaluations"), 1.0, 0.2);
  EXPECT_GT(slope("full", "factor_evaluations"), slope("substructure", "factor_evaluations") + 0.5);
  EXPECT_LT(slope("hierarchical", "gather_terms"), slope("full", "factor_evaluations"));
}

TEST(Figures, EdgeElementsAreSmallNearTheCommonEdge) {
  const Scene scene = bundled("two_surfaces_edge.obj");
  SolveOptions o;
  o.feps = 0.05;  // coarse: element sizes then grow with the distance (see tools/figures.cpp)
  o.aeps = scene.total_area() * 1e-4;
  const EdgeFigure fig = edge_figure(scene, o);
  // two_surfaces_edge.obj: the floor y = 0 and the wall z = 0 (both 4 x 4) meet along x in [0, 4].
  EXPECT_NEAR(fig.edge_a.y(), 0.0, 1e-12);
  EXPECT_NEAR(fig.edge_a.z(), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(fig.edge_a.x() - fig.edge_b.x()), 4.0, 1e-12);
  const Csv csv = parse(edge_csv(fig), {"element", "patch", "distance", "area", "size"});
  ASSERT_EQ(csv.rows.size(), fig.solution.faces.size());
  double area = 0.0, near = 0.0, far = 0.0;
  int n_near = 0, n_far = 0;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const double d = csv.num(i, "distance"), s = csv.num(i, "size");
    area += csv.num(i, "area");
    EXPECT_NEAR(s * s, csv.num(i, "area"), 1e-6 * csv.num(i, "area"));
    // A centroid at distance d from the edge of a square of side s within the patch: d >= s / 2.
    EXPECT_GE(d, 0.5 * s * (1 - 1e-9));
    EXPECT_LE(d, std::sqrt(2.0) * 4.0);
    if (d < 0.5) near += s, ++n_near;
    if (d > 2.0) far += s, ++n_far;
  }
  EXPECT_NEAR(area, 32.0, 1e-9);  // the leaves tile both surfaces
  ASSERT_GT(n_near, 0);
  ASSERT_GT(n_far, 0);
  EXPECT_LT(near / n_near, 0.5 * far / n_far) << "the lecture: refinement concentrates near the common edge";
}

TEST(Figures, FarSurfacesCountKSquaredAgainstTwoK) {
  const Scene scene = bundled("two_far_surfaces.obj");
  const std::vector<int> ks = {1, 4, 16};
  const Csv csv = parse(far_csv(far_rows(scene, ks)), {"k", "method", "elements", "cross_factors", "cross_pairs",
                                                       "form_factor_evaluations", "seconds"});
  ASSERT_EQ(csv.rows.size(), 9u);
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const double k = csv.num(i, "k");
    const std::string& m = csv.str(i, "method");
    if (m == "full") {
      EXPECT_EQ(csv.num(i, "elements"), 2 * k);
      EXPECT_EQ(csv.num(i, "cross_pairs"), k * k);
      EXPECT_EQ(csv.num(i, "cross_factors"), 2 * k * k);
    } else if (m == "substructure") {
      EXPECT_EQ(csv.num(i, "elements"), 2 * k);
      EXPECT_EQ(csv.num(i, "cross_pairs"), 2 * k);
    } else {
      EXPECT_EQ(m, "hierarchical");
      EXPECT_GE(csv.num(i, "cross_pairs"), 1);
      // Every link pair is gathered both ways (both factors are positive for facing surfaces).
      EXPECT_EQ(csv.num(i, "cross_factors"), 2 * csv.num(i, "cross_pairs"));
      EXPECT_LE(csv.num(i, "elements"), 2 * k);  // aeps = surface / k: never finer than the uniform mesh
    }
  }
  // At k = 16 the surfaces, 20 apart, need far fewer links than the 256 element pairs.
  EXPECT_EQ(csv.str(8, "method"), "hierarchical");
  EXPECT_LT(csv.num(8, "cross_pairs"), 0.25 * 16 * 16);
}

TEST(Figures, BarnesHutThetaZeroIsTheDirectSum) {
  const auto samples = barnes_hut_sweep({50, 200}, {0.0, 0.7}, 3, 200);
  const Csv csv = parse(barnes_hut_csv(samples), {"n", "theta", "mean_interactions", "max_interactions",
                                                  "naive_interactions", "relative_force_error", "seconds"});
  ASSERT_EQ(csv.rows.size(), 4u);
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    const double n = csv.num(i, "n");
    EXPECT_EQ(csv.num(i, "naive_interactions"), n - 1);
    if (csv.num(i, "theta") == 0.0) {
      EXPECT_EQ(csv.num(i, "mean_interactions"), n - 1);
      EXPECT_EQ(csv.num(i, "max_interactions"), n - 1);
      EXPECT_LT(csv.num(i, "relative_force_error"), 1e-12);
    } else {
      EXPECT_LT(csv.num(i, "mean_interactions"), n - 1);
      EXPECT_GT(csv.num(i, "relative_force_error"), 0.0);
      EXPECT_LT(csv.num(i, "relative_force_error"), 0.1);
    }
  }
}

TEST(Figures, JacobiContractsByTheLargestReflectance) {
  const Scene scene = bundled("cornell_box.obj");
  const auto runs = convergence_runs(scene, 16, 1e-6);
  ASSERT_EQ(runs.size(), 3u);
  const Csv csv = parse(convergence_csv(runs), {"method", "iteration", "change"});
  std::map<std::string, std::vector<double>> change;
  for (std::size_t i = 0; i < csv.rows.size(); ++i) {
    auto& c = change[csv.str(i, "method")];
    EXPECT_EQ(csv.num(i, "iteration"), double(c.size() + 1));
    c.push_back(csv.num(i, "change"));
  }
  double rho = 0.0;
  for (const Material& m : scene.materials) rho = std::max(rho, m.reflectance.maxCoeff());
  for (const auto& r : runs) {
    EXPECT_EQ(r.summary.termination, Termination::kConverged) << r.method;
    EXPECT_EQ(change[r.method].size(), std::size_t(r.summary.iterations)) << r.method;
    ASSERT_FALSE(change[r.method].empty());
    EXPECT_LT(change[r.method].back(), 1e-6) << r.method;
  }
  // Jacobi from B = E: |B_k+1 - B_k| <= ||rho F||_inf |B_k - B_k-1| with row sums of F at most 1
  // (closed box), while the largest radiosity (the divisor) only grows.
  const auto& full = change["full"];
  for (std::size_t i = 1; i < full.size(); ++i) EXPECT_LE(full[i], 1.02 * rho * full[i - 1]) << "iteration " << i + 1;
}

TEST(Figures, EqualTimeRowsAndImages) {
  const Scene scene = bundled("cornell_box.obj");
  EqualTimeOptions o;
  o.reference_elements = 64;
  o.first_elements = 16;
  o.calibration_runs = 1;
  o.samples_per_patch = 16;
  o.hierarchical.aeps = scene.total_area() * 3e-2;
  const EqualTimeFigure fig = equal_time_figure(scene, o);
  const Csv csv = parse(equal_time_csv(fig), {"method", "parameter", "value", "elements", "links", "seconds",
                                              "budget_seconds", "error_l2", "error_linf", "image", "error_image"});
  ASSERT_EQ(csv.rows.size(), 4u);
  EXPECT_EQ(csv.str(0, "method"), "full");
  EXPECT_EQ(csv.str(1, "method"), "substructure");
  EXPECT_EQ(csv.str(2, "method"), "hierarchical");
  EXPECT_EQ(csv.str(3, "method"), "reference");
  EXPECT_EQ(csv.num(2, "seconds"), csv.num(2, "budget_seconds"));
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(csv.num(i, "links"), double(fig.runs[i].summary.links));
    EXPECT_GT(csv.num(i, "error_l2"), 0.0);
    EXPECT_LT(csv.num(i, "error_l2"), 1.0);
    EXPECT_GT(csv.num(i, "error_linf"), 0.0);
    EXPECT_EQ(csv.str(i, "image"), "fig6_" + csv.str(i, "method") + ".png");
  }
  // Full runs are coarser than the reference (a finer mesh than any run is what makes it one).
  EXPECT_LT(csv.num(0, "elements"), csv.num(3, "elements"));
  const EqualTimeImages images = equal_time_images(scene, fig, 64, 48);
  ASSERT_EQ(images.renders.size(), 3u);
  ASSERT_EQ(images.errors.size(), 3u);
  for (const Image& im : images.renders) EXPECT_EQ(im.width * im.height, 64 * 48);
  EXPECT_GT(images.error_hi, 0.0);
}

}  // namespace
}  // namespace hrad
