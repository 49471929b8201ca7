// Faces a hair in front of other faces, facing them (the generated office's boxes stand 1 cm above
// the floor on their bottom faces): the floor is dark under each box and lit around it, a jump that
// elements at --aeps average away, so a box's bottom gathers the floor element's mean. Cutting the
// floor along the boxes' outlines (io/near_faces.h, as `hrad solve` does by default) puts the jump on
// patch boundaries; what linear elements then miss is near the ruler's noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "hrad/experiments/scene_generator.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/simpson_rule.h"
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

// A closed 5 x 2.6 x 4 m room (reflectance 0.6) lit by a 1 x 1 m panel under its ceiling, with boxes
// (reflectance 0.5) of several sizes whose bottoms float `gap` above the floor at `n` places; the index
// of each box's bottom face comes back in `bottoms`.
Scene room_with_floating_boxes(double gap, std::vector<int>* bottoms) {
  Scene s = test::make_box(
      5.0, 2.6, 4.0,
      {test::material(Rgb::Constant(0.6), Rgb::Zero(), "wall"), test::material(Rgb::Constant(0.5), Rgb::Zero(), "box"),
       test::material(Rgb::Zero(), Rgb::Constant(20.0), "lamp")},
      {0, 0, 0, 0, 0, 0});
  test::add_block(s, 2.0, 3.0, 2.56, 2.58, 1.5, 2.5, 2);  // the panel: only its bottom shows light
  for (std::size_t i = s.faces.size() - 6; i < s.faces.size(); ++i)
    if (s.patches[static_cast<std::size_t>(s.faces[i].patches[0])].normal.y() > -0.5) {
      s.faces[i].material = 1;
      s.patches[static_cast<std::size_t>(s.faces[i].patches[0])].material = 1;
    }
  for (const auto& [x0, z0, w, d, h] : {std::tuple{0.4, 0.5, 0.9, 0.6, 0.7}, std::tuple{3.6, 0.4, 0.5, 1.1, 0.45},
                                        std::tuple{1.2, 2.9, 1.4, 0.5, 0.9}, std::tuple{4.1, 3.0, 0.6, 0.6, 1.2}}) {
    const std::size_t first = s.faces.size();
    test::add_block(s, x0, x0 + w, gap, gap + h, z0, z0 + d, 1);
    for (std::size_t i = first; i < s.faces.size(); ++i)
      if (s.patches[static_cast<std::size_t>(s.faces[i].patches[0])].normal.y() < -0.5)
        bottoms->push_back(static_cast<int>(i));
  }
  return s;
}

// Guarantee: the bottoms of boxes floating 1 cm above a lit floor, which see only the dark floor under
// them and the light through the slit, reflect what the Monte Carlo ruler finds, within a factor of 2
// and 4 of its standard errors each, at the defaults once the floor is cut along them as read_scene()
// cuts it (cut_near_faces()), with constant and with linear elements. The control: whole, each gathers
// the mean of a lit floor element, more than 5 times the ruler's value.
TEST(NearFaces, BottomsOfBoxesACentimetreAboveTheFloorStayDarkCut) {
  std::vector<int> bottoms;
  const Scene whole = room_with_floating_boxes(0.01, &bottoms);
  Scene cut = whole;
  ASSERT_GT(cut_near_faces(cut).patches_added, 0u);
  ReferenceOptions r;
  r.samples = 16384;
  std::vector<FaceEstimate> ruler;
  reference_faces(whole, r, &ruler);
  const auto reflected = [&](const Scene& scene, Basis basis) {
    SolveOptions o;
    o.basis = basis;
    Solution sol;
    EXPECT_EQ(solve(scene, o, &sol).termination, Termination::kConverged);
    const std::vector<Rgb> faces = face_radiosity(scene, sol);  // area means over each face's patches
    std::vector<double> b;
    for (const int f : bottoms) b.push_back(faces[static_cast<std::size_t>(f)][0]);
    return b;
  };
  const std::vector<double> whole_constant = reflected(whole, Basis::kConstant);
  const std::vector<double> cut_constant = reflected(cut, Basis::kConstant);
  const std::vector<double> cut_linear = reflected(cut, Basis::kLinear);
  for (std::size_t k = 0; k < bottoms.size(); ++k) {
    const double truth = ruler[static_cast<std::size_t>(bottoms[k])].radiosity[0];
    const double se = ruler[static_cast<std::size_t>(bottoms[k])].radiosity_se[0];
    std::printf("bottom %zu: ruler %.4f +- %.4f, whole %.4f, cut %.4f, cut linear %.4f\n", k, truth, se,
                whole_constant[k], cut_constant[k], cut_linear[k]);
    for (const double b : {cut_constant[k], cut_linear[k]}) {
      EXPECT_LT(b, 2.0 * truth + 4.0 * se) << "bottom " << k;
      EXPECT_GT(b, 0.5 * truth - 4.0 * se) << "bottom " << k;
    }
    EXPECT_GT(whole_constant[k], 5.0 * (truth + 4.0 * se)) << "bottom " << k;
  }
}

