#include "hrad/analysis/error_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "hrad/core/face_geometry.h"
#include "hrad/core/rng.h"

namespace hrad {
namespace {

double ratio(double num, double den) {
  if (den > 0.0) return num / den;
  return num > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

// The point of stratum `stratum` of patch `patch`: its centre, or a uniform point in it drawn from
// a stream fixed by (patch, stratum).
Vec2 stratum_point(SampleLayout layout, int patch, std::uint64_t stratum) {
  if (layout == SampleLayout::centres) return Vec2(0.5, 0.5);
  detail::Rng rng((static_cast<std::uint64_t>(patch) << 32) ^ (stratum * 0x9e3779b97f4a7c15ULL));
  const double a = rng.uniform();
  return Vec2(a, rng.uniform());
}

void sample_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int m, int patch, SampleLayout layout,
                     std::size_t first, std::vector<SurfaceSample>* out) {
  const double area = 0.5 * (b - a).cross(c - a).norm() / (static_cast<double>(m) * m);
  auto grid = [&](int i, int j) {
    return Vec3(a + (static_cast<double>(i) / m) * (b - a) + (static_cast<double>(j) / m) * (c - a));
  };
  // A point of triangle (p, q, r): its centroid, or a uniform one (Turk 1990's square-root map).
  auto point = [&](const Vec3& p, const Vec3& q, const Vec3& r) {
    if (layout == SampleLayout::centres) return Vec3((p + q + r) / 3.0);
    const Vec2 st = stratum_point(layout, patch, out->size() - first);
    const double su = std::sqrt(st.x());
    return Vec3((1.0 - su) * p + su * (1.0 - st.y()) * q + su * st.y() * r);
  };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i + j < m; ++i) {
      out->push_back({point(grid(i, j), grid(i + 1, j), grid(i, j + 1)), area, patch});
      if (i + j + 2 <= m) out->push_back({point(grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1)), area, patch});
    }
}

}  // namespace

std::vector<SurfaceSample> patch_samples(const Scene& scene, int samples_per_patch, SampleLayout layout) {
  const int m = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples_per_patch)))));
  std::vector<SurfaceSample> out;
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const std::vector<Vec3>& v = scene.patches[p].vertices;
    const int patch = static_cast<int>(p);
    if (v.size() == 4) {
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          // The weight is the cell's area: the Jacobian at its centre (linear in u and v).
          const double uc = (i + 0.5) / m, wc = (j + 0.5) / m;
          const Vec3 xu = (1 - wc) * (v[1] - v[0]) + wc * (v[2] - v[3]);
          const Vec3 xv = (1 - uc) * (v[3] - v[0]) + uc * (v[2] - v[1]);
          const Vec2 st = stratum_point(layout, patch, static_cast<std::uint64_t>(j) * m + i);
          const double u = (i + st.x()) / m, w = (j + st.y()) / m;
          const Vec3 x = (1 - u) * (1 - w) * v[0] + u * (1 - w) * v[1] + u * w * v[2] + (1 - u) * w * v[3];
          out.push_back({x, xu.cross(xv).norm() / (static_cast<double>(m) * m), patch});
        }
    } else {
      const std::size_t first = out.size();
      for (std::size_t k = 1; k + 1 < v.size(); ++k)
        sample_triangle(v[0], v[k], v[k + 1], m, patch, layout, first, &out);
    }
  }
  return out;
}

SolutionSampler::SolutionSampler(const Scene& scene, const Solution& solution)
    : scene_(scene), solution_(solution), index_(scene.patches.size()) {
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    const int p = solution.face_patch[f];
    if (p >= 0 && static_cast<std::size_t>(p) < index_.size()) index_[p].leaves.push_back(static_cast<int>(f));
  }
  for (std::size_t p = 0; p < index_.size(); ++p) {
    const Patch& patch = scene.patches[p];
    PatchIndex& ix = index_[p];
    ix.origin = patch.vertices[0];
    ix.u = (patch.vertices[1] - patch.vertices[0]).normalized();
    ix.v = patch.normal.cross(ix.u);
    double size = 0.0;
    for (const Vec3& x : patch.vertices) size = std::max(size, (x - patch.vertices[0]).norm());
    ix.tolerance = 1e-6 * size;
    auto plane = [&](const Vec3& x) { return Vec2((x - ix.origin).dot(ix.u), (x - ix.origin).dot(ix.v)); };
    std::vector<std::pair<Vec2, Vec2>> boxes;
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int f : ix.leaves) {
      Vec2 blo = Vec2::Constant(std::numeric_limits<double>::infinity()), bhi = -blo;
      for (int vid : solution.faces[f]) {
        const Vec2 q = plane(solution.vertices[vid]);
        blo = blo.cwiseMin(q);
        bhi = bhi.cwiseMax(q);
      }
      boxes.emplace_back(blo.array() - ix.tolerance, bhi.array() + ix.tolerance);
      lo = lo.cwiseMin(boxes.back().first);
      hi = hi.cwiseMax(boxes.back().second);
    }
    if (ix.leaves.empty()) continue;
    ix.nu = ix.nv = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(ix.leaves.size()))));
    ix.lo = lo;
    ix.cell = Vec2(std::max((hi - lo).x(), 1e-300) / ix.nu, std::max((hi - lo).y(), 1e-300) / ix.nv);
    ix.buckets.assign(static_cast<std::size_t>(ix.nu) * ix.nv, {});
    for (std::size_t k = 0; k < ix.leaves.size(); ++k) {
      const int u0 = std::clamp(static_cast<int>((boxes[k].first.x() - lo.x()) / ix.cell.x()), 0, ix.nu - 1);
      const int u1 = std::clamp(static_cast<int>((boxes[k].second.x() - lo.x()) / ix.cell.x()), 0, ix.nu - 1);
      const int v0 = std::clamp(static_cast<int>((boxes[k].first.y() - lo.y()) / ix.cell.y()), 0, ix.nv - 1);
      const int v1 = std::clamp(static_cast<int>((boxes[k].second.y() - lo.y()) / ix.cell.y()), 0, ix.nv - 1);
      for (int j = v0; j <= v1; ++j)
        for (int i = u0; i <= u1; ++i) ix.buckets[static_cast<std::size_t>(j) * ix.nu + i].push_back(ix.leaves[k]);
    }
  }
}

