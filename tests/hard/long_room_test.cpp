// Long rooms: a closed W x H x L corridor whose end wall emits, every wall of reflectance rho.
// Closed and reflecting everywhere, it absorbs exactly the power its end wall emits
// (energy_balance(): A (1 - rho) / rho (B - E) summed over the elements, exact from B). The
// automatic element size (total area / 250) cuts the long walls into strips of aspect up to L / W;
// a contour kernel with one 3 x 3 Gauss rule per strip put the points of the strips beside the end
// wall metres from where its light arrives (3% of the power lost at L = 30 W, half at L = 100 W); the
// rule now takes near-square cells along a strip, up to kMaxReceiverCells of them
// (receiver_gauss_factor.h), which bounds the aspect it resolves: with 8 cells the loss grew again
// beyond about 8 x 4 : 1 (1.4e-3 at 0.75 x 1.25 x 60, 5.3e-3 at 1 x 1 x 100); with 1024, strips up to
// about 1400 : 1 keep cells of aspect 2 or less, at a cost linear in the aspect.
#include <gtest/gtest.h>

#include "../solvers/solver_test_scenes.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/solvers/solve.h"

namespace hrad {
namespace {

using test::add_polygon;
using test::material;

// The inward walls of [0, w] x [0, h] x [0, l]; the end wall z = 0 emits e (material 1) unless
// `open`, when the far end z = l is left out.
Scene corridor(double w, double h, double l, double rho, double e, bool open = false) {
  Scene s;
  s.materials = {material(Rgb::Constant(rho), Rgb::Zero()), material(Rgb::Constant(rho), Rgb::Constant(e))};
  const Vec3 c(w / 2, h / 2, l / 2);
  const auto wall = [&](std::vector<Vec3> v, int m) { add_polygon(s, v, c - polygon_centroid(v), m); };
  wall({{0, 0, 0}, {w, 0, 0}, {w, 0, l}, {0, 0, l}}, 0);
  wall({{0, h, 0}, {w, h, 0}, {w, h, l}, {0, h, l}}, 0);
  wall({{0, 0, 0}, {0, h, 0}, {0, h, l}, {0, 0, l}}, 0);
  wall({{w, 0, 0}, {w, h, 0}, {w, h, l}, {w, 0, l}}, 0);
  wall({{0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0}}, 1);
  if (!open) wall({{0, 0, l}, {w, 0, l}, {w, h, l}, {0, h, l}}, 0);
  return s;
}

// Guarantee: closed corridors 20 to 100 times as long as they are wide absorb what their end wall
// emits within 1e-3, for the full matrix and substructuring at the defaults (contour kernel).
TEST(LongRooms, ClosedCorridorsAbsorbWhatTheirEndWallEmits) {
  struct Case {
    double w, h, l, rho;
  };
  for (const Case& c : {Case{1.0, 1.0, 30.0, 0.5}, Case{1.25, 0.75, 20.0, 0.7}, Case{0.75, 1.25, 60.0, 0.5},
                        Case{1.0, 1.0, 100.0, 0.6}}) {
    const Scene s = corridor(c.w, c.h, c.l, c.rho, 1.0);
    for (Method m : {Method::kFull, Method::kSubstructure}) {
      SolveOptions o;
      o.method = m;
      Solution sol;
      const SolveSummary sum = solve(s, o, &sol);
      ASSERT_NE(sum.termination, Termination::kFailed) << sum.message;
      EXPECT_LT(energy_balance(s, sol).closed_scene_residual[0], 1e-3) << to_string(m) << " L " << c.l;
    }
  }
}

// Control: with its far end open, a corridor loses what leaves through the opening, and the
// balance above sees it: at L = 3 W the end wall alone sees the opening under Howell's C-11 factor
// (about 2.8% for a unit square at 3), so far more than 1e-3 goes missing.
TEST(LongRooms, AnOpenCorridorLosesPower) {
  const Scene s = corridor(1.0, 1.0, 3.0, 0.5, 1.0, true);
  SolveOptions o;
  o.method = Method::kFull;
  Solution sol;
  solve(s, o, &sol);
  EXPECT_GT(energy_balance(s, sol).closed_scene_residual[0], 0.02);
}

}  // namespace
}  // namespace hrad
