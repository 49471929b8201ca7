#include "hrad/analysis/error_metrics.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace hrad {
namespace {

Patch make_patch(std::vector<Vec3> v, int material = 0) {
  Patch p;
  p.vertices = std::move(v);
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < p.vertices.size(); ++i) n += p.vertices[i].cross(p.vertices[(i + 1) % p.vertices.size()]);
  p.area = 0.5 * n.norm();
  p.normal = n.normalized();
  p.material = material;
  return p;
}

Scene unit_square_scene() {
  Scene s;
  s.materials.push_back(Material{"grey", Rgb::Constant(0.5), Rgb::Zero()});
  s.patches.push_back(make_patch({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}));
  return s;
}

// The unit square cut at x = cut into two leaves with the given radiosities.
Solution split_square(double cut, const Rgb& left, const Rgb& right) {
  Solution s;
  s.vertices = {Vec3(0, 0, 0), Vec3(cut, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(cut, 1, 0), Vec3(0, 1, 0)};
  s.vertex_radiosity.assign(6, Rgb::Zero());
  s.faces = {{0, 1, 4, 5}, {1, 2, 3, 4}};
  s.face_patch = {0, 0};
  s.face_radiosity = {left, right};
  return s;
}

Solution whole_square(const Rgb& value) {
  Solution s;
  s.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  s.vertex_radiosity.assign(4, Rgb::Zero());
  s.faces = {{0, 1, 2, 3}};
  s.face_patch = {0};
  s.face_radiosity = {value};
  return s;
}

TEST(PatchSamples, WeightsAddUpToTheArea) {
  Scene s;
  s.materials.push_back(Material{});
  s.patches.push_back(make_patch(
      {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(3, 2, 0), Vec3(0.5, 2, 0)}));            // trapezoid: (4 + 2.5) / 2 * 2 = 6.5
  s.patches.push_back(make_patch({Vec3(0, 0, 1), Vec3(3, 0, 1), Vec3(0, 0, 5)}));  // triangle, 6
  const std::vector<SurfaceSample> samples = patch_samples(s, 100, SampleLayout::centres);
  ASSERT_EQ(samples.size(), 200u);
  double a0 = 0.0, a1 = 0.0;
  Vec3 c1 = Vec3::Zero();
  for (const SurfaceSample& x : samples) {
    (x.patch == 0 ? a0 : a1) += x.area;
    if (x.patch == 1) c1 += x.area * x.position;
  }
  EXPECT_NEAR(a0, 6.5, 1e-12);
  EXPECT_NEAR(a1, 6.0, 1e-12);
  // The triangle's samples are centroids of congruent pieces: their mean is the centroid (1, 0, 7/3).
  EXPECT_NEAR((c1 / a1 - Vec3(1, 0, 7.0 / 3)).norm(), 0.0, 1e-12);
  // Jittered: the same weights, one point inside each cell, the same set on every call.
  const std::vector<SurfaceSample> jittered = patch_samples(s, 100);
  ASSERT_EQ(jittered.size(), samples.size());
  const std::vector<SurfaceSample> again = patch_samples(s, 100);
  int moved = 0;
  for (std::size_t k = 0; k < jittered.size(); ++k) {
    EXPECT_EQ(jittered[k].area, samples[k].area);
    EXPECT_EQ(jittered[k].position, again[k].position);
    moved += (jittered[k].position - samples[k].position).norm() > 1e-6;
  }
  EXPECT_GT(moved, 190);
  // Quad cells: cell (i, j) of the trapezoid's bilinear map; its sample maps back into it.
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) {
      const Vec3& x = jittered[static_cast<std::size_t>(j * 10 + i)].position;
      const double v = x.y() / 2.0;                  // y = 2 v on this trapezoid
      const double left = 0.5 * v, right = 4.0 - v;  // x(u) between the slanted sides
      const double u = (x.x() - left) / (right - left);
      EXPECT_GE(u, i / 10.0 - 1e-12);
      EXPECT_LE(u, (i + 1) / 10.0 + 1e-12);
      EXPECT_GE(v, j / 10.0 - 1e-12);
      EXPECT_LE(v, (j + 1) / 10.0 + 1e-12);
    }
}

