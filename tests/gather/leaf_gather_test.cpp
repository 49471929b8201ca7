// The final gather over a solution's leaves (gather/leaf_gather.h) against closed forms, against
// itself leaf by leaf (the Barnes-Hut bound), and against the exact from-point visibility.
#include "hrad/gather/leaf_gather.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "../formfactor/howell.h"
#include "gather_test_scenes.h"
#include "hrad/core/error.h"
#include "hrad/core/rng.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/gather/from_point.h"

namespace hrad {
namespace {

using test::add_block;
using test::add_polygon;
using test::leaves_with;
using test::make_box;
using test::material;
using test::uniform_leaves;

// A unit-less square emitter [0, a]^2 at height c facing down, over a floor patch facing up; no
// other surface, so nothing occludes and the point-to-square factor is Howell's B-3 summed over the
// four rectangles that meet at the point's foot (each has the foot at a corner).
TEST(LeafGather, PointUnderASquareEmitterGathersHowellsFactor) {
  const double a = 2.0, c = 0.75, e = 3.0;
  const Scene s = test::square_emitter_over_floor(a, c, e);
  const Solution leaves =
      leaves_with(s, 0.05, [&](const Vec3&, int p) { return p == 1 ? Rgb(e, 2 * e, 0.5 * e) : Rgb::Constant(0.1); });
  for (double tolerance : {0.0, 1e-3}) {
    LeafGatherOptions o;
    o.tolerance = tolerance;
    const LeafGather gather(s, leaves, o);
    for (const auto& [u, v] : {std::pair{1.0, 1.0}, std::pair{0.3, 1.7}, std::pair{1.9, 0.05}}) {
      const double f = test::howell_b3(u, v, c) + test::howell_b3(a - u, v, c) + test::howell_b3(u, a - v, c) +
                       test::howell_b3(a - u, a - v, c);
      // On the floor patch, and the same point in space (no patch: it is classified, not paired).
      const std::vector<GatherPoint> points = {{Vec3(u, 0, v), Vec3::UnitY(), 0},
                                               {Vec3(u, 0.25, v), Vec3::UnitY(), -1}};
      const std::vector<Rgb> h = gather.gather(points);
      EXPECT_LT(test::relative_error(h[0][1], 2 * e * f), 1e-9) << u << "," << v;
      const double f_above = test::howell_b3(u, v, c - 0.25) + test::howell_b3(a - u, v, c - 0.25) +
                             test::howell_b3(u, a - v, c - 0.25) + test::howell_b3(a - u, a - v, c - 0.25);
      EXPECT_LT(test::relative_error(h[1][0], e * f_above), 1e-9);
      EXPECT_LT(test::relative_error(gather.radiosity(0, h[0])[2], 0.5 * 0.5 * e * f), 1e-9);
    }
  }
}

// A closed room with uniform emission E and reflectance rho has B = E / (1 - rho) everywhere, so
// the leaves carry it and every point gathers it: on a wall B(x) = E + rho H = E / (1 - rho); at any
// point inside, facing any way, H = B (its factors to the closed surface sum to 1). Walls meet in
// T-junctions so that leaves carry T-vertices.
TEST(LeafGather, ClosedRoomGathersTheClosedFormAtAnyPointFacingAnyWay) {
  const double rho = 0.6, e = 1.5, b = e / (1 - rho);
  const Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0}, true);
  const Solution leaves = leaves_with(
      box, 0.2, [&](const Vec3&, int) { return Rgb::Constant(b); }, [](int p) { return p % 2 ? 1.0 : 0.1; });
  detail::Rng rng(7);
  std::vector<GatherPoint> points;
  for (int i = 0; i < 40; ++i) {
    const Vec3 x(rng.uniform(0.05, 2.95), rng.uniform(0.05, 2.45), rng.uniform(0.05, 3.95));
    const double z = rng.uniform(-1, 1), phi = 2 * std::numbers::pi * rng.uniform();
    points.push_back({x, Vec3(std::sqrt(1 - z * z) * std::cos(phi), z, std::sqrt(1 - z * z) * std::sin(phi)), -1});
  }
  for (std::size_t p = 0; p < box.patches.size(); ++p) {
    const Patch& patch = box.patches[p];
    const Vec3 x = 0.3 * patch.vertices[0] + 0.5 * patch.vertices[1] + 0.2 * patch.vertices[2];
    points.push_back({x, patch.normal, static_cast<int>(p)});
  }
  for (double tolerance : {0.0, 1e-3}) {
    LeafGatherOptions o;
    o.tolerance = tolerance;
    const LeafGather gather(box, leaves, o);
    const std::vector<Rgb> h = gather.gather(points);
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_LT(test::relative_error(h[i][0], b), 1e-9) << i;
      if (points[i].patch >= 0)
        EXPECT_LT(test::relative_error(gather.radiosity(points[i].patch, h[i])[0], b), 1e-9) << i;
    }
  }
}

