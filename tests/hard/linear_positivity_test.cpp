// A linear leaf's field keeps its corners >= 0 where its mean is (push_pull.h limit_positivity()):
// the L2 projection of a field >= 0 onto a leaf's linear space dips below 0 at a corner where the
// field is steep (SPLASH-2's room: corners down to -0.34 without the limiter, where the walls are
// near 0.5), and such a corner sends negative light on.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "hrad/io/scene_reader.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

// The largest amount, over all channels and leaves, by which a leaf's corner lies below both 0 and the
// leaf's mean (a leaf whose mean is below 0 is flat: links deliver negative light to a few faces a
// hair in front of large elements, refinement_oracle.cpp shape_of()).
double worst_corner(const Solution& sol) {
  double worst = 0.0;
  for (std::size_t f = 0; f < sol.face_field.size(); ++f) {
    const ElementField& e = sol.face_field[f];
    for (int k = 0; k < e.corners; ++k)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::min(0.0, sol.face_radiosity[f][c]) - e.radiosity[static_cast<std::size_t>(k)][c]);
  }
  return worst;
}

// Guarantee: on SPLASH-2's room (boxes 1 unit and 0.001 units in front of its walls) with linear
// elements at the defaults, cut along the near faces or not, no leaf's corner lies below 0 unless
// its mean does, and none below its mean.
TEST(LinearPositivity, LeavesBesideBoxesAHairInFrontOfWallsKeepTheirCornersAtOrAbove0) {
  ObjReadOptions read;
  for (const bool cut : {false, true}) {
    read.cut_near_faces = cut;
    const Scene scene = read_scene(test::source_dir() + "/notebooks_data/scenes/peers/splash_room.obj", nullptr, read);
    SolveOptions o;
    o.basis = Basis::kLinear;
    Solution sol;
    const SolveSummary sum = solve(scene, o, &sol);
    ASSERT_NE(sum.termination, Termination::kFailed) << sum.message;
    ASSERT_EQ(sol.face_field.size(), sol.face_radiosity.size());
    EXPECT_LE(worst_corner(sol), 1e-12) << (cut ? "cut" : "uncut");
  }
}

}  // namespace
}  // namespace hrad
