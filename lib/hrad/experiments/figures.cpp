#include "hrad/experiments/figures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "hrad/analysis/power_law_fit.h"
#include "hrad/core/error.h"
#include "hrad/core/face_geometry.h"
#include "hrad/core/tone_map.h"
#include "hrad/experiments/sweep.h"
#include "hrad/render/render.h"

namespace hrad {
namespace {

void report(const ProgressFn& progress, const std::string& line) {
  if (progress) progress(line);
}

SolveOptions options_for(Method method, int threads) {
  SolveOptions o;
  o.method = method;
  o.threads = threads;
  return o;
}

// The lecture's substructuring: the input polygons shoot (N fixed), only the receivers are refined.
double input_polygons_shoot(const Scene& scene) {
  double largest = 0.0;
  for (const Patch& p : scene.patches) largest = std::max(largest, p.area);
  return largest;
}

// Leaves per patch of a solution.
std::vector<std::size_t> leaves_per_patch(const Solution& s, std::size_t patches) {
  std::vector<std::size_t> count(patches, 0);
  for (int p : s.face_patch) ++count[static_cast<std::size_t>(p)];
  return count;
}

double point_segment_distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (x - (a + t * ab)).norm();
}

// Area-weighted 95th percentile of the finite per-face values (the colour-bar top of an error image:
// a few elements where the reference is nearly black have huge relative errors).
double percentile95(const Solution& s, const std::vector<double>& value) {
  std::vector<std::pair<double, double>> by_value;
  double total = 0.0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (!std::isfinite(value[f])) continue;
    by_value.emplace_back(value[f], face_area(s, f));
    total += by_value.back().second;
  }
  std::sort(by_value.begin(), by_value.end());
  double acc = 0.0, hi = 0.0;
  for (const auto& [v, a] : by_value) {
    acc += a;
    hi = v;
    if (acc >= 0.95 * total) break;
  }
  return hi;
}

}  // namespace

// ---- Figure 1 ----------------------------------------------------------------------------------

std::vector<CostRow> cost_rows(const Scene& scene, const CostOptions& options, const ProgressFn& progress) {
  const double area = scene.total_area();
  std::vector<std::pair<std::string, SolveOptions>> settings;
  for (Method m : {Method::kFull, Method::kSubstructure})
    for (double n : m == Method::kFull ? options.element_counts : options.substructure_counts) {
      SolveOptions o = options_for(m, options.threads);
      o.max_area = area / n;
      if (m == Method::kSubstructure) o.patch_area = input_polygons_shoot(scene);
      settings.push_back({"max_area", o});
    }
  for (double fraction : options.aeps_fractions) {
    SolveOptions o = options_for(Method::kHierarchical, options.threads);
    o.aeps = area * fraction;
    o.feps = options.feps;
    settings.push_back({"aeps", o});
  }
  std::vector<CostRow> rows;
  for (const auto& [parameter, o] : settings) {
    const double value = parameter == "aeps" ? o.aeps : o.max_area;
    report(progress, fmt::format("figure 1: {} {}={:.4g}", to_string(o.method), parameter, value));
    const SolveSummary s = solve(scene, o, nullptr);
    rows.push_back(
        {std::string(to_string(o.method)), parameter, value, s.patches, s.elements, s.links, s.work, s.total_seconds});
  }
  return rows;
}

std::span<const CostMeasure> cost_measures() {
  static constexpr CostMeasure kMeasures[] = {
      {"factor_evaluations",
       [](const CostRow& r) { return double(r.work.form_factor_evaluations + r.work.point_factor_evaluations); }},
      {"gather_terms", [](const CostRow& r) { return double(r.work.gather_terms); }},
      {"segment_queries", [](const CostRow& r) { return double(r.work.segment_queries); }},
      {"seconds", [](const CostRow& r) { return r.seconds; }},
  };
  return kMeasures;
}

std::string cost_csv(const std::vector<CostRow>& rows) {
  std::string out =
      "method,parameter,value,patches,elements,links,element_factor_evaluations,point_factor_evaluations,"
      "gather_terms,segment_queries,seconds\n";
  for (const CostRow& r : rows)
    out += fmt::format("{},{},{:.9g},{},{},{},{},{},{},{},{:.6g}\n", r.method, r.parameter, r.value, r.patches,
                       r.elements, r.links, r.work.form_factor_evaluations, r.work.point_factor_evaluations,
                       r.work.gather_terms, r.work.segment_queries, r.seconds);
  return out;
}

