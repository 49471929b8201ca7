// Large-model options of the view-factor matrix: the cheap factor bound (pair_bound.h), the
// threshold's dropped pairs and the bound each row reports for them, and far pairs sampled without
// a shaft test (sample_below), on closed boxes and on a small generated urban model.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/experiments/scene_generator.h"
#include "hrad/experiments/urban_generator.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/viewfactors/pair_bound.h"
#include "hrad/viewfactors/view_factor_work.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

void expect_reciprocal_nonnegative(const ViewFactorMatrix& m) {
  for (std::size_t k = 0; k < m.exchange.size(); ++k) EXPECT_GE(m.exchange[k], 0.0);
  EXPECT_LE(max_reciprocity_error(m), 1e-12);
}

// A quad of half-sides (su, sv) about `centre`, facing `normal` (u, v unit and perpendicular).
std::vector<Vec3> quad(const Vec3& centre, const Vec3& u, const Vec3& v, double su, double sv) {
  return {centre - su * u - sv * v, centre + su * u - sv * v, centre + su * u + sv * v, centre - su * u + sv * v};
}

// The bound is at least the closed form both ways, on random quads in random orientations and
// distances (touching ones excluded: no bound there), and it does not depend on the unit of length.
TEST(PairBound, BoundsTheClosedFormBothWays) {
  detail::Rng rng(5);
  auto unit_vector = [&] {
    const double z = 2 * rng.uniform() - 1, phi = 2 * M_PI * rng.uniform(), s = std::sqrt(1 - z * z);
    return Vec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  int bounded = 0, facing = 0;
  for (int k = 0; k < 400; ++k) {
    Scene s;
    s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
    for (int side = 0; side < 2; ++side) {
      const Vec3 n = unit_vector(), t = n.unitOrthogonal(), b = n.cross(t);
      const Vec3 centre = side == 0 ? Vec3(Vec3::Zero()) : Vec3(unit_vector() * std::pow(10.0, 2.0 * rng.uniform()));
      add_polygon(s, quad(centre, t, b, 0.1 + rng.uniform(), 0.1 + rng.uniform()), n, 0);
    }
    const std::vector<PatchBoundShape> shapes = patch_bound_shapes(s);
    const FactorBound bound = factor_bound(shapes[0], shapes[1]);
    const PairFormFactor f = polygon_to_polygon(s.patches[0].vertices, s.patches[1].vertices);
    if (!std::isfinite(bound.pq)) continue;
    ++bounded;
    facing += f.from_to > 0.0 ? 1 : 0;
    EXPECT_GE(bound.pq, f.from_to) << k;
    EXPECT_GE(bound.qp, f.to_from) << k;
    for (Patch& p : s.patches)
      for (Vec3& v : p.vertices) v *= 1e3;
    for (Patch& p : s.patches) p.area *= 1e6;
    const std::vector<PatchBoundShape> scaled = patch_bound_shapes(s);
    const FactorBound b2 = factor_bound(scaled[0], scaled[1]);
    EXPECT_NEAR(b2.pq, bound.pq, 1e-12 * bound.pq) << k;
  }
  EXPECT_GT(bounded, 200);
  EXPECT_GT(facing, 50);
}

// Far apart and facing, the bound approaches A_q / (pi d^2), which the closed form approaches too:
// two unit squares facing each other 100 apart (Howell C-11's far limit) within 5%.
TEST(PairBound, TightForFarParallelSquares) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  add_polygon(s, quad(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitZ(), 0.5, 0.5), Vec3::UnitY(), 0);
  add_polygon(s, quad(Vec3(0, 100, 0), Vec3::UnitX(), Vec3::UnitZ(), 0.5, 0.5), -Vec3::UnitY(), 0);
  const std::vector<PatchBoundShape> shapes = patch_bound_shapes(s);
  const FactorBound bound = factor_bound(shapes[0], shapes[1]);
  const double f = polygon_to_polygon(s.patches[0].vertices, s.patches[1].vertices).from_to;
  EXPECT_GE(bound.pq, f);
  EXPECT_LE(bound.pq, 1.05 * f);
  // Facing away: both 0.
  add_polygon(s, quad(Vec3(0, -100, 0), Vec3::UnitX(), Vec3::UnitZ(), 0.5, 0.5), -Vec3::UnitY(), 0);
  const std::vector<PatchBoundShape> all = patch_bound_shapes(s);
  EXPECT_EQ(factor_bound(all[0], all[2]).pq, 0.0);
}

