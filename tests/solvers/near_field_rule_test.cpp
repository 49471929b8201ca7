// Near-field rules for linear elements (near_field_rule.h): the rule integrates the element's corner
// functions exactly, matching moments gives the target, and beside a lamp 1 mm in front of a wall the
// rule's moments make the pair reciprocal where the nine points are off by more than half.
#include "hrad/solvers/near_field_rule.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/simpson_rule.h"
#include "hrad/geometry/polygon.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/field_links.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/linear_basis.h"
#include "solver_test_scenes.h"

namespace hrad {
namespace {

// A wall element in the plane x = 0 facing +x, and a w x w lamp `gap` in front of it facing the wall.
struct LampPair {
  Scene scene;
  std::vector<Vec3> wall, lamp;
};

LampPair lamp_pair(double gap, double w) {
  LampPair p;
  p.wall = {{0, 0, 0}, {0, 0.6, 0}, {0, 0.6, 0.6}, {0, 0, 0.6}};
  p.lamp = {{gap, 0.2, 0.25}, {gap, 0.2 + w, 0.25}, {gap, 0.2 + w, 0.25 + w}, {gap, 0.2, 0.25 + w}};
  p.scene.materials = {test::material(Rgb::Constant(0.5), Rgb::Zero(), "wall"),
                       test::material(Rgb::Constant(0.5), Rgb::Constant(1.0), "lamp")};
  test::add_polygon(p.scene, p.wall, Vec3(1, 0, 0), 0);
  test::add_polygon(p.scene, p.lamp, Vec3(-1, 0, 0), 1);
  p.wall = p.scene.patches[0].vertices;
  p.lamp = p.scene.patches[1].vertices;
  return p;
}

FormFactorEvaluator unoccluded(const Scene& s) {
  Effects effects;
  effects.visibility = false;
  return FormFactorEvaluator(s, effects, nullptr, 16, FormFactorKernel::kPointContour);
}

double sum(const std::array<double, 4>& m) { return m[0] + m[1] + m[2] + m[3]; }

TEST(NearFieldRule, WeightsIntegrateTheElementsCornerFunctions) {
  // A skewed parallelogram and a triangle, the rule driven by a lamp close to them: whatever cells it
  // cut, its weights sum to the area and integrate each corner function to a quarter (a third) of it.
  const LampPair p = lamp_pair(1e-3, 0.25);
  const FormFactorEvaluator ev = unoccluded(p.scene);
  const std::vector<Vec3> quad{{0, 0, 0}, {0, 0.6, 0.1}, {0, 0.6, 0.7}, {0, 0, 0.6}};
  const std::vector<Vec3> triangle{{0, 0, 0}, {0, 0.7, 0.1}, {0, 0.2, 0.6}};
  for (const std::vector<Vec3>& element : {quad, triangle}) {
    const std::vector<RulePoint> rule =
        near_field_rule(ev, element, Vec3(1, 0, 0), {p.lamp}, kNearFieldRuleTolerance * 0.36);
    EXPECT_GT(rule.size(), 36u);  // cut towards the lamp's edges
    double area = 0.0;
    std::array<double, 4> psi{};
    for (const RulePoint& r : rule) {
      area += r.weight;
      for (int a = 0; a < 4; ++a) psi[static_cast<std::size_t>(a)] += r.weight * r.psi[static_cast<std::size_t>(a)];
    }
    const double exact = polygon_area(element);
    EXPECT_NEAR(area, exact, 1e-12 * exact);
    const int corners = static_cast<int>(element.size());
    for (int a = 0; a < corners; ++a) EXPECT_NEAR(psi[static_cast<std::size_t>(a)], exact / corners, 1e-12 * exact);
  }
}

TEST(NearFieldRule, MatchedValuesHaveTheTargetMoments) {
  const std::vector<Vec3> quad{{0, 0, 0}, {1, 0, 0}, {1.2, 0.8, 0}, {0.2, 0.8, 0}};
  const std::vector<Vec3> triangle{{0, 0, 0}, {1, 0, 0}, {0.3, 0.9, 0}};
  for (const std::vector<Vec3>& element : {quad, triangle}) {
    const SimpsonPoints s = simpson_points(element);
    const int vertex_count = static_cast<int>(element.size());
    std::array<double, 9> values{0.3, 0.1, 0.7, 0.2, 0.5, 0.9, 0.4, 0.6, 0.8};
    const std::array<double, 4> target{0.11, 0.05, 0.2, vertex_count == 4 ? 0.07 : 0.0};
    match_linear_moments(s, target, &values);
    for (int a = 0; a < vertex_count; ++a) {
      double m = 0.0;
      for (int k = 0; k < s.count; ++k)
        m += s.weight[static_cast<std::size_t>(k)] * linear_function(vertex_count, a, k) *
             values[static_cast<std::size_t>(k)];
      EXPECT_NEAR(m, target[static_cast<std::size_t>(a)], 1e-12);
    }
  }
}

TEST(NearFieldRule, MakesALampOneMillimetreFromAWallReciprocal) {
  // A 25 cm lamp 1 mm in front of a 60 cm wall element: the wall's nine points put its factor to the
  // lamp off the closed form by more than half (the control); each end's rule integrates it to 1e-3,
  // so A_wall F(wall -> lamp) = A_lamp F(lamp -> wall) holds by the rules.
  for (const double gap : {1e-3, 3e-4}) {
    const LampPair p = lamp_pair(gap, 0.25);
    const FormFactorEvaluator ev = unoccluded(p.scene);
    const double a_wall = polygon_area(p.wall), a_lamp = polygon_area(p.lamp);
    const double exchange = a_wall * polygon_to_polygon(p.wall, p.lamp).from_to;
    const SimpsonPoints s = simpson_points(p.wall);
    double nine = 0.0;
    for (int k = 0; k < s.count; ++k)
      nine += s.weight[static_cast<std::size_t>(k)] *
              ev.point_factor(s.x[static_cast<std::size_t>(k)], Vec3(1, 0, 0), p.lamp);
    EXPECT_GT(std::abs(nine / exchange - 1.0), 0.5) << "gap " << gap;
    const std::vector<RulePoint> wall_rule =
        near_field_rule(ev, p.wall, Vec3(1, 0, 0), {p.lamp}, kNearFieldRuleTolerance * a_wall);
    const std::vector<RulePoint> lamp_rule =
        near_field_rule(ev, p.lamp, Vec3(-1, 0, 0), {p.wall}, kNearFieldRuleTolerance * a_lamp);
    const double by_wall = sum(rule_moments(ev, wall_rule, Vec3(1, 0, 0), 0, p.lamp, 1, nullptr, false, 0));
    const double by_lamp = sum(rule_moments(ev, lamp_rule, Vec3(-1, 0, 0), 1, p.wall, 0, nullptr, false, 0));
    EXPECT_NEAR(by_wall / exchange, 1.0, 1e-3) << "gap " << gap;
    EXPECT_NEAR(by_lamp / exchange, 1.0, 1e-3) << "gap " << gap;
  }
}

}  // namespace
}  // namespace hrad
