// The power balance of a solution (reference/power_balance.h) on solutions written down by hand,
// whose fate of every watt is known in closed form, so that the balance is tested apart from any
// solver.
#include <gtest/gtest.h>

#include "../formfactor/howell.h"
#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/power_balance.h"
#include "reference_checks.h"

namespace hrad::test {
namespace {

// One leaf per patch, with the patch's polygon and the given radiosity.
Solution one_leaf_per_patch(const Scene& s, const std::vector<Rgb>& radiosity) {
  Solution sol;
  for (std::size_t p = 0; p < s.patches.size(); ++p) {
    std::vector<int> face;
    for (const Vec3& v : s.patches[p].vertices) {
      face.push_back(static_cast<int>(sol.vertices.size()));
      sol.vertices.push_back(v);
    }
    sol.faces.push_back(face);
    sol.face_patch.push_back(static_cast<int>(p));
    sol.face_radiosity.push_back(radiosity[p]);
  }
  sol.patch_radiosity = radiosity;
  return sol;
}

// Guarantee: in a closed box of uniform emission E and reflectance rho, B = E / (1 - rho) balances
// exactly (absorbed A (1 - rho) / rho (B - E) = A E), no ray escapes or lands on a back; a solution
// 1% too dark is flagged (nothing is sampled in a closed grey box, so its residual is exact).
TEST(PowerBalance, ClosedBoxBalancesExactlyAndAWrongSolutionIsFlagged) {
  const Rgb rho(0.5, 0.7, 0.9), e(1.0, 2.0, 0.5);
  const Scene s = make_box(1.0, 0.8, 1.7, {material(rho, e)}, {0, 0, 0, 0, 0, 0}, true);
  const Rgb b = e / (Rgb::Ones() - rho);
  PowerBalance pb = power_balance(s, one_leaf_per_patch(s, std::vector<Rgb>(s.patches.size(), b)));
  EXPECT_GT(pb.rays, 0u);
  EXPECT_EQ(pb.escaped.maxCoeff(), 0.0);
  EXPECT_EQ(pb.onto_backs.maxCoeff(), 0.0);
  EXPECT_EQ(pb.absorbed_black.maxCoeff(), 0.0);
  EXPECT_LT(pb.relative_residual(), 1e-12);
  EXPECT_TRUE(pb.balanced());
  // B 1% low: absorbed is A (1 - rho) / rho (0.99 B - E), short of A E by 0.01 A (1 - rho) / rho B
  // = 0.01 A E / rho of the emitted A E: 2% in the red channel.
  pb = power_balance(s, one_leaf_per_patch(s, std::vector<Rgb>(s.patches.size(), 0.99 * b)));
  EXPECT_NEAR(pb.relative_residual(), 0.01 / 0.5, 1e-12);
  EXPECT_FALSE(pb.balanced());
}

// Guarantee: two directly opposed unit squares at distance c (Howell C-11, factor F) in empty
// space, a black emitter (E, rho = 0) and a grey reflector (rho): the reflector's radiosity is
// B = rho F E exactly. Of the emitted power A E, the reflector absorbs (1 - rho) A F E, the emitter
// absorbs A F B (it is black), and A (1 - F) (E + B) escapes: the sampled terms agree with these
// within 4 standard errors, and the residual is 0 within its own.
TEST(PowerBalance, OpposedSquaresEscapeAndBlackAbsorptionMatchHowell) {
  const double c = 0.6, rho = 0.5;
  const Rgb e(2.0, 1.0, 3.0);
  Scene s;
  s.materials = {material(Rgb::Zero(), e), material(Rgb::Constant(rho), Rgb::Zero())};
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, Vec3::UnitZ(), 0);
  add_polygon(s, {{0, 0, c}, {1, 0, c}, {1, 1, c}, {0, 1, c}}, -Vec3::UnitZ(), 1);
  const double f = howell_c11(1, 1, c);
  const Rgb b = rho * f * e;
  PowerBalanceOptions o;
  o.rays = 1 << 17;
  const PowerBalance pb = power_balance(s, one_leaf_per_patch(s, {e, b}), o);
  EXPECT_NEAR(pb.absorbed_reflecting[0], (1 - rho) * f * e[0], 1e-12);
  const Rgb sampled = pb.escaped + pb.absorbed_black + pb.onto_backs;
  expect_agrees(sampled, pb.sampled_se, (1 - f) * (e + b) + f * b, 0.01, "escaped + black");
  expect_agrees(pb.absorbed_black, pb.sampled_se, f * b, 0.05, "black");
  EXPECT_EQ(pb.onto_backs.maxCoeff(), 0.0);
  for (int ch = 0; ch < 3; ++ch) EXPECT_LE(std::abs(pb.residual[ch]), 4 * pb.sampled_se[ch]) << ch;
  EXPECT_TRUE(pb.balanced());
}

}  // namespace
}  // namespace hrad::test
