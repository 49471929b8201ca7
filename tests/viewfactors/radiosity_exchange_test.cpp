// Radiant exchange solved by each radiosity solver (radiosity_exchange.h) against textbook
// enclosures: two plates with reradiating side walls (a three-surface enclosure; infinite parallel
// plates in the limit), concentric faceted spheres, concentric faceted cylinders closed by
// reradiating ends; energy balance in closed enclosures and agreement between the methods.
//
// Two resolutions per method:
//  * one element per input face (no subdivision, links between whole faces): the solver's system
//    is then the net radiation method on the faces, so it must give the matrix method's answer
//    (radiant_exchange.h on the view-factor matrix, an independent code path) to the factors'
//    accuracy. The analytic kernel is used throughout: exact unoccluded factors.
//  * refined elements: the radiosity may vary over a surface, as it does physically; compared
//    with closed forms whose assumptions (uniform radiosity, infinite length) the refined solution
//    does not share, at tolerances derived from the geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "../formfactor/howell.h"
#include "hrad/viewfactors/radiant_exchange.h"
#include "hrad/viewfactors/radiosity_exchange.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

constexpr Method kMethods[] = {Method::kFull, Method::kSubstructure, Method::kHierarchical};

// One element per input face: nothing is subdivided and hierarchical links join whole faces.
SolveOptions coarse(Method m) {
  SolveOptions o;
  o.method = m;
  o.kernel = FormFactorKernel::kAnalytic;
  o.max_area = o.patch_area = o.aeps = 1e12;
  o.clustering = Clustering::kOff;
  o.tolerance = 1e-12;
  o.max_iterations = 100000;
  return o;
}

// Refined: about `elements` elements (full, substructure: max_area = total / elements; hierarchical:
// aeps = total / (4 elements) and feps 1e-3, so it refines to a similar size where it needs to).
SolveOptions refined(Method m, const Scene& s, double elements) {
  SolveOptions o;
  o.method = m;
  o.kernel = FormFactorKernel::kAnalytic;
  o.max_area = s.total_area() / elements;
  o.aeps = s.total_area() / (4 * elements);
  o.feps = 1e-3;
  o.clustering = Clustering::kOff;
  o.tolerance = 1e-12;
  o.max_iterations = 100000;
  return o;
}

// Relative accuracy of the unoccluded factors a method gathers with (analytic kernel): the full
// matrix and substructuring ask the closed form for kSolverPairTolerance, hierarchical links for 1e-7.
double factor_accuracy(Method m) { return m == Method::kHierarchical ? 1e-7 : kSolverPairTolerance; }

// Total radiosity power sum A_u J_u: the scale the energy balance is measured against.
double radiosity_power(const SurfaceUnits& units, const RadiantExchange& x) {
  double p = 0.0;
  for (int u = 0; u < units.size(); ++u) p += units.area[u] * x.radiosity[u];
  return p;
}

// Floor and ceiling L x L at distance d (box L x d x L) at T1, T2 with emissivities e1, e2, the four
// side walls one reradiating group (net flux 0). Groups: bottom, top, sides.
Scene plates_box(double L, double d, double e1, double e2) {
  Scene s = make_box(L, d, L,
                     {material(Rgb::Constant(1 - e1), Rgb::Zero()), material(Rgb::Constant(1 - e2), Rgb::Zero()),
                      material(Rgb::Constant(0.5), Rgb::Zero())},
                     {0, 1, 2, 2, 2, 2});
  for (std::size_t f = 0; f < s.faces.size(); ++f) s.faces[f].group = f == 0 ? "bottom" : f == 1 ? "top" : "sides";
  return s;
}

// The three-surface network with one reradiating surface R (Incropera & DeWitt eq. 13.30; Siegel &
// Howell sec. 6.3): the net heat (W) leaving surface 1.
double network_q1(double a1, double a2, double e1, double e2, double f12, double f1r, double f2r, double t1,
                  double t2) {
  const double space = a1 * f12 + 1 / (1 / (a1 * f1r) + 1 / (a2 * f2r));
  return (black(t1) - black(t2)) / ((1 - e1) / (a1 * e1) + 1 / space + (1 - e2) / (a2 * e2));
}

