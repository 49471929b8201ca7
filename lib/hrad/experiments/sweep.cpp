#include "hrad/experiments/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "hrad/analysis/error_metrics.h"
#include "hrad/core/error.h"
#include "hrad/core/progress.h"
#include "hrad/core/stopwatch.h"
#include "hrad/experiments/final_gather.h"

namespace hrad {
namespace {

// A final gather's progress, (points done, points in all) every 2 s, as solve_progress lines with
// the time left; empty without solve_progress.
std::function<void(std::size_t, std::size_t)> gather_progress(const SweepOptions& sweep, std::string what,
                                                              const Stopwatch& watch) {
  if (!sweep.solve_progress) return {};
  return [&sweep, what = std::move(what), &watch](std::size_t done, std::size_t all) {
    if (done < all) sweep.solve_progress(progress_line(what, done, all, "points", watch.seconds()));
  };
}

SolveOptions base_options(Method method, const SweepOptions& sweep) {
  SolveOptions o;
  o.method = method;
  o.threads = sweep.threads;
  o.progress = sweep.solve_progress;
  if (sweep.visibility_samples > 0) o.visibility_samples = sweep.visibility_samples;
  if (method == Method::kHierarchical) {
    o.source_levels = sweep.source_levels;
    o.source_levels_near_lamps = sweep.source_levels_near_lamps;
  }
  return o;
}

}  // namespace

double reference_elements_aimed(const SweepOptions& options) {
  if (options.reference_elements > 0) return options.reference_elements;
  const double finest = 4.0 * *std::max_element(options.element_counts.begin(), options.element_counts.end());
  return options.final_gather ? std::min(finest, kFinalGatherReferenceElements) : finest;
}

Solution reflected_part(const Scene& scene, Solution solution) {
  for (std::size_t f = 0; f < solution.faces.size(); ++f)
    solution.face_radiosity[f] -= scene.material_of(scene.patches[solution.face_patch[f]]).emission;
  for (std::size_t f = 0; f < solution.face_field.size(); ++f)
    for (Rgb& b : solution.face_field[f].radiosity)
      b -= scene.material_of(scene.patches[solution.face_patch[f]]).emission;
  for (std::size_t p = 0; p < solution.patch_radiosity.size(); ++p)
    solution.patch_radiosity[p] -= scene.material_of(scene.patches[p]).emission;
  // A vertex is shared only by leaves of one plane and one material (ElementHierarchy::to_solution),
  // so any face around it gives its emission.
  std::vector<bool> done(solution.vertex_radiosity.size(), false);
  for (std::size_t f = 0; f < solution.faces.size(); ++f)
    for (int v : solution.faces[f])
      if (!done[v]) {
        solution.vertex_radiosity[v] -= scene.material_of(scene.patches[solution.face_patch[f]]).emission;
        done[v] = true;
      }
  return solution;
}

std::vector<std::pair<Method, SweepSetting>> sweep_settings(const Scene& scene, const SweepOptions& options) {
  const double area = scene.total_area();
  std::vector<std::pair<Method, SweepSetting>> settings;
  const auto add = [&](Method m, std::string parameter, double value, SolveOptions o) {
    settings.push_back({m, SweepSetting{std::move(parameter), value, std::move(o)}});
  };
  // Every method once per basis; the full matrix's linear elements iterate by Jacobi (solve.h).
  for (const Basis basis : options.bases)
    for (double n : options.element_counts) {
      SolveOptions o = base_options(Method::kFull, options);
      o.max_area = area / n;
      o.basis = basis;
      o.linear_solver = basis == Basis::kLinear ? LinearSolver::kJacobi : options.full_linear_solver;
      add(Method::kFull, "max_area", o.max_area, o);
    }
  std::vector<double> counts = options.element_counts;
  std::sort(counts.begin(), counts.end());
  const double median_count = counts[counts.size() / 2];
  for (const Basis basis : options.bases) {
    for (double n : options.element_counts) {
      SolveOptions o = base_options(Method::kSubstructure, options);
      o.max_area = area / n;
      o.basis = basis;
      add(Method::kSubstructure, "max_area", o.max_area, o);
    }
    for (double p : options.patch_counts) {
      SolveOptions o = base_options(Method::kSubstructure, options);
      o.max_area = area / median_count;
      o.patch_area = area / p;
      o.basis = basis;
      add(Method::kSubstructure, "patch_area", o.patch_area, o);
    }
  }
  for (const Push push : options.pushes)
    for (const Basis basis : options.bases) {
      for (double feps : options.feps_values) {
        SolveOptions o = base_options(Method::kHierarchical, options);
        o.feps = feps;
        o.aeps = area * options.feps_aeps_fraction;
        o.push = push;
        o.basis = basis;
        add(Method::kHierarchical, "feps", feps, o);
      }
      for (double fraction : options.aeps_fractions) {
        SolveOptions o = base_options(Method::kHierarchical, options);
        o.aeps = area * fraction;
        o.push = push;
        o.basis = basis;
        add(Method::kHierarchical, "aeps", o.aeps, o);
      }
    }
  return settings;
}

Reference make_reference(const Scene& scene, const SweepOptions& options) {
  const double n = reference_elements_aimed(options);
  SolveOptions o = base_options(Method::kFull, options);
  o.max_area = scene.total_area() / n;
  o.linear_solver = LinearSolver::kLu;
  // More visibility samples than any run, so that the reference's sampling noise stays below theirs.
  o.visibility_samples = 4 * o.visibility_samples;
  Reference ref;
  ref.summary = solve(scene, o, &ref.solution);
  if (options.final_gather) {
    const std::vector<SurfaceSample> samples = patch_samples(scene, options.samples_per_patch);
    FinalGatherOptions g;
    g.threads = options.threads;
    g.visibility_samples = o.visibility_samples;
    const Stopwatch watch;
    g.progress = gather_progress(options, "reference: final gather", watch);
    ref.gathered = final_gather_reflected(scene, ref.solution, samples, g);
    ref.gather_seconds = watch.seconds();
  }
  ref.solution = reflected_part(scene, std::move(ref.solution));
  ref.description = {
      {"kind", "converged solution computed independently of the runs judged"},
      {"method", "full"},
      {"linear_solver", "lu"},
      {"why",
       ref.gathered.empty()
           ? "a direct solve on a uniform mesh finer than any full-matrix run of the sweep: it shares the exact "
             "kernels with the runs but none of their discretisations or iterations"
           : "a direct solve on a uniform mesh, final-gathered at the error samples: it shares the exact kernels "
             "with the runs but none of their discretisations or iterations, and its own element error enters "
             "only through the gather's integral, so it need not be finer than the runs it judges"},
      {"elements_aimed_at", n},
      {"max_area", o.max_area},
      {"visibility_samples", o.visibility_samples},
      {"elements", ref.summary.elements},
      {"links", ref.summary.links},
      {"form_factor_evaluations", ref.summary.form_factor_evaluations},
      {"visibility_queries", ref.summary.visibility_queries},
      {"seconds", ref.summary.total_seconds},
      {"termination", std::string(to_string(ref.summary.termination))},
      {"samples_per_patch", options.samples_per_patch},
      {"final_gather", options.final_gather},
      {"final_gather_seconds", ref.gather_seconds},
      {"judged_against",
       options.final_gather
           ? "the reference solution's final gather at each sample: B(x) - E(x) = rho(x) sum_j F(x->j) V(x,j) B_j over "
             "its elements j, Lambert's exact point-to-polygon factor, visibility by stratified points per partly "
             "visible element (lib/hrad/experiments/final_gather.h)"
           : "the reference solution's own field (constant or interpolated, as the run)"},
      {"error_definition",
       "relative_l2 = sqrt(sum_k w_k |B(x_k)-Bref(x_k)|^2 / sum_k w_k |Bref(x_k)|^2), relative_linf = "
       "max_k |B-Bref| / max_k |Bref|, over fixed stratified samples x_k on every patch "
       "(lib/hrad/analysis/error_metrics.h), B the constant reflected radiosity B - E of the leaf containing x_k "
       "(the emission is input, not computed: including it would let the light dominate both sums); "
       "error_l2_smooth and error_linf_smooth measure the displayed field instead: the vertex radiosity "
       "interpolated linearly over each leaf, in both the run and the reference"}};
  return ref;
}

namespace {

// A sample's position as a key (patch_samples() is deterministic, so the runs' samples are the
// reference's to the bit).
struct SampleKey {
  std::size_t operator()(const std::pair<int, Vec3>& k) const {
    std::size_t h = std::hash<int>()(k.first);
    for (int c = 0; c < 3; ++c) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &k.second[c], sizeof bits);
      h = h * 1000003u ^ std::hash<std::uint64_t>()(bits);
    }
    return h;
  }
};
using GatheredLookup = std::unordered_map<std::pair<int, Vec3>, Rgb, SampleKey>;