// Guarantee: a closed room with a table top (a 1 x 0.5 x 0.02 m slab) 10 cm above its floor balances
// power within 1e-3 at the defaults, cut along the slab (the reader's default) or not (--no-cut-near-faces), and with
// the leaf push. Uncut, the slab's outline lies on the points of the floor's elements (halved from the room's corners),
// and the HSA push gained 0.96% of the power until the oracle tested the fields off them
// (ATableTopBalancesAtTheDefaultsWhereverItsOutlineFalls). `hrad solve --no-cut-near-faces` names the near
// pair.
TEST(NearFaces, ASlabATenthOfItsSizeAboveTheFloorBalancesCutOrNotAndWithTheLeafPush) {
  const std::string path = test::source_dir() + "/notebooks_data/scenes/slab_near_floor.obj";
  ObjReadOptions whole;
  whole.cut_near_faces = false;
  const auto balance = [](const Scene& scene, Push push) {
    SolveOptions o;
    o.push = push;
    Solution sol;
    EXPECT_NE(solve(scene, o, &sol).termination, Termination::kFailed);
    return power_balance(scene, sol);
  };
  const Scene scene = read_scene(path, nullptr, whole);
  const PowerBalance cut_hsa = balance(read_scene(path, nullptr, {}), Push::kHsa);
  const PowerBalance leaf = balance(scene, Push::kLeaf);
  const PowerBalance uncut = balance(scene, Push::kHsa);
  std::printf("residual of the emitted power: cut %.2e, leaf push %.2e, uncut HSA push %.2e\n",
              cut_hsa.relative_residual(), leaf.relative_residual(), uncut.relative_residual());
  for (const PowerBalance* b : {&cut_hsa, &leaf, &uncut}) {
    EXPECT_LT(b->relative_residual(), 1e-3);
    EXPECT_TRUE(b->balanced());
  }
}

// A closed 2.4 x 1.2 x 1.1 m room, a lamp housing under its ceiling whose bottom face emits, and a
// 1.2 x 0.55 x 0.03 m table top 12 cm above the floor, its corner at (x0, z0).
Scene table_room(double x0, double z0) {
  Scene s = test::make_box(2.4, 1.2, 1.1,
                           {test::material(Rgb::Constant(0.5), Rgb::Zero(), "wall"),
                            test::material(Rgb::Constant(0.6), Rgb::Zero(), "table"),
                            test::material(Rgb::Constant(0.5), Rgb::Constant(10.0), "light")},
                           {0, 0, 0, 0, 0, 0});
  const std::size_t first = s.patches.size();
  test::add_block(s, 1.05, 1.35, 1.17, 1.19, 0.4, 0.7, 0);
  for (std::size_t i = first; i < s.patches.size(); ++i)
    if (s.patches[i].normal.y() < -0.5) {
      s.patches[i].material = 2;
      s.faces[static_cast<std::size_t>(s.patches[i].face)].material = 2;
    }
  test::add_block(s, x0, x0 + 1.2, 0.12, 0.15, z0, z0 + 0.55, 1);
  return s;
}