// The Barnes-Hut gather differs from the leaf-by-leaf one by at most its per-point bound, and the
// bound by at most tolerance * B_mean * sum of the factors (1 in a convex room): the guarantee of
// leaf_gather.h, where visibility is exact (a convex room: nothing occludes). The field varies
// smoothly and steeply enough that the two differ, and leaves are grouped (else the test is empty).
TEST(LeafGather, BarnesHutStaysWithinItsBoundOfTheLeafByLeafGather) {
  const Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  const Solution leaves = leaves_with(
      box, 0.01,
      [](const Vec3& y, int p) {
        return Rgb(1.0 + 0.5 * std::sin(2 * y.x() + y.z()), 0.7 + 0.2 * std::cos(3 * y.y()), 0.1 * p + 0.2 * y.z());
      },
      [](int p) { return p == 2 ? 0.25 : 1.0; });
  detail::Rng rng(3);
  std::vector<GatherPoint> points;
  for (std::size_t p = 0; p < box.patches.size(); ++p)
    for (int k = 0; k < 6; ++k) {
      const Patch& patch = box.patches[p];
      const double s = rng.uniform(), t = rng.uniform();
      const Vec3 x =
          patch.vertices[0] + s * (patch.vertices[1] - patch.vertices[0]) + t * (patch.vertices[3] - patch.vertices[0]);
      points.push_back({x, patch.normal, static_cast<int>(p)});
    }
  LeafGatherOptions exact;
  exact.tolerance = 0.0;
  const std::vector<Rgb> reference = LeafGather(box, leaves, exact).gather(points);
  for (double tolerance : {1e-3, 1e-2, 1e-1}) {
    LeafGatherOptions o;
    o.tolerance = tolerance;
    const LeafGather gather(box, leaves, o);
    std::vector<double> bound;
    const std::vector<Rgb> h = gather.gather_with_bounds(points, &bound);
    double largest_difference = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double difference = (h[i] - reference[i]).abs().maxCoeff();
      largest_difference = std::max(largest_difference, difference);
      EXPECT_LE(difference, bound[i] + 1e-12 * reference[i].abs().maxCoeff()) << tolerance << " " << i;
      EXPECT_LE(bound[i], tolerance * gather.mean_radiosity() * (1 + 1e-12)) << tolerance << " " << i;
    }
    const GatherWork w = gather.work();
    EXPECT_GT(largest_difference, 0.0) << tolerance;
    EXPECT_LT(w.nodes_gathered, w.leaves_covered) << tolerance;
    if (tolerance >= 0.1) EXPECT_LT(w.nodes_gathered * 4, w.leaves_covered);  // four leaves a node on average
  }
}

