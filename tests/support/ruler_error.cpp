#include "support/ruler_error.h"

#include "hrad/core/error.h"

#include <cmath>

namespace hrad::test {

FaceErrors errors_against_ruler(const Scene& scene, const Solution& solution, const std::vector<FaceEstimate>& ruler) {
  if (ruler.size() != scene.faces.size()) throw Error("the ruler has an estimate per face of another scene");
  const std::vector<Rgb> b = face_radiosity(scene, solution);
  std::vector<FaceValues> faces;
  faces.reserve(scene.faces.size());
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    const Rgb e = scene.materials[static_cast<std::size_t>(scene.faces[f].material)].emission;
    faces.push_back({scene.faces[f].area, b[f] - e, ruler[f].radiosity - e, ruler[f].radiosity_se, ""});
  }
  return face_errors(faces);
}

FaceErrors solve_against_ruler(const Scene& scene, const std::vector<FaceEstimate>& ruler, SolveOptions options) {
  options.method = Method::kHierarchical;
  options.threads = 2;
  Solution solution;
  const SolveSummary summary = solve(scene, options, &solution);
  if (summary.termination != Termination::kConverged) throw Error("the solve did not converge: " + summary.message);
  return errors_against_ruler(scene, solution, ruler);
}

std::pair<double, double> ruler_mean(const Scene& scene, const std::vector<ProbePoint>& points, int patch,
                                     int samples) {
  ReferenceOptions o;
  o.samples = samples;
  std::vector<PointEstimate> out;
  reference_points(scene, points, o, &out);
  double mean = 0.0, variance = 0.0;
  const double n = static_cast<double>(out.size());
  for (const PointEstimate& e : out) {
    if (e.patch != patch) throw Error("ruler_mean: a point lies off the patch it is to measure");
    mean += e.radiosity[0] / n;
    variance += e.radiosity_se[0] * e.radiosity_se[0] / (n * n);
  }
  return {mean, std::sqrt(variance)};
}

}  // namespace hrad::test