// The reason for jittered samples. Reference B = x on the unit square, solution: a g x g grid of
// leaves, each holding the exact average of B over it (the best a constant element can do). The
// continuous relative L2 error is sqrt((h^2 / 12) / (1/3)) = h / 2 with h = 1/g. The 16 x 16 cell
// centres see it as 0 on the 16 x 16 grid (each centre is a leaf's centre) and as sqrt(3) h / 2,
// 1.7x too large, on the 32 x 32 grid (each centre lies on a leaf edge); the jittered samples
// measure h / 2 on both, within their sampling error.
Solution grid_of_averages(int g) {
  Solution s;
  for (int j = 0; j <= g; ++j)
    for (int i = 0; i <= g; ++i) s.vertices.emplace_back(double(i) / g, double(j) / g, 0.0);
  s.vertex_radiosity.assign(s.vertices.size(), Rgb::Zero());
  for (int j = 0; j < g; ++j)
    for (int i = 0; i < g; ++i) {
      const int a = j * (g + 1) + i;
      s.faces.push_back({a, a + 1, a + g + 2, a + g + 1});
      s.face_patch.push_back(0);
      s.face_radiosity.push_back(Rgb::Constant((i + 0.5) / g));
    }
  return s;
}

TEST(ErrorMetrics, JitteredSamplesDoNotAliasWithQuadtreeLeaves) {
  const Scene scene = unit_square_scene();
  const auto b_is_x = [](const Vec3& x, int) { return Rgb::Constant(x.x()); };
  for (const int g : {16, 32}) {
    const Solution s = grid_of_averages(g);
    const double exact = 0.5 / g;
    const double centres =
        compare_to_function(scene, s, b_is_x, 256, Emitters::include, Field::constant, SampleLayout::centres)
            .relative_l2;
    const double jittered = compare_to_function(scene, s, b_is_x, 256).relative_l2;
    EXPECT_NEAR(jittered, exact, 0.1 * exact) << g;
    if (g == 16) EXPECT_LT(centres, 1e-12);
    if (g == 32) EXPECT_GT(centres, 1.6 * exact);
  }
}

TEST(ErrorMetrics, SolutionAgainstItselfIsZero) {
  const Scene scene = unit_square_scene();
  const Solution s = split_square(0.3, Rgb(1, 2, 3), Rgb(0.5, 0.1, 0.2));
  const ErrorMetrics m = compare_solutions(scene, s, s);
  EXPECT_EQ(m.relative_l2, 0.0);
  EXPECT_EQ(m.relative_linf, 0.0);
  EXPECT_EQ(m.unmatched, 0u);
  EXPECT_EQ(m.samples, 256u);
}

TEST(ErrorMetrics, AreaWeightedAcrossDifferentMeshes) {
  // Reference: one leaf of value 1. Solution: the quarter x < 1/4 is 1.4, the rest exact.
  // rel L2 = sqrt(0.25 * 3 * 0.16 / (3 * 1)) = 0.2; rel Linf = sqrt(3) 0.4 / sqrt(3) = 0.4.
  const Scene scene = unit_square_scene();
  const ErrorMetrics m =
      compare_solutions(scene, split_square(0.25, Rgb::Constant(1.4), Rgb::Constant(1.0)), whole_square(Rgb::Ones()));
  EXPECT_NEAR(m.relative_l2, 0.2, 1e-12);
  EXPECT_NEAR(m.relative_linf, 0.4, 1e-12);
  EXPECT_NEAR(m.rms_absolute, std::sqrt(0.25 * 3 * 0.16), 1e-12);
  ASSERT_EQ(m.patch_relative_l2.size(), 1u);
  EXPECT_NEAR(m.patch_relative_l2[0], 0.2, 1e-12);
  ASSERT_EQ(m.face_relative_l2.size(), 2u);
  EXPECT_NEAR(m.face_relative_l2[0], 0.4, 1e-12);
  EXPECT_EQ(m.face_relative_l2[1], 0.0);
  EXPECT_EQ(m.unmatched, 0u);
}

