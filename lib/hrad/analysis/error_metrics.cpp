#include "hrad/analysis/error_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hrad/render/face_geometry.h"

namespace hrad {
namespace {

double ratio(double num, double den) {
  if (den > 0.0) return num / den;
  return num > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

void sample_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int m, int patch, std::vector<SurfaceSample>* out) {
  const double area = 0.5 * (b - a).cross(c - a).norm() / (static_cast<double>(m) * m);
  auto grid = [&](int i, int j) { return Vec3(a + (static_cast<double>(i) / m) * (b - a) + (static_cast<double>(j) / m) * (c - a)); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i + j < m; ++i) {
      out->push_back({(grid(i, j) + grid(i + 1, j) + grid(i, j + 1)) / 3.0, area, patch});
      if (i + j + 2 <= m) out->push_back({(grid(i + 1, j) + grid(i + 1, j + 1) + grid(i, j + 1)) / 3.0, area, patch});
    }
}

}  // namespace

std::vector<SurfaceSample> patch_samples(const Scene& scene, int samples_per_patch) {
  const int m = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples_per_patch)))));
  std::vector<SurfaceSample> out;
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const std::vector<Vec3>& v = scene.patches[p].vertices;
    const int patch = static_cast<int>(p);
    if (v.size() == 4) {
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const double u = (i + 0.5) / m, w = (j + 0.5) / m;
          const Vec3 x = (1 - u) * (1 - w) * v[0] + u * (1 - w) * v[1] + u * w * v[2] + (1 - u) * w * v[3];
          const Vec3 xu = (1 - w) * (v[1] - v[0]) + w * (v[2] - v[3]);
          const Vec3 xv = (1 - u) * (v[3] - v[0]) + u * (v[2] - v[1]);
          out.push_back({x, xu.cross(xv).norm() / (static_cast<double>(m) * m), patch});
        }
    } else {
      for (std::size_t k = 1; k + 1 < v.size(); ++k) sample_triangle(v[0], v[k], v[k + 1], m, patch, &out);
    }
  }
  return out;
}

SolutionSampler::SolutionSampler(const Scene& scene, const Solution& solution)
    : scene_(scene), solution_(solution), leaves_of_patch_(scene.patches.size()) {
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    const int p = solution.face_patch[f];
    if (p >= 0 && static_cast<std::size_t>(p) < leaves_of_patch_.size()) leaves_of_patch_[p].push_back(static_cast<int>(f));
  }
}

int SolutionSampler::leaf_at(const Vec3& x, int patch, bool* matched) const {
  const Patch& P = scene_.patches[patch];
  double size = 0.0;
  for (const Vec3& v : P.vertices) size = std::max(size, (v - P.vertices[0]).norm());
  const double tol = 1e-6 * size;
  int best = -1;
  double best_inside = -std::numeric_limits<double>::infinity();
  for (int f : leaves_of_patch_[patch]) {
    const std::vector<int>& face = solution_.faces[f];
    double inside = std::numeric_limits<double>::infinity();  // min signed distance to the edges' lines
    for (std::size_t i = 0; i < face.size() && inside > best_inside; ++i) {
      const Vec3& a = solution_.vertices[face[i]];
      const Vec3 e = solution_.vertices[face[(i + 1) % face.size()]] - a;
      const double len = e.norm();
      if (len == 0.0) continue;
      inside = std::min(inside, e.cross(x - a).dot(P.normal) / len);
    }
    if (inside >= -tol) {
      if (matched) *matched = true;
      return f;
    }
    if (inside > best_inside) {
      best_inside = inside;
      best = f;
    }
  }
  if (matched) *matched = false;
  return best;
}

Rgb SolutionSampler::value_at(const Vec3& x, int patch, bool* matched) const {
  const int f = leaf_at(x, patch, matched);
  return f < 0 ? Rgb::Zero() : solution_.face_radiosity[f];
}