int SolutionSampler::leaf_at(const Vec3& x, int patch, bool* matched) const {
  const PatchIndex& ix = index_[patch];
  const Vec3& normal = scene_.patches[patch].normal;
  // Smallest signed distance from x to the lines of leaf f's edges (positive inside, CCW);
  // stops early once below `floor`.
  auto insideness = [&](int f, double floor) {
    const std::vector<int>& face = solution_.faces[f];
    double inside = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < face.size() && inside > floor; ++i) {
      const Vec3& a = solution_.vertices[face[i]];
      const Vec3 e = solution_.vertices[face[(i + 1) % face.size()]] - a;
      const double len = e.norm();
      if (len == 0.0) continue;
      inside = std::min(inside, e.cross(x - a).dot(normal) / len);
    }
    return inside;
  };
  if (!ix.buckets.empty()) {
    const Vec2 q((x - ix.origin).dot(ix.u), (x - ix.origin).dot(ix.v));
    const int i = static_cast<int>(std::floor((q.x() - ix.lo.x()) / ix.cell.x()));
    const int j = static_cast<int>(std::floor((q.y() - ix.lo.y()) / ix.cell.y()));
    if (i >= 0 && j >= 0 && i < ix.nu && j < ix.nv)
      for (int f : ix.buckets[static_cast<std::size_t>(j) * ix.nu + i])
        if (insideness(f, -ix.tolerance) >= -ix.tolerance) {
          if (matched) *matched = true;
          return f;
        }
  }
  // No leaf contains x: the one whose edges it violates least.
  int best = -1;
  double best_inside = -std::numeric_limits<double>::infinity();
  for (int f : ix.leaves) {
    const double inside = insideness(f, best_inside);
    if (inside > best_inside) {
      best_inside = inside;
      best = f;
    }
  }
  if (matched) *matched = best >= 0 && best_inside >= -ix.tolerance;
  return best;
}

Rgb SolutionSampler::value_at(const Vec3& x, int patch, bool* matched, Field field) const {
  const int f = leaf_at(x, patch, matched);
  if (f < 0) return Rgb::Zero();
  return field == Field::constant ? element(f, x) : interpolated(f, x);
}

Rgb SolutionSampler::element(int face, const Vec3& x) const {
  if (solution_.face_field.empty()) return solution_.face_radiosity[face];
  return element_field_at(solution_.face_field[static_cast<std::size_t>(face)], x);
}

Rgb SolutionSampler::interpolated(int face, const Vec3& x) const {
  const std::vector<int>& ids = solution_.faces[face];
  const Vec3& normal = scene_.patches[solution_.face_patch[face]].normal;
  // The fan triangle (v0, vk, vk+1) whose smallest barycentric coordinate at x is largest: the
  // one containing x, or the nearest for a point just outside the leaf.
  const Vec3& a = solution_.vertices[ids[0]];
  double best_min = -std::numeric_limits<double>::infinity();
  Rgb best = solution_.face_radiosity[face];
  for (std::size_t k = 1; k + 1 < ids.size(); ++k) {
    const Vec3& b = solution_.vertices[ids[k]];
    const Vec3& c = solution_.vertices[ids[k + 1]];
    const double twice_area = (b - a).cross(c - a).dot(normal);
    if (!(twice_area > 0.0)) continue;  // a degenerate fan triangle (collinear T-vertices)
    const double wa = (b - x).cross(c - x).dot(normal) / twice_area;
    const double wb = (c - x).cross(a - x).dot(normal) / twice_area;
    const double wc = 1.0 - wa - wb;
    const double smallest = std::min({wa, wb, wc});
    if (smallest <= best_min) continue;
    best_min = smallest;
    best = wa * solution_.vertex_radiosity[ids[0]] + wb * solution_.vertex_radiosity[ids[k]] +
           wc * solution_.vertex_radiosity[ids[k + 1]];
  }
  return best;
}

