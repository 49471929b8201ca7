#include "hrad/reference/power_balance.h"

#include <algorithm>
#include <cmath>

#include "hrad/core/rng.h"
#include "hrad/geometry/patch_plane.h"
#include "hrad/geometry/polygon.h"
#include "hrad/reference/embree_scene.h"
#include "hrad/reference/path_tracer.h"
#include "hrad/reference/running_stats.h"

namespace hrad {

double PowerBalance::relative_residual() const {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    if (emitted[c] > 0.0) worst = std::max(worst, std::abs(residual[c]) / emitted[c]);
  return worst;
}

double PowerBalance::allowed() const {
  double worst = -1.0, allowance = kPowerBalanceTolerance;
  for (int c = 0; c < 3; ++c)
    if (emitted[c] > 0.0 && std::abs(residual[c]) / emitted[c] > worst) {
      worst = std::abs(residual[c]) / emitted[c];
      allowance = kPowerBalanceTolerance + kPowerBalanceStandardErrors * sampled_se[c] / emitted[c];
    }
  return allowance;
}

PowerBalance power_balance(const Scene& scene, const Solution& solution, const PowerBalanceOptions& options) {
  PowerBalance out;
  for (const Patch& p : scene.patches) out.emitted += p.area * scene.material_of(p).emission;

  // The leaves' fans of triangles, each weighted by its area times the leaf's mean radiosity.
  struct Triangle {
    Vec3 a, ab, ac;
    int leaf;
  };
  std::vector<Triangle> triangles;
  std::vector<double> cdf;
  double total = 0.0;
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    const Patch& patch = scene.patches[static_cast<std::size_t>(solution.face_patch[f])];
    const Material& m = scene.material_of(patch);
    const Rgb& b = solution.face_radiosity[f];
    const std::vector<int>& face = solution.faces[f];
    double area = 0.0;
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3& a = solution.vertices[static_cast<std::size_t>(face[0])];
      const Vec3 ab = solution.vertices[static_cast<std::size_t>(face[k])] - a;
      const Vec3 ac = solution.vertices[static_cast<std::size_t>(face[k + 1])] - a;
      const double t = 0.5 * ab.cross(ac).dot(patch.normal);
      area += t;
      if (b.mean() > 0.0 && t > 0.0) {
        total += t * b.mean();
        triangles.push_back({a, ab, ac, static_cast<int>(f)});
        cdf.push_back(total);
      }
    }
    out.leaving += area * b;
    for (int c = 0; c < 3; ++c)
      if (m.reflectance[c] > 0.0)
        out.absorbed_reflecting[c] += area * (1.0 - m.reflectance[c]) / m.reflectance[c] * (b[c] - m.emission[c]);
  }

  if (options.rays > 0 && total > 0.0) {
    const EmbreeScene rays(scene);
    RayCounts counts;
    detail::Rng rng(options.seed);
    detail::RunningStats black, backs, escaped, lost;
    for (int i = 0; i < options.rays; ++i) {
      const double u = rng.uniform() * total;
      const std::size_t k = std::min<std::size_t>(
          static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()), cdf.size() - 1);
      const Triangle& t = triangles[k];
      double s = rng.uniform(), r = rng.uniform();
      if (s + r > 1.0) {
        s = 1.0 - s;
        r = 1.0 - r;
      }
      const auto leaf = static_cast<std::size_t>(t.leaf);
      const Patch& patch = scene.patches[static_cast<std::size_t>(solution.face_patch[leaf])];
      const Vec3& n = patch.normal;
      // Onto the patch's plane, which is the ray caster's (embree_scene.h): a patch's vertices may
      // lie off it by the rounding of the input file.
      Vec3 x = t.a + s * t.ab + r * t.ac;
      x -= n * (n.dot(x) - detail::plane_offset(patch));
      const Rgb weight = total * solution.face_radiosity[leaf] / solution.face_radiosity[leaf].mean();
      const RayHit hit = rays.closest_hit(x, detail::cosine_direction(n, rng), counts);
      Rgb to_black = Rgb::Zero(), to_back = Rgb::Zero(), away = Rgb::Zero();
      if (hit.patch < 0) {
        away = weight;
      } else if (!hit.front) {
        to_back = weight;
      } else {
        const Rgb& rho = scene.material_of(scene.patches[static_cast<std::size_t>(hit.patch)]).reflectance;
        for (int c = 0; c < 3; ++c) to_black[c] = rho[c] > 0.0 ? 0.0 : weight[c];
      }
      black.add(to_black);
      backs.add(to_back);
      escaped.add(away);
      lost.add(to_black + to_back + away);
    }
    out.absorbed_black = black.mean;
    out.onto_backs = backs.mean;
    out.escaped = escaped.mean;
    out.sampled_se = lost.standard_error();
    out.rays = counts.total();
  }
  out.residual = out.emitted - out.absorbed_reflecting - out.absorbed_black - out.onto_backs - out.escaped;
  return out;
}

}  // namespace hrad
