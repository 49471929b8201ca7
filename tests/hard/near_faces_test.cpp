// Faces a hair in front of other faces, facing them (the generated office's boxes stand 1 cm above
// the floor on their bottom faces): the floor is dark under each box and lit around it, a jump that
// elements at --aeps average away, so a box's bottom gathers the floor element's mean. Cutting the
// floor along the boxes' outlines (io/near_faces.h, `hrad solve --cut-near-faces`) puts the jump on
// patch boundaries; what linear elements then miss is near the ruler's noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "hrad/experiments/scene_generator.h"
#include "hrad/io/near_faces.h"
#include "hrad/io/scene_reader.h"
#include "hrad/reference/power_balance.h"
#include "hrad/reference/reference.h"
#include "hrad/solvers/solve.h"
#include "support/ruler_error.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

SolveOptions with_basis(Basis basis) {
  SolveOptions o;
  o.basis = basis;
  return o;
}

// Guarantee: on a generated 300-polygon office, cutting the faces along the near faces at least
// halves the error per polygon against the Monte Carlo ruler (its noise removed) with linear
// elements, and takes a fifth of it away with constant ones; the faces keep their areas.
TEST(NearFaces, CuttingAlongBoxesAboveTheFloorHalvesTheOfficesError) {
  SceneGeneratorOptions g;
  g.polygons = 300;
  const Scene scene = to_scene(generate_scene(g));
  Scene cut = scene;
  const NearCuts cuts = cut_near_faces(cut);
  EXPECT_GT(cuts.patches_added, 0u);
  ASSERT_EQ(cut.faces.size(), scene.faces.size());
  for (std::size_t f = 0; f < scene.faces.size(); ++f)
    EXPECT_NEAR(cut.faces[f].area, scene.faces[f].area, 1e-9 * scene.faces[f].area) << f;
  ReferenceOptions r;
  r.samples = 32768;
  std::vector<FaceEstimate> ruler;
  reference_faces(scene, r, &ruler);
  const double constant = test::solve_against_ruler(scene, ruler, with_basis(Basis::kConstant)).noise_corrected;
  const double constant_cut = test::solve_against_ruler(cut, ruler, with_basis(Basis::kConstant)).noise_corrected;
  const double linear = test::solve_against_ruler(scene, ruler, with_basis(Basis::kLinear)).noise_corrected;
  const double linear_cut = test::solve_against_ruler(cut, ruler, with_basis(Basis::kLinear)).noise_corrected;
  std::printf(
      "per-polygon error against the ruler without its noise: constant %.2f%% -> %.2f%% cut, linear %.2f%% "
      "-> %.2f%% cut (%zu patches added)\n",
      100 * constant, 100 * constant_cut, 100 * linear, 100 * linear_cut, cuts.patches_added);
  EXPECT_LT(linear_cut, 0.5 * linear);
  EXPECT_LT(constant_cut, 0.8 * constant);
}

// Guarantee: a closed room with a table top (a 1 x 0.5 x 0.02 m slab) 10 cm above its floor balances
// power within 1e-3 at the defaults once the floor is cut along the slab (--cut-near-faces), and uncut
// with the leaf push. The control, a gap this test documents: uncut, the default HSA push gains more
// than 5e-3 of the emitted power (1.0%, whatever --aeps: 0.95-1.1% from total/280 to total/18000);
// the slab 30 cm up balances (6e-4). `hrad solve` warns of both the near pair and the imbalance.
TEST(NearFaces, ASlabATenthOfItsSizeAboveTheFloorBalancesCutOrWithTheLeafPush) {
  const std::string path = test::source_dir() + "/notebooks_data/scenes/slab_near_floor.obj";
  ObjReadOptions cut;
  cut.cut_near_faces = true;
  const auto balance = [](const Scene& scene, Push push) {
    SolveOptions o;
    o.push = push;
    Solution sol;
    EXPECT_NE(solve(scene, o, &sol).termination, Termination::kFailed);
    return power_balance(scene, sol);
  };
  const Scene scene = read_scene(path, nullptr, {});
  const PowerBalance cut_hsa = balance(read_scene(path, nullptr, cut), Push::kHsa);
  EXPECT_LT(cut_hsa.relative_residual(), 1e-3);
  EXPECT_TRUE(cut_hsa.balanced());
  const PowerBalance leaf = balance(scene, Push::kLeaf);
  EXPECT_LT(leaf.relative_residual(), 1e-3);
  const PowerBalance uncut = balance(scene, Push::kHsa);
  std::printf("residual of the emitted power: cut %.2e, leaf push %.2e, uncut HSA push %.2e\n",
              cut_hsa.relative_residual(), leaf.relative_residual(), uncut.relative_residual());
  EXPECT_GT(uncut.relative_residual(), 5e-3);
  EXPECT_FALSE(uncut.balanced());
}

}  // namespace
}  // namespace hrad