// With exact from-point visibility (visible regions) the bound holds around an occluder too, and
// the leaf-by-leaf gather with sampled visibility (per leaf, and rays shared over the point) agrees
// with the exact one within its sampling error.
TEST(LeafGather, OccludedRoomAgreesWithExactVisibility) {
  Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  add_block(box, 1.0, 2.0, 0.8, 1.4, 1.5, 2.5, 0);
  const Solution leaves = leaves_with(box, 0.25, [](const Vec3& y, int) {
    return Rgb(1.0 + 0.3 * std::sin(2 * y.x() + y.z()), 1.0, 0.5 + 0.1 * y.y());
  });
  const std::vector<GatherPoint> points = {{Vec3(1.4, 0, 2.1), Vec3::UnitY(), 0},
                                           {Vec3(0.2, 0, 0.5), Vec3::UnitY(), 0},
                                           {Vec3(1.6, 2.0, 1.2), Vec3(0.2, -1, 0.3).normalized(), -1}};
  LeafGatherOptions o;
  o.visibility = VisibilityMode::exact;
  o.tolerance = 0.0;
  const std::vector<Rgb> exact = LeafGather(box, leaves, o).gather(points);
  o.tolerance = 0.05;
  const LeafGather grouped(box, leaves, o);
  std::vector<double> bound;
  const std::vector<Rgb> h = grouped.gather_with_bounds(points, &bound);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_LE((h[i] - exact[i]).abs().maxCoeff(), bound[i] + 1e-12) << i;
  // Sampled visibility, 256 points per partly visible leaf (kernel-weighted fraction): within 1%.
  LeafGatherOptions sampled;
  sampled.tolerance = 0.0;
  sampled.visibility_samples = 256;
  const std::vector<Rgb> per_leaf = LeafGather(box, leaves, sampled).gather(points);
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_LT((per_leaf[i] - exact[i]).abs().maxCoeff(), 1e-2 * exact[i].maxCoeff()) << i;
}

// Sampled per node, a partly visible node is opened to its leaves however uniform it is, so with
// one radiosity per patch (the grouping's bound is 0) the grouped gather is the leaf-by-leaf one to
// rounding: the same leaves, the same seeds, the same points, wherever visibility is partial. A
// uniform light gathered whole and sampled with k points instead resolved the occluder's shadow
// edge across it k times more coarsely than the leaves do.
TEST(LeafGather, PartlyVisibleNodesAreSampledLeafByLeaf) {
  Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  add_block(box, 1.0, 2.0, 0.8, 1.4, 1.5, 2.5, 0);
  const Solution leaves =
      leaves_with(box, 0.1, [](const Vec3&, int p) { return Rgb(1.0 + 0.1 * p, 1.0, 2.0 - 0.05 * p); });
  const std::vector<GatherPoint> points = {{Vec3(1.4, 0, 2.1), Vec3::UnitY(), 0},
                                           {Vec3(0.9, 0, 1.3), Vec3::UnitY(), 0},
                                           {Vec3(1.6, 0.5, 1.2), Vec3(0.2, 1, 0.3).normalized(), -1}};
  for (bool classify : {true, false}) {
    LeafGatherOptions o;
    o.classify_points = classify;
    o.visibility_samples = 16;
    o.tolerance = 0.0;
    const LeafGather by_leaf(box, leaves, o);
    const std::vector<Rgb> reference = by_leaf.gather(points);
    o.tolerance = 0.05;
    const LeafGather grouped(box, leaves, o);
    const std::vector<Rgb> h = grouped.gather(points);
    for (std::size_t i = 0; i < points.size(); ++i)
      EXPECT_LT((h[i] - reference[i]).abs().maxCoeff(), 1e-12 * reference[i].maxCoeff()) << classify << " " << i;
    EXPECT_EQ(grouped.work().rays, by_leaf.work().rays) << classify;                      // the same samples
    EXPECT_GT(grouped.work().rays, 0u) << classify;                                       // some leaf is partly visible
    EXPECT_LT(grouped.work().nodes_gathered, by_leaf.work().nodes_gathered) << classify;  // and some grouping happened
  }
}