GatheredLookup gathered_lookup(const Scene& scene, const Reference& reference, int samples_per_patch) {
  GatheredLookup lookup;
  if (reference.gathered.empty()) return lookup;
  const std::vector<SurfaceSample> samples = patch_samples(scene, samples_per_patch);
  for (std::size_t i = 0; i < samples.size(); ++i)
    lookup[{samples[i].patch, samples[i].position}] = reference.gathered[i];
  return lookup;
}

// Error of a run against the reference: its final gather at the samples when there is one (a point
// off the samples, the centroid of a leaf no sample falls in, takes the reference's own field).
ErrorMetrics judge(const Scene& scene, const Solution& run, const Reference& reference, const GatheredLookup& lookup,
                   int samples_per_patch, Field field) {
  if (lookup.empty())
    return compare_solutions(scene, run, reference.solution, samples_per_patch, Emitters::include, field);
  const SolutionSampler fallback(scene, reference.solution);
  return compare_to_function(
      scene, run,
      [&](const Vec3& x, int patch) {
        const auto it = lookup.find({patch, x});
        return it != lookup.end() ? it->second : fallback.value_at(x, patch, nullptr, field);
      },
      samples_per_patch, Emitters::include, field);
}

}  // namespace

std::vector<SweepRow> run_sweep(const Scene& scene, const Reference& reference, const SweepOptions& options) {
  const auto settings = sweep_settings(scene, options);
  const GatheredLookup lookup = gathered_lookup(scene, reference, options.samples_per_patch);
  const bool gather_runs = options.gather_runs && !reference.gathered.empty();
  const std::vector<SurfaceSample> samples =
      gather_runs ? patch_samples(scene, options.samples_per_patch) : std::vector<SurfaceSample>{};
  std::vector<SweepRow> rows;
  int done = 0;
  for (const auto& [method, setting] : settings) {
    if (options.progress)
      options.progress(done, static_cast<int>(settings.size()),
                       fmt::format("{} {}={:.4g}", to_string(method), setting.parameter, setting.value));
    Solution solution;
    SolvedHierarchy kept;
    SolveSummary s;
    try {
      s = solve(scene, setting.options, &solution, gather_runs && options.gather_through_links ? &kept : nullptr);
    } catch (const Error& e) {
      ++done;
      if (options.progress)
        options.progress(
            done, static_cast<int>(settings.size()),
            fmt::format("skipped {} {}={:.4g}: {}", to_string(method), setting.parameter, setting.value, e.what()));
      continue;
    }
    SweepRow row;
    if (gather_runs) {
      FinalGatherOptions g;
      g.tolerance = options.gather_tolerance;
      g.threads = options.threads;
      if (options.visibility_samples > 0) g.visibility_samples = options.visibility_samples;
      g.links = &kept;
      GatherWork work;
      const Stopwatch watch;
      g.progress = gather_progress(options, "final gather", watch);  // a fine run's takes minutes too
      const std::vector<Rgb> gathered = final_gather_reflected(scene, solution, samples, g, &work);
      row.gather_seconds = watch.seconds();
      row.gather_work = work.total();
      const ErrorMetrics m = compare_at_samples(scene, samples, gathered, reference.gathered);
      row.error_l2_gathered = m.relative_l2;
      row.error_linf_gathered = m.relative_linf;
    }
    const Solution reflected = reflected_part(scene, std::move(solution));
    const ErrorMetrics e = judge(scene, reflected, reference, lookup, options.samples_per_patch, Field::constant);
    const ErrorMetrics smooth =
        judge(scene, reflected, reference, lookup, options.samples_per_patch, Field::interpolated);
    row.method = std::string(to_string(method));
    if (method == Method::kHierarchical && setting.options.push == Push::kLeaf) row.method += "_leaf";
    if (setting.options.basis == Basis::kLinear) row.method += "_linear";
    row.parameter = setting.parameter;
    row.value = setting.value;
    row.elements = s.elements;
    row.links = s.links;
    row.form_factor_evaluations = s.form_factor_evaluations;
    row.visibility_queries = s.visibility_queries;
    row.seconds = s.total_seconds;
    row.error_l2 = e.relative_l2;
    row.error_linf = e.relative_linf;
    row.error_l2_smooth = smooth.relative_l2;
    row.error_linf_smooth = smooth.relative_linf;
    row.iterations = s.iterations;
    row.termination = std::string(to_string(s.termination));
    row.change_per_iteration = s.change_per_iteration;
    rows.push_back(std::move(row));
    ++done;
  }
  if (options.progress) options.progress(done, done, "done");
  return rows;
}

