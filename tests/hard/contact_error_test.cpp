// Contacts against the ruler: in the generated pillar hall the ceiling lights lie beside the walls
// and the pillars stand on the floor and under the ceiling. A constant element at --aeps (here the
// input polygon itself) gathers what its neighbour across the contact sends as that neighbour's
// mean, where the kernel peaks over the neighbour's near strip: the lights reflect the walls' mean,
// not the bright strip beside them (README "Limits": the generated scenes' error per polygon).
// Linear elements send their gradient, and --source-levels splits the sources there; both take
// the per-polygon error down several times at about the defaults' cost. The judge is the Monte
// Carlo ruler (reference.h), which shares no kernel with the solver, scored as `hrad compare`
// scores (analysis/face_error.h). The ruler's noise counts against the solver wherever that makes
// the test harder: the control's error is taken without it, the others' with it.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "hrad/experiments/scene_generator.h"
#include "hrad/reference/reference.h"
#include "hrad/solvers/solve.h"
#include "support/ruler_error.h"

namespace hrad {
namespace {

// Guarantee: on a 432-polygon pillar hall the defaults err by more than 4% per polygon (the
// control: constant elements across contacts), and linear elements and 3 source levels each by
// less than a third of that.
TEST(ContactError, LinearElementsAndSourceLevelsResolveTheHallsContacts) {
  SceneGeneratorOptions g;
  g.layout = SceneLayout::kPillars;
  g.polygons = 300;
  const Scene scene = to_scene(generate_scene(g));
  ASSERT_EQ(scene.faces.size(), 432u);
  ReferenceOptions r;
  r.samples = 32768;
  std::vector<FaceEstimate> ruler;
  reference_faces(scene, r, &ruler);
  SolveOptions defaults, linear, levels;
  linear.basis = Basis::kLinear;
  levels.source_levels = 3;
  const FaceErrors d = test::solve_against_ruler(scene, ruler, defaults);
  const double e0 = d.noise_corrected;
  const double e_linear = test::solve_against_ruler(scene, ruler, linear).relative_l2;
  const double e_levels = test::solve_against_ruler(scene, ruler, levels).relative_l2;
  std::printf(
      "per-polygon error against the ruler (its noise %.2f%%): defaults %.2f%% without the noise, --basis linear "
      "%.2f%% and --source-levels 3 %.2f%% with it\n",
      100 * d.reference_noise, 100 * e0, 100 * e_linear, 100 * e_levels);
  EXPECT_GT(e0, 0.04);
  EXPECT_LT(e_linear, e0 / 3.0);
  EXPECT_LT(e_levels, e0 / 3.0);
}

}  // namespace
}  // namespace hrad