TEST(ErrorMetrics, ConstantOffsetGivesItsRelativeNorm) {
  const Scene scene = unit_square_scene();
  const Rgb ref(0.2, 0.5, 0.7), offset(0.1, -0.2, 0.3);
  const ErrorMetrics m = compare_solutions(scene, split_square(0.6, ref + offset, ref + offset), whole_square(ref));
  const double expected = std::sqrt(0.01 + 0.04 + 0.09) / std::sqrt(0.04 + 0.25 + 0.49);
  EXPECT_NEAR(m.relative_l2, expected, 1e-12);
  EXPECT_NEAR(m.relative_linf, expected, 1e-12);
}

// Values known only at the samples (a final gather there): a constant offset on one of two patches
// gives its area-weighted relative norm over the whole, the offset patch its own relative norm, the
// other 0; the largest sample error over the largest reference value is the Linf error.
TEST(ErrorMetrics, ValuesAtSamplesGiveTheirAreaWeightedNorm) {
  Scene scene = unit_square_scene();
  scene.patches.push_back(make_patch({Vec3(2, 0, 0), Vec3(5, 0, 0), Vec3(5, 1, 0), Vec3(2, 1, 0)}));  // area 3
  const std::vector<SurfaceSample> samples = patch_samples(scene, 16);
  const Rgb ref(0.2, 0.5, 0.7), offset(0.1, -0.2, 0.3);
  std::vector<Rgb> values, reference;
  for (const SurfaceSample& x : samples) {
    reference.push_back(ref);
    values.push_back(x.patch == 1 ? ref + offset : ref);
  }
  const ErrorMetrics m = compare_at_samples(scene, samples, values, reference);
  const double patch = std::sqrt(0.01 + 0.04 + 0.09) / std::sqrt(0.04 + 0.25 + 0.49);
  EXPECT_NEAR(m.relative_l2, patch * std::sqrt(3.0 / 4.0), 1e-12);
  EXPECT_NEAR(m.relative_linf, patch, 1e-12);
  EXPECT_EQ(m.patch_relative_l2[0], 0.0);
  EXPECT_NEAR(m.patch_relative_l2[1], patch, 1e-12);
  EXPECT_EQ(m.samples, samples.size());
  EXPECT_TRUE(m.face_relative_l2.empty());
}

TEST(ErrorMetrics, EmittersCanBeLeftOut) {
  // Patch 0 (emitting) is 10% off everywhere, patch 1 (plain) exact: only the former counts.
  Scene scene = unit_square_scene();
  scene.materials.push_back(Material{"light", Rgb::Constant(0.5), Rgb::Constant(5.0)});
  scene.patches[0].material = 1;
  Patch second = scene.patches[0];
  for (Vec3& v : second.vertices) v.z() = 1.0;
  second.material = 0;
  scene.patches.push_back(second);
  Solution ref = whole_square(Rgb::Constant(5.0)), sol = whole_square(Rgb::Constant(5.5));
  for (int k = 0; k < 4; ++k) {
    ref.vertices.push_back(ref.vertices[k] + Vec3(0, 0, 1));
    sol.vertices.push_back(sol.vertices[k] + Vec3(0, 0, 1));
  }
  for (Solution* s : {&ref, &sol}) {
    s->faces.push_back({4, 5, 6, 7});
    s->face_patch.push_back(1);
    s->face_radiosity.push_back(Rgb::Constant(1.0));
  }
  // Included: sqrt(0.25 / (25 + 1)) over equal areas.
  EXPECT_NEAR(compare_solutions(scene, sol, ref).relative_l2, std::sqrt(0.25 / 26.0), 1e-12);
  const ErrorMetrics m = compare_solutions(scene, sol, ref, 64, Emitters::exclude);
  EXPECT_EQ(m.relative_l2, 0.0);
  EXPECT_EQ(m.samples, 64u);
  EXPECT_TRUE(std::isnan(m.patch_relative_l2[0]));
  EXPECT_TRUE(std::isnan(m.face_relative_l2[0]));
  EXPECT_EQ(m.face_relative_l2[1], 0.0);
}