ErrorMetrics compare_to_function(const Scene& scene, const Solution& solution,
                                 const std::function<Rgb(const Vec3&, int)>& reference, int samples_per_patch,
                                 Emitters emitters, Field field, SampleLayout layout) {
  auto skipped = [&](int patch) {
    return emitters == Emitters::exclude && scene.material_of(scene.patches[patch]).is_emitter();
  };
  std::vector<SurfaceSample> samples = patch_samples(scene, samples_per_patch, layout);
  std::erase_if(samples, [&](const SurfaceSample& s) { return skipped(s.patch); });
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
    const Rgb b = f < 0                      ? Rgb::Zero()
                  : field == Field::constant ? sampler.element(f, s.position)
                                             : sampler.interpolated(f, s.position);
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
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t p = 0; p < scene.patches.size(); ++p)
    m.patch_relative_l2[p] = skipped(static_cast<int>(p)) ? nan : std::sqrt(ratio(patch_err[p], patch_ref[p]));
  m.face_relative_l2.resize(solution.faces.size());
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    if (skipped(solution.face_patch[f])) {
      m.face_relative_l2[f] = nan;
      continue;
    }
    if (!face_hit[f]) {  // a leaf smaller than the sample spacing: compare at its centroid
      const Rgb r = reference(face_centroid(solution, f), solution.face_patch[f]);
      face_err[f] = (solution.face_radiosity[f] - r).matrix().squaredNorm();
      face_ref[f] = r.matrix().squaredNorm();
    }
    m.face_relative_l2[f] = std::sqrt(ratio(face_err[f], face_ref[f]));
  }
  return m;
}

ErrorMetrics compare_at_samples(const Scene& scene, std::span<const SurfaceSample> samples, std::span<const Rgb> values,
                                std::span<const Rgb> reference) {
  if (values.size() != samples.size() || reference.size() != samples.size())
    throw std::invalid_argument("compare_at_samples: the values and the reference must have one entry per sample");
  ErrorMetrics m;
  m.samples = samples.size();
  std::vector<double> patch_err(scene.patches.size(), 0.0), patch_ref(scene.patches.size(), 0.0);
  double err = 0.0, ref = 0.0, area = 0.0, max_err = 0.0, max_ref = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const SurfaceSample& s = samples[k];
    const double e2 = (values[k] - reference[k]).matrix().squaredNorm(), r2 = reference[k].matrix().squaredNorm();
    err += s.area * e2;
    ref += s.area * r2;
    area += s.area;
    max_err = std::max(max_err, std::sqrt(e2));
    max_ref = std::max(max_ref, std::sqrt(r2));
    patch_err[static_cast<std::size_t>(s.patch)] += s.area * e2;
    patch_ref[static_cast<std::size_t>(s.patch)] += s.area * r2;
  }
  m.relative_l2 = std::sqrt(ratio(err, ref));
  m.relative_linf = ratio(max_err, max_ref);
  m.rms_absolute = area > 0.0 ? std::sqrt(err / area) : 0.0;
  m.patch_relative_l2.resize(scene.patches.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p)
    m.patch_relative_l2[p] = std::sqrt(ratio(patch_err[p], patch_ref[p]));
  return m;
}

ErrorMetrics compare_solutions(const Scene& scene, const Solution& solution, const Solution& reference,
                               int samples_per_patch, Emitters emitters, Field field, SampleLayout layout) {
  const SolutionSampler ref_sampler(scene, reference);
  std::size_t ref_unmatched = 0;
  ErrorMetrics m = compare_to_function(
      scene, solution,
      [&](const Vec3& x, int patch) {
        bool matched = true;
        const Rgb r = ref_sampler.value_at(x, patch, &matched, field);
        if (!matched) ++ref_unmatched;
        return r;
      },
      samples_per_patch, emitters, field, layout);
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
      e.absorbed_power[c] +=
          rho > 0.0 ? a * (1.0 - rho) / rho * (b[c] - mat.emission[c]) : std::numeric_limits<double>::quiet_NaN();
    }
  }
  for (int c = 0; c < 3; ++c)
    e.closed_scene_residual[c] = e.emitted_power[c] > 0.0
                                     ? std::abs(e.emitted_power[c] - e.absorbed_power[c]) / e.emitted_power[c]
                                     : std::numeric_limits<double>::quiet_NaN();
  return e;
}

}  // namespace hrad