// At one element per face the four side walls are images of each other under the box's symmetry,
// so their radiosity is equal and the solver's system is the three-surface network exactly: q1,
// the walls' net flux 0 and the energy balance (of the radiosity power) to the factors' accuracy:
// 1e-9 for the full matrix and substructuring (kSolverPairTolerance), 1e-7 for hierarchical links
// (their factors are asked for 1e-7, refinement_oracle.cpp).
TEST(RadiosityExchange, ThreeSurfaceNetworkAtOneElementPerFace) {
  const double L = 4.0, d = 1.0, e1 = 0.8, e2 = 0.3, t1 = 600.0, t2 = 300.0;
  const Scene s = plates_box(L, d, e1, e2);
  const SurfaceUnits units = group_units(s);
  const std::vector<SurfaceCondition> bc = {{SurfaceCondition::Kind::kTemperature, t1},
                                            {SurfaceCondition::Kind::kTemperature, t2},
                                            {SurfaceCondition::Kind::kHeatFlux, 0.0}};
  const double a1 = L * L, f12 = howell_c11(L, L, d);
  const double q1 = network_q1(a1, a1, e1, e2, f12, 1 - f12, 1 - f12, t1, t2);
  for (const Method m : kMethods) {
    const RadiosityExchange r = solve_exchange_by_radiosity(s, units, bc, coarse(m));
    SCOPED_TRACE(std::string(to_string(m)));
    const double tolerance = factor_accuracy(m);
    EXPECT_EQ(r.summary.elements, s.patches.size());
    EXPECT_NEAR(r.exchange.heat_flux[0] * a1, q1, tolerance * q1);
    EXPECT_NEAR(r.exchange.heat_flux[1] * a1, -q1, tolerance * q1);
    EXPECT_NEAR(r.exchange.heat_flux[2], 0.0, tolerance * q1 / a1);
    EXPECT_NEAR(r.exchange.sky_heat, 0.0, tolerance * radiosity_power(units, r.exchange));
    EXPECT_GT(r.exchange.temperature[2], t2);
    EXPECT_LT(r.exchange.temperature[2], t1);
  }
}

