// Hierarchical radiosity (HSA 1991) against closed forms and invariants: closed rooms
// (B = E / (1 - rho)), the faceted sphere (area mean Ebar / (1 - rho)), energy balance, closure of
// both link operators, stability, scale invariance, link counts, refinement near an edge,
// determinism.
#include "hrad/solvers/hierarchical.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "hrad/analysis/error_metrics.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/obj_reader.h"
#include "hrad/solvers/cluster_transfer.h"
#include "hrad/solvers/hsa_links.h"
#include "hrad/solvers/leaf_links.h"
#include "hrad/solvers/push_pull.h"
#include "hrad/solvers/refine.h"
#include "hrad/solvers/refinement_oracle.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/solver_context.h"
#include "solver_test_scenes.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

std::string scene_path(const std::string& name) { return test::source_dir() + "/notebooks_data/scenes/" + name; }

using test::add_polygon;
using test::make_faceted_sphere;
using test::scaled;

// The six inward-facing walls of the box [0,a] x [0,b] x [0,c]; wall k uses materials[k].
Scene make_box(double a, double b, double c, const std::vector<Material>& materials) {
  Scene s;
  s.materials = materials;
  auto m = [&](int k) { return std::min<int>(k, static_cast<int>(materials.size()) - 1); };
  const Vec3 centre(a / 2, b / 2, c / 2);
  auto wall = [&](std::vector<Vec3> v, int k) { add_polygon(s, v, centre - polygon_centroid(v), m(k)); };
  wall({{0, 0, 0}, {a, 0, 0}, {a, 0, c}, {0, 0, c}}, 0);  // floor
  wall({{0, b, 0}, {a, b, 0}, {a, b, c}, {0, b, c}}, 1);  // ceiling
  wall({{0, 0, 0}, {0, b, 0}, {0, b, c}, {0, 0, c}}, 2);  // x = 0
  wall({{a, 0, 0}, {a, b, 0}, {a, b, c}, {a, 0, c}}, 3);  // x = a
  wall({{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}}, 4);  // z = 0
  wall({{0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}}, 5);  // z = c
  return s;
}

Material gray(double rho, double e) { return {"m", Rgb::Constant(rho), Rgb::Constant(e)}; }

double area_mean(const Scene& s, const Solution& sol, int channel) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.patches.size(); ++i) sum += s.patches[i].area * sol.patch_radiosity[i][channel];
  return sum / s.total_area();
}

SolveSummary solve_hr(const Scene& s, Solution* sol, SolveOptions o = {}) {
  o.method = Method::kHierarchical;
  return solve_hierarchical(s, o, sol);
}

SolveOptions with_push(Push push) {
  SolveOptions o;
  o.push = push;
  return o;
}

// --- Closed rooms: B = E / (1 - rho) ------------------------------------------------------------

double worst_patch_deviation(const Solution& sol, double expected) {
  double worst = 0.0;
  for (const Rgb& b : sol.patch_radiosity) worst = std::max(worst, std::abs(b[0] / expected - 1.0));
  return worst;
}

double worst_element_deviation(const Solution& sol, double expected) {
  double worst = 0.0;
  for (const Rgb& b : sol.face_radiosity) worst = std::max(worst, std::abs(b[0] / expected - 1.0));
  return worst;
}

// |absorbed / emitted - 1| of a solution of a closed scene (channel 0).
double power_residual(const Scene& s, const Solution& sol) { return energy_balance(s, sol).closed_scene_residual[0]; }

class ClosedBoxLeafPush : public ::testing::TestWithParam<double> {};

TEST_P(ClosedBoxLeafPush, EveryElementIsEOverOneMinusRho) {
  // With links resolved to the leaves (Push::kLeaf, leaf_links.h) each leaf gathers its ancestors'
  // links with its own factor, so its factors sum to 1 (closure) up to quadrature: every element
  // within 1% of E / (1 - rho) for rho up to 0.99.
  const double rho = GetParam();
  const double e = 3.0;
  const Scene s = make_box(4.0, 2.5, 5.0, {gray(rho, e)});
  Solution sol;
  const SolveSummary sum = solve_hr(s, &sol, with_push(Push::kLeaf));
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_GT(sum.elements, 6u);  // it did refine
  const double expected = e / (1.0 - rho);
  EXPECT_LT(worst_element_deviation(sol, expected), 0.01);
  EXPECT_NEAR(area_mean(s, sol, 0) / expected, 1.0, 5e-3);
}