// A closed box cut into many rectangles, with a threshold: rows lose at most what they report,
// so each row sum plus its dropped bound still reaches 1 (closure within the dropped bound), and
// kept pairs are those of the full matrix, bit for bit.
TEST(ViewFactorScale, ClosedBoxClosesWithinTheDroppedBound) {
  const Scene s = make_cut_box(3, 2, 4, 6, 11);
  ViewFactorOptions cut = plain_options();
  cut.threshold = 2e-3;
  const ViewFactorMatrix full = compute_view_factors(s, face_units(s), plain_options());
  const ViewFactorMatrix m = compute_view_factors(s, face_units(s), cut);
  EXPECT_GT(m.counters.skipped_pairs, 0u);
  EXPECT_EQ(m.counters.partial, 0u);
  expect_reciprocal_nonnegative(m);
  double largest_bound = 0.0;
  for (int u = 0; u < m.n; ++u) {
    EXPECT_LE(m.row_sum(u), 1.0 + 1e-9) << u;
    EXPECT_GE(m.row_sum(u) + m.skipped_bound[u], 1.0 - 1e-9) << u;
    largest_bound = std::max(largest_bound, m.skipped_bound[u]);
    for (int v = 0; v < m.n; ++v)
      if (m.factor(u, v) != 0.0) EXPECT_EQ(m.factor(u, v), full.factor(u, v)) << u << " " << v;
  }
  EXPECT_GT(largest_bound, 0.0);
}

// The urban generator's model (open, buildings on a ground in T-junctions), and its matrix with 64
// rays per partly visible pair (so that runs with other options sample the pairs they share alike).
struct SmallUrban {
  Scene scene = to_scene(generate_urban({300, 2}));
  SurfaceUnits units = face_units(scene);
  ViewFactorOptions options = [] {
    ViewFactorOptions o = plain_options();
    o.pair.min_rays = o.pair.max_rays = 64;
    return o;
  }();
  ViewFactorMatrix full = compute_view_factors(scene, units, options);
};

const SmallUrban& small_urban() {
  static const SmallUrban urban;
  return urban;
}

// On the small urban model, against the run without threshold, every dropped factor
// is below the threshold, each row's lost factor is at most its reported bound, kept factors are
// the same bits; both stages of the drop (cheap bound, closed form) are exercised.
TEST(ViewFactorScale, UrbanThresholdBoundCoversWhatWasDropped) {
  const SmallUrban& urban = small_urban();
  const ViewFactorMatrix& full = urban.full;
  ViewFactorOptions cut = urban.options;
  cut.threshold = 1e-3;
  const ViewFactorMatrix m = compute_view_factors(urban.scene, urban.units, cut);
  EXPECT_GT(m.counters.skipped_pairs, m.counters.dropped_by_closed_form);
  EXPECT_GT(m.counters.dropped_by_closed_form, 0u);
  expect_reciprocal_nonnegative(m);
  int rows_losing = 0;
  for (int u = 0; u < m.n; ++u) {
    double lost = 0.0;
    for (std::int64_t k = full.row_begin[u]; k < full.row_begin[u + 1]; ++k) {
      const int v = full.column[static_cast<std::size_t>(k)];
      const double f = full.factor(u, k), g = m.factor(u, v);
      if (g != 0.0) {
        EXPECT_EQ(f, g) << u << " " << v;
      } else {
        EXPECT_LT(f, cut.threshold * (1 + 1e-6)) << u << " " << v;
        lost += f;
      }
    }
    rows_losing += lost > 0.0 ? 1 : 0;
    EXPECT_LE(lost, m.skipped_bound[u] * (1 + 1e-6)) << u;
    EXPECT_NEAR(m.row_sum(u) + lost, full.row_sum(u), 1e-12) << u;
  }
  EXPECT_GT(rows_losing, m.n / 2);
}