nlohmann::json cost_fits(const std::vector<CostRow>& rows) {
  nlohmann::json j;
  j["model"] =
      "measure ~ a elements^b, least squares in log space (Ceres, lib/hrad/analysis/power_law_fit.h), for work "
      "the solves counted (lib/hrad/solvers/work.h) and their seconds";
  std::map<std::string, std::vector<const CostRow*>> by_method;
  for (const CostRow& r : rows)
    if (r.elements > 0) by_method[r.method].push_back(&r);
  for (const auto& [method, list] : by_method)
    for (const CostMeasure& m : cost_measures()) {
      std::vector<double> x, y;
      for (const CostRow* r : list) {
        x.push_back(double(r->elements));
        y.push_back(m.of(*r));
      }
      const std::set<double> distinct(x.begin(), x.end());
      const bool positive = std::all_of(y.begin(), y.end(), [](double v) { return v > 0.0; });
      j["methods"][method][m.name] =
          distinct.size() >= 3 && positive ? fit_json(fit_power_law(x, y)) : nlohmann::json();
    }
  return j;
}

// ---- Figure 2 ----------------------------------------------------------------------------------

EdgeFigure edge_figure(const Scene& scene, SolveOptions options) {
  if (scene.patches.size() < 2) throw Error(fmt::format("{}: figure 2 needs two patches sharing an edge", scene.path));
  const Patch& p0 = scene.patches[0];
  const Patch& p1 = scene.patches[1];
  double scale = 0.0;
  for (const Vec3& v : p0.vertices) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  std::vector<Vec3> shared;
  for (const Vec3& a : p0.vertices)
    for (const Vec3& b : p1.vertices)
      if ((a - b).norm() <= 1e-9 * std::max(1.0, scale)) shared.push_back(a);
  if (shared.size() != 2)
    throw Error(
        fmt::format("{}: patches 0 and 1 share {} vertices, not an edge (figure 2)", scene.path, shared.size()));

  EdgeFigure fig;
  fig.edge_a = shared[0];
  fig.edge_b = shared[1];
  options.method = Method::kHierarchical;
  fig.summary = solve(scene, options, &fig.solution);
  for (std::size_t f = 0; f < fig.solution.faces.size(); ++f) {
    EdgeElementRow r;
    r.element = static_cast<int>(f);
    r.patch = fig.solution.face_patch[f];
    r.distance = point_segment_distance(face_centroid(fig.solution, f), fig.edge_a, fig.edge_b);
    r.area = face_area(fig.solution, f);
    r.size = std::sqrt(r.area);
    fig.rows.push_back(r);
  }
  return fig;
}

std::string edge_csv(const EdgeFigure& figure) {
  std::string out = "element,patch,distance,area,size\n";
  for (const EdgeElementRow& r : figure.rows)
    out += fmt::format("{},{},{:.9g},{:.9g},{:.9g}\n", r.element, r.patch, r.distance, r.area, r.size);
  return out;
}

// ---- Figure 3 ----------------------------------------------------------------------------------

std::vector<FarRow> far_rows(const Scene& scene, const std::vector<int>& ks, double feps, int threads,
                             const ProgressFn& progress) {
  if (scene.patches.size() != 2)
    throw Error(fmt::format("{}: figure 3 needs exactly two patches, got {}", scene.path, scene.patches.size()));
  const double patch_area = std::max(scene.patches[0].area, scene.patches[1].area);
  std::vector<FarRow> rows;
  for (int k : ks) {
    for (Method m : {Method::kFull, Method::kSubstructure, Method::kHierarchical}) {
      SolveOptions o = options_for(m, threads);
      if (m == Method::kHierarchical) {
        o.aeps = patch_area / k;
        o.feps = feps;
      } else {
        o.max_area = patch_area / k;
        if (m == Method::kSubstructure) o.patch_area = input_polygons_shoot(scene);
      }
      report(progress, fmt::format("figure 3: k={} {}", k, to_string(m)));
      Solution s;
      const SolveSummary summary = solve(scene, o, &s);
      const std::vector<std::size_t> n = leaves_per_patch(s, 2);
      FarRow r;
      r.k = k;
      r.method = std::string(to_string(m));
      r.elements = summary.elements;
      r.form_factor_evaluations = summary.form_factor_evaluations;
      r.seconds = summary.total_seconds;
      switch (m) {
        case Method::kFull:
          r.cross_pairs = n[0] * n[1];
          r.cross_factors = 2 * n[0] * n[1];
          break;
        case Method::kSubstructure:  // every element receives from the one other patch
          r.cross_pairs = n[0] + n[1];
          r.cross_factors = n[0] + n[1];
          break;
        case Method::kHierarchical:  // two patches: every link joins the two surfaces
          r.cross_factors = summary.links;
          r.cross_pairs =
              static_cast<std::size_t>(summary.figures.count("link_pairs") ? summary.figures.at("link_pairs") : 0.0);
          break;
      }
      rows.push_back(r);
    }
  }
  return rows;
}

