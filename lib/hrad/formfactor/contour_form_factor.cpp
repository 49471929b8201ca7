#include "hrad/formfactor/contour_form_factor.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "hrad/formfactor/edge_pair_integral.h"

namespace hrad::detail {

ContourSum contour_area_factor(std::span<const Vec3> from, std::span<const Vec3> to) {
  const std::size_t m = from.size(), n = to.size();
  // Per-edge and per-(edge, vertex) quantities, computed once and shared by the edge pairs (an edge
  // of `from` and a vertex of `to` serve the two edges of `to` that meet there); the endpoint terms
  // lazily, since parallel and perpendicular pairs do not use them.
  thread_local std::vector<Segment> edges_from, edges_to;
  thread_local std::vector<EndpointTerms> terms;
  thread_local std::vector<char> ready;
  edges_from.resize(m);
  edges_to.resize(n);
  for (std::size_t i = 0; i < m; ++i) edges_from[i] = make_segment(from[i], from[i + 1 == m ? 0 : i + 1]);
  for (std::size_t j = 0; j < n; ++j) edges_to[j] = make_segment(to[j], to[j + 1 == n ? 0 : j + 1]);
  terms.resize(m * n);
  ready.assign(m * n, 0);
  auto endpoint = [&](std::size_t i, std::size_t k) -> const EndpointTerms& {
    const std::size_t index = i * n + k;
    if (!ready[index]) {
      terms[index] = endpoint_terms(edges_from[i], to[k]);
      ready[index] = 1;
    }
    return terms[index];
  };
  double sum = 0.0, magnitude = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Segment& p = edges_from[i];
    if (p.length == 0.0) continue;
    for (std::size_t j = 0; j < n; ++j) {
      const Segment& q = edges_to[j];
      const double cosine = p.dir.dot(q.dir);
      if (cosine == 0.0 || q.length == 0.0) continue;  // perpendicular edges contribute nothing
      // Parallel pairs use their own closed form and no endpoint terms (edge_pair_integral.cpp).
      const bool parallel = parallel_directions(p.dir.cross(q.dir));
      static const EndpointTerms kUnused;
      const EdgePairIntegral k = edge_pair_log_integral(p, q, parallel ? kUnused : endpoint(i, j),
                                                        parallel ? kUnused : endpoint(i, j + 1 == n ? 0 : j + 1));
      sum += cosine * k.value;
      magnitude += std::abs(cosine) * k.magnitude;
    }
  }
  // Both contours counter-clockwise about their own fronts, which face each other.
  return {sum / (2.0 * std::numbers::pi), magnitude / (2.0 * std::numbers::pi)};
}

}  // namespace hrad::detail