INSTANTIATE_TEST_SUITE_P(Reflectances, ClosedBoxLeafPush, ::testing::Values(0.5, 0.9, 0.99));

TEST(Hierarchical, HsaPushKeepsAClosedRoomsPatchesAndPowerAtModerateReflectance) {
  // The HSA push (the default) gives each leaf its ancestors' links' factor fields, interpolated
  // over the leaf (push_pull.h), so a leaf's factors sum to 1 only up to the interpolation error
  // the oracle bounds (feps), and an element's radiosity errs by about that times rho / (1 - rho).
  // Guaranteed at rho = 0.5 and the defaults: each patch within 1% of E / (1 - rho) and the
  // absorbed power within 1e-3 of the emitted.
  const double rho = 0.5, e = 3.0;
  for (const bool t_junctions : {false, true}) {
    const Scene s = test::make_box(4.0, 2.5, 5.0, {gray(rho, e)}, {0, 0, 0, 0, 0, 0}, t_junctions);
    Solution sol;
    const SolveSummary sum = solve_hr(s, &sol);
    ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
    const double expected = e / (1.0 - rho);
    EXPECT_LT(worst_patch_deviation(sol, expected), 0.01) << "t-junctions " << t_junctions;
    EXPECT_LT(power_residual(s, sol), 1e-3) << "t-junctions " << t_junctions;
  }
}

TEST(Hierarchical, TJunctionBoxElementsAreEOverOneMinusRhoAtAnyFeps) {
  // Walls cut into strips meet in T-junctions. The leaves' factors (Push::kLeaf) sum to 1 whatever
  // the links' levels, so even a coarse feps (few, coarse links) keeps every element within 1% at
  // rho = 0.99.
  const double rho = 0.99;
  const Scene s = test::make_box(4.0, 2.5, 5.0, {gray(rho, 1.0)}, {0, 0, 0, 0, 0, 0}, true);
  const double expected = 1.0 / (1.0 - rho);
  for (const double feps : {0.05, 0.01}) {
    SolveOptions o = with_push(Push::kLeaf);
    o.feps = feps;
    Solution sol;
    const SolveSummary sum = solve_hr(s, &sol, o);
    ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
    EXPECT_LT(worst_element_deviation(sol, expected), 0.01) << "feps " << feps;
  }
}

// The factors each leaf gathers through either link operator: a gather with radiosity 1 on every
// node and point, pushed to the leaves with rho = 1 and E = 0.
struct LeafSums {
  std::vector<double> hsa, leaf, area;  // by leaf, in all_leaves() order
};