// Guarantee: a table top a tenth of its size above the floor, uncut, balances power within 1e-3 at
// the defaults wherever its outline falls on the floor's elements, also on the lines their own
// points lie on. Each element's factor field is tested and fitted at its corners, edge midpoints and
// centre, and the floor's halves, quarters, ... put those points on an outline at x = 0.6, 1.8 and
// z = 0.275, 0.825: there the field from the table's bottom looks smooth at the points, and the
// slab bottom's links to the floor's coarse elements spread its shadow over them (the solve gained
// 8.3e-3 of the power). The oracle also compares the factor with the points' biquadratic at four
// points off every halving line where a side floats close in front of the other
// (refinement_oracle.cpp, off_grid_deviation()). The control: at such a floor element the
// biquadratic through the 9 points errs by more than a third of the factor's range there.
TEST(NearFaces, ATableTopBalancesAtTheDefaultsWhereverItsOutlineFalls) {
  const auto residual = [](const Scene& scene) {
    Solution sol;
    EXPECT_EQ(solve(scene, SolveOptions{}, &sol).termination, Termination::kConverged);
    return power_balance(scene, sol).relative_residual();
  };
  for (const auto& [x0, z0] :
       {std::pair{0.737, 0.183}, std::pair{0.431, 0.311}, std::pair{0.913, 0.077}, std::pair{0.6, 0.275}}) {
    SCOPED_TRACE(::testing::Message() << "table at " << x0 << ", " << z0);
    const double r = residual(table_room(x0, z0));
    std::printf("residual of the emitted power, table at %.3f, %.3f: %.2e\n", x0, z0, r);
    EXPECT_LT(r, 1e-3);
  }
  // The floor element [0, 1.2] x [0, 0.55] of the aligned table: its edge midpoints and centre lie on
  // the table's edges, its far corner under the table.
  const std::vector<Vec3> element{{0, 0, 0}, {0, 0, 0.55}, {1.2, 0, 0.55}, {1.2, 0, 0}};
  const std::vector<Vec3> bottom{{0.6, 0.12, 0.275}, {1.8, 0.12, 0.275}, {1.8, 0.12, 0.825}, {0.6, 0.12, 0.825}};
  const Vec3 up(0, 1, 0);
  std::array<double, 9> f{};
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < 9; ++k) {
    const double u = kSimpsonQuadUv[k][0], v = kSimpsonQuadUv[k][1];
    const Vec3 x = bilinear_point(element, u, v);
    f[static_cast<std::size_t>(k)] = point_to_polygon(x, up, bottom);
    lo = std::min(lo, f[static_cast<std::size_t>(k)]);
    hi = std::max(hi, f[static_cast<std::size_t>(k)]);
  }
  const auto lagrange = [](int k, double t) {
    return k == 0 ? 2.0 * (t - 0.5) * (t - 1.0) : k == 1 ? -4.0 * t * (t - 1.0) : 2.0 * t * (t - 0.5);
  };
  double worst = 0.0;
  for (const double u : {1.0 / 3.0, 2.0 / 3.0})
    for (const double v : {1.0 / 3.0, 2.0 / 3.0}) {
      double fit = 0.0;
      for (int k = 0; k < 9; ++k)
        fit += lagrange(static_cast<int>(2 * kSimpsonQuadUv[k][0]), u) *
               lagrange(static_cast<int>(2 * kSimpsonQuadUv[k][1]), v) * f[static_cast<std::size_t>(k)];
      const Vec3 x = bilinear_point(element, u, v);
      worst = std::max(worst, std::abs(point_to_polygon(x, up, bottom) - fit));
    }
  std::printf("the 9 points' biquadratic off them: off by %.3f, the points' range %.3f\n", worst, hi - lo);
  EXPECT_GT(worst, (hi - lo) / 3.0);
}

}  // namespace
}  // namespace hrad
