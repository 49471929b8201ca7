// The guarantees of view_factor_matrix.h on scenes of our own: non-negativity, obstructed <=
// unobstructed, reciprocity to 1e-12, closure of closed enclosures within 1e-9 where visibility is
// exact (and within the reported sampling error elsewhere), unit and thread independence, the
// closure adjustment, and the threshold's reported bound.
#include <gtest/gtest.h>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/viewfactors/closure.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

// Unobstructed F between units from polygon_to_polygon() on every pair of their patches (an
// independent sum, not the code under test).
double unobstructed(const Scene& s, const SurfaceUnits& units, int u, int v) {
  double e = 0.0;
  for (std::size_t p = 0; p < s.patches.size(); ++p)
    for (std::size_t q = 0; q < s.patches.size(); ++q)
      if (p != q && units.of_patch(s, int(p)) == u && units.of_patch(s, int(q)) == v)
        e += s.patches[p].area * polygon_to_polygon(s.patches[p].vertices, s.patches[q].vertices).from_to;
  return e / units.area[static_cast<std::size_t>(u)];
}

void expect_reciprocal_nonnegative(const ViewFactorMatrix& m) {
  for (int u = 0; u < m.n; ++u)
    for (int v = 0; v < m.n; ++v) {
      EXPECT_GE(m.factor(u, v), 0.0);
      EXPECT_LE(std::abs(m.area[u] * m.factor(u, v) - m.area[v] * m.factor(v, u)), 1e-12 * m.area[u]) << u << " " << v;
    }
  EXPECT_LE(max_reciprocity_error(m), 1e-12);
}

// Random closed boxes whose walls are cut into rectangles (T-junctions, coplanar neighbours,
// slivers of 1e-4): convex, so every pair is classified exactly and every row sums to 1 (the
// enclosure's closure) within 1e-9; reciprocity within 1e-12; no negative factor. (Few cuts: the
// closed form costs milliseconds for pairs that touch along an edge.)
TEST(ViewFactorGuarantees, RandomCutBoxesClose) {
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const Scene s = make_cut_box(1.0 + seed, 1.0, 0.5 * seed, 2, seed);
    const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
    EXPECT_EQ(m.counters.partial, 0u);
    for (int u = 0; u < m.n; ++u) EXPECT_NEAR(m.row_sum(u), 1.0, 1e-9) << "seed " << seed << " face " << u;
    expect_reciprocal_nonnegative(m);
  }
}

// A closed room with a floating block (its six faces outward): pairs the block shadows are partly
// visible. Obstructed <= unobstructed for every pair; rows still sum to 1 within 5 reported
// sampling errors (a closed enclosure); reciprocity and non-negativity as everywhere.
TEST(ViewFactorGuarantees, ObstructedRoom) {
  Scene s = make_box(4, 3, 5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 1.0, 2.5, 0.8, 1.7, 1.5, 3.0, 0);
  const SurfaceUnits units = face_units(s);
  const ViewFactorMatrix m = compute_view_factors(s, units, plain_options());
  EXPECT_GT(m.counters.partial, 0u);
  expect_reciprocal_nonnegative(m);
  for (int u = 0; u < m.n; ++u) {
    EXPECT_NEAR(m.row_sum(u), 1.0, 5 * m.sampling_error[u] + 1e-9) << u;
    for (int v = 0; v < m.n; ++v)
      EXPECT_LE(m.factor(u, v), unobstructed(s, units, u, v) * (1 + 1e-9) + 1e-15) << u << " " << v;
  }
}