LeafSums leaf_factor_sums(const Scene& s, double feps, bool fields) {
  SolveOptions o;
  o.feps = feps;
  o.aeps = s.total_area() / 1000.0;
  SolverContext ctx(s, o, Method::kHierarchical);
  ElementHierarchy h(s);
  const ClusterTransfer geometry(s, h, nullptr);
  std::vector<Rgb> clusters;
  const ErrorBoundOracle oracle(h, nullptr, geometry, ctx.evaluator(), {o.feps, 0.0, o.aeps, fields},
                                source_weights(s, 1), 1, &clusters);
  std::vector<Candidate> work;
  for (int i = 0; i < static_cast<int>(s.patches.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(s.patches.size()); ++j) work.push_back({h.root(i), h.root(j)});
  const RefineResult refined = refine(h, nullptr, oracle, std::move(work), {});
  ElementHierarchy unit = h;  // rho = 1, E = 0: a leaf's radiosity is what it gathered
  for (std::size_t i = 0; i < unit.size(); ++i) {
    unit.node(static_cast<NodeId>(i)).emission = Rgb::Zero();
    unit.node(static_cast<NodeId>(i)).reflectance = Rgb::Ones();
  }
  const PushPull push_pull(s, unit, nullptr, 1);
  const HsaLinks hsa(refined.links, h, nullptr, geometry);
  const LeafLinks leaf(h, ctx.evaluator(), refined.links);
  LeafSums sums;
  for (const LinkOperator* op : {static_cast<const LinkOperator*>(&hsa), static_cast<const LinkOperator*>(&leaf)}) {
    NodeField field = push_pull.make_field();
    for (Rgb& b : field.radiosity) b = Rgb::Ones();
    push_pull.pull(field);  // moments of B = 1
    field.clear_gathered();
    op->gather(field);
    push_pull.push_pull(field);
    std::vector<double>& out = op == &hsa ? sums.hsa : sums.leaf;
    for (const NodeId l : h.all_leaves()) out.push_back(field.radiosity[static_cast<std::size_t>(l)][0]);
  }
  for (const NodeId l : h.all_leaves()) sums.area.push_back(h.node(l).area);
  return sums;
}

TEST(Hierarchical, EachLeafsFactorsSumToOneInAClosedRoomWithTheLeafPush) {
  // Closure per leaf (Push::kLeaf): the terms a leaf gathers (its own links' factors and its
  // ancestors' links with its own quadrature factors, scaled to each link's exchange) tile the
  // room seen from it, so they sum to 1 up to the quadrature.
  const Scene s = make_box(4.0, 2.5, 5.0, {gray(0.5, 1.0)});
  const LeafSums sums = leaf_factor_sums(s, 0.05, false);
  double worst = 0.0;
  for (const double t : sums.leaf) worst = std::max(worst, std::abs(t - 1.0));
  EXPECT_LT(worst, 1e-3);
}

TEST(Hierarchical, HsaLinksTileEachPatchAndBoundEachLeafsClosureByTheOracle) {
  // The HSA push (hsa_links.h): a patch's links tile its view of the closed room, so the area mean
  // of its leaves' factor sums is 1 up to the links' factors (analytic, or the two sides' Simpson
  // quadratures where they agree to 1e-3); a leaf's own sum strays from 1 by the interpolation error
  // of the fields it receives, which the oracle keeps within feps per link on its path.
  const Scene s = make_box(4.0, 2.5, 5.0, {gray(0.5, 1.0)});
  const double feps = 0.01;
  const LeafSums sums = leaf_factor_sums(s, feps, true);
  double mean = 0.0, area = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < sums.hsa.size(); ++i) {
    mean += sums.area[i] * sums.hsa[i];
    area += sums.area[i];
    worst = std::max(worst, std::abs(sums.hsa[i] - 1.0));
  }
  EXPECT_NEAR(mean / area, 1.0, 1e-4);
  EXPECT_LT(worst, 3.0 * feps);
}

