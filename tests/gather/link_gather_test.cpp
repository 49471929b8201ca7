// The final gather through a hierarchical solve's links (gather/link_gather.h) against closed forms
// and against the all-patches gather (gather/leaf_gather.h), with its work counted per point.
#include "hrad/gather/link_gather.h"

#include <cmath>
#include <limits>
#include <set>

#include <gtest/gtest.h>

#include "../formfactor/howell.h"
#include "gather_test_scenes.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/core/error.h"
#include "hrad/core/rng.h"
#include "hrad/gather/leaf_gather.h"
#include "hrad/io/obj_reader.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

using test::make_box;
using test::material;

using test::solve_keeping;

// Gathers the points one at a time and checks that each evaluated at most one point factor per link
// on its leaf's path (per patch of a cluster source) when sources are gathered whole.
std::vector<Rgb> gather_counting(const LinkGather& gather, const SolvedHierarchy& kept,
                                 std::span<const GatherPoint> points, bool whole) {
  std::vector<Rgb> h;
  for (const GatherPoint& p : points) {
    const GatherWork before = gather.work();
    h.push_back(gather.gather(std::span<const GatherPoint>(&p, 1))[0]);
    const GatherWork done = gather.work() - before;
    const NodeId leaf = gather.leaf_at(p.patch, p.position);
    EXPECT_EQ(done.points, 1u);
    if (whole) EXPECT_LE(done.node_visits, gather.sources_on_path(leaf));
    if (!kept.tree) EXPECT_EQ(gather.sources_on_path(leaf), gather.links_on_path(leaf));
  }
  return h;
}

// A closed room with uniform emission E and reflectance rho has B = E / (1 - rho) everywhere. Every
// node of a solve's hierarchy is given that value, so what is tested is the gather: the sources of
// a leaf's path tile every other patch, so its point factors sum to 1 and B(x) = E + rho H = B, as
// the all-patches gather finds. Walls meet in T-junctions; the hierarchy is refined unevenly.
TEST(LinkGather, ClosedRoomGathersTheClosedFormAsTheAllPatchesGather) {
  const double rho = 0.6, e = 1.5, b = e / (1 - rho);
  const Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0}, true);
  for (const Clustering clustering : {Clustering::kOff, Clustering::kOn}) {
    SolveOptions o;
    o.clustering = clustering;
    o.feps = 0.003;
    Solution solution;
    SolvedHierarchy kept = solve_keeping(box, o, &solution);
    ASSERT_GT(kept.links.size(), box.patches.size());
    for (std::size_t i = 0; i < kept.hierarchy->size(); ++i)
      kept.hierarchy->node(static_cast<NodeId>(i)).radiosity = Rgb::Constant(b);
    for (Rgb& f : solution.face_radiosity) f = Rgb::Constant(b);
    detail::Rng rng(3);
    std::vector<GatherPoint> points;
    for (std::size_t p = 0; p < box.patches.size(); ++p)
      for (int k = 0; k < 6; ++k) {
        const Patch& patch = box.patches[p];
        const double u = rng.uniform(), v = rng.uniform() * (1 - u);
        const Vec3 x = patch.vertices[0] + u * (patch.vertices[1] - patch.vertices[0]) +
                       v * (patch.vertices[3] - patch.vertices[0]);
        points.push_back({x, patch.normal, static_cast<int>(p)});
      }
    const LeafGather all(box, solution);
    for (const double tolerance : {std::numeric_limits<double>::infinity(), 0.0}) {
      LinkGatherOptions o;
      o.tolerance = tolerance;
      o.open_partly_visible = false;
      const LinkGather links(box, kept, o);
      const std::vector<Rgb> h = gather_counting(links, kept, points, std::isinf(tolerance));
      const std::vector<Rgb> reference = all.gather(points);
      for (std::size_t i = 0; i < points.size(); ++i) {
        EXPECT_LT(test::relative_error(links.radiosity(points[i].patch, h[i])[0], b), 1e-9) << i;
        EXPECT_LT(test::relative_error(h[i][0], reference[i][0]), 1e-9) << i;
      }
    }
  }
}

