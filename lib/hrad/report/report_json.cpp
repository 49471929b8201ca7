#include "hrad/report/report_json.h"

#include "hrad/geometry/polygon.h"
#include "hrad/io/atomic_file.h"

namespace hrad {
namespace {

nlohmann::json rgb(const Rgb& v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

}  // namespace

nlohmann::json solve_report_json(const Scene& scene, const SolveOptions& options, const SolveSummary& summary,
                                 const Solution& solution) {
  using nlohmann::json;
  json j;
  j["scene"] = scene.path;
  j["method"] = std::string(to_string(summary.method));
  // The options as the solve used them (automatic values filled in, the method's own kernel).
  const SolveOptions& used = summary.used;
  (void)options;
  j["options"] = {{"max_area", used.max_area},
                  {"patch_area", used.patch_area},
                  {"feps", used.feps},
                  {"bfeps", used.bfeps},
                  {"aeps", used.aeps},
                  {"source_levels", used.source_levels},
                  {"source_levels_near_lamps", used.source_levels_near_lamps},
                  {"tolerance", used.tolerance},
                  {"max_iterations", used.max_iterations},
                  {"linear_solver", std::string(to_string(used.linear_solver))},
                  {"effects", std::string(to_string(used.effects))},
                  {"kernel", std::string(to_string(used.kernel))},
                  {"visibility_samples", used.visibility_samples},
                  {"seed", used.seed},
                  {"power_noise", used.power_noise},
                  {"closure", used.close_closed_scenes ? "auto" : "off"},
                  {"clustering", std::string(to_string(used.clustering))},
                  {"push", std::string(to_string(used.push))},
                  {"basis", std::string(to_string(used.basis))},
                  {"balance", used.balance},
                  {"threads", used.threads}};
  j["termination"] = std::string(to_string(summary.termination));
  j["status"] = std::string(to_string(summary.termination));
  j["message"] = summary.message;
  j["iterations"] = summary.iterations;
  j["elements"] = summary.elements;
  j["links"] = summary.links;
  j["patch_count"] = summary.patches;
  j["form_factor_evaluations"] = summary.form_factor_evaluations;
  j["visibility_queries"] = summary.visibility_queries;
  j["work"] = {{"gather_terms", summary.work.gather_terms},
               {"point_factor_evaluations", summary.work.point_factor_evaluations},
               {"form_factor_evaluations", summary.work.form_factor_evaluations},
               {"segment_queries", summary.work.segment_queries},
               {"shaft_queries", summary.work.shaft_queries},
               {"link_bytes", summary.work.link_bytes},
               {"candidate_pairs", summary.work.candidate_pairs}};
  json seconds = json::object();
  seconds["total"] = summary.total_seconds;
  for (const auto& [name, s] : summary.seconds) seconds[name] = s;
  j["seconds"] = seconds;
  j["effects"] = {{"visibility", summary.effects.visibility},
                  {"color_channels", summary.effects.color_channels},
                  {"bounces", summary.effects.bounces},
                  {"cull_facing_away", summary.effects.cull_facing_away},
                  {"reasons", summary.effects.reasons}};
  j["change_per_iteration"] = summary.change_per_iteration;
  j["peak_memory_bytes"] = summary.peak_memory_bytes;
  json figures = json::object();
  for (const auto& [name, v] : summary.figures) figures[name] = v;
  j["figures"] = figures;

  // Energy: the elements' areas from their polygons (faces may carry T-vertices, which do not
  // change the area).
  double emitted = 0.0, radiated = 0.0;
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    std::vector<Vec3> poly;
    for (int v : solution.faces[f]) poly.push_back(solution.vertices[static_cast<std::size_t>(v)]);
    const double area = polygon_area(poly);
    const Patch& patch = scene.patches[static_cast<std::size_t>(solution.face_patch[f])];
    emitted += area * scene.material_of(patch).emission.mean();
    radiated += area * solution.face_radiosity[f].mean();
  }
  j["energy"] = {{"emitted_power", emitted}, {"radiosity_power", radiated}};

  json patches = json::array();
  const std::vector<Rgb> radiosity = face_radiosity(scene, solution);
  for (std::size_t i = 0; i < scene.faces.size(); ++i) {
    const InputFace& face = scene.faces[i];
    const Material& m = scene.materials[static_cast<std::size_t>(face.material)];
    patches.push_back({{"face", i},
                       {"line", face.line},
                       {"group", face.group},
                       {"material", m.name},
                       {"area", face.area},
                       {"emission", rgb(m.emission)},
                       {"reflectance", rgb(m.reflectance)},
                       {"radiosity", rgb(radiosity[i])}});
  }
  j["patches"] = patches;
  return j;
}

nlohmann::json power_balance_json(const PowerBalance& b) {
  return {{"emitted", b.emitted.mean()},
          {"absorbed_reflecting", b.absorbed_reflecting.mean()},
          {"absorbed_black", b.absorbed_black.mean()},
          {"onto_backs", b.onto_backs.mean()},
          {"escaped", b.escaped.mean()},
          {"sampled_se", b.sampled_se.mean()},
          {"residual", b.residual.mean()},
          {"relative_residual", b.relative_residual()},
          {"allowed", b.allowed()},
          {"balanced", b.balanced()},
          {"rays", b.rays}};
}

void write_json_file(const std::string& path, const nlohmann::json& report) {
  write_file_atomically(path, [&](std::ostream& out) { out << report.dump(2) << "\n"; });
}

}  // namespace hrad
