// Faces a hair in front of other faces, facing them (the generated office's boxes stand 1 cm above
// the floor on their bottom faces): the floor is dark under each box and lit around it, a jump that
// elements at --aeps average away, so a box's bottom gathers the floor element's mean. Cutting the
// floor along the boxes' outlines (io/near_faces.h, `hrad solve --cut-near-faces`) puts the jump on
// patch boundaries; what linear elements then miss is near the ruler's noise.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "hrad/experiments/scene_generator.h"
#include "hrad/io/near_faces.h"
#include "hrad/reference/reference.h"
#include "hrad/solvers/solve.h"
#include "support/ruler_error.h"

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

}  // namespace
}  // namespace hrad