// A square emitter [0, a]^2 at height c facing down over a floor: the emitter reflects nothing, so
// each of its nodes shows B = E, and a point on the floor gathers E times Howell's factor (B-3 summed
// over the four rectangles meeting at the point's foot), however the links split the emitter.
TEST(LinkGather, PointUnderASquareEmitterGathersHowellsFactor) {
  const test::SolvedSquareEmitter solved = test::solved_square_emitter();
  const double a = solved.a, c = solved.c, e = solved.e;
  const Scene& s = solved.scene;
  const Solution& solution = solved.solution;
  const SolvedHierarchy& kept = solved.kept;
  const LinkGather gather(s, kept);
  std::vector<GatherPoint> points;
  std::vector<double> factors;
  for (const auto& [u, v] : {std::pair{1.0, 1.0}, std::pair{0.3, 1.7}, std::pair{1.9, 0.05}, std::pair{-2.0, 4.0}}) {
    points.push_back({Vec3(u, 0, v), Vec3::UnitY(), 0});
    factors.push_back(test::howell_b3(u, v, c) + test::howell_b3(a - u, v, c) + test::howell_b3(u, a - v, c) +
                      test::howell_b3(a - u, a - v, c));
  }
  // The emitter's radiosity is uniform: its sources are gathered whole at any tolerance.
  const std::vector<Rgb> h = gather_counting(gather, kept, points, true);
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_LT(test::relative_error(h[i][1], 2 * e * factors[i]), 1e-9) << i;
    EXPECT_LT(test::relative_error(gather.radiosity(0, h[i])[2], 0.5 * 0.5 * e * factors[i]), 1e-9) << i;
  }
  // Points in space have no leaf: refused without an all-patches gather, handed to it with one.
  const std::vector<GatherPoint> in_space = {{Vec3(1, 0.25, 1), Vec3::UnitY(), -1}};
  EXPECT_THROW(gather.gather(in_space), Error);
  const LeafGather all(s, solution);
  const LinkGather with_space(s, kept, {}, &all);
  EXPECT_EQ(with_space.gather(in_space)[0][0], all.gather(in_space)[0][0]);
}

const Scene& cornell() {
  static const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return s;
}