TEST(Hierarchical, OracleRefinesALargeElementNearASmallOneThoughTheAverageFactorIsSmall) {
  // A 10 x 10 floor and a 0.5 x 0.5 square facing it 0.3 above one corner. The floor's average
  // factor to the square is tiny (HSA's test F(p -> q) < feps would link them), but the floor's
  // corner sees the square with a factor 0.19 (Howell's catalogue A-13), which no field over the
  // whole floor through its corner, edge-midpoint and centre points represents: the oracle splits.
  // Far above the floor the factor is uniform over it and small: a link.
  Scene s;
  s.materials = {gray(0.5, 1.0)};
  add_polygon(s, {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}, {0, 0, 10}}, Vec3(0, 1, 0), 0);
  add_polygon(s, {{0, 0.3, 0}, {0.5, 0.3, 0}, {0.5, 0.3, 0.5}, {0, 0.3, 0.5}}, Vec3(0, -1, 0), 0);
  const double feps = 0.05;
  auto decide = [&](const Scene& scene) {
    SolverContext ctx(scene, SolveOptions{}, Method::kHierarchical);
    const ElementHierarchy h(scene);
    const ClusterTransfer geometry(scene, h, nullptr);
    std::vector<Rgb> clusters;
    const ErrorBoundOracle oracle(h, nullptr, geometry, ctx.evaluator(), {feps, 0.0, 1e-6}, {1.0, 1.0}, 1, &clusters);
    Candidate c{h.root(0), h.root(1)};
    oracle.decide(c);
    return c;
  };
  const Decision split = decide(s).decision;
  EXPECT_TRUE(split == Decision::kSplitP || split == Decision::kSplitQ);
  Scene far = s;
  for (Vec3& v : far.patches[1].vertices) v.y() = 1000.0;
  const Candidate linked = decide(far);
  ASSERT_EQ(linked.decision, Decision::kLink);
  // Reciprocal, and the square's factor to the floor below it is about A / (pi d^2) (the floor
  // seen from 1000 away as a small disc off the axis: within 1%).
  EXPECT_NEAR(linked.f_pq * 100.0, linked.f_qp * 0.25, 1e-12 * linked.f_qp);
  EXPECT_NEAR(linked.f_qp / (100.0 / (std::numbers::pi * 1000.0 * 1000.0)), 1.0, 0.01);
}

TEST(Hierarchical, ClosedBoxWithAFloatingBlockNeedsVisibility) {
  // The enclosure between a room and a cube floating inside it is closed too: B = E / (1 - rho)
  // everywhere, but now the factors depend on the visibility oracle (partly visible pairs).
  const double rho = 0.5;
  const double e = 1.0;
  Scene s = make_box(4.0, 3.0, 4.0, {gray(rho, e)});
  const Vec3 lo(1.5, 1.0, 1.5), hi(2.5, 2.0, 2.5);
  const Vec3 c = (lo + hi) / 2;
  const Vec3 corners[8] = {{lo.x(), lo.y(), lo.z()}, {hi.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), lo.z()},
                           {lo.x(), hi.y(), lo.z()}, {lo.x(), lo.y(), hi.z()}, {hi.x(), lo.y(), hi.z()},
                           {hi.x(), hi.y(), hi.z()}, {lo.x(), hi.y(), hi.z()}};
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    std::vector<Vec3> v = {corners[f[0]], corners[f[1]], corners[f[2]], corners[f[3]]};
    add_polygon(s, v, polygon_centroid(v) - c, 0);  // the cube's faces face outward
  }
  Solution sol;
  const SolveSummary sum = solve_hr(s, &sol);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_TRUE(sum.effects.visibility);
  const double expected = e / (1.0 - rho);
  // Sampled visibility (kDefaultVisibilitySamples point pairs per partly visible pair) breaks closure a little: the
  // mean stays within 1%, single patches (the cube's faces) within 5%.
  EXPECT_NEAR(area_mean(s, sol, 0) / expected, 1.0, 0.01);
  EXPECT_LT(worst_patch_deviation(sol, expected), 0.05);
}

TEST(Hierarchical, FacetedSphereAreaMeanIsMeanEmissionOverOneMinusRho) {
  // Any closed enclosure with uniform rho: sum_i A_i B_i = sum_i A_i E_i / (1 - rho) (reciprocity
  // and closure of the factors). Only the top cap emits here, so B itself is far from uniform.
  const double rho = 0.7;
  const Scene s = make_faceted_sphere(2.0, 6, 8, gray(rho, 0.0), gray(rho, 5.0));
  double emitted = 0.0;
  for (const Patch& p : s.patches) emitted += p.area * s.material_of(p).emission[0];
  const double e_bar = emitted / s.total_area();
  Solution sol;
  SolveOptions o;
  o.feps = 0.02;  // fewer links than the default: the area mean needs no more
  const SolveSummary sum = solve_hr(s, &sol, o);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_NEAR(area_mean(s, sol, 0) / (e_bar / (1.0 - rho)), 1.0, 0.01);
  // and the unlit bottom is much darker than the lit cap
  EXPECT_LT(sol.patch_radiosity.back()[0], sol.patch_radiosity.front()[0]);
}