// The shared rays (PartialSampling::shared, the image's estimator) are unbiased: over many
// seeds their mean approaches the exact gather within a few standard errors, at a point whose
// view of several patches is partly blocked.
// Shared rays are allocated by systematic sampling: every entry gets the integer part of its
// expected count m w_i / W or one more, the counts sum to m, and over many offsets each entry's
// mean count is its expected count (to the Monte Carlo error of 4000 draws).
TEST(LeafGather, SystematicCountsKeepEachEntrysExpectedCount) {
  const std::vector<double> w = {0.5, 3.0, 0.0, 1.25, 7.0, 0.05};
  const double total = 11.8;
  const int m = 37;
  std::vector<double> mean(w.size(), 0.0);
  std::vector<int> counts;
  const int draws = 4000;
  for (int d = 0; d < draws; ++d) {
    EXPECT_DOUBLE_EQ(detail::systematic_counts(w, m, static_cast<std::uint64_t>(d), &counts), total / m);
    int sum = 0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      const double expected = m * w[i] / total;
      EXPECT_GE(counts[i], std::floor(expected)) << i;
      EXPECT_LE(counts[i], std::ceil(expected)) << i;
      sum += counts[i];
      mean[i] += counts[i] / double(draws);
    }
    EXPECT_EQ(sum, m);
  }
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(mean[i], m * w[i] / total, 0.05) << i;
  EXPECT_EQ(detail::systematic_counts(std::vector<double>{0.0, 0.0}, m, 1, &counts), 0.0);
  EXPECT_EQ(counts, (std::vector<int>{0, 0}));
}

