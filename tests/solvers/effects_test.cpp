// The effects analysis: what is switched off and why, and that `--effects all` gives the same answer.
#include "hrad/solvers/effects.h"

#include <gtest/gtest.h>

#include "hrad/solvers/solve.h"
#include "hrad/visibility/visibility.h"
#include "solver_test_scenes.h"

namespace hrad {
namespace {

using test::material;

bool mentions(const Effects& e, const std::string& what) {
  for (const std::string& r : e.reasons)
    if (r.find(what) != std::string::npos) return true;
  return false;
}

TEST(Effects, ConvexGrayRoomNeedsNeitherVisibilityNorColour) {
  const Scene s = test::make_box(1, 1, 1, {material(Rgb::Constant(0.5), Rgb::Constant(1))}, {0, 0, 0, 0, 0, 0});
  const auto vis = make_visibility(s);
  const Effects e = analyse_effects(s, EffectsMode::kAuto, vis.get());
  EXPECT_FALSE(e.visibility);
  EXPECT_EQ(e.color_channels, 1);
  EXPECT_TRUE(e.bounces);
  EXPECT_TRUE(e.cull_facing_away);
  EXPECT_TRUE(mentions(e, "visibility: off"));
  EXPECT_TRUE(mentions(e, "1 channel"));
}

TEST(Effects, BlockNeedsVisibilityAndColourNeedsThreeChannels) {
  Scene s = test::make_box(1, 1, 1, {material(Rgb(0.5, 0.5, 0.4), Rgb::Constant(1))}, {0, 0, 0, 0, 0, 0});
  test::add_block(s, 0.3, 0.6, 0.0, 0.4, 0.3, 0.6, 0);
  const auto vis = make_visibility(s);
  const Effects e = analyse_effects(s, EffectsMode::kAuto, vis.get());
  EXPECT_TRUE(e.visibility);
  EXPECT_EQ(e.color_channels, 3);
  EXPECT_TRUE(mentions(e, "visibility: on"));
}

TEST(Effects, NoReflectionMeansNoBounces) {
  const Scene s = test::make_box(1, 1, 1, {material(Rgb::Zero(), Rgb(1, 2, 3))}, {0, 0, 0, 0, 0, 0});
  const Effects e = analyse_effects(s, EffectsMode::kAuto, nullptr);
  EXPECT_FALSE(e.bounces);
  EXPECT_FALSE(e.visibility);
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    SolveOptions o;
    o.method = m;
    o.max_area = 0.2;
    Solution sol;
    const SolveSummary sum = solve(s, o, &sol);
    EXPECT_EQ(sum.termination, Termination::kDirect);
    EXPECT_EQ(sum.form_factor_evaluations, 0u);
    for (const Rgb& b : sol.face_radiosity) EXPECT_TRUE((b == Rgb(1, 2, 3)).all());
  }
}

TEST(Effects, AllForcesEverythingOn) {
  const Scene s = test::make_box(1, 1, 1, {material(Rgb::Constant(0.5), Rgb::Constant(1))}, {0, 0, 0, 0, 0, 0});
  const Effects e = analyse_effects(s, EffectsMode::kAll, nullptr);
  EXPECT_TRUE(e.visibility);
  EXPECT_EQ(e.color_channels, 3);
  EXPECT_TRUE(e.bounces);
  EXPECT_FALSE(e.cull_facing_away);
}

// The shortcuts must not change the answer: same radiosity with every effect forced on.
void expect_same_with_all_effects(const Scene& s, Method m, double max_area) {
  SolveOptions o;
  o.method = m;
  o.max_area = max_area;
  o.tolerance = 1e-13;
  Solution automatic, all;
  const SolveSummary sa = solve(s, o, &automatic);
  o.effects = EffectsMode::kAll;
  const SolveSummary sl = solve(s, o, &all);
  EXPECT_TRUE(sl.effects.visibility);
  ASSERT_EQ(automatic.face_radiosity.size(), all.face_radiosity.size());
  for (std::size_t f = 0; f < all.face_radiosity.size(); ++f)
    EXPECT_LT(((automatic.face_radiosity[f] - all.face_radiosity[f]).abs() / all.face_radiosity[f]).maxCoeff(), 1e-9)
        << to_string(m) << " face " << f;
  (void)sa;
}

TEST(Effects, AllGivesTheSameRadiosityInAConvexRoom) {
  const Scene s = test::make_box(
      1, 0.7, 1.2, {material(Rgb::Constant(0.6), Rgb::Zero()), material(Rgb::Constant(0.6), Rgb::Constant(3))},
      {0, 1, 0, 0, 0, 0});
  for (const Method m : {Method::kFull, Method::kSubstructure}) expect_same_with_all_effects(s, m, 0.1);
}

TEST(Effects, AllGivesTheSameRadiosityWithOcclusionAndColour) {
  Scene s =
      test::make_box(1, 1, 1, {material(Rgb(0.6, 0.3, 0.2), Rgb::Zero()), material(Rgb(0.5, 0.5, 0.5), Rgb(4, 3, 2))},
                     {0, 1, 0, 0, 0, 0});
  test::add_block(s, 0.3, 0.6, 0.0, 0.4, 0.3, 0.6, 0);
  for (const Method m : {Method::kFull, Method::kSubstructure}) expect_same_with_all_effects(s, m, 0.1);
}

}  // namespace
}  // namespace hrad