TEST(Hierarchical, UniformlyEmittingFacetedSphereIsEOverOneMinusRhoPerElement) {
  // Triangles at the poles, trapezoids between: B = E / (1 - rho) on every element at rho = 0.99
  // with links resolved to the leaves (closure per leaf).
  const double rho = 0.99;
  const Scene s = make_faceted_sphere(2.0, 6, 8, gray(rho, 1.0), gray(rho, 1.0));
  Solution sol;
  const SolveSummary sum = solve_hr(s, &sol, with_push(Push::kLeaf));
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_LT(worst_element_deviation(sol, 1.0 / (1.0 - rho)), 0.01);
}

// A closed 3 x 2 x 4 room whose walls differ in reflectance and colour; only the ceiling emits.
Scene coloured_room() {
  return make_box(3.0, 2.0, 4.0,
                  {gray(0.3, 0.0),
                   gray(0.8, 10.0),
                   {"red", Rgb(0.7, 0.1, 0.1), Rgb::Zero()},
                   {"green", Rgb(0.1, 0.6, 0.2), Rgb::Zero()},
                   gray(0.5, 0.0),
                   gray(0.6, 0.0)});
}

TEST(Hierarchical, EnergyBalanceInAClosedColouredRoom) {
  // Power absorbed equals power emitted: sum_i A_i (1 - rho_i) H_i = sum_i A_i E_i with the
  // irradiance H_i = (B_i - E_i) / rho_i. Walls differ in reflectance; only the ceiling emits.
  const Scene s = coloured_room();
  Solution sol;
  const SolveSummary sum = solve_hr(s, &sol);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  // |emitted - absorbed| / emitted per channel (analysis/error_metrics.h: absorbed = A (1 - rho) H).
  const EnergyBalance balance = energy_balance(s, sol);
  for (int c = 0; c < 3; ++c) EXPECT_LT(balance.closed_scene_residual[c], 0.01) << "channel " << c;
}

// --- Stability -------------------------------------------------------------------------------

TEST(Hierarchical, NearlyLosslessRoomConvergesOrSaysSoWithoutNaN) {
  // At rho = 0.999 Jacobi contracts by ~0.999 per step: with too few iterations the answer is a
  // status and finite values; given enough it converges, and since each leaf's factors sum to 1
  // (Push::kLeaf: no eigenvalue of rho K above 1), to E / (1 - rho) per element.
  const double rho = 0.999;
  const Scene s = make_box(4.0, 2.5, 5.0, {gray(rho, 1.0)});
  Solution sol;
  SolveOptions o = with_push(Push::kLeaf);
  o.max_iterations = 1000;
  SolveSummary sum = solve_hr(s, &sol, o);
  EXPECT_EQ(sum.termination, Termination::kMaxIterations) << sum.message;
  for (const Rgb& b : sol.face_radiosity) {
    ASSERT_TRUE(b.isFinite().all());
    EXPECT_GE(b[0], 1.0);  // never below the emission
  }
  o.max_iterations = 40000;
  sum = solve_hr(s, &sol, o);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_LT(worst_element_deviation(sol, 1.0 / (1.0 - rho)), 0.01);
}

