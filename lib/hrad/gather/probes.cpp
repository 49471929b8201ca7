#include "hrad/gather/probes.h"

#include "hrad/geometry/front_patch.h"
#include "hrad/geometry/patch_plane.h"

namespace hrad {

std::vector<ProbeValue> gather_probes(const FinalGather& gather, std::span<const ProbePoint> points,
                                      ProgressReporter* progress) {
  const Scene& scene = gather.scene();
  const double tolerance = probe_tolerance(scene);
  std::vector<GatherPoint> at(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    GatherPoint& g = at[i];
    g.position = points[i].position;
    g.normal = points[i].normal.normalized();
    g.patch = front_patch_at(scene, g.position, g.normal, tolerance);
    if (g.patch >= 0) {
      const Patch& p = scene.patches[static_cast<std::size_t>(g.patch)];
      g.position -= p.normal * (p.normal.dot(g.position) - detail::plane_offset(p));
      g.normal = p.normal;
    }
  }
  const std::vector<Rgb> h = gather.gather(at, progress);
  std::vector<ProbeValue> values(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    values[i].patch = at[i].patch;
    values[i].irradiance = h[i];
    if (at[i].patch >= 0) values[i].radiosity = gather.radiosity(at[i].patch, h[i]);
  }
  return values;
}

std::vector<ProbePoint> grid_points(const ProbeGrid& g) {
  const int a = g.axis, u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
  Vec3 normal = Vec3::Zero();
  normal[a] = g.facing_positive ? 1.0 : -1.0;
  std::vector<ProbePoint> points;
  points.reserve(static_cast<std::size_t>(g.nu) * static_cast<std::size_t>(g.nv));
  for (int j = 0; j < g.nv; ++j)
    for (int i = 0; i < g.nu; ++i) {
      ProbePoint p;
      p.position[a] = g.height;
      p.position[u] = g.u0 + (i + 0.5) * (g.u1 - g.u0) / g.nu;
      p.position[v] = g.v0 + (j + 0.5) * (g.v1 - g.v0) / g.nv;
      p.normal = normal;
      points.push_back(p);
    }
  return points;
}

}  // namespace hrad
