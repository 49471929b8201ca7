// The hard-case suite (CTest label `hard`): configurations where radiosity codes lose precision,
// leak, divide by zero or stall. Each test states the outcome it guarantees; README "Hard cases"
// lists them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../formfactor/howell.h"
#include "../solvers/solver_test_scenes.h"
#include "../support/temp_dir.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/io/obj_reader.h"
#include "hrad/solvers/solve.h"

namespace hrad {
namespace {

using test::add_polygon;
using test::make_box;
using test::material;

// Runs a solve and checks what every hard case must give: finite radiosity everywhere.
Solution solve_finite(const Scene& scene, const SolveOptions& options, SolveSummary* summary = nullptr) {
  Solution sol;
  const SolveSummary s = solve(scene, options, &sol);
  for (const Rgb& b : sol.face_radiosity) EXPECT_TRUE(b.allFinite());
  EXPECT_NE(s.termination, Termination::kFailed) << s.message;
  if (summary) *summary = s;
  return sol;
}

double max_relative_deviation(const Solution& sol, double expected) {
  double worst = 0.0;
  for (const Rgb& b : sol.face_radiosity) worst = std::max(worst, (b - expected).abs().maxCoeff() / expected);
  return worst;
}

SolveOptions full(double max_area) {
  SolveOptions o;
  o.method = Method::kFull;
  o.max_area = max_area;
  o.kernel = FormFactorKernel::kAnalytic;  // exact and reciprocal: energy balance to rounding
  return o;
}

std::vector<Vec3> square(const Vec3& o, const Vec3& u, const Vec3& v) { return {o, o + u, o + u + v, o + v}; }

// Nearly coplanar neighbours: two unit squares sharing an edge, bent by eps out of their plane.
// Outcome: 0 <= F <= 1 - cos(eps/2) + 1e-15, the factor between infinitely long strips at interior angle
// pi - eps (2D crossed strings, Hottel), which bounds the finite squares' factor; reciprocal.
TEST(HardCases, NearlyCoplanarAdjacentPatches) {
  for (double eps : {1e-2, 1e-4, 1e-6, 1e-8}) {
    const auto a = square({0, 0, 0}, {0, 0, 1}, {1, 0, 0});  // y = 0, normal +y
    const Vec3 dir(-std::cos(eps), std::sin(eps), 0);        // the other square bends up by eps
    const auto b = square({0, 0, 0}, dir, {0, 0, 1});
    const PairFormFactor f = polygon_to_polygon(a, b);
    ASSERT_TRUE(std::isfinite(f.from_to) && std::isfinite(f.to_from)) << eps;
    EXPECT_GE(f.from_to, 0.0);
    // 1 - cos(eps/2) = eps^2/8 to rounding here; the kernel's own rounding near a shared edge is
    // about 1e-16 absolute (its edge terms are of order 1).
    EXPECT_LE(f.from_to, eps * eps / 8 + 1e-15) << eps;
    EXPECT_NEAR(f.from_to, f.to_from, 1e-15);
  }
}

// Patches meeting at very small angles: a closed wedge (two 1 x 1 plates at angle alpha, a strip
// closing it, two triangular caps). Outcome: the factors from each plate to the rest of the closed
// wedge sum to 1 within 1e-10, for alpha down to 1e-4.
TEST(HardCases, PatchesMeetingAtVerySmallAngles) {
  for (double alpha : {1e-1, 1e-2, 1e-3, 1e-4}) {
    const Vec3 p0(0, 0, 0), p1(0, 0, 1), a1(1, 0, 0), b1(std::cos(alpha), std::sin(alpha), 0);
    // Interior is the thin wedge between the plates; fronts face into it.
    std::vector<std::vector<Vec3>> faces = {{p0, a1, a1 + p1, p1},       // lower plate
                                            {p0, p1, b1 + p1, b1},       // upper plate
                                            {a1, b1, b1 + p1, a1 + p1},  // closing strip
                                            {p0, b1, a1},                // cap z = 0
                                            {p1, a1 + p1, b1 + p1}};     // cap z = 1
    const Vec3 inside = (a1 + b1) / 3 + Vec3(0, 0, 0.5);
    for (auto& f : faces)
      if (newell_normal(f).dot(inside - f[0]) < 0) std::reverse(f.begin(), f.end());
    for (int from : {0, 1}) {
      double sum = 0.0;
      for (int to = 0; to < 5; ++to)
        if (to != from) sum += polygon_to_polygon(faces[from], faces[to]).from_to;
      EXPECT_NEAR(sum, 1.0, 1e-10) << "alpha " << alpha << " plate " << from;
    }
  }
}

// Slivers: a closed unit box whose floor is cut into a strip of width 1e-6 and the rest.
// Outcome: with uniform emission E and reflectance rho, B = E/(1-rho) on every element within 1e-8
// (full matrix, LU), which needs every row of factors, the sliver's included, to sum to 1.
TEST(HardCases, SliverPatchesAspect1e6) {
  const double rho = 0.9, e = 1.0, w = 1e-6;
  Scene s;
  s.materials = {material(Rgb::Constant(rho), Rgb::Constant(e))};
  const Vec3 c(0.5, 0.5, 0.5);
  const auto wall = [&](std::vector<Vec3> v) { add_polygon(s, v, c - polygon_centroid(v), 0); };
  wall(square({0, 0, 0}, {w, 0, 0}, {0, 0, 1}));      // sliver, 1e-6 x 1
  wall(square({w, 0, 0}, {1 - w, 0, 0}, {0, 0, 1}));  // the rest of the floor
  wall(square({0, 1, 0}, {1, 0, 0}, {0, 0, 1}));
  wall(square({0, 0, 0}, {0, 1, 0}, {0, 0, 1}));
  wall(square({1, 0, 0}, {0, 1, 0}, {0, 0, 1}));
  wall(square({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  wall(square({0, 0, 1}, {1, 0, 0}, {0, 1, 0}));
  // Every patch stays one element: the sliver's rows are the hard ones.
  const Solution sol = solve_finite(s, full(2.0));
  EXPECT_LT(max_relative_deviation(sol, e / (1 - rho)), 1e-8);
}

// Near-coincident parallel patches: unit squares at gap 1e-9 of their size, and the same at scales
// 1e-8 and 1e8. Outcome: Howell's C-11 within 1e-9 relative, reciprocal, F <= 1.
TEST(HardCases, NearCoincidentParallelPatches) {
  for (double scale : {1e-8, 1.0, 1e8}) {
    const double gap = 1e-9 * scale;
    const auto a = square({0, 0, 0}, {0, 0, scale}, {scale, 0, 0});    // faces +y
    const auto b = square({0, gap, 0}, {scale, 0, 0}, {0, 0, scale});  // faces -y
    const PairFormFactor f = polygon_to_polygon(a, b);
    EXPECT_NEAR(f.from_to, test::howell_c11(1, 1, 1e-9), 1e-9) << scale;
    EXPECT_LE(f.from_to, 1.0);
    EXPECT_NEAR(f.from_to, f.to_from, 1e-15);
  }
}

// One file spanning 1e-3 to 1e3: a closed 1000-box whose floor holds a 1e-3 square (the floor is
// cut around it). Outcome: uniform E and rho give B = E/(1-rho) within 1e-8 on every element.
TEST(HardCases, SceneSpanning1e3To1e3) {
  const double L = 1000.0, t = 1e-3, rho = 0.5, e = 2.0;
  Scene s;
  s.materials = {material(Rgb::Constant(rho), Rgb::Constant(e))};
  const Vec3 c(L / 2, L / 2, L / 2);
  const auto wall = [&](std::vector<Vec3> v) { add_polygon(s, v, c - polygon_centroid(v), 0); };
  const double m = L / 2;  // the tiny square sits at (m, 0, m)
  wall(square({m, 0, m}, {t, 0, 0}, {0, 0, t}));
  wall(square({0, 0, 0}, {m, 0, 0}, {0, 0, L}));              // x < m
  wall(square({m + t, 0, 0}, {L - m - t, 0, 0}, {0, 0, L}));  // x > m + t
  wall(square({m, 0, 0}, {t, 0, 0}, {0, 0, m}));              // strip below
  wall(square({m, 0, m + t}, {t, 0, 0}, {0, 0, L - m - t}));  // strip above
  wall(square({0, L, 0}, {L, 0, 0}, {0, 0, L}));
  wall(square({0, 0, 0}, {0, L, 0}, {0, 0, L}));
  wall(square({L, 0, 0}, {0, L, 0}, {0, 0, L}));
  wall(square({0, 0, 0}, {L, 0, 0}, {0, L, 0}));
  wall(square({0, 0, L}, {L, 0, 0}, {0, L, 0}));
  const Solution sol = solve_finite(s, full(L * L / 8));
  EXPECT_LT(max_relative_deviation(sol, e / (1 - rho)), 1e-8);
}

// The same scene at scales about 1e-6 and 1e6. Outcome, for every method:
//  * scaled by 2^-20 and 2^20 (exact in binary floating point, so the geometry is the same up to
//    the unit), a room with an occluding block gives the same element radiosity within 1e-9;
//  * scaled by 1e-6 and 1e6 (rounded coordinates), a convex room gives the same within 1e-9 (full,
//    substructuring) and 1e-5 (hierarchical: see below).
//    With occluders, decimal scaling moves rays that graze an edge exactly (a block standing on the
//    floor) to either side of it, so single elements may differ by the sampling error there.
void expect_scale_invariant(const Scene& scene, std::initializer_list<double> scales, double hierarchical_bound) {
  for (Method method : {Method::kFull, Method::kSubstructure, Method::kHierarchical}) {
    SolveOptions o;
    o.method = method;
    o.max_area = 0.09;  // not at a split boundary of these walls (areas / 4^k), so rounding cannot flip a split
    o.aeps = 0.011;
    const Solution unit = solve_finite(scene, o);
    for (double k : scales) {
      SolveOptions ok = o;
      ok.max_area *= k * k;
      ok.aeps *= k * k;
      const Solution sol = solve_finite(test::scaled(scene, k), ok);
      ASSERT_EQ(sol.face_radiosity.size(), unit.face_radiosity.size()) << to_string(method) << " scale " << k;
      double worst = 0.0;
      for (std::size_t f = 0; f < unit.face_radiosity.size(); ++f)
        worst = std::max(worst, (sol.face_radiosity[f] - unit.face_radiosity[f]).abs().maxCoeff() /
                                    unit.face_radiosity[f].abs().maxCoeff());
      EXPECT_LT(worst, method == Method::kHierarchical ? hierarchical_bound : 1e-9)
          << to_string(method) << " scale " << k;
    }
  }
}

TEST(HardCases, SameSceneAtScales1e6And1eMinus6) {
  const std::vector<Material> m = {material(Rgb::Constant(0.6), Rgb::Zero()),
                                   material(Rgb::Constant(0.3), Rgb::Constant(5))};
  Scene blocked = make_box(1, 0.8, 1.2, m, {0, 1, 0, 0, 0, 0});
  test::add_block(blocked, 0.3, 0.6, 0, 0.4, 0.3, 0.7, 0);
  expect_scale_invariant(blocked, {std::ldexp(1.0, -20), std::ldexp(1.0, 20)}, 1e-9);
  // Hierarchical radiosity iterates to its tolerance (1e-6 of the largest reflected radiosity) and
  // rounding moves where it stops by less than that: the two answers agree to 1e-5 of each face.
  expect_scale_invariant(make_box(1, 0.8, 1.2, m, {0, 1, 0, 0, 0, 0}), {1e-6, 1e6}, 1e-5);
}

// Reflectance 0.999 in a closed room: Jacobi contracts by 0.999 per iteration at best. Outcome:
//  * with few iterations every iterative solver stops with a status (kMaxIterations) and finite values;
//  * given enough, the hierarchical solver converges to E/(1-rho) within 1e-3 per element (its
//    links are resolved to the leaves on both sides, so every element's factors sum to 1);
//  * the full matrix (LU) is exact to 1e-8.
TEST(HardCases, Reflectance0999ClosedRoom) {
  const double rho = 0.999, e = 1.0;
  const Scene box = make_box(1, 1, 1, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0});
  for (Method method : {Method::kSubstructure, Method::kHierarchical}) {
    SolveOptions o;
    o.method = method;
    o.max_area = 0.1;
    o.max_iterations = 50;
    SolveSummary s;
    solve_finite(box, o, &s);
    EXPECT_EQ(s.termination, Termination::kMaxIterations) << to_string(method) << ": " << s.message;
    EXPECT_EQ(s.iterations, 50);
  }
  // Per element with links resolved to the leaves (each leaf's factors sum to 1): within 1e-3. The
  // HSA push's leaves sum to 1 only up to the interpolation of their links' fields, and what they
  // send and receive is correlated with that (a leaf that gathers a little too much also shines a
  // little brighter), which 1 / (1 - rho) = 1000 amplifies: the area mean within 1e-2.
  for (const Push push : {Push::kLeaf, Push::kHsa}) {
    SolveOptions hr;
    hr.method = Method::kHierarchical;
    hr.max_iterations = 40000;
    hr.tolerance = 1e-7;
    hr.push = push;
    Solution sol;
    const SolveSummary s = solve(box, hr, &sol);
    for (const Rgb& b : sol.face_radiosity) EXPECT_TRUE(b.allFinite());
    EXPECT_FALSE(s.message.empty());
    EXPECT_EQ(s.termination, Termination::kConverged) << s.message;
    if (push == Push::kLeaf) EXPECT_LT(max_relative_deviation(sol, e / (1 - rho)), 1e-3);
    double mean = 0.0;
    for (std::size_t i = 0; i < box.patches.size(); ++i)
      mean += box.patches[i].area * sol.patch_radiosity[i][0] / box.total_area();
    EXPECT_NEAR(mean * (1 - rho) / e, 1.0, push == Push::kLeaf ? 1e-3 : 1e-2) << to_string(push);
  }
  const Solution lu = solve_finite(box, full(0.1));
  EXPECT_LT(max_relative_deviation(lu, e / (1 - rho)), 1e-8);
}

// An emitter touching receivers: a light square lying on the floor in a corner of a closed box (it
// shares edges with two walls and the rest of the floor). Outcome: with the analytic kernel all
// emitted power is absorbed (closed scene, convex: no visibility needed) within 1e-9.
TEST(HardCases, EmitterTouchingReceivers) {
  Scene s =
      make_box(1, 1, 1, {material(Rgb::Constant(0.7), Rgb::Zero()), material(Rgb::Constant(0.2), Rgb::Constant(10))},
               {0, 0, 0, 0, 0, 0});
  // Cut the light out of the floor: floor patch 0 becomes the light [0, 0.25] x [0, 0.25] plus the rest.
  s.patches.erase(s.patches.begin());
  s.faces.erase(s.faces.begin());
  for (std::size_t i = 0; i < s.patches.size(); ++i) {
    s.patches[i].face = static_cast<int>(i);
    s.faces[i].patches = {static_cast<int>(i)};
  }
  const Vec3 c(0.5, 0.5, 0.5);
  const auto floor = [&](std::vector<Vec3> v, int m) { add_polygon(s, v, c - polygon_centroid(v), m); };
  floor(square({0, 0, 0}, {0.25, 0, 0}, {0, 0, 0.25}), 1);
  floor(square({0.25, 0, 0}, {0.75, 0, 0}, {0, 0, 1}), 0);
  floor(square({0, 0, 0.25}, {0.25, 0, 0}, {0, 0, 0.75}), 0);
  SolveSummary summary;
  const Solution sol = solve_finite(s, full(0.02), &summary);
  const EnergyBalance eb = energy_balance(s, sol);
  EXPECT_LT(eb.closed_scene_residual.maxCoeff(), 1e-9) << ::testing::PrintToString(summary.effects.reasons);
}

// A tiny emitter in a huge room: a 1 cm light 1 m below the ceiling of a 1 km box. Outcome: the walls
// absorb the emitted power within 1e-5 (full, LU, analytic kernel; the light hides bits of the
// ceiling, so sampled visibility enters), within 1e-4 with the hierarchical solver's leaf push and
// 1e-2 with its HSA push (the radiosity varies by orders of magnitude over the walls, and the
// leaves' closure errors, within feps, are correlated with it).
TEST(HardCases, TinyEmitterInHugeRoom) {
  const double L = 1000.0, t = 0.01;
  Scene s = make_box(L, L, L, {material(Rgb::Constant(0.5), Rgb::Zero()), material(Rgb::Zero(), Rgb::Constant(1e6))},
                     {0, 0, 0, 0, 0, 0});
  const Vec3 c(L / 2, L / 2, L / 2);
  // Just below the ceiling, facing down.
  add_polygon(s, square({L / 2, L - 1, L / 2}, {t, 0, 0}, {0, 0, t}), Vec3(0, -1, 0), 1);
  const Solution sol = solve_finite(s, full(L * L / 16));
  // rho = 0 on the light: the balance is over the walls, which absorb everything that leaves it.
  double emitted = 1e6 * t * t, absorbed = 0.0;
  for (std::size_t f = 0; f < sol.faces.size(); ++f) {
    const Patch& p = s.patches[sol.face_patch[f]];
    if (s.material_of(p).is_emitter()) continue;
    double area = 0.0;
    std::vector<Vec3> poly;
    for (int v : sol.faces[f]) poly.push_back(sol.vertices[v]);
    area = polygon_area(poly);
    absorbed += area * (1 - 0.5) / 0.5 * sol.face_radiosity[f][0];
  }
  EXPECT_NEAR(absorbed / emitted, 1.0, 1e-5);
  // The hierarchical solver once stopped after the direct light here (its convergence test divided
  // by the light's radiosity, 1e6 against 1e-5 on the walls) and returned half the absorbed power.
  for (const Push push : {Push::kLeaf, Push::kHsa}) {
    SolveOptions hr;
    hr.method = Method::kHierarchical;
    hr.push = push;
    const Solution h = solve_finite(s, hr);
    double absorbed_hr = 0.0;
    for (std::size_t f = 0; f < h.faces.size(); ++f) {
      if (s.material_of(s.patches[h.face_patch[f]]).is_emitter()) continue;
      std::vector<Vec3> poly;
      for (int v : h.faces[f]) poly.push_back(h.vertices[v]);
      absorbed_hr += polygon_area(poly) * (1 - 0.5) / 0.5 * h.face_radiosity[f][0];
    }
    EXPECT_NEAR(absorbed_hr / emitted, 1.0, push == Push::kLeaf ? 1e-4 : 1e-2) << to_string(push);
  }
}

// Non-planar and non-convex input faces: a closed box read from OBJ whose top is an L-shaped
// hexagon plus a square (a non-convex face) and whose floor has one corner 1e-3 below its plane
// (split into triangles along the diagonal that keeps the box convex). Outcome: uniform E and rho
// give B = E/(1-rho) within 1e-6 on every element. (Not 1e-8: the exact occlusion test is
// conservative for the split faces and turns visibility on, and the sampled pairs near the fold
// carry a small visibility error; measured 3.8e-7.)
TEST(HardCases, NonPlanarAndNonConvexInputFaces) {
  test::TempDir dir;
  dir.write("m.mtl", "newmtl w\nKd 0.8 0.8 0.8\nKe 1 1 1\n");
  const std::string obj =
      dir.write("box.obj",
                "mtllib m.mtl\nusemtl w\n"
                "v 0 0 0\nv 1 0 0\nv 1 -0.001 1\nv 0 0 1\n"  // 1-4 bottom corners, 3 below the plane
                "v 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"       // 5-8 top corners
                "v 0.5 1 0.5\nv 1 1 0.5\nv 0.5 1 1\n"        // 9-11 top inner points
                "f 1 4 3 2\n"                                // floor, non-planar, faces +y
                "f 6 10 9 11 8 5\n"                          // top L-shape (non-convex), faces -y
                "f 10 7 11 9\n"                              // top remaining square, faces -y
                "f 1 5 8 4\n"                                // x = 0, faces +x
                "f 2 3 7 6\n"                                // x = 1, faces -x
                "f 4 8 7 3\n"                                // z = 1, faces -z
                "f 1 2 6 5\n");                              // z = 0, faces +z
  std::vector<std::string> warnings;
  const Scene s = read_obj_scene(obj, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("non-planar"), std::string::npos);
  EXPECT_EQ(s.faces.size(), 7u);
  EXPECT_EQ(s.patches.size(), 2u + 4u + 1u + 4u);  // floor 2 triangles, L-shape 4 triangles
  SolveSummary summary;
  const Solution sol = solve_finite(s, full(0.1), &summary);
  EXPECT_LT(max_relative_deviation(sol, 1.0 / (1 - 0.8)), 1e-6) << ::testing::PrintToString(summary.effects.reasons);
}

}  // namespace
}  // namespace hrad
