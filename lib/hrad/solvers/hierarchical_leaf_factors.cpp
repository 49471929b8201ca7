#include "hrad/solvers/hierarchical_leaf_factors.h"

#include <array>
#include <cmath>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/geometry/polygon.h"

namespace hrad::detail {

double leaf_form_factor(std::span<const Vec3> element, std::span<const Vec3> source) {
  const Vec3 n = newell_normal(element).normalized();
  double sum = 0.0, weights = 0.0;
  if (element.size() == 4) {
    // 2 x 2 Gauss-Legendre on the bilinear map of [0,1]^2 onto the quad, weighted by its Jacobian
    // (exact for the area; degree 3 in (u, v)).
    const double g = 0.5 / std::sqrt(3.0);
    const std::array<double, 2> t = {0.5 - g, 0.5 + g};
    const Vec3 &a = element[0], &b = element[1], &c = element[2], &d = element[3];
    for (const double u : t)
      for (const double v : t) {
        const Vec3 x = (1 - u) * (1 - v) * a + u * (1 - v) * b + u * v * c + (1 - u) * v * d;
        const Vec3 du = (1 - v) * (b - a) + v * (c - d);
        const Vec3 dv = (1 - u) * (d - a) + u * (c - b);
        const double w = du.cross(dv).norm();
        sum += w * point_to_polygon(x, n, source);
        weights += w;
      }
  } else {
    // Strang & Fix's 3-point rule (barycentric (2/3, 1/6, 1/6) and permutations; degree 2).
    for (int k = 0; k < 3; ++k) {
      const Vec3 x = (2.0 / 3.0) * element[k] + (1.0 / 6.0) * (element[(k + 1) % 3] + element[(k + 2) % 3]);
      sum += point_to_polygon(x, n, source);
      weights += 1.0;
    }
  }
  return sum / weights;
}

std::vector<Link> leaf_links(const ElementHierarchy& h, std::span<const LinkPair> pairs) {
  // Directed links first, then the leaves each one reaches, then the factors in parallel.
  struct Directed {
    NodeId receiver, source;
    double factor, visibility;
    std::size_t first;  // offset of its leaf links in the output
  };
  std::vector<Directed> directed;
  directed.reserve(2 * pairs.size());
  std::size_t total = 0;
  std::vector<std::vector<NodeId>> leaves_of(h.size());  // memoised leaves_below of interior receivers
  auto add = [&](NodeId r, NodeId s, double f, double vis) {
    if (f <= 0.0) return;
    const ElementNode& n = h.node(r);
    std::size_t count = 1;
    if (!n.is_leaf()) {
      std::vector<NodeId>& l = leaves_of[static_cast<std::size_t>(r)];
      if (l.empty()) l = h.leaves_below(r);
      count = l.size();
    }
    directed.push_back({r, s, f, vis, total});
    total += count;
  };
  for (const LinkPair& pair : pairs) {
    add(pair.p, pair.q, pair.estimate.value, pair.estimate.visibility);
    add(pair.q, pair.p, pair.estimate.reverse, pair.estimate.visibility);
  }
  std::vector<Link> links(total);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, directed.size(), 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Directed& d = directed[i];
                        if (h.node(d.receiver).is_leaf()) {
                          links[d.first] = {d.receiver, d.source, d.factor};
                          continue;
                        }
                        const std::vector<NodeId>& l = leaves_of[static_cast<std::size_t>(d.receiver)];
                        const std::span<const Vec3> source = h.node(d.source).polygon();
                        for (std::size_t k = 0; k < l.size(); ++k)
                          links[d.first + k] = {l[k], d.source,
                                                d.visibility * leaf_form_factor(h.node(l[k]).polygon(), source)};
                      }
                    });
  return links;
}

}  // namespace hrad::detail