TEST(Hierarchical, ScaledScenesGiveTheSameAnswer) {
  // Without occlusion every decision depends on factors and area ratios only: the same mesh, the
  // same links and the same radiosity up to the iteration tolerance (1e-6), from micrometres to
  // megametres.
  const Scene base = coloured_room();
  Solution reference;
  const SolveSummary ref_sum = solve_hr(base, &reference);
  // Rounded (decimal) scales move where the iteration stops by less than its tolerance: 1e-5 of
  // each face (its tolerance is relative to the largest reflected radiosity).
  for (const double factor : {1e6, 1e-6}) {
    const double tolerance = 1e-5;
    Solution sol;
    const SolveSummary sum = solve_hr(scaled(base, factor), &sol);
    EXPECT_EQ(sum.elements, ref_sum.elements) << "scale " << factor;
    EXPECT_EQ(sum.links, ref_sum.links) << "scale " << factor;
    ASSERT_EQ(sol.face_radiosity.size(), reference.face_radiosity.size());
    for (std::size_t i = 0; i < sol.face_radiosity.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const double r = reference.face_radiosity[i][c];
        ASSERT_NEAR(sol.face_radiosity[i][c], r, tolerance * r) << "scale " << factor << " face " << i;
      }
    }
  }
  // With occlusion the visibility samples are seeded from the coordinates' bits, so a scaled
  // scene samples differently: the same answer within the sampling error.
  const Scene room = read_obj_scene(scene_path("simple_room.obj"));
  Solution room_ref, room_small;
  solve_hr(room, &room_ref);
  solve_hr(scaled(room, 1e-6), &room_small);
  for (std::size_t i = 0; i < room_ref.patch_radiosity.size(); ++i) {
    const double r = room_ref.patch_radiosity[i].maxCoeff();
    EXPECT_NEAR(room_small.patch_radiosity[i].maxCoeff(), r, 0.02 * r) << "simple_room patch " << i;
  }
}

// --- Links and refinement ----------------------------------------------------------------------

TEST(Hierarchical, FarSurfacesNeedFewLinksComparedWithTheFullMatrix) {
  // Lecture sec. 2: two 4 x 4 surfaces 20 apart exchange light through a handful of links, where
  // the full matrix at the smallest element size allowed (aeps) needs n^2 factors; two surfaces
  // meeting along an edge need far more links at the same tolerances.
  const Scene far = read_obj_scene(scene_path("two_far_surfaces.obj"));
  const Scene edge = read_obj_scene(scene_path("two_surfaces_edge.obj"));
  SolveOptions o;
  o.aeps = 16.0 / 256.0;  // 16 x 16 elements per surface at most
  Solution sol;
  const SolveSummary sum_far = solve_hr(far, &sol, o);
  const double n = far.total_area() / o.aeps;  // full-matrix elements at the same element size
  EXPECT_GE(sum_far.links, 2u);
  EXPECT_LT(static_cast<double>(sum_far.links), 1e-3 * n * n);
  const SolveSummary sum_edge = solve_hr(edge, &sol, o);
  EXPECT_GT(sum_edge.links, 20 * sum_far.links);
  EXPECT_GT(sum_edge.elements, 4 * sum_far.elements);
}

TEST(Hierarchical, RefinesNearACommonEdge) {
  // At the lecture's feps = 0.02 with room to refine (aeps = 1/1024 of a surface): pairs close to
  // the edge see each other under large factors and are split to aeps; far from it they are not.
  const Scene s = read_obj_scene(scene_path("two_surfaces_edge.obj"));
  SolveOptions o;
  o.feps = 0.02;
  o.aeps = 16.0 / 1024.0;
  Solution sol;
  solve_hr(s, &sol, o);
  // The surfaces meet along the x axis (y = z = 0); distance of a face centroid from it.
  double near_area = 1e300, far_area = 0.0;
  for (std::size_t f = 0; f < sol.faces.size(); ++f) {
    std::vector<Vec3> poly;
    for (int v : sol.faces[f]) poly.push_back(sol.vertices[v]);
    const Vec3 c = polygon_centroid(poly);
    const double d = std::hypot(c.y(), c.z());
    const double a = polygon_area(poly);
    if (d < 0.5) near_area = std::min(near_area, a);
    if (d > 3.0) far_area = std::max(far_area, a);
  }
  EXPECT_LE(near_area * 16.0, far_area) << "near " << near_area << " far " << far_area;
}

// --- Determinism and BF refinement --------------------------------------------------------------

