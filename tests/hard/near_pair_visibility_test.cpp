// The sampled visible fraction of a pair closer than its size against the exact occluded factor
// (visible regions in rational arithmetic, integrated by Gauss-Legendre): a shelf board 5 mm from
// its upright, under the next board, where the kernel peaks at the gap and the far parts are shaded;
// a floor meeting a wall behind a fin, where the ratio estimator's bias shows from few point pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "hrad/formfactor/gauss_legendre.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/geometry/polygon.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/visibility/occluded_form_factor.h"
#include "hrad/visibility/visibility.h"

namespace hrad {
namespace {

// The integral of f over [xs.front(), xs.back()] x [ys.front(), ys.back()]: 8-point Gauss-Legendre
// on each cell of the two grids.
template <class F>
double integrate(const std::vector<double>& xs, const std::vector<double>& ys, F f) {
  const detail::GaussRule g = detail::gauss_legendre(8);
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i)
    for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
      const double hx = 0.5 * (xs[i + 1] - xs[i]), hy = 0.5 * (ys[j + 1] - ys[j]);
      for (std::size_t a = 0; a < g.nodes.size(); ++a)
        for (std::size_t b = 0; b < g.nodes.size(); ++b)
          sum += g.weights[a] * g.weights[b] * hx * hy *
                 f(xs[i] + hx * (1.0 + g.nodes[a]), ys[j] + hy * (1.0 + g.nodes[b]));
    }
  return sum;
}

// The sampled visible fraction of the pair receiver = patch 0, source = patch 1 of a scene of
// three polygons (the third occludes), against the exact fraction.
class NearPairVisibility : public ::testing::Test {
 protected:
  using Quad = std::vector<Vec3>;

  void build(const Quad& receiver, const Quad& source, const Quad& occluder) {
    s_.materials.push_back(test::material(Rgb::Constant(0.5), Rgb::Zero()));
    test::add_polygon(s_, receiver, newell_normal(receiver).normalized(), 0);
    test::add_polygon(s_, source, newell_normal(source).normalized(), 0);
    test::add_polygon(s_, occluder, newell_normal(occluder).normalized(), 0);
    visibility_ = make_visibility(s_);
    evaluator_.emplace(s_, effects_, visibility_.get(), 64, FormFactorKernel::kAnalytic);
  }

  const Quad& receiver() const { return s_.patches[0].vertices; }
  const Quad& source() const { return s_.patches[1].vertices; }

  // Exact: the occluded point factor of each point of the receiver (in the plane z = 0, facing +z),
  // integrated over the cells of the grids xs x ys (graded where it changes fast); the fraction is
  // the ratio of the occluded to the bare integral on the same points.
  double exact_fraction(const std::vector<double>& xs, const std::vector<double>& ys) const {
    const Vec3 up(0, 0, 1);
    const double seen = integrate(
        xs, ys, [&](double x, double y) { return occluded_point_to_polygon(s_, Vec3(x, y, 0), up, 0, source(), 1); });
    const double bare =
        integrate(xs, ys, [&](double x, double y) { return point_to_polygon(Vec3(x, y, 0), up, source()); });
    return seen / bare;
  }

  // Mean and standard error of the mean of `streams` independent estimates from `pairs` point
  // pairs each; with `controlled`, the estimate leans on the pair's exact exchange, the pairs
  // drawn as two independent halves (its fallback coefficient an estimate of the fraction from a
  // stream of its own, as the refinement oracle's test is).
  std::pair<double, double> mean_fraction(int pairs, int streams, bool controlled) const {
    const FormFactorEvaluator& ev = *evaluator_;
    const double exchange = polygon_area(receiver()) * ev.analytic(receiver(), source()).from_to;
    double sum = 0.0, sum2 = 0.0;
    for (int k = 1; k <= streams; ++k) {
      const auto stream = static_cast<std::uint64_t>(k);
      const PairVisibility v = ev.pair_visibility(receiver(), 0, source(), 1, nullptr, pairs, stream, controlled);
      const double f =
          controlled
              ? v.controlled(exchange,
                             ev.pair_visibility(receiver(), 0, source(), 1, nullptr, pairs, stream + 1000000).fraction)
              : v.fraction;
      sum += f, sum2 += f * f;
    }
    const double mean = sum / streams;
    return {mean, std::sqrt((sum2 / streams - mean * mean) / (streams - 1))};
  }

  Scene s_;
  Effects effects_;
  std::unique_ptr<Visibility> visibility_;
  std::optional<FormFactorEvaluator> evaluator_;
};

