// Large-model options of the view-factor matrix: the cheap factor bound (pair_bound.h), the
// threshold's dropped pairs and the bound each row reports for them, and far pairs sampled without
// a shaft test (sample_below), on closed boxes and on a small generated urban model.
#include <gtest/gtest.h>

#include <cmath>

#include "hrad/experiments/scene_generator.h"
#include "hrad/experiments/urban_generator.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/viewfactors/pair_bound.h"
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

}  // namespace
}  // namespace hrad::test