TEST(ErrorMetrics, AnalyticReferenceMatchesTheMidpointRule) {
  // B = 1/2 against Bref(x) = x (all channels): the midpoint rule with h = 1/16 integrates x^2 to
  // 1/3 - h^2/12 and (x - 1/2)^2 to 1/12 - h^2/12, so rel L2 = sqrt((1/12 - h2/12) / (1/3 - h2/12)),
  // close to the continuous 1/2.
  const Scene scene = unit_square_scene();
  const ErrorMetrics m = compare_to_function(
      scene, whole_square(Rgb::Constant(0.5)), [](const Vec3& x, int) { return Rgb::Constant(x.x()); }, 256,
      Emitters::include, Field::constant, SampleLayout::centres);
  const double h2 = 1.0 / 256;
  EXPECT_NEAR(m.relative_l2, std::sqrt((1.0 / 12 - h2 / 12) / (1.0 / 3 - h2 / 12)), 1e-12);
  EXPECT_NEAR(m.relative_l2, 0.5, 2e-3);
  // Linf: the largest |x - 1/2| at a sample is 15/32, the largest x is 31/32.
  EXPECT_NEAR(m.relative_linf, 15.0 / 31.0, 1e-12);
}

TEST(SolutionSampler, FindsLeavesWithTVerticesAndFallsBackOutside) {
  // A leaf with a T-vertex on its top edge (a pentagon with a collinear vertex) next to two quads.
  const Scene scene = unit_square_scene();
  Solution s;
  s.vertices = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0.5, 1, 0),
                Vec3(0, 1, 0), Vec3(1, 0, 0),   Vec3(1, 0.5, 0),   Vec3(1, 1, 0)};
  s.faces = {{0, 1, 2, 3, 4}, {1, 5, 6, 2}, {2, 6, 7, 3}};
  s.face_patch = {0, 0, 0};
  s.face_radiosity = {Rgb::Constant(1), Rgb::Constant(2), Rgb::Constant(3)};
  const SolutionSampler sampler(scene, s);
  bool matched = false;
  EXPECT_EQ(sampler.leaf_at(Vec3(0.25, 0.9, 0), 0, &matched), 0);
  EXPECT_TRUE(matched);
  EXPECT_EQ(sampler.leaf_at(Vec3(0.75, 0.25, 0), 0), 1);
  EXPECT_EQ(sampler.leaf_at(Vec3(0.75, 0.75, 0), 0), 2);
  EXPECT_EQ(sampler.leaf_at(Vec3(1.2, 0.8, 0), 0, &matched), 2);  // outside: the nearest leaf
  EXPECT_FALSE(matched);
}

TEST(SolutionSampler, FindsTheRightLeafAmongMany) {
  // A 40 x 40 grid of leaves on the unit square: the leaf containing (x, y) is floor(40 y) * 40 + floor(40 x).
  const Scene scene = unit_square_scene();
  const int g = 40;
  Solution s;
  for (int j = 0; j <= g; ++j)
    for (int i = 0; i <= g; ++i) s.vertices.emplace_back(double(i) / g, double(j) / g, 0.0);
  for (int j = 0; j < g; ++j)
    for (int i = 0; i < g; ++i) {
      const int a = j * (g + 1) + i;
      s.faces.push_back({a, a + 1, a + g + 2, a + g + 1});
      s.face_patch.push_back(0);
      s.face_radiosity.push_back(Rgb::Constant(j * g + i));
    }
  const SolutionSampler sampler(scene, s);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const double x = u(rng), y = u(rng);
    const int expected = static_cast<int>(y * g) * g + static_cast<int>(x * g);
    const int leaf = sampler.leaf_at(Vec3(x, y, 0), 0);
    // Points within the tolerance of a shared edge may go to either neighbour.
    if (leaf != expected) {
      EXPECT_LT(std::min(std::abs(x * g - std::round(x * g)), std::abs(y * g - std::round(y * g))), 1e-4);
    }
  }
}

// A closed unit cube seen from inside: six inward-facing patches with one material.
Scene closed_cube(const Rgb& rho, const Rgb& emission) {
  Scene s;
  s.materials.push_back(Material{"m", rho, emission});
  const Vec3 c[8] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                     Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  const int quads[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
  for (const auto& q : quads) s.patches.push_back(make_patch({c[q[0]], c[q[1]], c[q[2]], c[q[3]]}));
  return s;
}

Solution one_leaf_per_patch(const Scene& scene, const Rgb& b) {
  Solution s;
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    std::vector<int> face;
    for (const Vec3& v : scene.patches[p].vertices) {
      face.push_back(static_cast<int>(s.vertices.size()));
      s.vertices.push_back(v);
    }
    s.faces.push_back(face);
    s.face_patch.push_back(static_cast<int>(p));
    s.face_radiosity.push_back(b);
  }
  return s;
}