// Far pairs sampled against the whole scene instead of their shafts' occluders (with a threshold
// below them): row sums agree with the full matrix's within their reported sampling errors (5
// combined standard errors) and dropped bounds, and every factor stays at most its unobstructed
// value; the same bits on one thread and on two.
TEST(ViewFactorScale, FarPairsSampledAgreeWithShaftTests) {
  const SmallUrban& urban = small_urban();
  const Scene& s = urban.scene;
  const ViewFactorMatrix& full = urban.full;
  ViewFactorOptions far = urban.options;
  far.sample_below = 3e-3;
  far.pair.far_rays = 16;
  far.threshold = 1e-4;
  far.threads = 2;
  const ViewFactorMatrix m = compute_view_factors(s, urban.units, far);
  far.threads = 1;
  const ViewFactorMatrix one = compute_view_factors(s, urban.units, far);
  EXPECT_EQ(one.column, m.column);
  EXPECT_EQ(one.exchange, m.exchange);
  EXPECT_EQ(one.skipped_bound, m.skipped_bound);
  EXPECT_GT(m.counters.shaft_skipped, m.counters.patch_pairs / 20);
  expect_reciprocal_nonnegative(m);
  for (int u = 0; u < m.n; ++u) {
    EXPECT_NEAR(m.row_sum(u), full.row_sum(u),
                5 * std::hypot(m.sampling_error[u], full.sampling_error[u]) + m.skipped_bound[u] + 1e-12)
        << u;
    for (std::int64_t k = m.row_begin[u]; k < m.row_begin[u + 1]; ++k) {
      const int v = m.column[static_cast<std::size_t>(k)];
      const double f = polygon_to_polygon(s.patches[static_cast<std::size_t>(u)].vertices,
                                          s.patches[static_cast<std::size_t>(v)].vertices)
                           .from_to;
      EXPECT_LE(m.factor(u, k), f * (1 + 1e-5)) << u << " " << v;
    }
  }
}

