#include "hrad/core/solution.h"

#include <cmath>

#include <Eigen/Dense>

#include "hrad/core/scene.h"

namespace hrad {

Rgb element_field_at(const ElementField& e, const Vec3& x) {
  if (e.corners == 3) {
    // Barycentric coordinates by areas in the triangle's plane (signed, so a point just outside
    // extrapolates the same linear function).
    const Vec3 n = (e.x[1] - e.x[0]).cross(e.x[2] - e.x[0]);
    const double a = n.squaredNorm();
    if (!(a > 0.0)) return (e.radiosity[0] + e.radiosity[1] + e.radiosity[2]) / 3.0;
    const double l1 = n.dot((x - e.x[0]).cross(e.x[2] - e.x[0])) / a;
    const double l2 = n.dot((e.x[1] - e.x[0]).cross(x - e.x[0])) / a;
    return (1.0 - l1 - l2) * e.radiosity[0] + l1 * e.radiosity[1] + l2 * e.radiosity[2];
  }
  // Newton's method on x(u, v) - x = 0, projected on the element's tangent vectors: a convex
  // planar quad's bilinear map is one-to-one, and the iteration from the centre converges in a few
  // steps.
  double u = 0.5, v = 0.5;
  for (int it = 0; it < 20; ++it) {
    const Vec3 p = (1 - u) * (1 - v) * e.x[0] + u * (1 - v) * e.x[1] + u * v * e.x[2] + (1 - u) * v * e.x[3];
    const Vec3 xu = (1 - v) * (e.x[1] - e.x[0]) + v * (e.x[2] - e.x[3]);
    const Vec3 xv = (1 - u) * (e.x[3] - e.x[0]) + u * (e.x[2] - e.x[1]);
    Eigen::Matrix2d j;
    j << xu.dot(xu), xu.dot(xv), xv.dot(xu), xv.dot(xv);
    const Vec3 r = x - p;
    const Eigen::Vector2d step = j.ldlt().solve(Eigen::Vector2d(xu.dot(r), xv.dot(r)));
    if (!step.allFinite()) break;
    u += step[0];
    v += step[1];
    if (std::abs(step[0]) + std::abs(step[1]) < 1e-14) break;
  }
  return (1 - u) * (1 - v) * e.radiosity[0] + u * (1 - v) * e.radiosity[1] + u * v * e.radiosity[2] +
         (1 - u) * v * e.radiosity[3];
}

std::vector<Rgb> face_radiosity(const Scene& scene, const Solution& solution) {
  std::vector<Rgb> out;
  out.reserve(scene.faces.size());
  for (const InputFace& face : scene.faces) {
    Rgb sum = Rgb::Zero();
    double area = 0.0;
    for (const int p : face.patches) {
      const double a = scene.patches[static_cast<std::size_t>(p)].area;
      if (static_cast<std::size_t>(p) < solution.patch_radiosity.size())
        sum += a * solution.patch_radiosity[static_cast<std::size_t>(p)];
      area += a;
    }
    out.push_back(area > 0.0 ? Rgb(sum / area) : Rgb::Zero());
  }
  return out;
}

}  // namespace hrad
