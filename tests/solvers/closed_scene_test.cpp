// Closing the sends of a scene that keeps its light (solvers/closed_scene.h): a closed room's
// power balances by construction whatever the sample stream, a room with an opening or a back in
// sight is left exactly as it was, and the share of rays the test loses is the share of the power
// the reference's own rays (reference/power_balance.h, Embree) find escaping or landing on backs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hrad/analysis/error_metrics.h"
#include "hrad/reference/power_balance.h"
#include "hrad/solvers/closed_scene.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/solved_hierarchy.h"
#include "solver_test_scenes.h"

namespace hrad {
namespace {

enum class Room { kClosed, kOpenEnd, kShelf };

// A 5 x 3 x 4 room (rho 0.6) lit by the underside of a closed lamp box below its ceiling, with two
// floating blocks between lamp and floor. kOpenEnd leaves out the wall z = 4; kShelf adds a
// one-sided shelf, its front up, whose back the floor sees.
Scene room(Room kind) {
  std::vector<Material> materials{test::material(Rgb::Constant(0.6), Rgb::Zero(), "wall"),
                                  test::material(Rgb::Constant(0.4), Rgb::Constant(20.0), "light")};
  Scene s = test::make_box(5.0, 3.0, 4.0, materials, {0, 0, 0, 0, 0, 0}, true);
  if (kind == Room::kOpenEnd)
    std::erase_if(s.patches, [](const Patch& p) { return p.normal.z() < -0.5; });  // the wall z = 4
  const std::size_t lamp = s.patches.size();
  test::add_block(s, 2.1, 2.9, 2.7, 2.8, 1.6, 2.4, 0);
  for (std::size_t i = lamp; i < s.patches.size(); ++i)
    if (s.patches[i].normal.y() < -0.5) s.patches[i].material = 1;
  test::add_block(s, 1.0, 2.2, 1.0, 1.4, 1.2, 2.0, 0);
  test::add_block(s, 3.0, 3.6, 0.5, 1.5, 2.2, 3.1, 0);
  if (kind == Room::kShelf)
    test::add_polygon(s, {{3.8, 2, 0.2}, {4.6, 2, 0.2}, {4.6, 2, 1}, {3.8, 2, 1}}, Vec3::UnitY(), 0);
  for (std::size_t i = 0; i < s.patches.size(); ++i) s.patches[i].face = static_cast<int>(i);
  s.faces.clear();
  for (const Patch& p : s.patches)
    s.faces.push_back({p.group, p.material, 0, p.area, {static_cast<int>(s.faces.size())}});
  return s;
}

struct Solved {
  Solution solution;
  SolveSummary summary;
  double residual = 0.0;  ///< (emitted - absorbed) / emitted
};

Solved solve_room(const Scene& s, std::uint64_t seed, bool closure, SolvedHierarchy* kept = nullptr) {
  SolveOptions o;
  o.method = Method::kHierarchical;
  o.seed = seed;
  o.close_closed_scenes = closure;
  Solved out;
  out.summary = solve(s, o, &out.solution, kept);
  EXPECT_EQ(out.summary.termination, Termination::kConverged) << out.summary.message;
  const EnergyBalance e = energy_balance(s, out.solution);
  out.residual = (e.emitted_power[0] - e.absorbed_power[0]) / e.emitted_power[0];
  return out;
}

double figure(const SolveSummary& s, const char* name) {
  const auto it = s.figures.find(name);
  return it == s.figures.end() ? -1.0 : it->second;
}

// Guarantee: in a closed room whose links sample their visibility (blocks between the lamp and the
// floor), every sample stream's solve finds the room closed, closes every leaf, and absorbs what it
// emits to 1e-5 (the iteration stops at 1e-6 of the reflected power); with --closure off the same
// streams err by the links' sampling noise, more than 1e-4 in one of them at least (the control).
TEST(ClosedScene, AClosedRoomsPowerBalancesByConstructionInEverySampleStream) {
  const Scene s = room(Room::kClosed);
  double largest_off = 0.0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE(::testing::Message() << "--seed " << seed);
    const Solved closed = solve_room(s, seed, true);
    EXPECT_EQ(figure(closed.summary, "closed_scene"), 1.0);
    EXPECT_EQ(figure(closed.summary, "closure_unclosed_leaves"), 0.0);  // every leaf closed
    EXPECT_LT(std::abs(closed.residual), 1e-5);
    const Solved off = solve_room(s, seed, false);
    EXPECT_EQ(figure(off.summary, "closed_scene"), -1.0);  // not tested
    largest_off = std::max(largest_off, std::abs(off.residual));
  }
  EXPECT_GT(largest_off, 1e-4);
}

// Guarantee: a room open at one end, or closed but with a one-sided shelf whose back the floor
// sees, is found open (their light leaves, or lands on a back, and closing would make light), and
// its solution is the one --closure off gives, bit for bit.
TEST(ClosedScene, AnOpeningOrABackInSightLeavesTheSolutionAsItWas) {
  for (const Room kind : {Room::kOpenEnd, Room::kShelf}) {
    const Scene s = room(kind);
    SCOPED_TRACE(::testing::Message() << s.patches.size() << " patches");
    const Solved tested = solve_room(s, 1, true), off = solve_room(s, 1, false);
    EXPECT_EQ(figure(tested.summary, "closed_scene"), 0.0);
    EXPECT_GT(figure(tested.summary, "closure_test_lost_rays"), 0.0);
    ASSERT_EQ(tested.solution.face_radiosity.size(), off.solution.face_radiosity.size());
    for (std::size_t f = 0; f < off.solution.face_radiosity.size(); ++f)
      EXPECT_TRUE((tested.solution.face_radiosity[f] == off.solution.face_radiosity[f]).all()) << "face " << f;
  }
}

// Guarantee: the rays the test casts are drawn as the solution's light leaves its surfaces: the
// share of them that leaves the open room or lands on the shelf's back agrees, within 4 combined
// standard errors, with the share of the leaving power (sum A B) that the reference's own rays find
// escaping or landing on backs (power_balance(), Embree, no kernel shared).
TEST(ClosedScene, TheLostShareOfTheTestsRaysIsTheLostShareOfThePower) {
  for (const Room kind : {Room::kOpenEnd, Room::kShelf}) {
    const Scene s = room(kind);
    SolvedHierarchy kept;
    const Solved solved = solve_room(s, 1, false, &kept);
    const ElementHierarchy& h = *kept.hierarchy;
    std::vector<Rgb> radiosity(h.size());
    for (std::size_t i = 0; i < h.size(); ++i) radiosity[i] = h.node(static_cast<NodeId>(i)).radiosity;
    const auto visibility = make_visibility(s);
    const LightLoss loss = light_loss(s, h, radiosity, *visibility, {.rays = 1 << 16, .allowed_lost = 1 << 16}, 11);
    ASSERT_GT(loss.lost, 0u);
    const double p = static_cast<double>(loss.lost) / static_cast<double>(loss.rays);
    const double p_se = std::sqrt(p * (1.0 - p) / static_cast<double>(loss.rays));
    PowerBalanceOptions po;
    po.rays = 1 << 18;
    const PowerBalance pb = power_balance(s, solved.solution, po);
    const double q = (pb.escaped[0] + pb.onto_backs[0]) / pb.leaving[0];
    const double q_se = pb.sampled_se[0] / pb.leaving[0];
    SCOPED_TRACE(::testing::Message() << "test " << p << " +- " << p_se << " (" << loss.rays << " rays), reference "
                                      << q << " +- " << q_se);
    EXPECT_GT(q, 1e-3);
    EXPECT_LT(std::abs(p - q), 4.0 * std::hypot(p_se, q_se));
  }
}

// Guarantee: the lost rays a plan allows stand for at most kClosureLoss of the emitted power (their
// share times the leaving power over the emitted), and its rays grow with that ratio within their
// bounds, so that a scene that loses more is caught however much its surfaces reflect.
TEST(ClosedScene, ThePlansAllowedLossStandsForAtMostATenThousandthOfThePower) {
  for (const double ratio : {0.5, 1.0, 2.5, 10.0, 50.0, 100.0, 1e9}) {
    SCOPED_TRACE(::testing::Message() << "leaving / emitted " << ratio);
    const ClosureTestPlan plan = closure_test_plan(ratio, 1.0);
    EXPECT_LE(static_cast<double>(plan.allowed_lost) / static_cast<double>(plan.rays) * ratio, kClosureLoss);
    EXPECT_GE(plan.rays, kLeastClosureTestRays);
    EXPECT_LE(plan.rays, kMostClosureTestRays);
    if (ratio * kClosureTestRaysPerLeavingPower <= static_cast<double>(kMostClosureTestRays))
      EXPECT_GE(static_cast<double>(plan.rays), ratio * kClosureTestRaysPerLeavingPower);
  }
  EXPECT_EQ(closure_test_plan(1.0, 0.0).rays, kLeastClosureTestRays);
}

}  // namespace
}  // namespace hrad