// The work estimate's sample of pairs on the small urban model: a high estimate of the pairs
// actually stored (at least them, and within 3 binomial standard errors of 4096 draws plus their
// share above them), and the refusals it leads to: memory names --threshold, a dense output beyond
// the disk names the sparse formats, and an unknown limit (0) refuses nothing.
TEST(ViewFactorScale, WorkEstimateFromSampledPairs) {
  const SmallUrban& urban = small_urban();
  ViewFactorOptions options = urban.options;
  options.threshold = 1e-4;
  PairSample sample;
  options.before_pairs = [&](const PairSample& s) { sample = s; };
  const ViewFactorMatrix m = compute_view_factors(urban.scene, urban.units, options);
  ASSERT_EQ(sample.sampled, 4096);
  EXPECT_EQ(sample.pairs, double(m.counters.patch_pairs));
  const double stored = 0.5 * double(m.nonzeros());  // face units: no diagonal
  const double se = std::sqrt(stored / sample.pairs * (1 - stored / sample.pairs) / sample.sampled) * sample.pairs;
  EXPECT_GE(sample.stored, stored);
  EXPECT_LE(sample.stored, stored + 6 * se);

  const double n = m.n;
  const ViewFactorWork small = estimate_view_factor_work(sample, n, n, MatrixFormat::kDense);
  EXPECT_GE(small.output_bytes, 2 * n * n);    // every value at least "0,"
  EXPECT_GE(small.memory_bytes, stored * 24);  // two entries of (int, double) per stored pair
  // A city's proportions (20k faces, 2.4% of pairs stored): the sparse output is the smaller.
  PairSample city;
  city.pairs = 2e8;
  city.stored = 4.8e6;
  const ViewFactorWork dense = estimate_view_factor_work(city, 2e4, 2e4, MatrixFormat::kDense);
  const ViewFactorWork sparse = estimate_view_factor_work(city, 2e4, 2e4, MatrixFormat::kMatrixMarket);
  EXPECT_LT(sparse.output_bytes, 0.8 * dense.output_bytes);
  auto refusal = [&](const ViewFactorWork& w, MatrixFormat f, double memory, double disk) -> std::string {
    try {
      check_view_factor_work(w, options, f, "F", memory, disk);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refusal(dense, MatrixFormat::kDense, 0, 0), "");
  EXPECT_NE(refusal(dense, MatrixFormat::kDense, dense.memory_bytes, 0).find("--threshold"), std::string::npos);
  EXPECT_NE(refusal(dense, MatrixFormat::kDense, 0, dense.output_bytes).find("sparse format"), std::string::npos);
  EXPECT_EQ(refusal(sparse, MatrixFormat::kMatrixMarket, 0, dense.output_bytes), "");
}

// Calibration of the reported row errors, with far pairs sampled and a row budget, against a
// reference with 1024 rays per partly visible pair (its own reported errors combined). If the
// errors are honest standard errors of unbiased row sums (after the row cap, which only moves a
// row above 1 towards its true value), a row differs from the reference by more than k combined
// errors (less what it dropped, on the low side) with the normal tails' probability p_k at most:
// rows beyond k = 1, 2, 3 must be at most N p_k + 3 sqrt(N p_k (1 - p_k)) + 1 of the N sampled
// rows (3 binomial standard deviations; rows share pairs, so they are not quite independent).
TEST(ViewFactorScale, RowErrorsAreCalibratedAgainstAReference) {
  const SmallUrban& urban = small_urban();
  ViewFactorOptions reference = urban.options;
  reference.pair.min_rays = reference.pair.max_rays = 1024;
  const ViewFactorMatrix r = compute_view_factors(urban.scene, urban.units, reference);
  ViewFactorOptions far = urban.options;
  far.sample_below = 3e-3;
  far.threshold = 1e-4;
  far.row_error = 0.01;
  const ViewFactorMatrix m = compute_view_factors(urban.scene, urban.units, far);
  ASSERT_GT(m.counters.shaft_skipped, 0u);
  int rows = 0;
  std::array<int, 3> beyond{};
  for (int u = 0; u < m.n; ++u) {
    const double sigma = std::hypot(m.sampling_error[u], r.sampling_error[u]);
    if (!(sigma > 0.0)) continue;
    ++rows;
    const double d = m.row_sum(u) - r.row_sum(u);
    const double off = d > 0.0 ? d : std::max(0.0, -d - m.skipped_bound[u]);
    for (int k = 1; k <= 3; ++k) beyond[k - 1] += off > k * sigma ? 1 : 0;
  }
  ASSERT_GT(rows, 100);
  RecordProperty("rows", rows);
  RecordProperty("beyond_1_2_3", fmt::format("{} {} {}", beyond[0], beyond[1], beyond[2]));
  const std::array<double, 3> tail = {std::erfc(1 / std::sqrt(2.0)), std::erfc(2 / std::sqrt(2.0)),
                                      std::erfc(3 / std::sqrt(2.0))};
  for (int k = 0; k < 3; ++k) {
    const double expected = rows * tail[k];
    EXPECT_LE(beyond[k], expected + 3 * std::sqrt(expected * (1 - tail[k])) + 1) << "k = " << k + 1 << ", " << rows;
  }
}

}  // namespace
}  // namespace hrad::test