// The default hierarchical solve of the Cornell box (518 leaves), gathered at the error samples
// both ways, each point's reflected light rho H compared in relative L2:
//  * at the defaults (rays shared by a point's partly visible sources, decided from its leaf) and
//    per source (64 points on each, classified from the point) the two gathers estimate the same
//    sum (every source's leaves under the same Barnes-Hut tolerance, visibility from the point),
//    each with its own visibility samples, so they differ by their sampling noise: at most the two
//    gathers' own differences between two seeds added (two unbiased estimates with noise s1, s2
//    differ by about sqrt(s1^2 + s2^2), and one seed change by sqrt(2) s); a systematic difference
//    (a source missed or counted twice, a link's or a leaf's visibility trusted where it does not
//    hold) of that size fails;
//  * with every source whole and only the links' own visibility (one point factor per link on the
//    path: counted), the coarse sources' mean radiosity costs accuracy: within the 2% the gathered
//    field is to reach against the reference, with fewer factors than the all-patches gather.
TEST(LinkGather, CornellBoxAgreesWithTheAllPatchesGather) {
  Solution solution;
  const SolvedHierarchy kept = solve_keeping(cornell(), SolveOptions{}, &solution);
  const std::vector<SurfaceSample> samples = patch_samples(cornell(), 16);
  std::vector<GatherPoint> points;
  for (const SurfaceSample& s : samples)
    points.push_back({s.position, cornell().patches[static_cast<std::size_t>(s.patch)].normal, s.patch});
  const auto reflected = [&](std::vector<Rgb> h) {
    for (std::size_t i = 0; i < points.size(); ++i)
      h[i] *= cornell().material_of(cornell().patches[static_cast<std::size_t>(points[i].patch)]).reflectance;
    return h;
  };
  const auto l2 = [&](const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    return compare_at_samples(cornell(), samples, a, b).relative_l2;
  };
  LeafGatherOptions other_seed;
  other_seed.seed = 2;
  const LeafGather all(cornell(), solution);
  const std::vector<Rgb> h_all = reflected(all.gather(points));
  const std::vector<Rgb> h_all_2 = reflected(LeafGather(cornell(), solution, other_seed).gather(points));

  EXPECT_GT(l2(h_all, h_all_2), 0.0);  // the visibility is sampled: the bound is not zero
  LinkGatherOptions per_source;
  per_source.partial = PartialSampling::per_node;
  per_source.visibility_samples = 64;
  per_source.classify_points = true;
  for (const LinkGatherOptions& o : {LinkGatherOptions{}, per_source}) {
    LinkGatherOptions o_2 = o;
    o_2.seed = 2;
    const LinkGather links(cornell(), kept, o);
    const std::vector<Rgb> h_links = reflected(links.gather(points));
    const std::vector<Rgb> h_links_2 = reflected(LinkGather(cornell(), kept, o_2).gather(points));
    const double noise = l2(h_all, h_all_2) + l2(h_links, h_links_2);
    std::printf(
        "%s: link vs all-patches gather %.4g (seed to seed: all-patches %.4g, links %.4g); rays per point %.0f "
        "vs %.0f\n",
        o.partial == PartialSampling::shared ? "shared rays" : "per source", l2(h_links, h_all), l2(h_all, h_all_2),
        l2(h_links, h_links_2), double(links.work().rays) / points.size(), double(all.work().rays) / points.size());
    EXPECT_LE(l2(h_links, h_all), noise);
  }

  LinkGatherOptions whole;
  whole.tolerance = std::numeric_limits<double>::infinity();
  whole.open_partly_visible = false;
  whole.gather_uncovered = false;
  const LinkGather coarse(cornell(), kept, whole);
  const std::vector<Rgb> h_whole = reflected(gather_counting(coarse, kept, points, true));
  std::printf("whole sources: link vs all-patches gather %.4g; factors per point %.1f vs %.1f\n", l2(h_whole, h_all),
              double(coarse.work().node_visits) / points.size(), double(all.work().node_visits) / points.size());
  EXPECT_LT(coarse.work().node_visits, all.work().node_visits);
  EXPECT_LT(l2(h_whole, h_all), 0.02);
}

// A leaf's points share its classifications (each source once from the leaf, not once per point),
// not their values: gathered together, points on the Cornell box's floor around the blocks (where
// sources are partly visible) get exactly what each gets gathered alone, with fewer shaft tests.
TEST(LinkGather, PointsOfALeafShareItsClassificationsNotTheirValues) {
  Solution solution;
  const SolvedHierarchy kept = solve_keeping(cornell(), SolveOptions{}, &solution);
  std::vector<GatherPoint> points;
  int floor = -1;
  for (std::size_t q = 0; q < cornell().patches.size(); ++q)
    if (cornell().patches[q].normal.y() > 0.99 &&
        (floor < 0 || cornell().patches[q].area > cornell().patches[static_cast<std::size_t>(floor)].area))
      floor = static_cast<int>(q);
  ASSERT_GE(floor, 0);
  for (const SurfaceSample& s : patch_samples(cornell(), 144))
    if (s.patch == floor) points.push_back({s.position, Vec3::UnitY(), s.patch});
  const LinkGather together(cornell(), kept), alone(cornell(), kept);
  const std::vector<Rgb> h = together.gather(points);
  std::set<NodeId> leaves;
  for (std::size_t i = 0; i < points.size(); ++i) {
    leaves.insert(together.leaf_at(points[i].patch, points[i].position));
    const Rgb single = alone.gather(std::span<const GatherPoint>(&points[i], 1))[0];
    for (int c = 0; c < 3; ++c) EXPECT_EQ(h[i][c], single[c]) << i;
  }
  ASSERT_LT(leaves.size(), points.size());  // some leaf holds several points
  EXPECT_GT(together.work().rays, 0u);      // some source is partly visible
  EXPECT_EQ(together.work().rays, alone.work().rays);
  EXPECT_LT(together.work().classifications, alone.work().classifications);
}

