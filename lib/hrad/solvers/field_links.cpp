#include "hrad/solvers/field_links.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/formfactor/simpson_rule.h"
#include "hrad/solvers/linear_basis.h"
#include "hrad/visibility/sampling.h"

namespace hrad {
namespace {

// A boundary point casts its rays from this fraction of the way towards the element's centre: from
// the boundary itself a ray can graze a neighbouring patch that meets it there.
constexpr double kRayStart = 1.0 / 16.0;

void visible_fractions(const FormFactorEvaluator& ev, const ElementNode& r, const ElementNode& s,
                       const std::vector<int>* occluders, int rays, std::uint64_t seed, PointFactors* side) {
  const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
  const int centre = side->points.count - 1;
  const Vec3& c = side->points.x[static_cast<std::size_t>(centre)];
  for (int i = 0; i < side->points.count; ++i) {
    double& f = side->factor[static_cast<std::size_t>(i)];
    if (!(f > 0.0)) continue;
    const Vec3& x = side->points.x[static_cast<std::size_t>(i)];
    const Vec3 start = i == centre ? x : Vec3(x + kRayStart * (c - x));
    const KernelVisibility k = ev.visibility_from_point(start, n, r.patch, s.polygon(), s.patch, occluders, rays,
                                                        detail::mix_seed(seed, static_cast<std::uint64_t>(i)));
    // No ray carried weight (the point sees the source edge-on): half, the least biased guess.
    f *= k.weight > 0.0 ? k.visible / k.weight : 0.5;
  }
}

// The source's weights over its moments: its points' factors in the Bernstein form (a positive
// average of its radiosity, linear_basis.h bernstein_weighting()) over their integral against its
// basis (basis_integrals()), so a uniform radiosity sends itself. A source none of whose points sees
// the receiver sends its mean.
std::array<double, 9> source_weights(const PointFactors& source, double area) {
  const int functions = basis_functions(source.points);
  const std::array<double, 9> basis = basis_integrals(source.points, area);
  const std::array<double, 9> g = bernstein_weighting(source.factor, source.points.count);
  double integral = 0.0;
  for (int m = 0; m < functions; ++m) integral += basis[static_cast<std::size_t>(m)] * g[static_cast<std::size_t>(m)];
  std::array<double, 9> w{};
  for (int m = 0; m < functions; ++m)
    w[static_cast<std::size_t>(m)] = integral > 0.0 ? g[static_cast<std::size_t>(m)] / integral : 1.0 / area;
  return w;
}

}  // namespace

PointFactors point_factors(const FormFactorEvaluator& ev, const ElementNode& r, std::span<const Vec3> source) {
  PointFactors side;
  side.points = simpson_points(r.polygon());
  const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
  const int centre = side.points.count - 1;
  const Vec3& c = side.points.x[static_cast<std::size_t>(centre)];
  for (int i = 0; i < side.points.count; ++i) {
    const Vec3& x = side.points.x[static_cast<std::size_t>(i)];
    side.factor[static_cast<std::size_t>(i)] =
        i == centre ? ev.point_factor(x, n, source) : ev.point_factor(x, n, Vec3(c - x), source);
  }
  return side;
}

void pair_fields(const FormFactorEvaluator& ev, const ElementNode& a, const ElementNode& b, int rays,
                 FieldEntry* a_from_b, FieldEntry* b_from_a) {
  *a_from_b = FieldEntry{};
  *b_from_a = FieldEntry{};
  if (a.patch == b.patch || ev.faces_away(a.polygon(), b.polygon())) return;
  PointFactors sa = point_factors(ev, a, b.polygon()), sb = point_factors(ev, b, a.polygon());
  if (ev.effects().visibility) {
    std::vector<int> occluders;
    const PairClass cls = ev.classify(a.polygon(), a.patch, b.polygon(), b.patch, nullptr, &occluders);
    if (cls == PairClass::kFullyHidden || cls == PairClass::kFacingAway) return;
    if (cls == PairClass::kPartial) {
      const std::uint64_t seed = ev.pair_seed(a.polygon(), a.patch, b.polygon(), b.patch);
      visible_fractions(ev, a, b, &occluders, rays, detail::mix_seed(seed, 1), &sa);
      visible_fractions(ev, b, a, &occluders, rays, detail::mix_seed(seed, 2), &sb);
    }
  }
  a_from_b->factor = sa.factor;
  b_from_a->factor = sb.factor;
  a_from_b->weight = source_weights(sb, b.area);
  b_from_a->weight = source_weights(sa, a.area);
}

FieldLinks::FieldLinks(std::vector<NodeId> receivers, std::vector<NodeId> sources)
    : receivers_(std::move(receivers)),
      sources_(std::move(sources)),
      entries_(receivers_.size() * sources_.size(), FieldEntry{}) {}

void FieldLinks::gather(NodeField& field) const {
  const std::size_t cols = sources_.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers_.size(), 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        PointValues& h = field.irradiance[static_cast<std::size_t>(receivers_[i])];
                        const FieldEntry* row = entries_.data() + i * cols;
                        for (std::size_t j = 0; j < cols; ++j) {
                          const FieldEntry& e = row[j];
                          const PointValues& m = field.radiosity_moments[static_cast<std::size_t>(sources_[j])];
                          Rgb b = Rgb::Zero();
                          for (int k = 0; k < 9; ++k)
                            b += e.weight[static_cast<std::size_t>(k)] * m[static_cast<std::size_t>(k)];
                          for (int k = 0; k < 9; ++k)
                            h[static_cast<std::size_t>(k)] += e.factor[static_cast<std::size_t>(k)] * b;
                        }
                      }
                    });
}

}  // namespace hrad