// Black surfaces (eps = 1: nothing reflects and (J - E) / rho would be 0 / 0; the solvers must still
// gather H), then gray ones with fixed net fluxes, nonzero among them: at one element per face each
// method gives the matrix method's heat and temperatures (radiant_exchange.h on the same faces'
// matrix) to the factors' accuracy.
TEST(RadiosityExchange, BlackSurfacesAndFixedFluxesMatchTheMatrixMethod) {
  const Scene s = make_box(2, 1, 3, {material(Rgb::Zero(), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  const SurfaceUnits black = face_units(s);
  const ViewFactorMatrix f = compute_view_factors(s, black, plain_options());
  SurfaceUnits gray = black;
  gray.emissivity = {0.9, 0.5, 0.3, 1.0, 0.7, 0.2};
  using K = SurfaceCondition::Kind;
  const std::vector<SurfaceCondition> temperatures = {{K::kTemperature, 500}, {K::kTemperature, 300},
                                                      {K::kTemperature, 350}, {K::kTemperature, 420},
                                                      {K::kTemperature, 280}, {K::kTemperature, 600}};
  const std::vector<SurfaceCondition> mixed = {{K::kTemperature, 500}, {K::kTemperature, 300},
                                               {K::kHeatFlux, 800.0},  {K::kTemperature, 420},
                                               {K::kHeatFlux, 0.0},    {K::kHeatFlux, -300.0}};
  for (const auto& [units, bc] : {std::pair{black, temperatures}, std::pair{gray, mixed}}) {
    const RadiantExchange ref = solve_radiant_exchange(f, units.emissivity, bc);
    double largest = 0.0;
    for (double q : ref.heat_flux) largest = std::max(largest, std::abs(q));
    for (const Method m : kMethods) {
      SCOPED_TRACE(std::string(to_string(m)));
      const RadiosityExchange r = solve_exchange_by_radiosity(s, units, bc, coarse(m));
      const double tolerance = factor_accuracy(m);
      for (int u = 0; u < units.size(); ++u) {
        EXPECT_NEAR(r.exchange.heat_flux[u], ref.heat_flux[u], tolerance * largest) << u;
        EXPECT_NEAR(r.exchange.temperature[u], ref.temperature[u], tolerance * ref.temperature[u]) << u;
      }
    }
  }
}

// Refined, the plates' radiosity falls towards their edges (the network's uniform radiosity is an
// approximation). Whatever the distribution, the reradiating walls pass on between none and all
// of the plates' open share 1 - F12, so the net heat lies between the network without walls
// (space conductance A1 F12) and infinite parallel plates, sigma (T1^4 - T2^4) / (1/e1 + 1/e2 - 1);
// the latter is the limit L/d -> oo, so the shortfall against it must shrink as L/d grows.
// Energy balance, of the radiosity power: the rows' closure, so the factors' accuracy (as above;
// the iterations stop at 1e-12). Unoccluded, so no sampled visibility enters.
TEST(RadiosityExchange, PlatesApproachInfinitePlatesRefined) {
  const double d = 1.0, e1 = 0.8, e2 = 0.3, t1 = 600.0, t2 = 300.0;
  const double infinite = (black(t1) - black(t2)) / (1 / e1 + 1 / e2 - 1);
  for (const Method m : kMethods) {
    SCOPED_TRACE(std::string(to_string(m)));
    double last_shortfall = INFINITY;
    for (const double L : {1.0, 4.0, 16.0}) {
      const Scene s = plates_box(L, d, e1, e2);
      const SurfaceUnits units = group_units(s);
      const RadiosityExchange r = solve_exchange_by_radiosity(
          s, units,
          {{SurfaceCondition::Kind::kTemperature, t1},
           {SurfaceCondition::Kind::kTemperature, t2},
           {SurfaceCondition::Kind::kHeatFlux, 0.0}},
          refined(m, s, 400));
      const double f12 = howell_c11(L, L, d);
      const double no_walls = (black(t1) - black(t2)) / ((1 - e1) / e1 + 1 / f12 + (1 - e2) / e2);
      const double q = r.exchange.heat_flux[0];
      EXPECT_GT(q, no_walls) << L;
      EXPECT_LT(q, infinite) << L;
      const double shortfall = (infinite - q) / infinite;
      EXPECT_LT(shortfall, last_shortfall) << L;
      last_shortfall = shortfall;
      EXPECT_NEAR(r.exchange.heat_flux[2], 0.0, 1e-8 * infinite) << L;
      EXPECT_NEAR(r.exchange.sky_heat, 0.0, factor_accuracy(m) * radiosity_power(units, r.exchange)) << L;
    }
  }
}


// Concentric spheres, faceted (inner outward, outer inward), groups inner and outer. Two-surface
// enclosure (Siegel & Howell sec. 6.3): Q = sigma A1 (T1^4 - T2^4) / (1/e1 + (1-e2)/e2 (r1/r2)^2) for
// true spheres, whose radiosity is uniform by symmetry. The faceting changes A1 and A1/A2 (the
// inner polyhedron's area falls short of the sphere's by its relative deficit), so the tolerance is
// twice that deficit, as for the matrix method (exchange_test.cpp).
TEST(RadiosityExchange, ConcentricSpheres) {
  const double r1 = 1.0, r2 = 2.0, e1 = 0.6, e2 = 0.4, t1 = 500.0, t2 = 300.0;
  const Scene s = make_concentric_spheres(r1, r2, e1, e2);
  const SurfaceUnits units = group_units(s);
  const double a1 = units.area[1];
  const double true_a1 = 4 * std::numbers::pi * r1 * r1;
  const double sphere = kStefanBoltzmann * true_a1 * (std::pow(t1, 4) - std::pow(t2, 4)) /
                        (1 / e1 + (1 - e2) / e2 * (r1 / r2) * (r1 / r2));
  const double deficit = 1 - a1 / true_a1;
  ASSERT_GT(deficit, 0.0);
  for (const Method m : kMethods) {
    SCOPED_TRACE(std::string(to_string(m)));
    const RadiosityExchange r = solve_exchange_by_radiosity(
        s, units, {{SurfaceCondition::Kind::kTemperature, t2}, {SurfaceCondition::Kind::kTemperature, t1}},
        refined(m, s, 150));
    EXPECT_NEAR(r.exchange.heat_flux[1] * a1, sphere, 2 * deficit * sphere);
    EXPECT_NEAR(r.exchange.heat_flux[0] * units.area[0], -sphere, 2 * deficit * sphere);
    const std::string key(to_string(m));
    ::testing::Test::RecordProperty(key + "_error", fmt::format("{:.3g}", r.exchange.heat_flux[1] * a1 / sphere - 1));
    ::testing::Test::RecordProperty(key + "_balance",
                                    fmt::format("{:.3g}", r.exchange.sky_heat / radiosity_power(units, r.exchange)));
  }
}

// Coaxial prisms of `sides` sides (circumradii r1 < r2, length L; the inner facing out, the outer
// in), their ends closed by annuli of `sides` trapezoids; long faces cut along the axis into
// pieces of aspect 4 or less. Groups: inner, outer, ends; materials 0, 1, 2.
Scene coaxial_prisms(double r1, double r2, double L, int sides, const std::vector<Material>& materials) {
  Scene s;
  s.materials = materials;
  auto at = [&](double r, int j, double z) {
    const double phi = 2 * std::numbers::pi * j / sides;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
  };
  const double width = 2 * r1 * std::sin(std::numbers::pi / sides);
  const int pieces = std::max(1, static_cast<int>(std::ceil(L / (4 * width))));
  for (int j = 0; j < sides; ++j) {
    for (int k = 0; k < pieces; ++k) {
      const double z0 = L * k / pieces, z1 = L * (k + 1) / pieces;
      for (const double r : {r1, r2}) {
        std::vector<Vec3> v = {at(r, j, z0), at(r, j + 1, z0), at(r, j + 1, z1), at(r, j, z1)};
        const Vec3 c = polygon_centroid(v), axis(0, 0, c.z());
        add_polygon(s, v, r == r1 ? c - axis : axis - c, r == r1 ? 0 : 1);
        s.faces.back().group = r == r1 ? "inner" : "outer";
      }
    }
    for (const double z : {0.0, L}) {
      add_polygon(s, {at(r1, j, z), at(r1, j + 1, z), at(r2, j + 1, z), at(r2, j, z)},
                  Vec3(0, 0, z == 0.0 ? 1.0 : -1.0), 2);
      s.faces.back().group = "ends";
    }
  }
  return s;
}

// Concentric cylinders: the infinite closed form (Incropera & DeWitt table 13.3; Siegel & Howell
// sec. 6.3) q1 = sigma (T1^4 - T2^4) / (1/e1 + (A1/A2)(1/e2 - 1)) per unit area of the inner one,
// A1/A2 = r1/r2 for prisms of equal circumradius ratio. A finite pair closed by reradiating ends
// (net flux 0) departs from it by the ends' share of what the inner surface sends, which falls as
// r/L: the relative error must shrink as L/r2 goes 1, 2, 4 and stay below the inner surface's
// factor to the ends (from the view-factor matrix): the most of the inner surface's emission the
// ends can turn away from the outer one. The methods agree within 1% (substructuring's patches
// shoot their mean radiosity; full and hierarchical resolve the same elements).
TEST(RadiosityExchange, ConcentricCylindersApproachTheInfiniteForm) {
  const double r1 = 1.0, r2 = 2.0, e1 = 0.5, e2 = 0.7, t1 = 800.0, t2 = 400.0;
  const int sides = 12;
  const double infinite = (black(t1) - black(t2)) / (1 / e1 + r1 / r2 * (1 / e2 - 1));
  const std::vector<Material> materials = {material(Rgb::Constant(1 - e1), Rgb::Zero()),
                                           material(Rgb::Constant(1 - e2), Rgb::Zero()),
                                           material(Rgb::Constant(0.5), Rgb::Zero())};
  double last[3] = {INFINITY, INFINITY, INFINITY};
  for (const double L : {2.0, 4.0, 8.0}) {
    const Scene s = coaxial_prisms(r1, r2, L, sides, materials);
    const SurfaceUnits units = group_units(s);
    const ViewFactorMatrix f = compute_view_factors(s, units, plain_options());
    double full = 0.0;
    for (const Method m : kMethods) {
      SCOPED_TRACE(std::string(to_string(m)));
      const RadiosityExchange r = solve_exchange_by_radiosity(s, units,
                                                              {{SurfaceCondition::Kind::kTemperature, t1},
                                                               {SurfaceCondition::Kind::kTemperature, t2},
                                                               {SurfaceCondition::Kind::kHeatFlux, 0.0}},
                                                              refined(m, s, 200));
      const double q = r.exchange.heat_flux[0];
      const double error = std::abs(q / infinite - 1);
      const auto k = static_cast<std::size_t>(m);
      EXPECT_LT(error, last[k]) << L;
      EXPECT_LT(error, f.factor(0, 2)) << L;
      last[k] = error;
      const std::string key = fmt::format("{}_L{:g}", to_string(m), L);
      ::testing::Test::RecordProperty(key + "_error", fmt::format("{:.3g}", error));
      ::testing::Test::RecordProperty(key + "_balance",
                                      fmt::format("{:.3g}", r.exchange.sky_heat / radiosity_power(units, r.exchange)));
      if (m == Method::kFull) full = q;
      EXPECT_NEAR(q, full, 0.01 * full) << L;
    }
  }
}

}  // namespace
}  // namespace hrad::test