TEST(LeafGather, SharedRaysAreUnbiased) {
  Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  add_block(box, 1.0, 2.0, 0.0, 1.4, 1.5, 2.5, 0);
  const Solution leaves = leaves_with(box, 0.25, [](const Vec3& y, int) { return Rgb::Constant(1.0 + 0.3 * y.y()); });
  const std::vector<GatherPoint> point = {{Vec3(1.3, 0, 1.2), Vec3::UnitY(), 0}};
  LeafGatherOptions o;
  o.visibility = VisibilityMode::exact;
  const double exact = LeafGather(box, leaves, o).gather(point)[0][0];
  o.visibility = VisibilityMode::sampled;
  o.partial = PartialSampling::shared;
  o.classify_points = false;
  o.visibility_samples = 8;
  double sum = 0.0, sum2 = 0.0;
  const int runs = 400;
  for (int seed = 1; seed <= runs; ++seed) {
    o.seed = static_cast<std::uint64_t>(seed);
    const double v = LeafGather(box, leaves, o).gather(point)[0][0];
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / runs, se = std::sqrt((sum2 / runs - mean * mean) / (runs - 1));
  EXPECT_GT(se, 0.0);  // the point does see partly blocked leaves
  EXPECT_LT(std::abs(mean - exact), 4 * se) << mean << " vs " << exact << " se " << se;
}

// A point's value does not depend on the batch it comes in, its place there, or the thread count.
TEST(LeafGather, SamePointSameValueInAnyBatch) {
  Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  add_block(box, 1.0, 2.0, 0.0, 1.4, 1.5, 2.5, 0);
  const Solution leaves = leaves_with(box, 0.1, [](const Vec3& y, int) { return Rgb::Constant(1.0 + 0.3 * y.y()); });
  LeafGatherOptions o;
  o.partial = PartialSampling::shared;
  o.classify_points = false;
  const LeafGather gather(box, leaves, o);
  std::vector<GatherPoint> points;
  for (int i = 0; i < 64; ++i) points.push_back({Vec3(0.1 + 0.04 * i, 0, 0.3 + 0.05 * i), Vec3::UnitY(), 0});
  const std::vector<Rgb> all = gather.gather(points);
  const std::vector<GatherPoint> one = {points[37]};
  EXPECT_TRUE((gather.gather(one)[0] == all[37]).all());
  std::vector<GatherPoint> reversed(points.rbegin(), points.rend());
  const std::vector<Rgb> back = gather.gather(reversed);
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_TRUE((back[points.size() - 1 - i] == all[i]).all()) << i;
}

// The quadtree rebuilt from the leaves alone: every leaf of a mesh made by the hierarchy's splits
// finds its region, every region is tiled, and each root's mean is its patch's area mean.
TEST(LeafQuadtrees, RebuildTheHierarchyFromItsLeaves) {
  const Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  const Solution leaves = leaves_with(
      box, 0.05, [](const Vec3& y, int) { return Rgb(1 + y.x(), 1 + y.y(), 1 + y.z()); },
      [](int p) { return 1.0 + p; });
  const detail::LeafQuadtrees trees(box, leaves);
  EXPECT_EQ(trees.unplaced_leaves(), 0u);
  std::size_t leaf_nodes = 0;
  for (std::size_t i = 0; i < trees.size(); ++i) {
    EXPECT_TRUE(trees.node(static_cast<int>(i)).tiled) << i;
    leaf_nodes += trees.node(static_cast<int>(i)).is_leaf();
  }
  EXPECT_EQ(leaf_nodes, leaves.faces.size());
  for (std::size_t p = 0; p < box.patches.size(); ++p) {
    Rgb sum = Rgb::Zero();
    double area = 0.0;
    for (std::size_t f = 0; f < leaves.faces.size(); ++f) {
      if (leaves.face_patch[f] != static_cast<int>(p)) continue;
      std::vector<Vec3> poly;
      for (int v : leaves.faces[f]) poly.push_back(leaves.vertices[static_cast<std::size_t>(v)]);
      sum += polygon_area(poly) * leaves.face_radiosity[f];
      area += polygon_area(poly);
    }
    const detail::LeafQuadtreeNode& root = trees.node(trees.root(static_cast<int>(p)));
    EXPECT_NEAR(root.area, box.patches[p].area, 1e-12 * box.patches[p].area);
    EXPECT_LT(((root.mean - sum / area).abs() / (sum / area).abs()).maxCoeff(), 1e-12);
  }
}

// A mesh not made by those splits (leaves cut along a diagonal) still reaches every leaf: leaves no
// region contains hang from the root, which is then gathered leaf by leaf (not tiled by regions).
TEST(LeafQuadtrees, ForeignMeshesKeepEveryLeaf) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, Vec3::UnitY(), 0);
  Solution leaves;
  leaves.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  leaves.faces = {{0, 1, 2}, {0, 2, 3}};
  leaves.face_patch = {0, 0};
  leaves.face_radiosity = {Rgb::Constant(1.0), Rgb::Constant(3.0)};
  const detail::LeafQuadtrees trees(s, leaves);
  EXPECT_EQ(trees.unplaced_leaves(), 2u);
  const detail::LeafQuadtreeNode& root = trees.node(trees.root(0));
  EXPECT_EQ(root.leaves, 2u);
  EXPECT_TRUE(root.tiled);  // the two triangles cover the square
  EXPECT_DOUBLE_EQ(root.mean[0], 2.0);
  EXPECT_DOUBLE_EQ(root.mean_deviation[0], 1.0);
}

TEST(LeafGather, BadOptionsNameTheOption) {
  LeafGatherOptions o;
  o.tolerance = -1;
  EXPECT_THROW(validate_leaf_gather_options(o), Error);
  try {
    validate_leaf_gather_options(o);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--gather-tolerance"), std::string::npos);
  }
  o.tolerance = 0;
  o.visibility_samples = 0;
  try {
    validate_leaf_gather_options(o);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--visibility-samples"), std::string::npos);
  }
}

}  // namespace
}  // namespace hrad