nlohmann::json fit_json(const PowerLawFit& fit) {
  return {{"a", fit.a},
          {"b", fit.b},
          {"a_stderr", fit.a_stderr},
          {"b_stderr", fit.b_stderr},
          {"points", fit.points},
          {"rms_log_residual", fit.rms_log_residual},
          {"converged", fit.converged}};
}

namespace {

// Fits y ~ a x^b over rows, or null when fewer than 3 distinct positive x (no standard error then).
nlohmann::json maybe_fit(const std::vector<const SweepRow*>& rows, const std::function<double(const SweepRow&)>& x_of,
                         const std::function<double(const SweepRow&)>& y_of) {
  std::vector<double> x, y;
  std::set<double> distinct;
  for (const SweepRow* r : rows) {
    const double xi = x_of(*r), yi = y_of(*r);
    if (xi > 0 && yi > 0 && std::isfinite(xi) && std::isfinite(yi)) {
      x.push_back(xi);
      y.push_back(yi);
      distinct.insert(xi);
    }
  }
  if (distinct.size() < 3) return nullptr;
  return fit_json(fit_power_law(x, y));
}

double solve_seconds(const SweepRow& r) { return r.seconds; }

// A field's time: the solve's, and for the gathered field the gather's on top.
double solve_and_gather_seconds(const SweepRow& r) { return r.seconds + r.gather_seconds; }

// The fields a sweep measures: name suffix, description, error column, time.
struct SweepField {
  const char* suffix;
  const char* description;
  double SweepRow::*error;
  double (*seconds)(const SweepRow&);
};
constexpr SweepField kFields[] = {
    {"", "constant element radiosity", &SweepRow::error_l2, &solve_seconds},
    {"_smooth", "interpolated vertex radiosity (as displayed)", &SweepRow::error_l2_smooth, &solve_seconds},
    {"_gathered", "final gather of the solution at the samples (time: solve and gather)", &SweepRow::error_l2_gathered,
     &solve_and_gather_seconds},
};

// Seconds a method needs to reach `target` relative L2 error: the fastest run at or below the target
// (measured), and a log-log interpolation between it and the slower-error run just before it. Rows
// that did not measure the field (nan) are left out.
nlohmann::json time_to_error(const std::vector<const SweepRow*>& all_rows, double target, double SweepRow::*error,
                             double (*seconds_of)(const SweepRow&) = &solve_seconds) {
  std::vector<const SweepRow*> rows;  // the runs that measured this field
  for (const SweepRow* r : all_rows)
    if (std::isfinite(r->*error)) rows.push_back(r);
  nlohmann::json j;
  j["target_error_l2"] = target;
  if (rows.empty()) {
    j["reached"] = false;
    j["note"] = "not measured";
    return j;
  }
  std::vector<const SweepRow*> by_time = rows;
  std::sort(by_time.begin(), by_time.end(), [&](auto* a, auto* b) { return seconds_of(*a) < seconds_of(*b); });
  const SweepRow* first = nullptr;
  std::size_t k = 0;
  for (; k < by_time.size(); ++k)
    if (by_time[k]->*error <= target) {
      first = by_time[k];
      break;
    }
  if (!first) {
    const SweepRow* best =
        *std::min_element(rows.begin(), rows.end(), [&](auto* a, auto* b) { return a->*error < b->*error; });
    j["reached"] = false;
    j["best_error_l2"] = best->*error;
    j["slowest_seconds"] = seconds_of(*by_time.back());
    return j;
  }
  j["reached"] = true;
  j["measured_seconds"] = seconds_of(*first);
  j["run"] = {{"parameter", first->parameter}, {"value", first->value}, {"error_l2", first->*error}};
  double interpolated = seconds_of(*first);
  // The latest faster run that missed the target brackets it from above in error.
  for (std::size_t i = k; i-- > 0;) {
    const SweepRow* prev = by_time[i];
    if (prev->*error > target && seconds_of(*prev) > 0 && seconds_of(*first) > seconds_of(*prev)) {
      const double t = std::log(target / prev->*error) / std::log(first->*error / prev->*error);
      interpolated = std::exp(std::log(seconds_of(*prev)) + t * std::log(seconds_of(*first) / seconds_of(*prev)));
      break;
    }
  }
  j["interpolated_seconds"] = interpolated;
  return j;
}

}  // namespace