TEST(Hierarchical, SameInputSameOutputBitwiseAtAnyThreadCount) {
  const Scene s = read_obj_scene(scene_path("simple_room.obj"));
  for (const Push push : {Push::kHsa, Push::kLeaf}) {
    SolveOptions o = with_push(push);
    o.threads = 1;
    Solution a, b;
    const SolveSummary sa = solve_hr(s, &a, o);
    o.threads = 2;
    const SolveSummary sb = solve_hr(s, &b, o);
    EXPECT_EQ(sa.links, sb.links);
    EXPECT_EQ(sa.iterations, sb.iterations);
    ASSERT_EQ(a.face_radiosity.size(), b.face_radiosity.size());
    for (std::size_t i = 0; i < a.face_radiosity.size(); ++i) {
      for (int c = 0; c < 3; ++c) ASSERT_EQ(a.face_radiosity[i][c], b.face_radiosity[i][c]) << "face " << i;
    }
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    for (std::size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i], b.vertices[i]);
  }
}

TEST(Hierarchical, BfRefinementReRefinesAfterSolvingAndStaysInTheRoom) {
  // With only the ceiling emitting, the first pass (B = E) cannot see that the lit walls matter;
  // HSA sec. 4.2 refines again with the solved B, so the mesh grows after the first pass.
  const double rho = 0.8;
  const Scene s = make_box(4.0, 2.5, 5.0, {gray(rho, 0.0), gray(rho, 10.0)});
  SolveOptions o;
  o.bfeps = 0.02;  // radiosity units: 0.2% of the emission
  Solution sol;
  const SolveSummary sum = solve_hr(s, &sol, o);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_GE(sum.figures.at("refine_passes"), 2.0);
  double emitted = 0.0;
  for (const Patch& p : s.patches) emitted += p.area * s.material_of(p).emission[0];
  EXPECT_NEAR(area_mean(s, sol, 0) / (emitted / s.total_area() / (1.0 - rho)), 1.0, 0.01);
}

TEST(Hierarchical, NoReflectionMeansBEqualsE) {
  const Scene s = make_box(1.0, 1.0, 1.0, {gray(0.0, 2.0)});
  Solution sol;
  const SolveSummary sum = solve_hr(s, &sol);
  EXPECT_EQ(sum.termination, Termination::kDirect);
  EXPECT_EQ(sum.links, 0u);
  for (const Rgb& b : sol.face_radiosity) EXPECT_EQ(b[0], 2.0);
}

// Guarantee: more point pairs (--visibility-samples) lower the noise of what the links carry and
// do not coarsen the links: an element pair's tests cast the same rays at every sample count, so a
// run with more samples keeps at least the links of one with fewer (it drops fewer partly visible
// pairs whose samples were all blocked). Where a point's rays grew with the samples, its doubt
// shrank and the Cornell box's partly visible pairs linked coarser: 32.8k links at 64 samples,
// 30.6k at 128 and 29.3k at 256.
TEST(Hierarchical, MoreVisibilitySamplesDoNotCoarsenTheLinks) {
  const Scene s = read_obj_scene(scene_path("cornell_box.obj"));
  Solution sol;
  std::size_t fewer = 0;
  for (const int samples : {64, 128, 256}) {
    SolveOptions o;
    o.visibility_samples = samples;
    const SolveSummary sum = solve_hr(s, &sol, o);
    ASSERT_EQ(sum.termination, Termination::kConverged);
    EXPECT_GE(sum.links, fewer) << samples << " samples";
    fewer = sum.links;
  }
}

TEST(Hierarchical, DefaultsAreRelativeToTheScene) {
  const Scene s = make_box(1.0, 2.0, 3.0, {gray(0.5, 1.0)});
  const HierarchicalTolerances t = hierarchical_tolerances(s, SolveOptions{});
  EXPECT_DOUBLE_EQ(t.aeps, kAutoAepsFraction * s.total_area());
  SolveOptions o;
  o.aeps = 0.01;
  o.bfeps = 0.5;
  const HierarchicalTolerances given = hierarchical_tolerances(s, o);
  EXPECT_EQ(given.aeps, 0.01);
  EXPECT_EQ(given.bfeps, 0.5);
  EXPECT_EQ(given.feps, 0.0);
}

}  // namespace
}  // namespace hrad
