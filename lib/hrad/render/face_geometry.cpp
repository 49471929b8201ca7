#include "hrad/render/face_geometry.h"

namespace hrad {

Vec3 face_vector_area(const Solution& solution, std::size_t f) {
  const std::vector<int>& face = solution.faces[f];
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 0; i < face.size(); ++i) {
    const Vec3& a = solution.vertices[face[i]];
    const Vec3& b = solution.vertices[face[(i + 1) % face.size()]];
    sum += a.cross(b);
  }
  return 0.5 * sum;
}

Vec3 face_centroid(const Solution& solution, std::size_t f) {
  const std::vector<int>& face = solution.faces[f];
  Vec3 sum = Vec3::Zero();
  for (int v : face) sum += solution.vertices[v];
  return face.empty() ? sum : Vec3(sum / static_cast<double>(face.size()));
}

}  // namespace hrad