TEST(EnergyBalance, FurnaceIsBalancedAndAnErrorShows) {
  // Uniform emission E and reflectance rho everywhere in a closed room: B = E / (1 - rho).
  const Rgb rho(0.5, 0.8, 0.25), e(1.0, 2.0, 3.0);
  const Scene scene = closed_cube(rho, e);
  const EnergyBalance exact = energy_balance(scene, one_leaf_per_patch(scene, e / (1.0 - rho)));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(exact.emitted_power[c], 6.0 * e[c], 1e-12);
    EXPECT_NEAR(exact.radiosity_power[c], 6.0 * e[c] / (1.0 - rho[c]), 1e-12);
    EXPECT_NEAR(exact.closed_scene_residual[c], 0.0, 1e-12);
  }
  // B 10% too high in the red channel: absorbed = 6 (1 - 0.5)/0.5 (2.2 - 1) = 7.2 vs emitted 6.
  const EnergyBalance off = energy_balance(scene, one_leaf_per_patch(scene, Rgb(2.2, 10.0, 4.0)));
  EXPECT_NEAR(off.absorbed_power[0], 7.2, 1e-12);
  EXPECT_NEAR(off.closed_scene_residual[0], 0.2, 1e-12);
  // A black material hides its irradiance: NaN, not a made-up number.
  const Scene black = closed_cube(Rgb(0.0, 0.5, 0.5), e);
  EXPECT_TRUE(std::isnan(energy_balance(black, one_leaf_per_patch(black, e)).closed_scene_residual[0]));
}

}  // namespace
}  // namespace hrad

namespace hrad {
namespace {

// Field::interpolated reproduces a linear field exactly on any fan of a leaf (two leaves with a
// shared edge here), where the constant field cannot.
TEST(ErrorMetrics, InterpolatedFieldIsExactForLinearVertexValues) {
  const Scene scene = unit_square_scene();
  const auto linear = [](const Vec3& x) { return Rgb(1.0 + 2.0 * x.x() + 3.0 * x.y(), 2.0, 0.5 + x.y()); };
  Solution s = split_square(0.3, Rgb::Ones(), Rgb::Ones());
  for (std::size_t v = 0; v < s.vertices.size(); ++v) s.vertex_radiosity[v] = linear(s.vertices[v]);
  const auto reference = [&](const Vec3& x, int) { return linear(x); };
  EXPECT_LT(compare_to_function(scene, s, reference, 400, Emitters::include, Field::interpolated).relative_l2, 1e-14);
  EXPECT_GT(compare_to_function(scene, s, reference, 400, Emitters::include, Field::constant).relative_l2, 0.1);
}

// Vertex values 0, 0, 1, 1 (y = 0 and y = 1) interpolate to B = y; against the constant 1/2 the
// midpoint samples of an m x m grid give sum_j ((j + 1/2)/m - 1/2)^2 / m = (m^2 - 1) / (12 m^2).
TEST(ErrorMetrics, InterpolatedFieldAgainstAConstantByHand) {
  const Scene scene = unit_square_scene();
  Solution s = whole_square(Rgb::Constant(0.5));
  s.vertex_radiosity = {Rgb::Zero(), Rgb::Zero(), Rgb::Ones(), Rgb::Ones()};
  const int m = 16;
  const ErrorMetrics e = compare_to_function(
      scene, s, [](const Vec3&, int) { return Rgb::Constant(0.5); }, m * m, Emitters::include, Field::interpolated,
      SampleLayout::centres);
  EXPECT_NEAR(e.relative_l2, std::sqrt((m * m - 1.0) / (12.0 * m * m)) / 0.5, 1e-12);
  EXPECT_NEAR(e.relative_linf, (0.5 - 0.5 / m) / 0.5, 1e-12);
  EXPECT_EQ(compare_to_function(
                scene, s, [](const Vec3&, int) { return Rgb::Constant(0.5); }, m * m)
                .relative_l2,
            0.0);
}

}  // namespace
}  // namespace hrad