// Guarantee: the mean of 800 independent 64-pair estimates lies within 4 of its standard errors of
// the exact fraction, and those errors are small enough to show a bias of 2%.
TEST_F(NearPairVisibility, VisibleFractionOfAPairCloserThanItsSizeIsUnbiased) {
  // A shelf board's top (receiver) 5 mm from its upright (source), the next board 30 cm above:
  // the board sees the upright's foot, the next board hides the rest. The kernel peaks at the
  // 5 mm gap; area-uniform point pairs seldom land there and their ratio of kernel sums, weighted
  // towards the shaded far parts, comes out low (their mean fraction is 8% below the exact one here).
  const double gap = 0.005, depth = 0.4, shelf = 0.3;
  build({{gap, 0, 0}, {depth, 0, 0}, {depth, 1, 0}, {gap, 1, 0}}, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}},
        {{gap, 0, shelf}, {gap, 1, shelf}, {depth, 1, shelf}, {depth, 0, shelf}});
  const double exact = exact_fraction({gap, 0.0055, 0.0065, 0.009, 0.015, 0.03, 0.06, 0.12, 0.25, depth},
                                      {0, 0.005, 0.02, 0.08, 0.25, 0.5, 0.75, 0.92, 0.98, 0.995, 1});
  ASSERT_GT(exact, 0.3);
  ASSERT_LT(exact, 0.9);
  const auto [mean, sigma] = mean_fraction(64, 800, false);
  EXPECT_NEAR(mean, exact, 4.0 * sigma + 1e-4 * exact) << "sigma " << sigma;
  EXPECT_LT(sigma, 0.005 * exact);  // precise enough to see a bias of 2%
}

// Guarantee: from 8 point pairs the ratio of kernel sums is biased low by more than 4 standard
// errors of a mean over 20,000 streams (the control: the weights and the outcomes correlate); the
// estimate that leans on the exact exchange (a control variate, cross-fitted between two halves) has
// its mean within 4 of them (plus the exact integral's 5e-4) of the exact fraction, and a spread no
// more than a tenth above the ratio's.
TEST_F(NearPairVisibility, ExactExchangeRemovesTheRatioBiasOfFewPairs) {
  // A floor (receiver) meeting a wall (source) along an edge, a fin 30 cm high across the floor 30
  // cm from the wall: floor points before the fin, which carry most of the kernel (the wall fills
  // their sky), see all of the wall; those behind it see its upper part only.
  const double fin = 0.3;
  build({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}},
        {{fin, 0, 0}, {fin, 1, 0}, {fin, 1, fin}, {fin, 0, fin}});
  const double exact = exact_fraction({0, 0.001, 0.01, 0.05, 0.1, 0.2, fin, fin + 0.05, 0.5, 0.75, 1},
                                      {0, 0.005, 0.02, 0.08, 0.25, 0.5, 0.75, 0.92, 0.98, 0.995, 1});
  ASSERT_GT(exact, 0.5);
  ASSERT_LT(exact, 0.8);
  const int pairs = 8, streams = 20000;
  const auto [ratio, ratio_sigma] = mean_fraction(pairs, streams, false);
  const auto [controlled, controlled_sigma] = mean_fraction(pairs, streams, true);
  EXPECT_LT(ratio, exact - 4.0 * ratio_sigma) << "ratio " << ratio << " exact " << exact;
  EXPECT_NEAR(controlled, exact, 4.0 * controlled_sigma + 5e-4) << "sigma " << controlled_sigma;
  EXPECT_LT(controlled_sigma, 1.1 * ratio_sigma);
}

// Guarantee: the point pairs pair_visibility() hands back (which the refinement oracle pools into
// its points' visibility) are the ones its fraction is made of: as many as carried weight, their
// kernel-weighted outcomes giving the fraction, each point on its polygon, and each outcome the one
// the fin's geometry gives for that segment.
TEST_F(NearPairVisibility, ItsPairsAreThePointsAndOutcomesItsFractionIsMadeOf) {
  const double fin = 0.3;
  build({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}},
        {{fin, 0, 0}, {fin, 1, 0}, {fin, 1, fin}, {fin, 0, fin}});
  std::vector<VisibilityPair> pairs;
  const PairVisibility v = evaluator_->pair_visibility(receiver(), 0, source(), 1, nullptr, 256, 3, true, &pairs);
  ASSERT_EQ(static_cast<int>(pairs.size()), v.rays);
  double weight = 0.0, visible = 0.0;
  int blocked = 0;
  for (const VisibilityPair& pair : pairs) {
    weight += pair.weight;
    if (pair.visible) visible += pair.weight;
    EXPECT_NEAR(pair.x.z(), 0.0, 1e-12);
    EXPECT_NEAR(pair.y.x(), 0.0, 1e-12);
    EXPECT_TRUE(pair.x.x() >= 0.0 && pair.x.x() <= 1.0 && pair.x.y() >= 0.0 && pair.x.y() <= 1.0);
    EXPECT_TRUE(pair.y.y() >= 0.0 && pair.y.y() <= 1.0 && pair.y.z() >= 0.0 && pair.y.z() <= 1.0);
    // The segment from the floor point behind the fin to the wall point crosses the fin's plane at
    // the height y.z (x.x - fin) / x.x; the fin spans the floor's whole width.
    const bool crosses_fin = pair.x.x() > fin && pair.y.z() * (pair.x.x() - fin) / pair.x.x() < fin;
    if (std::abs(pair.x.x() - fin) > 1e-9) EXPECT_EQ(pair.visible, !crosses_fin) << pair.x.transpose();
    blocked += pair.visible ? 0 : 1;
  }
  EXPECT_GT(blocked, 0);
  EXPECT_LT(blocked, v.rays);
  EXPECT_EQ(v.rays - blocked, v.visible_rays);
  EXPECT_NEAR(visible / weight, v.fraction, 1e-12);
}

}  // namespace
}  // namespace hrad