// The exact visible region (--exact): no sampling; rows of the obstructed room close to the Gauss
// rule's accuracy, and each factor agrees with the sampled one within 5 of its sampling errors.
TEST(ViewFactorGuarantees, ExactRegionAgreesWithSampling) {
  Scene s = make_box(2, 1.5, 2, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  add_block(s, 0.7, 1.3, 0.5, 0.9, 0.7, 1.3, 0);
  ViewFactorOptions exact = plain_options();
  exact.pair.partial = PartialVisibility::kExactRegion;
  const ViewFactorMatrix e = compute_view_factors(s, face_units(s), exact);
  ViewFactorOptions sampled = plain_options();
  sampled.pair.fraction_error = 0.002;
  sampled.pair.max_rays = 1 << 16;
  const ViewFactorMatrix m = compute_view_factors(s, face_units(s), sampled);
  EXPECT_GT(e.counters.regions, 0u);
  expect_reciprocal_nonnegative(e);
  for (int u = 0; u < m.n; ++u) {
    EXPECT_EQ(e.sampling_error[u], 0.0);
    EXPECT_NEAR(e.row_sum(u), 1.0, 2e-3) << u;
    for (int v = 0; v < m.n; ++v)
      EXPECT_NEAR(e.factor(u, v), m.factor(u, v), 5 * m.sampling_error[u] + 1e-3 * m.factor(u, v) + 1e-12)
          << u << " " << v;
  }
}

// Unit independence: the same room in millimetres and in 1/1024 m gives the same factors to 1e-12
// relative (closed forms are scale-free; sampling seeds are relative to each patch).
TEST(ViewFactorGuarantees, IndependentOfUnitOfLength) {
  Scene s = make_box(4, 3, 5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 1.0, 2.5, 0.8, 1.7, 1.5, 3.0, 0);
  const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
  for (const double scale : {1000.0, 1.0 / 1024.0}) {
    const Scene t = scaled(s, scale);
    const ViewFactorMatrix n = compute_view_factors(t, face_units(t), plain_options());
    for (int u = 0; u < m.n; ++u)
      for (int v = 0; v < m.n; ++v)
        EXPECT_NEAR(n.factor(u, v), m.factor(u, v), 1e-12 + 1e-12 * m.factor(u, v)) << scale;
  }
}

// One thread or two: the same bits (pairs are merged in patch order).
TEST(ViewFactorGuarantees, SameBitsAtAnyThreadCount) {
  Scene s = make_box(2, 1, 1.5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 0.5, 1.2, 0.3, 0.6, 0.4, 0.9, 0);
  ViewFactorOptions one = plain_options(), two = plain_options();
  one.threads = 1;
  two.threads = 2;
  const ViewFactorMatrix a = compute_view_factors(s, face_units(s), one);
  const ViewFactorMatrix b = compute_view_factors(s, face_units(s), two);
  EXPECT_EQ(a.column, b.column);
  EXPECT_EQ(a.exchange, b.exchange);
}

// The row budget (--row-error): in a closed room with an obstacle every row must sum to 1 (the
// enclosure's closure, independent of the code), and the sampled rows do within 4 of the larger of
// the target and their reported error, with the same bits at any thread count.
TEST(ViewFactorGuarantees, RowErrorBudgetClosesRows) {
  Scene s = make_box(4, 3, 5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 1.0, 2.5, 0.8, 1.7, 1.5, 3.0, 0);
  ViewFactorOptions options = plain_options();
  options.row_error = 0.004;
  options.threads = 1;
  const ViewFactorMatrix m = compute_view_factors(s, face_units(s), options);
  ASSERT_GT(m.counters.partial, 0u);
  expect_reciprocal_nonnegative(m);
  for (int u = 0; u < m.n; ++u)
    EXPECT_NEAR(m.row_sum(u), 1.0, 4 * std::max(options.row_error, m.sampling_error[u])) << u;
  options.threads = 2;
  const ViewFactorMatrix b = compute_view_factors(s, face_units(s), options);
  EXPECT_EQ(m.column, b.column);
  EXPECT_EQ(m.exchange, b.exchange);
}

// Groups: A_I F_IJ is the sum of A_i F_ij over the faces of I and J (area-weighted), and a group
// of several walls sees itself.
TEST(ViewFactorGuarantees, GroupsAreAreaWeightedSums) {
  Scene s = make_box(2, 1, 1.5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  for (std::size_t f = 0; f < s.faces.size(); ++f) s.faces[f].group = f % 3 == 0 ? "a" : f % 3 == 1 ? "b" : "c";
  const SurfaceUnits faces = face_units(s), groups = group_units(s);
  const ViewFactorMatrix mf = compute_view_factors(s, faces, plain_options());
  const ViewFactorMatrix mg = compute_view_factors(s, groups, plain_options());
  ASSERT_EQ(mg.n, 3);
  for (int g = 0; g < 3; ++g) {
    EXPECT_NEAR(mg.row_sum(g), 1.0, 1e-9);
    for (int h = 0; h < 3; ++h) {
      double e = 0.0;
      for (int i = 0; i < mf.n; ++i)
        for (int j = 0; j < mf.n; ++j)
          if (groups.of_face[i] == g && groups.of_face[j] == h) e += mf.area[i] * mf.factor(i, j);
      EXPECT_NEAR(mg.area[g] * mg.factor(g, h), e, 1e-12 * mg.area[g]);
    }
  }
  expect_reciprocal_nonnegative(mg);
}

// The closure adjustment on a matrix whose rows do not close (sampled visibility): afterwards rows
// sum to 1 within 1e-12, A_u F_uv stays exactly symmetric, zeros stay zero, and it moves no factor
// by more than the rows were off. On a matrix that already closes it moves nothing.
TEST(ViewFactorGuarantees, EnforceClosureKeepsReciprocity) {
  Scene s = make_box(4, 3, 5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 1.0, 2.5, 0.8, 1.7, 1.5, 3.0, 0);
  ViewFactorOptions coarse = plain_options();
  coarse.pair.fraction_error = 0.05;
  coarse.pair.max_rays = 64;
  const ViewFactorMatrix before = compute_view_factors(s, face_units(s), coarse);
  ViewFactorMatrix m = before;
  const ClosureReport r = enforce_closure(m);
  EXPECT_GT(r.max_row_error_before, 1e-6);
  EXPECT_LE(r.max_row_error_after, 1e-12);
  EXPECT_EQ(r.clamped, 0);
  EXPECT_LE(r.max_factor_change, r.max_row_error_before);
  for (int u = 0; u < m.n; ++u) {
    EXPECT_NEAR(m.row_sum(u), 1.0, 1e-12);
    for (int v = 0; v < m.n; ++v) {
      EXPECT_EQ(m.area[u] * m.factor(u, v) / m.area[u], m.factor(u, v));
      EXPECT_EQ(before.factor(u, v) == 0.0, m.factor(u, v) == 0.0);
    }
  }
  expect_reciprocal_nonnegative(m);
  for (std::size_t k = 0; k < m.column.size(); ++k) EXPECT_GE(m.exchange[k], 0.0);

  const Scene box = make_box(1, 2, 3, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  ViewFactorMatrix closed = compute_view_factors(box, face_units(box), plain_options());
  const ClosureReport none = enforce_closure(closed);
  EXPECT_LE(none.max_factor_change, 1e-12);
}

// --threshold: pairs are dropped only where their unobstructed factor is below the threshold, and each
// row's reported bound covers what it lost: sum_v (F_full - F_pruned)_uv <= skipped_bound_u. The
// pairs that were kept have the same factors.
TEST(ViewFactorGuarantees, ThresholdBoundCoversSkippedFactors) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  detail::Rng rng(3);
  add_cut_rectangle(s, Vec3(0, 0, 0), Vec3(160, 0, 0), Vec3(0, 0, 160), Vec3::UnitY(), 8, rng, 0.3);  // ground
  for (int k = 0; k < 4; ++k) {
    const double x = 20 + 120 * (k % 2), z = 20 + 120 * (k / 2);
    add_block(s, x, x + 2, 0.5, 3 + k, z, z + 2, 0);  // floating: no contact with the ground
  }
  ViewFactorOptions pruned = plain_options();
  pruned.threshold = 1e-3;
  const ViewFactorMatrix full = compute_view_factors(s, face_units(s), plain_options());
  const ViewFactorMatrix cut = compute_view_factors(s, face_units(s), pruned);
  EXPECT_GT(cut.counters.skipped_pairs, 0u);
  expect_reciprocal_nonnegative(cut);
  for (int u = 0; u < full.n; ++u) {
    double lost = 0.0;
    for (int v = 0; v < full.n; ++v) {
      const double f = full.factor(u, v), g = cut.factor(u, v);
      if (g != 0.0)
        EXPECT_EQ(f, g);
      else
        lost += f;
      if (g == 0.0 && f > 0.0) EXPECT_LT(f, pruned.threshold + 5 * full.sampling_error[u]);
    }
    EXPECT_LE(lost, cut.skipped_bound[u] + 5 * full.sampling_error[u] + 1e-15) << u;
    EXPECT_LE(cut.row_sum(u), 1.0 + 5 * cut.sampling_error[u] + 1e-9);
  }
}

// Far pairs sampled (sample_below) and a row budget on random closed boxes cut into rectangles
// (T-junctions, coplanar neighbours, slivers) around a floating block: every guarantee holds with
// sampling on. 0 <= F; F <= the unobstructed closed form (evaluated here at its default accuracy);
// reciprocity within 1e-12; no row above 1 (+1e-9); rows none of whose pairs were sampled or dropped
// (if any) close to 1 within 1e-9; every row closes within 5 of its reported errors plus what it dropped and
// what the row cap took. With 16 rays per pair many sampled rows exceed 1 before the cap: those
// rows end at exactly 1.
TEST(ViewFactorGuarantees, SampledFarPairsKeepEveryGuarantee) {
  int capped_rows = 0;
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    Scene s = make_cut_box(2.0 + seed, 1.5, 1.0 + 0.5 * seed, 4, seed, 0.02);
    add_block(s, 0.6, 1.4, 0.4, 0.9, 0.3, 0.8, 0);
    const SurfaceUnits units = face_units(s);
    ViewFactorOptions options = plain_options();
    options.sample_below = 0.02;
    options.threshold = 1e-4;
    options.row_error = 0.05;
    options.pair.far_rays = 16;
    const ViewFactorMatrix m = compute_view_factors(s, units, options);
    ASSERT_GT(m.counters.shaft_skipped, 0u);
    ASSERT_GT(m.counters.partial, m.counters.shaft_skipped);
    expect_reciprocal_nonnegative(m);
    capped_rows += static_cast<int>(m.counters.capped_rows);
    for (int u = 0; u < m.n; ++u) {
      EXPECT_LE(m.row_sum(u), 1.0 + 1e-9) << seed << " " << u;
      EXPECT_NEAR(m.row_sum(u) + m.capped[u], 1.0, 5 * m.sampling_error[u] + m.skipped_bound[u] + 1e-9)
          << seed << " " << u;
      if (m.sampling_error[u] == 0.0 && m.skipped_bound[u] == 0.0 && m.capped[u] == 0.0)
        EXPECT_NEAR(m.row_sum(u), 1.0, 1e-9) << seed << " " << u;
      for (std::int64_t k = m.row_begin[u]; k < m.row_begin[u + 1]; ++k) {
        const int v = m.column[static_cast<std::size_t>(k)];
        const double f = polygon_to_polygon(s.patches[static_cast<std::size_t>(u)].vertices,
                                            s.patches[static_cast<std::size_t>(v)].vertices)
                             .from_to;
        EXPECT_LE(m.factor(u, k), f * (1 + 1e-9)) << seed << " " << u << " " << v;
      }
    }
  }
  EXPECT_GT(capped_rows, 0);
}

// The row cap on its own: closed rooms with a block, 16 rays per partly visible pair, so that
// sampled rows often exceed 1. Rows end at most at 1; each row that exceeded 1 ends at exactly 1
// (so at least capped_rows rows sum to 1 within 1e-12); what the cap took is reported and only
// rows with sampled pairs lose any; reciprocity stays within 1e-12.
TEST(ViewFactorGuarantees, RowCapBoundsRowsAtOne) {
  ViewFactorOptions options = plain_options();
  options.pair.min_rays = options.pair.max_rays = 16;
  int capped_total = 0;
  for (int seed = 0; seed < 4; ++seed) {
    Scene t = make_box(4, 3, 5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
    add_block(t, 1.0 + 0.1 * seed, 2.5, 0.8, 1.7, 1.5, 3.0 - 0.1 * seed, 0);
    const ViewFactorMatrix m = compute_view_factors(t, face_units(t), options);
    expect_reciprocal_nonnegative(m);
    int at_one = 0;
    for (int u = 0; u < m.n; ++u) {
      EXPECT_LE(m.row_sum(u), 1.0 + 1e-12) << u;
      at_one += std::abs(m.row_sum(u) - 1.0) <= 1e-12 ? 1 : 0;
      if (m.capped[u] > 0.0) EXPECT_GT(m.sampling_error[u], 0.0) << u;
      EXPECT_GE(m.capped[u], 0.0);
    }
    EXPECT_GE(at_one, static_cast<int>(m.counters.capped_rows));
    capped_total += static_cast<int>(m.counters.capped_rows);
  }
  EXPECT_GT(capped_total, 0);
}

}  // namespace
}  // namespace hrad::test