ErrorMetrics compare_to_function(const Scene& scene, const Solution& solution,
                                 const std::function<Rgb(const Vec3&, int)>& reference, int samples_per_patch) {
  const std::vector<SurfaceSample> samples = patch_samples(scene, samples_per_patch);
  const SolutionSampler sampler(scene, solution);
  ErrorMetrics m;
  m.samples = samples.size();
  std::vector<double> patch_err(scene.patches.size(), 0.0), patch_ref(scene.patches.size(), 0.0);
  std::vector<double> face_err(solution.faces.size(), 0.0), face_ref(solution.faces.size(), 0.0);
  std::vector<bool> face_hit(solution.faces.size(), false);
  double err = 0.0, ref = 0.0, area = 0.0, max_err = 0.0, max_ref = 0.0;
  for (const SurfaceSample& s : samples) {
    bool matched = true;
    const int f = sampler.leaf_at(s.position, s.patch, &matched);
    if (!matched) ++m.unmatched;
    const Rgb b = f < 0 ? Rgb::Zero() : solution.face_radiosity[f];
    const Rgb r = reference(s.position, s.patch);
    const double e2 = (b - r).matrix().squaredNorm(), r2 = r.matrix().squaredNorm();
    err += s.area * e2;
    ref += s.area * r2;
    area += s.area;
    max_err = std::max(max_err, std::sqrt(e2));
    max_ref = std::max(max_ref, std::sqrt(r2));
    patch_err[s.patch] += s.area * e2;
    patch_ref[s.patch] += s.area * r2;
    if (f >= 0) {
      face_err[f] += s.area * e2;
      face_ref[f] += s.area * r2;
      face_hit[f] = true;
    }
  }
  m.relative_l2 = std::sqrt(ratio(err, ref));
  m.relative_linf = ratio(max_err, max_ref);
  m.rms_absolute = area > 0.0 ? std::sqrt(err / area) : 0.0;
  m.patch_relative_l2.resize(scene.patches.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p) m.patch_relative_l2[p] = std::sqrt(ratio(patch_err[p], patch_ref[p]));
  m.face_relative_l2.resize(solution.faces.size());
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    if (!face_hit[f]) {  // a leaf smaller than the sample spacing: compare at its centroid
      const Rgb r = reference(face_centroid(solution, f), solution.face_patch[f]);
      face_err[f] = (solution.face_radiosity[f] - r).matrix().squaredNorm();
      face_ref[f] = r.matrix().squaredNorm();
    }
    m.face_relative_l2[f] = std::sqrt(ratio(face_err[f], face_ref[f]));
  }
  return m;
}

ErrorMetrics compare_solutions(const Scene& scene, const Solution& solution, const Solution& reference,
                               int samples_per_patch) {
  const SolutionSampler ref_sampler(scene, reference);
  std::size_t ref_unmatched = 0;
  ErrorMetrics m = compare_to_function(
      scene, solution,
      [&](const Vec3& x, int patch) {
        bool matched = true;
        const Rgb r = ref_sampler.value_at(x, patch, &matched);
        if (!matched) ++ref_unmatched;
        return r;
      },
      samples_per_patch);
  m.unmatched += ref_unmatched;
  return m;
}

EnergyBalance energy_balance(const Scene& scene, const Solution& solution) {
  EnergyBalance e;
  for (const Patch& p : scene.patches) e.emitted_power += p.area * scene.material_of(p).emission;
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    const Material& mat = scene.material_of(scene.patches[solution.face_patch[f]]);
    const double a = face_area(solution, f);
    const Rgb& b = solution.face_radiosity[f];
    e.radiosity_power += a * b;
    for (int c = 0; c < 3; ++c) {
      const double rho = mat.reflectance[c];
      e.absorbed_power[c] += rho > 0.0 ? a * (1.0 - rho) / rho * (b[c] - mat.emission[c])
                                       : std::numeric_limits<double>::quiet_NaN();
    }
  }
  for (int c = 0; c < 3; ++c)
    e.closed_scene_residual[c] = e.emitted_power[c] > 0.0
                                     ? std::abs(e.emitted_power[c] - e.absorbed_power[c]) / e.emitted_power[c]
                                     : std::numeric_limits<double>::quiet_NaN();
  return e;
}

}  // namespace hrad
