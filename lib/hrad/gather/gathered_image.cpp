#include "hrad/gather/gathered_image.h"

#include <vector>

#include "hrad/core/stopwatch.h"
#include "hrad/render/rasterizer.h"

namespace hrad {

GatheredImage render_gathered(const Solution& s, const FinalGather& gather, const RenderOptions& o) {
  const Stopwatch total;
  const Scene& scene = gather.scene();
  const int passes = std::max(1, o.samples_per_pixel);
  const Camera& camera = o.camera;
  // The visible leaf at every sample of every pass, then one gather over all of them.
  struct Hit {
    int x, y;
  };
  std::vector<Hit> hits;
  std::vector<GatherPoint> points;
  std::vector<Vec3> leaf;
  std::vector<Rgb> zero;
  for (int pass = 0; pass < passes; ++pass) {
    Rasterizer r(camera, 0.0, o.samples_per_pixel > 1 ? pass : -1, passes, o.seed);
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      if (o.cull_back_faces && !faces_camera(s, f, camera)) continue;
      leaf.clear();
      for (int v : s.faces[f]) leaf.push_back(s.vertices[static_cast<std::size_t>(v)]);
      zero.assign(leaf.size(), Rgb::Zero());
      r.fill_polygon(leaf, zero, static_cast<int>(f));
    }
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const int f = r.id(x, y);
        if (f < 0) continue;
        const int patch = s.face_patch[static_cast<std::size_t>(f)];
        const Patch& p = scene.patches[static_cast<std::size_t>(patch)];
        // The sample's ray meets the leaf's plane (the patch's) at the point it sees.
        const Vec2 at = r.sample_position(x, y);
        const Vec3 d = pixel_direction(camera, at.x(), at.y());
        const Vec3& v0 = s.vertices[static_cast<std::size_t>(s.faces[static_cast<std::size_t>(f)][0])];
        const double t = p.normal.dot(v0 - camera.position) / p.normal.dot(d);
        hits.push_back({x, y});
        points.push_back({camera.position + t * d, p.normal, patch});
      }
  }
  const GatherWork before = gather.work();
  const Stopwatch gathering;
  ProgressReporter progress("final gather", points.size(), "points", o.progress);
  const std::vector<Rgb> h = gather.gather(points, &progress);
  progress.finish();
  GatheredImage out;
  out.gather_seconds = gathering.seconds();
  out.work = gather.work() - before;
  PixelAverager average(camera.width, camera.height, passes, o.exposure, o.background);
  for (std::size_t i = 0; i < points.size(); ++i)
    average.add(hits[i].x, hits[i].y, gather.radiosity(points[i].patch, h[i]));
  out.display = average.display();
  out.radiosity = average.linear();
  out.points = points.size();
  out.seconds = total.seconds();
  return out;
}

}  // namespace hrad