std::string far_csv(const std::vector<FarRow>& rows) {
  std::string out = "k,method,elements,cross_factors,cross_pairs,form_factor_evaluations,seconds\n";
  for (const FarRow& r : rows)
    out += fmt::format("{},{},{},{},{},{},{:.6g}\n", r.k, r.method, r.elements, r.cross_factors, r.cross_pairs,
                       r.form_factor_evaluations, r.seconds);
  return out;
}

// ---- Figure 4 ----------------------------------------------------------------------------------

std::string barnes_hut_csv(const std::vector<BarnesHutSample>& samples) {
  std::string out = "n,theta,mean_interactions,max_interactions,naive_interactions,relative_force_error,seconds\n";
  for (const BarnesHutSample& s : samples)
    out += fmt::format("{},{:.6g},{:.9g},{},{:.9g},{:.9g},{:.6g}\n", s.n, s.theta, s.mean_interactions,
                       s.max_interactions, s.naive_interactions, s.relative_force_error, s.seconds);
  return out;
}

// ---- Figure 5 ----------------------------------------------------------------------------------

std::vector<ConvergenceRun> convergence_runs(const Scene& scene, double full_elements, double tolerance, int threads,
                                             const ProgressFn& progress) {
  std::vector<ConvergenceRun> runs;
  for (Method m : {Method::kFull, Method::kSubstructure, Method::kHierarchical}) {
    SolveOptions o = options_for(m, threads);
    o.tolerance = tolerance;
    if (m != Method::kHierarchical) o.max_area = scene.total_area() / full_elements;
    if (m == Method::kFull) o.linear_solver = LinearSolver::kJacobi;
    report(progress, fmt::format("figure 5: {}", to_string(m)));
    runs.push_back({std::string(to_string(m)), solve(scene, o, nullptr)});
  }
  return runs;
}

std::string convergence_csv(const std::vector<ConvergenceRun>& runs) {
  std::string out = "method,iteration,change\n";
  for (const ConvergenceRun& r : runs)
    for (std::size_t i = 0; i < r.summary.change_per_iteration.size(); ++i)
      out += fmt::format("{},{},{:.9g}\n", r.method, i + 1, r.summary.change_per_iteration[i]);
  return out;
}

// ---- Figure 6 ----------------------------------------------------------------------------------

