// A small lamp a millimetre from a wall in a closed room: the lamp is a thin closed housing (so the
// room stays closed) one of whose faces emits. Facing into the room, the lamp is an ordinary source
// and every method at its defaults balances power. Facing the wall, nearly all of its power lands
// on a patch of wall of its own size, 1 mm away, while the wall's elements are larger than the
// lamp: the contour kernel's Gauss points on such an element lie under the lamp or beside it, and
// its factor to the lamp would be off by the footprint's share of the element (closure holds,
// reciprocity does not, and the error becomes power). The kernel takes the closed form for such
// floating pairs (FormFactorKernel::kPointContour). The hierarchical solver's smallest elements
// (--aeps) are larger than the lamp; it balances once the links at the footprint's elements are
// decided with the brightness the first solve found there.
#include <gtest/gtest.h>

#include <cmath>

#include "../solvers/solver_test_scenes.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/io/near_faces.h"
#include "hrad/solvers/solve.h"

namespace hrad {
namespace {

// A closed room a x b x c (reflectance 0.7) with a housing of w x w x 1 cm (reflectance 0.5) whose
// face towards -x (the wall x = 0, `gap` away) or towards +x (into the room) emits 50.
Scene lamp_room(double gap, bool facing_wall, double w = 0.25) {
  const double a = 3.6, b = 2.7, c = 3.1;
  Scene s = test::make_box(a, b, c,
                           {test::material(Rgb::Constant(0.7), Rgb::Zero(), "wall"),
                            test::material(Rgb::Constant(0.5), Rgb::Zero(), "housing"),
                            test::material(Rgb::Constant(0.5), Rgb::Constant(50.0), "light")},
                           {0, 0, 0, 0, 0, 0});
  const std::size_t first = s.patches.size();
  const double y = 1.3, z = 1.7;
  test::add_block(s, gap, gap + 0.01, y, y + w, z, z + w, 1);
  const double side = facing_wall ? -1.0 : 1.0;
  for (std::size_t i = first; i < s.patches.size(); ++i) {
    if (s.patches[i].normal.x() * side > 0.5) {
      s.patches[i].material = 2;
      s.faces[static_cast<std::size_t>(s.patches[i].face)].material = 2;
    }
  }
  return s;
}

// |absorbed - emitted| / emitted of the solve at the defaults (with the closed-form kernel when `analytic`).
double residual(const Scene& s, Method method, bool analytic) {
  SolveOptions o;
  o.method = method;
  if (analytic) o.kernel = FormFactorKernel::kAnalytic;
  Solution sol;
  const SolveSummary sum = solve(s, o, &sol);
  EXPECT_TRUE(sum.termination == Termination::kConverged || sum.termination == Termination::kDirect) << sum.message;
  return energy_balance(s, sol).closed_scene_residual[0];
}

// |absorbed - emitted| / emitted of a hierarchical solve with `o` (its method set), which must
// converge; its summary in `sum` when not null.
double hierarchical_residual(const Scene& s, SolveOptions o, SolveSummary* sum = nullptr) {
  o.method = Method::kHierarchical;
  Solution sol;
  const SolveSummary summary = solve(s, o, &sol);
  EXPECT_EQ(summary.termination, Termination::kConverged) << summary.message;
  if (sum != nullptr) *sum = summary;
  return energy_balance(s, sol).closed_scene_residual[0];
}

// Guarantee: a lamp 1 mm in front of a wall, emitting into the room, balances power within 1e-3 with
// the full matrix, substructuring and hierarchical radiosity at their defaults.
TEST(LampNearWall, FacingIntoTheRoomBalancesPowerForEveryMethod) {
  const Scene s = lamp_room(1e-3, false);
  for (const Method m : {Method::kFull, Method::kSubstructure, Method::kHierarchical}) {
    SCOPED_TRACE(to_string(m));
    EXPECT_LT(std::abs(residual(s, m, false)), 1e-3);
  }
}

// The control: the near field is real. The 3 x 3 Gauss rule on the wall (one element) puts its
// points where the lamp's 1 mm-wide edge band is not, and its factor to the lamp's face is off by
// far more than the 1e-3 the solvers must balance to.
TEST(LampNearWall, TheWallsGaussRuleMissesTheLampsNearField) {
  const std::vector<Vec3> wall{{0, 0, 0}, {0, 2.7, 0}, {0, 2.7, 3.1}, {0, 0, 3.1}};
  for (const double gap : {1e-3, 3e-4}) {
    const double y = 1.3, z = 1.7, w = 0.25;
    const std::vector<Vec3> lamp{{gap, y, z}, {gap, y, z + w}, {gap, y + w, z + w}, {gap, y + w, z}};
    const double exact = polygon_to_polygon(wall, lamp).from_to;
    const double rule = receiver_gauss_factor(wall, lamp);
    EXPECT_GT(std::abs(rule - exact), 0.05 * exact) << "gap " << gap;
  }
}

// Guarantee: the lamp facing the wall, 1 mm or 0.3 mm away, 25 cm or 8 cm wide, balances power
// within 1e-3 with the full matrix and substructuring at their defaults (the contour kernel, its
// receivers' points graded towards the edges of the elements floating in front of them) and with
// --kernel analytic; substructuring's two kernels agree within 2e-4. The partly visible pairs around
// the lamp are closer than their size and carry large factors: their visible fractions sample the
// source by solid angle (sampled by area, the 25 cm lamp 1 mm away is 1.2e-3 off).
TEST(LampNearWall, FacingTheWallBalancesPower) {
  for (const double w : {0.25, 0.08})
    for (const double gap : {1e-3, 3e-4}) {
      SCOPED_TRACE(::testing::Message() << "lamp " << w << " gap " << gap);
      const Scene s = lamp_room(gap, true, w);
      EXPECT_LT(std::abs(residual(s, Method::kFull, true)), 1e-3);
      EXPECT_LT(std::abs(residual(s, Method::kFull, false)), 1e-3);
      const double sub = residual(s, Method::kSubstructure, false);
      EXPECT_NEAR(sub, residual(s, Method::kSubstructure, true), 2e-4);
      EXPECT_LT(std::abs(sub), 1e-3);
    }
}

// Guarantee: hierarchical radiosity balances the lamp facing the wall within 1e-3 at its defaults and
// with elements down to a sixteenth of their area (aeps), though its smallest elements are larger
// than the lamp's footprint. The first solve weighs the wall as a reflector of the room's mean
// radiosity; the footprint is hundreds of times brighter, and the links from the wall's coarse
// elements carried it with a field that cannot follow it (17% of the power too much on
// lamp_near_wall.obj at --aeps 0.004, total / 16500). The solver decides those links again with
// the brightness it found (ErrorBoundOracle::observe()).
TEST(LampNearWall, HierarchicalRadiosityBalancesTheLampFacingTheWall) {
  for (const auto& [w, gap] : {std::pair{0.25, 1e-3}, std::pair{0.08, 3e-4}}) {
    const Scene s = lamp_room(gap, true, w);
    for (const double fraction : {0.0, 1.0 / 16000.0}) {
      SCOPED_TRACE(::testing::Message() << "lamp " << w << " gap " << gap << " aeps/total " << fraction);
      SolveOptions o;
      o.aeps = fraction * s.total_area();
      EXPECT_LT(std::abs(hierarchical_residual(s, o)), 1e-3);
    }
  }
}

// Guarantee: cut along the lamp's outline (cut_near_faces(), as read_scene() does by default), the wall's
// footprint is a patch of its own, as bright as the lamp, and sends about 1% of its power into the
// room through the slit between the housing and the wall; hierarchical radiosity balances power
// within 1e-3 at its defaults. The footprint's pairs with the room's elements are partly visible,
// and the first refinement, weighing the footprint as a reflector of the room's mean radiosity,
// samples each with a few point pairs that mostly meet the housing: pairs that no sample saw
// through were dropped for good, and the slit's light lost (0.6% of the power on
// lamp_near_wall.obj). They are decided again with the brightness found, as links are.
TEST(LampNearWall, CutAlongTheLampTheFootprintsLightThroughTheSlitIsKept) {
  for (const auto& [w, gap] : {std::pair{0.25, 1e-3}, std::pair{0.12, 2e-3}}) {
    SCOPED_TRACE(::testing::Message() << "lamp " << w << " gap " << gap);
    Scene s = lamp_room(gap, true, w);
    const std::size_t before = s.patches.size();
    cut_near_faces(s);
    ASSERT_GT(s.patches.size(), before);  // the wall was cut
    EXPECT_LT(std::abs(hierarchical_residual(s, SolveOptions{})), 1e-3);
  }
}

// Guarantee: with linear elements at the defaults, the 25 cm lamp facing the wall 1 mm away
// balances power within 1e-3. A linear leaf beside the lamp receives through its links' fields, its
// slope follows them, and it sent by the same fields: their errors came back as light (5.3e-3 of
// the lamp's power) until a closed leaf sends its power times what a uniform radiosity on it sends
// (send_closure.h).
TEST(LampNearWall, LinearElementsBalanceTheLampFacingTheWall) {
  SolveOptions o;
  o.basis = Basis::kLinear;
  EXPECT_LT(std::abs(hierarchical_residual(lamp_room(1e-3, true), o)), 1e-3);
}

// Guarantee: with the wall's elements split below aeps as sources (--source-levels 2), constant
// and linear, the lamp facing the wall 1 mm away balances power within 1e-3. The parts under the
// lamp's edge took the fields of the wall's other links, fitted over a larger element, at full
// strength while their own link to the lamp took much of their hemisphere: they sent more than
// their radiosity, and the room gained 1.8e-3 of the lamp's power with constant elements (1.6e-3
// with linear ones on notebooks_data/scenes/lamp_near_wall.obj) (send_closure.h).
TEST(LampNearWall, SourcesSplitBelowAepsBalanceThePower) {
  const Scene s = lamp_room(1e-3, true);
  for (const Basis basis : {Basis::kConstant, Basis::kLinear}) {
    SCOPED_TRACE(basis == Basis::kLinear ? "linear" : "constant");
    SolveOptions o;
    o.basis = basis;
    o.source_levels = 2;
    SolveSummary sum;
    EXPECT_LT(std::abs(hierarchical_residual(s, o, &sum)), 1e-3);
    EXPECT_GT(sum.elements, 400u);  // split below aeps (the defaults stop at 390)
  }
}

// Guarantee: the stopping test bounds the reflected power of the answer, not only its brightest
// leaf. With sources split below aeps (--source-levels 2), the wall's leaves under the lamp reflect
// ~1000x more than the other walls; stopping when the largest change was 1e-6 of the largest
// reflected radiosity left the reflected power 3.6e-4 short of the converged answer (and the
// balance 5e-4 off). At the default tolerance the reflected power is within 10x the tolerance of a
// solve to 1e-12 on the same links.
TEST(LampNearWall, TheStoppingTestBoundsTheReflectedPowerBesideABrightFootprint) {
  const Scene s = lamp_room(1e-3, true);
  auto reflected_power = [&](double tolerance, SolveSummary* sum) {
    SolveOptions o;
    o.method = Method::kHierarchical;
    o.source_levels = 2;
    o.tolerance = tolerance;
    Solution sol;
    *sum = solve(s, o, &sol);
    double power = 0.0, brightest = 0.0, walls = 0.0;
    for (std::size_t p = 0; p < s.patches.size(); ++p)
      power += s.patches[p].area * (sol.patch_radiosity[p][0] - s.material_of(s.patches[p]).emission[0]);
    for (std::size_t f = 0; f < sol.faces.size(); ++f) {
      const Patch& patch = s.patches[static_cast<std::size_t>(sol.face_patch[f])];
      const double b = sol.face_radiosity[f][0] - s.material_of(patch).emission[0];
      brightest = std::max(brightest, b);
      if (patch.material == 0 && patch.normal.x() < 0.5) walls = std::max(walls, b);
    }
    EXPECT_GT(brightest, 300.0 * walls);  // the case: a footprint far brighter than the room
    return power;
  };
  SolveSummary loose, tight;
  const double p_loose = reflected_power(1e-6, &loose), p_tight = reflected_power(1e-12, &tight);
  ASSERT_EQ(loose.termination, Termination::kConverged) << loose.message;
  ASSERT_EQ(tight.termination, Termination::kConverged) << tight.message;
  ASSERT_EQ(loose.elements, tight.elements);  // the same refinement
  EXPECT_LT(std::abs(p_loose - p_tight) / p_tight, 1e-5);
}

}  // namespace
}  // namespace hrad
