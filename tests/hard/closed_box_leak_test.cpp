// Closed boxes of zero-thickness walls (closed_box_scenes.h): no light gets into a closed box lit
// from outside, none out of a closed crate lit from inside, for every method, whatever the
// tessellation, the angles and where the light comes from. The expected radiosity is exactly 0:
// every path from the light to the other side of the walls crosses them, and the visibility
// oracle decides each crossing exactly on points that lie exactly on their patches
// (Visibility::segment_blocked(), sight()). A box with a real opening is the control: light gets
// in, so the tests can fail.
#include <gtest/gtest.h>

#include <random>

#include "closed_box_scenes.h"
#include "hrad/solvers/solve.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/visibility.h"

namespace hrad {
namespace {

using test::LeakScene;

SolveOptions method(Method m, double max_area) {
  SolveOptions o;
  o.method = m;
  o.max_area = max_area;
  o.patch_area = 4 * max_area;  // substructuring: shooting patches are elements' parents, also rounded
  o.aeps = max_area / 4;
  o.clustering = Clustering::kOff;  // element links only: cluster links are tested below
  o.visibility_samples = 16;        // exactness does not depend on how many pairs are sampled
  return o;
}

double largest(const Solution& sol, const std::vector<int>& patches) {
  double b = 0.0;
  for (int p : patches) b = std::max(b, sol.patch_radiosity[static_cast<std::size_t>(p)].maxCoeff());
  return b;
}

double mean(const Solution& sol, const Scene& s, const std::vector<int>& patches) {
  double sum = 0.0, area = 0.0;
  for (int p : patches) {
    sum += s.patches[static_cast<std::size_t>(p)].area * sol.patch_radiosity[static_cast<std::size_t>(p)].mean();
    area += s.patches[static_cast<std::size_t>(p)].area;
  }
  return sum / area;
}

struct Case {
  Vec3 size;  ///< dyadic
  int cells;
  int frame;  ///< leak_frame()
  Vec3 shift;
  std::uint64_t seed;
};

// Sizes, tessellations and frames of the boxes (closed_box_scenes.h).
const Case kCases[] = {{{1.0, 1.3125, 0.875}, 2, 0, {0.25, -0.125, 0.75}, 1},
                       {{0.375, 2.125, 0.75}, 3, 1, {-1.5, 0.5, 0.25}, 3},
                       {{3.0, 2.0, 5.0}, 2, 2, {0.0, 2.0, -1.0}, 4}};

// Guarantee: the inside of a closed box lit from outside (directly and by a large reflecting
// ground under it) stays exactly dark, with the full matrix, substructuring and hierarchical
// radiosity; its outside faces are lit (not vacuous).
TEST(ClosedBoxes, NoLightGetsIntoABoxLitFromOutside) {
  for (const Case& c : kCases) {
    const LeakScene s =
        test::box_above_ground(c.size, 0.3 * c.size.z(), 1.5, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
    const double element = s.scene.total_area() / 100;
    for (Method m : {Method::kFull, Method::kSubstructure, Method::kHierarchical}) {
      Solution sol;
      solve(s.scene, method(m, element), &sol);
      EXPECT_EQ(largest(sol, s.inside), 0.0) << to_string(m) << " seed " << c.seed;
      EXPECT_GT(mean(sol, s.scene, s.outside), 1e-3) << to_string(m) << " seed " << c.seed;
      EXPECT_GT(mean(sol, s.scene, s.around), 1e-3) << to_string(m) << " seed " << c.seed;
    }
  }
}

// Guarantee: a lamp inside a closed crate lights nothing outside it: the room and the crate's
// outside faces stay exactly dark for every method; the crate's inside is lit.
TEST(ClosedBoxes, NoLightGetsOutOfACrateLitFromInside) {
  for (const Case& c : {kCases[0], kCases[2]}) {
    const LeakScene s = test::crate_in_room(c.size, 1.5, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
    const double element = s.scene.total_area() / 100;
    for (Method m : {Method::kFull, Method::kSubstructure, Method::kHierarchical}) {
      Solution sol;
      solve(s.scene, method(m, element), &sol);
      EXPECT_EQ(largest(sol, s.around), 0.0) << to_string(m) << " seed " << c.seed;
      EXPECT_EQ(largest(sol, s.outside), 0.0) << to_string(m) << " seed " << c.seed;
      EXPECT_GT(mean(sol, s.scene, s.inside), 1e-3) << to_string(m) << " seed " << c.seed;
    }
  }
}

// Control: the same boxes with one wall triangle (and its twin) removed let light in, so the
// tests above would see a leak.
TEST(ClosedBoxes, ABoxWithAnOpeningLetsLightIn) {
  for (const Case& c : {kCases[0], kCases[1]}) {
    LeakScene s =
        test::box_above_ground(c.size, 0.3 * c.size.z(), 1.5, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
    // A triangle of the lid (the last wall), which the light above sees.
    test::open_box(s, s.inside.size() - 3);
    Solution sol;
    solve(s.scene, method(Method::kFull, s.scene.total_area() / 100), &sol);
    EXPECT_GT(largest(sol, s.inside), 1e-3) << "seed " << c.seed;
  }
}

// Clustered hierarchical radiosity at its defaults: links with a cluster end share what they carry
// among the patches of each end facing the other (hsa_links.h). The boxes' inside faces face
// outside clusters too; they must get nothing. Sizes, tessellations and frames of their own.
const Case kClusteredCases[] = {{{1.5, 0.75, 1.125}, 3, 2, {1.0, -0.5, 0.25}, 11},
                                {{0.5, 2.5, 0.625}, 3, 1, {0.25, 0.75, -1.5}, 12}};

SolveOptions clustered() {
  SolveOptions o;
  o.method = Method::kHierarchical;
  o.clustering = Clustering::kOn;
  return o;
}

// Guarantee: with clustering, the inside of a closed box lit from outside stays exactly dark (and
// its outside is lit); cluster links are made (not vacuous).
TEST(ClosedBoxes, ClusterLinksLetNoLightIntoABoxLitFromOutside) {
  for (const Case& c : kClusteredCases) {
    const LeakScene s =
        test::box_above_ground(c.size, 0.25 * c.size.z(), 1.75, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
    Solution sol;
    const SolveSummary sum = solve(s.scene, clustered(), &sol);
    EXPECT_GT(sum.figures.at("cluster_link_pairs"), 0.0) << "seed " << c.seed;
    EXPECT_EQ(largest(sol, s.inside), 0.0) << "seed " << c.seed;
    EXPECT_GT(mean(sol, s.scene, s.outside), 1e-3) << "seed " << c.seed;
  }
}

// Guarantee: with clustering, a lamp inside a closed crate lights nothing outside it, exactly.
TEST(ClosedBoxes, ClusterLinksLetNoLightOutOfACrateLitFromInside) {
  for (const Case& c : kClusteredCases) {
    const LeakScene s = test::crate_in_room(c.size, 1.75, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
    Solution sol;
    const SolveSummary sum = solve(s.scene, clustered(), &sol);
    EXPECT_GT(sum.figures.at("cluster_link_pairs"), 0.0) << "seed " << c.seed;
    EXPECT_EQ(largest(sol, s.around), 0.0) << "seed " << c.seed;
    EXPECT_EQ(largest(sol, s.outside), 0.0) << "seed " << c.seed;
    EXPECT_GT(mean(sol, s.scene, s.inside), 1e-3) << "seed " << c.seed;
  }
}

// Control: with clustering, a box with an opening in its lid lets light in.
TEST(ClosedBoxes, ClusterLinksLetLightThroughAnOpening) {
  const Case& c = kClusteredCases[0];
  LeakScene s =
      test::box_above_ground(c.size, 0.25 * c.size.z(), 1.75, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
  test::open_box(s, s.inside.size() - 3);
  Solution sol;
  solve(s.scene, clustered(), &sol);
  EXPECT_GT(largest(sol, s.inside), 1e-3);
}

// Guarantee (the oracle itself): on a box turned by arbitrary angles, points sampled on the inside
// faces see each other across the empty box (their back-to-back twins never block them, whichever
// side of the plane a sample's rounding fell on), and no point of an outside face sees a point of
// an inside face.
TEST(ClosedBoxes, SampledPointsOnTwoSidedWallsAreDecidedOnTheirPatches) {
  const Case& c = kCases[2];
  const LeakScene s = test::box_above_ground(c.size, 0.25, 1.5, c.cells, test::leak_frame(c.frame, c.shift), c.seed);
  const auto v = make_visibility(s.scene);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<std::size_t> pick(0, s.inside.size() - 1);
  auto point = [&](int patch) {
    return detail::PolygonSampler(s.scene.patches[static_cast<std::size_t>(patch)].vertices).point(u(rng), u(rng));
  };
  int facing = 0, seen = 0;
  for (int i = 0; i < 20000; ++i) {
    const int a = s.inside[pick(rng)], b = s.inside[pick(rng)];
    const auto& pa = s.scene.patches[static_cast<std::size_t>(a)];
    const auto& pb = s.scene.patches[static_cast<std::size_t>(b)];
    if (pa.normal.dot(pb.normal) > 0.5) continue;  // one wall: its triangles are coplanar to rounding
    const Vec3 x = point(a), y = point(b);
    const Sight sight = v->sight(x, a, y, b);
    ASSERT_NE(sight, Sight::kBlocked) << i;  // nothing stands inside the box
    facing += sight == Sight::kVisible;
    ASSERT_FALSE(v->segment_blocked(x, a, y, b)) << i;
    const int o = s.outside[pick(rng)];
    ASSERT_NE(v->sight(point(o), o, y, b), Sight::kVisible) << i;
    seen += v->sight(point(o), o, point(s.around[0]), s.around[0]) == Sight::kVisible;
  }
  EXPECT_GT(facing, 5000);  // not vacuous: many inside pairs face each other
  EXPECT_GT(seen, 100);     // and the outside faces do see the ground
}

}  // namespace
}  // namespace hrad