nlohmann::json sweep_fits(const std::vector<SweepRow>& rows, double target_error) {
  std::map<std::string, std::vector<const SweepRow*>> by_method, size_runs;
  for (const SweepRow& r : rows) {
    by_method[r.method].push_back(&r);
    if (r.parameter != "patch_area") size_runs[r.method].push_back(&r);  // runs whose element count varies
  }
  const auto elements = [](const SweepRow& r) { return double(r.elements); };
  nlohmann::json j;
  j["model"] = "y ~ a x^b, least squares in log space (Ceres), one standard error (lib/hrad/analysis/power_law_fit.h)";
  for (const auto& [method, list] : by_method) {
    nlohmann::json m;
    m["time_vs_elements"] = maybe_fit(
        size_runs[method], +elements, +[](const SweepRow& r) { return r.seconds; });
    m["links_vs_elements"] = maybe_fit(
        size_runs[method], +elements, +[](const SweepRow& r) { return double(r.links); });
    for (const SweepField& f : kFields)
      m[std::string("time_to_target_error") + f.suffix] = time_to_error(list, target_error, f.error, f.seconds);
    j["methods"][method] = std::move(m);
  }
  if (by_method.count("hierarchical")) {
    std::vector<const SweepRow*> feps_runs;
    for (const SweepRow* r : by_method["hierarchical"])
      if (r->parameter == "feps") feps_runs.push_back(r);
    j["methods"]["hierarchical"]["error_vs_feps"] = maybe_fit(
        feps_runs, +[](const SweepRow& r) { return r.value; }, +[](const SweepRow& r) { return r.error_l2; });
  }
  // The headline: how much faster hierarchical radiosity reaches the target error than the full matrix.
  const auto& methods = j["methods"];
  if (!methods.contains("full") || !methods.contains("hierarchical")) return j;
  for (const SweepField& fd : kFields) {
    const char* field = fd.suffix;
    const auto& full = methods["full"][std::string("time_to_target_error") + field];
    const auto& hr = methods["hierarchical"][std::string("time_to_target_error") + field];
    if (full.contains("note") || hr.contains("note")) continue;  // a field these rows did not measure
    nlohmann::json s;
    s["field"] = fd.description;
    s["target_error_l2"] = target_error;
    if (hr["reached"] && full["reached"]) {
      s["full_over_hierarchical_measured"] =
          full["measured_seconds"].get<double>() / hr["measured_seconds"].get<double>();
      s["full_over_hierarchical_interpolated"] =
          full["interpolated_seconds"].get<double>() / hr["interpolated_seconds"].get<double>();
    } else if (hr["reached"]) {
      s["full_over_hierarchical_at_least"] =
          full["slowest_seconds"].get<double>() / hr["measured_seconds"].get<double>();
      s["note"] = "the full matrix did not reach the target in this sweep: the ratio is a lower bound";
    } else {
      s["note"] = "the hierarchical solver did not reach the target in this sweep";
    }
    // Where both methods stop short of the target, the same comparison at the lowest error both
    // reached (the larger of their best errors), so that every sweep states a measured ratio.
    const double common = std::max(full.contains("best_error_l2") ? full["best_error_l2"].get<double>() : 0.0,
                                   hr.contains("best_error_l2") ? hr["best_error_l2"].get<double>() : 0.0);
    if (common > target_error) {
      const nlohmann::json f = time_to_error(by_method["full"], common, fd.error, fd.seconds),
                           h = time_to_error(by_method["hierarchical"], common, fd.error, fd.seconds);
      nlohmann::json c;
      c["error_l2"] = common;
      c["full_seconds"] = f["interpolated_seconds"];
      c["hierarchical_seconds"] = h["interpolated_seconds"];
      c["full_over_hierarchical_interpolated"] =
          f["interpolated_seconds"].get<double>() / h["interpolated_seconds"].get<double>();
      j[std::string("speedup_at_common_error") + field] = std::move(c);
    }
    j[std::string("speedup") + field] = std::move(s);
  }
  // Beyond the runs: where neither reached the target, the fits' estimate of each method's time to
  // it, error ~ k n^-g and seconds ~ a n^b over the runs that vary the element count (max_area for
  // the full matrix, aeps for HR): n* = (k / target)^(1/g), time a n*^b. An extrapolation, labelled.
  for (const SweepField& fd : kFields) {
    const char* field = fd.suffix;
    if (!j.contains(std::string("speedup") + field)) continue;
    if (j[std::string("speedup") + field].contains("full_over_hierarchical_measured")) continue;
    nlohmann::json x;
    x["note"] = "extrapolated from power-law fits beyond the sweep's runs, not measured";
    x["target_error_l2"] = target_error;
    bool both = true;
    for (const char* method : {"full", "hierarchical"}) {
      std::vector<const SweepRow*> runs;
      for (const SweepRow* r : by_method[method])
        if (r->parameter == (std::string(method) == "full" ? "max_area" : "aeps")) runs.push_back(r);
      const nlohmann::json err = maybe_fit(runs, elements, [&](const SweepRow& r) { return r.*fd.error; });
      const nlohmann::json time = maybe_fit(runs, elements, fd.seconds);
      if (err.is_null() || time.is_null() || !(err["b"].get<double>() < 0.0)) {
        both = false;
        break;
      }
      const double n = std::pow(err["a"].get<double>() / target_error, -1.0 / err["b"].get<double>());
      x[method] = {{"error_vs_elements", err},
                   {"elements", n},
                   {"seconds", time["a"].get<double>() * std::pow(n, time["b"].get<double>())}};
    }
    if (!both) continue;
    x["full_over_hierarchical"] = x["full"]["seconds"].get<double>() / x["hierarchical"]["seconds"].get<double>();
    j[std::string("speedup_extrapolated") + field] = std::move(x);
  }
  return j;
}

std::string sweep_csv(const std::vector<SweepRow>& rows) {
  std::string out =
      "method,parameter,value,elements,links,form_factor_evaluations,visibility_queries,seconds,error_l2,error_linf,"
      "iterations,termination,error_l2_smooth,error_linf_smooth,error_l2_gathered,error_linf_gathered,gather_seconds,"
      "gather_work\n";
  for (const SweepRow& r : rows)
    out += fmt::format("{},{},{:.9g},{},{},{},{},{:.6g},{:.9g},{:.9g},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.6g},{}\n",
                       r.method, r.parameter, r.value, r.elements, r.links, r.form_factor_evaluations,
                       r.visibility_queries, r.seconds, r.error_l2, r.error_linf, r.iterations, r.termination,
                       r.error_l2_smooth, r.error_linf_smooth, r.error_l2_gathered, r.error_linf_gathered,
                       r.gather_seconds, r.gather_work);
  return out;
}

}  // namespace hrad