// With each point classifying its partly visible sources (classify_points) and sampling each on its
// own (per_node), a point's value does not depend on whether its leaf classified a source first
// (the leaf's shaft holds the point's; where the leaf is decisive the point's samples all agree), so
// the values are the same when every leaf classifies first, when none does, and when each point is
// gathered alone; only the shaft tests differ. Points on the Cornell box's floor and the blocks'
// tops, where sources are partly visible. Every source is gathered leaf by leaf (tolerance 0): a
// point's own test may find partly visible a source that its leaf's shaft settled as fully visible
// (a link is partial until a shaft proves it visible), and the opening bound, which counts a partly
// visible source's kernel from 0, would then open it further than the leaf-first walk does.
TEST(LinkGather, ClassifyingFromTheLeafFirstOrNotGivesTheSameValues) {
  Solution solution;
  const SolvedHierarchy kept = solve_keeping(cornell(), SolveOptions{}, &solution);
  std::vector<GatherPoint> points;
  for (const SurfaceSample& s : patch_samples(cornell(), 144))
    if (cornell().patches[static_cast<std::size_t>(s.patch)].normal.y() > 0.99)
      points.push_back({s.position, Vec3::UnitY(), s.patch});
  LinkGatherOptions leaf_first, point_first;
  leaf_first.classify_points = point_first.classify_points = true;
  leaf_first.tolerance = point_first.tolerance = 0.0;
  leaf_first.visibility_samples = point_first.visibility_samples = 64;
  leaf_first.partial = point_first.partial = PartialSampling::per_node;
  leaf_first.leaf_first_points = 1;
  point_first.leaf_first_points = std::numeric_limits<int>::max();
  const LinkGather a(cornell(), kept, leaf_first), b(cornell(), kept, point_first);
  const std::vector<Rgb> ha = a.gather(points), hb = b.gather(points);
  LinkGatherOptions defaults_classified;
  defaults_classified.classify_points = true;
  defaults_classified.tolerance = 0.0;
  defaults_classified.visibility_samples = 64;
  defaults_classified.partial = PartialSampling::per_node;
  const LinkGather one(cornell(), kept, defaults_classified);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Rgb single = one.gather(std::span<const GatherPoint>(&points[i], 1))[0];
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(ha[i][c], hb[i][c]) << i;
      EXPECT_EQ(ha[i][c], single[c]) << i;
    }
  }
  EXPECT_GT(a.work().rays, 0u);  // some source is partly visible
  // A source its leaf settled may be only possibly partly visible to the point's own test, and sampled.
  EXPECT_LE(a.work().rays, b.work().rays);
  EXPECT_NE(a.work().classifications, b.work().classifications);
}

TEST(LinkGather, BadOptionsNameTheOption) {
  const Scene box = make_box(1, 1, 1, {material(Rgb::Constant(0.5), Rgb::Constant(1.0))}, {0, 0, 0, 0, 0, 0});
  Solution solution;
  const SolvedHierarchy kept = solve_keeping(box, SolveOptions{}, &solution);
  for (const auto& [tolerance, samples, option] :
       {std::tuple{-1.0, 64, "--gather-tolerance"}, std::tuple{std::nan(""), 64, "--gather-tolerance"},
        std::tuple{0.01, 0, "--visibility-samples"}}) {
    LinkGatherOptions o;
    o.tolerance = tolerance;
    o.visibility_samples = samples;
    try {
      const LinkGather gather(box, kept, o);
      ADD_FAILURE() << option;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(LinkGather(box, SolvedHierarchy{}), Error);
}

}  // namespace
}  // namespace hrad
