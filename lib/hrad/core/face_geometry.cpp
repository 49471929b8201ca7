#include "hrad/core/face_geometry.h"

namespace hrad {

Vec3 face_vector_area(const Solution& solution, std::size_t f) {
  // Relative to the first vertex: the same sum (translation-invariant for a closed polygon), without
  // the cancellation of absolute positions (a 1e-6 element 1 km from the origin came out 100x too big).
  const std::vector<int>& face = solution.faces[f];
  Vec3 sum = Vec3::Zero();
  if (face.empty()) return sum;
  const Vec3& origin = solution.vertices[face[0]];
  for (std::size_t i = 1; i + 1 < face.size(); ++i)
    sum += (solution.vertices[face[i]] - origin).cross(solution.vertices[face[i + 1]] - origin);
  return 0.5 * sum;
}

Vec3 face_centroid(const Solution& solution, std::size_t f) {
  const std::vector<int>& face = solution.faces[f];
  Vec3 sum = Vec3::Zero();
  for (int v : face) sum += solution.vertices[v];
  return face.empty() ? sum : Vec3(sum / static_cast<double>(face.size()));
}

}  // namespace hrad