EqualTimeFigure equal_time_figure(const Scene& scene, const EqualTimeOptions& options, const ProgressFn& progress) {
  EqualTimeFigure fig;
  const double area = scene.total_area();
  {
    SolveOptions o = options_for(Method::kFull, options.threads);
    o.max_area = area / options.reference_elements;
    report(progress,
           fmt::format("figure 6: reference (full matrix, LU, {} elements aimed at)", options.reference_elements));
    fig.reference_summary = solve(scene, o, &fig.reference);
  }
  const Solution reference_reflected = reflected_part(scene, fig.reference);

  const auto measure = [&](EqualTimeRun run) {
    run.error = compare_solutions(scene, reflected_part(scene, run.solution), reference_reflected,
                                  options.samples_per_patch, Emitters::exclude);
    return run;
  };

  // The budget: the hierarchical solve at the given settings.
  SolveOptions hr = options.hierarchical;
  hr.method = Method::kHierarchical;
  hr.threads = options.threads;
  report(progress, "figure 6: hierarchical (sets the time budget)");
  EqualTimeRun hr_run;
  hr_run.method = "hierarchical";
  hr_run.parameter = "feps";
  hr_run.value = hr.feps;
  hr_run.summary = solve(scene, hr, &hr_run.solution);
  fig.budget_seconds = hr_run.summary.total_seconds;
  if (hr_run.summary.figures.count("feps")) hr_run.value = hr_run.summary.figures.at("feps");  // the default applied

  // Full and substructuring: element counts scaled by the measured time (full ~ n^2 factors,
  // substructuring ~ n N), starting from a small mesh; the run closest to the budget (in log time) is kept.
  for (Method m : {Method::kFull, Method::kSubstructure}) {
    const double exponent = m == Method::kFull ? 2.0 : 1.0;
    double n = options.first_elements;
    EqualTimeRun best;
    double best_miss = INFINITY;
    for (int c = 0; c < std::max(1, options.calibration_runs); ++c) {
      SolveOptions o = options_for(m, options.threads);
      o.max_area = area / n;
      report(progress, fmt::format("figure 6: {} calibration {} (max_area = total / {:.0f})", to_string(m), c + 1, n));
      EqualTimeRun run;
      run.method = std::string(to_string(m));
      run.parameter = "max_area";
      run.value = o.max_area;
      run.summary = solve(scene, o, &run.solution);
      const double t = std::max(run.summary.total_seconds, 1e-4);
      const double miss = std::abs(std::log(t / std::max(fig.budget_seconds, 1e-4)));
      if (miss < best_miss) {
        best_miss = miss;
        best = std::move(run);
      }
      // At most a quarter of the reference's elements: the reference must be finer than every run it judges
      // (a run on its mesh would differ from it by the solver's tolerance only).
      const double next = std::clamp(n * std::pow(fig.budget_seconds / t, 1.0 / exponent), 8.0,
                                     std::max(8.0, options.reference_elements / 4));
      if (std::abs(std::log(next / n)) < 0.05) break;
      n = next;
    }
    fig.runs.push_back(measure(std::move(best)));
  }
  fig.runs.push_back(measure(std::move(hr_run)));
  return fig;
}

std::string equal_time_csv(const EqualTimeFigure& figure) {
  std::string out =
      "method,parameter,value,elements,links,seconds,budget_seconds,error_l2,error_linf,image,error_image\n";
  for (const EqualTimeRun& r : figure.runs)
    out += fmt::format("{},{},{:.9g},{},{},{:.6g},{:.6g},{:.9g},{:.9g},fig6_{}.png,fig6_{}_error.png\n", r.method,
                       r.parameter, r.value, r.summary.elements, r.summary.links, r.summary.total_seconds,
                       figure.budget_seconds, r.error.relative_l2, r.error.relative_linf, r.method, r.method);
  out += fmt::format(
      "reference,max_area,{:.9g},{},{},{:.6g},{:.6g},0,0,,\n",
      figure.reference_summary.figures.count("max_area") ? figure.reference_summary.figures.at("max_area") : 0.0,
      figure.reference_summary.elements, figure.reference_summary.links, figure.reference_summary.total_seconds,
      figure.budget_seconds);
  return out;
}

EqualTimeImages equal_time_images(const Scene& scene, const EqualTimeFigure& figure, int width, int height) {
  std::vector<bool> emitter(scene.patches.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p) emitter[p] = scene.material_of(scene.patches[p]).is_emitter();
  RenderOptions render;
  render.camera = default_camera(figure.reference, width, height);
  render.exposure = auto_exposure(figure.reference, emitter);
  EqualTimeImages images;
  for (const EqualTimeRun& r : figure.runs)
    images.error_hi = std::max(images.error_hi, percentile95(r.solution, r.error.face_relative_l2));
  if (!(images.error_hi > 0.0)) images.error_hi = 1.0;
  FalseColourOptions colours;
  colours.lo = 0.0;
  colours.hi = images.error_hi;
  for (const EqualTimeRun& r : figure.runs) {
    images.renders.push_back(render_solution(r.solution, render));
    images.errors.push_back(render_false_colour(r.solution, r.error.face_relative_l2, render, colours));
  }
  return images;
}

}  // namespace hrad
