#include "hrad/formfactor/contour_form_factor.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "hrad/formfactor/edge_pair_integral.h"

namespace hrad::detail {
namespace {

// Up to this many edges and (edge, vertex) combinations (two octagons) the per-call tables live on
// the stack.
constexpr std::size_t kStackEdges = 16, kStackPairs = 64;

// Per-edge and per-(edge, vertex) quantities, computed once and shared by the edge pairs (an edge
// of `from` and a vertex of `to` serve the two edges of `to` that meet there; a vertex of `from`
// and one of `to` serve two such combinations); the endpoint terms lazily, since parallel and
// perpendicular pairs do not use them. The tables have m, n and m * n entries.
struct Tables {
  Segment* edges_from;
  Segment* edges_to;
  EndpointTerms* terms;
  VertexPairLog* logs;
  char* ready;  // bit 0: terms, bit 1: logs
};

ContourSum contour_sum(std::span<const Vec3> from, std::span<const Vec3> to, const Tables& t) {
  const std::size_t m = from.size(), n = to.size();
  for (std::size_t i = 0; i < m; ++i) t.edges_from[i] = make_segment(from[i], from[i + 1 == m ? 0 : i + 1]);
  for (std::size_t j = 0; j < n; ++j) t.edges_to[j] = make_segment(to[j], to[j + 1 == n ? 0 : j + 1]);
  std::fill(t.ready, t.ready + m * n, char(0));
  auto vertex_log = [&](std::size_t i, std::size_t k) -> const VertexPairLog& {
    const std::size_t index = i * n + k;
    if (!(t.ready[index] & 2)) {
      t.logs[index] = vertex_pair_log(from[i], to[k]);
      t.ready[index] |= 2;
    }
    return t.logs[index];
  };
  auto endpoint = [&](std::size_t i, std::size_t k) -> const EndpointTerms& {
    const std::size_t index = i * n + k;
    if (!(t.ready[index] & 1)) {
      t.terms[index] = endpoint_terms(t.edges_from[i], to[k], vertex_log(i, k), vertex_log(i + 1 == m ? 0 : i + 1, k));
      t.ready[index] |= 1;
    }
    return t.terms[index];
  };
  double sum = 0.0, magnitude = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Segment& p = t.edges_from[i];
    if (p.length == 0.0) continue;
    for (std::size_t j = 0; j < n; ++j) {
      const Segment& q = t.edges_to[j];
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

}  // namespace

ContourSum contour_area_factor(std::span<const Vec3> from, std::span<const Vec3> to) {
  const std::size_t m = from.size(), n = to.size();
  if (m <= kStackEdges && n <= kStackEdges && m * n <= kStackPairs) {
    // Storage only: every entry read is written first (the ready flags), so nothing is initialised.
    union Storage {
      Storage() {}
      struct {
        Segment edges_from[kStackEdges], edges_to[kStackEdges];
        EndpointTerms terms[kStackPairs];
        VertexPairLog logs[kStackPairs];
      } s;
    } storage;
    char ready[kStackPairs];
    return contour_sum(from, to, {storage.s.edges_from, storage.s.edges_to, storage.s.terms, storage.s.logs, ready});
  }
  thread_local std::vector<Segment> edges_from, edges_to;
  thread_local std::vector<EndpointTerms> terms;
  thread_local std::vector<VertexPairLog> logs;
  thread_local std::vector<char> ready;
  edges_from.resize(m);
  edges_to.resize(n);
  terms.resize(m * n);
  logs.resize(m * n);
  ready.resize(m * n);
  return contour_sum(from, to, {edges_from.data(), edges_to.data(), terms.data(), logs.data(), ready.data()});
}

}  // namespace hrad::detail
