#include "hrad/formfactor/receiver_gauss_factor.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "hrad/formfactor/gauss_legendre.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

void receiver_gauss_points(std::span<const Vec3> p, const Vec3& n, std::vector<detail::WeightedPoint>& out) {
  out.clear();
  if (p.size() != 4) {
    detail::polygon_quadrature(p, n, 2, out);
    return;
  }
  // An elongated quad takes the rule on each of a row of near-square cells of its parameter square:
  // one 3 x 3 rule spread over a long element puts its points far from where the light of a polygon
  // near one end arrives (the elements along a corridor from its end wall). The points still do not
  // depend on the source, so closure holds as before.
  const double lu = 0.5 * ((p[1] - p[0]).norm() + (p[2] - p[3]).norm());
  const double lv = 0.5 * ((p[3] - p[0]).norm() + (p[2] - p[1]).norm());
  // k cells where the sides' ratio is between sqrt(2) (k - 1/2) and sqrt(2) (k + 1/2): cells of aspect
  // below ~2, and thresholds irrational, so that no ratio of short decimal or binary lengths sits on
  // one (a scaled scene rounds its lengths and must keep its rules).
  const auto cells = [](double along, double across) {
    if (!(across > 0.0)) return 1;
    const auto k = static_cast<long>(std::floor(along / across / std::numbers::sqrt2 + 0.5));
    return static_cast<int>(std::clamp(k, 1L, kMaxReceiverCells));
  };
  const int mu = cells(lu, lv), mv = cells(lv, lu);
  const detail::GaussRule g = detail::gauss_legendre(3);
  for (int a = 0; a < mu; ++a)
    for (std::size_t i = 0; i < g.nodes.size(); ++i) {
      const double u = (a + 0.5 * (g.nodes[i] + 1.0)) / mu;
      for (int b = 0; b < mv; ++b)
        for (std::size_t j = 0; j < g.nodes.size(); ++j) {
          const double v = (b + 0.5 * (g.nodes[j] + 1.0)) / mv;
          const Vec3 x = (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
          const Vec3 du = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
          const Vec3 dv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
          out.push_back({x, 0.25 * g.weights[i] * g.weights[j] * du.cross(dv).norm() / (mu * mv)});
        }
    }
}

double receiver_gauss_factor(std::span<const Vec3> receiver, std::span<const Vec3> source, double rel_tol,
                             int* point_count) {
  thread_local std::vector<detail::WeightedPoint> points;
  const Vec3 n = newell_normal(receiver).normalized();
  receiver_gauss_points(receiver, n, points);
  if (point_count != nullptr) *point_count = static_cast<int>(points.size());
  double sum = 0.0, area = 0.0;
  for (const detail::WeightedPoint& p : points) {
    sum += p.weight * point_to_polygon(p.x, n, source, rel_tol);
    area += p.weight;  // the weights' own sum, so that factors to a closed surface sum to 1 exactly
  }
  return area > 0.0 ? std::max(0.0, sum / area) : 0.0;
}

namespace {

// The vertices' mean and the largest distance from it: a bounding sphere (not the smallest).
std::pair<Vec3, double> vertex_sphere(std::span<const Vec3> p) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : p) c += v;
  c /= static_cast<double>(p.size());
  double r2 = 0.0;
  for (const Vec3& v : p) r2 = std::max(r2, (v - c).squaredNorm());
  return {c, std::sqrt(r2)};
}

}  // namespace

double receiver_factor_by_distance(std::span<const Vec3> receiver, std::span<const Vec3> source, double centroid_ratio,
                                   int* point_count) {
  const auto [rc, rr] = vertex_sphere(receiver);
  const auto [sc, sr] = vertex_sphere(source);
  const double gap = (rc - sc).norm() - rr - sr;
  if (!(gap > 0.0) || 2.0 * rr > centroid_ratio * gap)
    return receiver_gauss_factor(receiver, source, kLambertSumOnly, point_count);
  if (point_count != nullptr) *point_count = 1;
  // A quad's bilinear centre and a triangle's centroid are the vertices' mean; other polygons
  // take the area centroid.
  const Vec3 x = receiver.size() <= 4 ? rc : polygon_centroid(receiver);
  return std::max(0.0, point_to_polygon(x, newell_normal(receiver).normalized(), source, kLambertSumOnly));
}

}  // namespace hrad
