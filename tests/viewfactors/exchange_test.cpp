// Radiant exchange (radiant_exchange.h) against textbook enclosures: two plates with reradiating
// side walls (a three-surface enclosure, and in the limit infinite parallel plates), concentric
// faceted spheres (the two-surface enclosure), and Gebhart's / Hottel's formulation against the
// net radiation method on an open, obstructed model with a sky.
#include <gtest/gtest.h>

#include <numbers>

#include "../formfactor/howell.h"
#include "hrad/viewfactors/closure.h"
#include "hrad/viewfactors/radiant_exchange.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

// Two plates L x L at distance d (floor and ceiling of a box) at T1, T2, the four side walls one
// reradiating surface (net flux 0). The three-surface network (Siegel & Howell, "Thermal Radiation
// Heat Transfer", sec. 6.3; Incropera & DeWitt eq. 13.30):
//   q1 A1 = sigma (T1^4 - T2^4) / [(1-e1)/(A1 e1) + 1/(A1 F12 + 1/(1/(A1 F1R) + 1/(A2 F2R))) + (1-e2)/(A2 e2)]
// with F12 = Howell C-11. Matched to 1e-9. Infinite parallel plates, sigma (T1^4 - T2^4) / (1/e1 + 1/e2 - 1),
// is the limit d/L -> 0: the side walls carry between none and all of the open share 1 - F12, so
// the result lies between the network with the walls black-absent (space conductance A1 F12) and
// the infinite plates (A1): asserted at L/d = 1000.
TEST(RadiantExchange, PlatesWithReradiatingWalls) {
  for (const double L : {1.0, 1000.0}) {
    const double d = 1.0, e1 = 0.8, e2 = 0.3, t1 = 600.0, t2 = 300.0;
    Scene s = make_box(L, d, L,
                       {material(Rgb::Constant(1 - e1), Rgb::Zero()), material(Rgb::Constant(1 - e2), Rgb::Zero()),
                        material(Rgb::Constant(0.5), Rgb::Zero())},
                       {0, 1, 2, 2, 2, 2});
    for (std::size_t f = 0; f < s.faces.size(); ++f) s.faces[f].group = f == 0 ? "bottom" : f == 1 ? "top" : "sides";
    const SurfaceUnits units = group_units(s);
    const ViewFactorMatrix m = compute_view_factors(s, units, plain_options());
    ASSERT_EQ(m.n, 3);
    const RadiantExchange r = solve_radiant_exchange(m, units.emissivity,
                                                     {{SurfaceCondition::Kind::kTemperature, t1},
                                                      {SurfaceCondition::Kind::kTemperature, t2},
                                                      {SurfaceCondition::Kind::kHeatFlux, 0.0}});
    const double a1 = L * L, a2 = L * L, ar = 4 * L * d;
    const double f12 = howell_c11(L, L, d), f1r = 1 - f12, f2r = 1 - f12;
    const double space = a1 * f12 + 1 / (1 / (a1 * f1r) + 1 / (a2 * f2r));
    const double q1 = (black(t1) - black(t2)) / ((1 - e1) / (a1 * e1) + 1 / space + (1 - e2) / (a2 * e2)) / a1;
    EXPECT_NEAR(r.heat_flux[0], q1, 1e-9 * q1) << L;
    EXPECT_NEAR(r.heat_flux[1] * a2, -q1 * a1, 1e-9 * q1 * a1);  // what the bottom sends, the top receives
    EXPECT_NEAR(r.heat_flux[2], 0.0, 1e-9 * q1);
    EXPECT_NEAR(r.sky_heat, 0.0, 1e-8 * q1 * a1);  // closed: nothing leaves
    // The reradiating walls sit at the temperature their irradiation sets (J = H).
    EXPECT_NEAR(r.radiosity[2], r.irradiation[2], 1e-9 * r.irradiation[2]);
    EXPECT_GT(r.temperature[2], t2);
    EXPECT_LT(r.temperature[2], t1);
    (void)ar;
    if (L > 100) {
      const double infinite = (black(t1) - black(t2)) / (1 / e1 + 1 / e2 - 1);
      const double no_walls = (black(t1) - black(t2)) / ((1 - e1) / e1 + 1 / f12 + (1 - e2) / e2);
      EXPECT_LE(r.heat_flux[0], infinite);
      EXPECT_GE(r.heat_flux[0], no_walls);
      EXPECT_NEAR(r.heat_flux[0], infinite, 1e-3 * infinite);
    }
  }
}

// Concentric spheres, faceted (inner outward, outer inward), as two groups; the closure adjustment
// makes the sampled outer row close. Two-surface enclosure (Siegel & Howell sec. 6.3):
//   Q = sigma (T1^4 - T2^4) / [(1-e1)/(A1 e1) + 1/(A1 F12) + (1-e2)/(A2 e2)], matched to 1e-9 with the
// matrix's own F12 (which is 1 within 1e-9: the inner polyhedron is convex). Against true spheres,
// Q = sigma A1 (T1^4 - T2^4) / (1/e1 + (1-e2)/e2 (r1/r2)^2): the faceting changes A1 and A1/A2, so the
// tolerance is twice the faceted inner sphere's relative area deficit.
TEST(RadiantExchange, ConcentricSpheres) {
  const double r1 = 1.0, r2 = 2.0, e1 = 0.6, e2 = 0.4, t1 = 500.0, t2 = 300.0;
  const Scene outer = make_concentric_spheres(r1, r2, e1, e2);
  const SurfaceUnits units = group_units(outer);
  ViewFactorMatrix m = compute_view_factors(outer, units, plain_options());
  ASSERT_EQ(m.n, 2);
  // inner: all visible; its pairs the shaft test leaves undecided are sampled to fraction 1, and
  // what the row cap takes from them (the outer row's sampled sum above 1) is reported
  EXPECT_NEAR(m.row_sum(1) + m.capped[1], 1.0, 1e-9);
  EXPECT_NEAR(m.factor(1, 1), 0.0, 1e-15);  // convex: sees nothing of itself
  const ClosureReport closure = enforce_closure(m);
  EXPECT_LE(closure.max_row_error_after, 1e-12);
  const RadiantExchange r = solve_radiant_exchange(
      m, units.emissivity, {{SurfaceCondition::Kind::kTemperature, t2}, {SurfaceCondition::Kind::kTemperature, t1}});
  const double a1 = m.area[1], a2 = m.area[0], f12 = m.factor(1, 0);
  const double q = (black(t1) - black(t2)) / ((1 - e1) / (a1 * e1) + 1 / (a1 * f12) + (1 - e2) / (a2 * e2));
  EXPECT_NEAR(r.heat_flux[1] * a1, q, 1e-9 * q);
  EXPECT_NEAR(r.heat_flux[0] * a2, -q, 1e-9 * q);
  const double true_a1 = 4 * std::numbers::pi * r1 * r1;
  const double sphere = kStefanBoltzmann * true_a1 * (std::pow(t1, 4) - std::pow(t2, 4)) /
                        (1 / e1 + (1 - e2) / e2 * (r1 / r2) * (r1 / r2));
  const double deficit = 1 - a1 / true_a1;
  EXPECT_GT(deficit, 0.0);
  EXPECT_NEAR(r.heat_flux[1] * a1, sphere, 2 * deficit * sphere);
}

// Gebhart's absorption factors / Hottel's total exchange areas give the net radiation method's
// heat at fixed temperatures to 1e-9, on an open model (a box without its ceiling, with a block:
// sampled pairs, a sky at 250 K); Gebhart's rows sum to 1 (energy) and A_i e_i B_ij is symmetric.
TEST(RadiantExchange, GebhartAndHottelAgreeWithNetRadiation) {
  Scene s = make_box(3, 2, 4, {material(Rgb::Constant(0.2), Rgb::Zero()), material(Rgb::Constant(0.7), Rgb::Zero())},
                     {0, 0, 1, 1, 0, 1});
  s.patches.erase(s.patches.begin() + 1);
  s.faces.erase(s.faces.begin() + 1);
  for (std::size_t p = 0; p < s.patches.size(); ++p)
    s.patches[p].face = static_cast<int>(p), s.faces[p].patches = {static_cast<int>(p)};
  add_block(s, 1.0, 2.0, 0.5, 1.2, 1.0, 2.5, 1);
  const SurfaceUnits units = face_units(s);
  const ViewFactorMatrix m = compute_view_factors(s, units, plain_options());
  std::vector<SurfaceCondition> conditions;
  std::vector<double> temperature;
  for (int i = 0; i < m.n; ++i) {
    temperature.push_back(280.0 + 15.0 * i);
    conditions.push_back({SurfaceCondition::Kind::kTemperature, temperature.back()});
  }
  const double sky = 250.0;
  const RadiantExchange r = solve_radiant_exchange(m, units.emissivity, conditions, sky);
  const std::vector<double> q = net_heat_by_exchange_areas(m, units.emissivity, temperature, sky);
  const std::vector<double> b = gebhart_factors(m, units.emissivity);
  double scale = 0.0;
  for (int i = 0; i < m.n; ++i) scale = std::max(scale, std::abs(r.heat_flux[i] * m.area[i]));
  for (int i = 0; i < m.n; ++i) {
    EXPECT_NEAR(q[i], r.heat_flux[i] * m.area[i], 1e-9 * scale) << i;
    double row = 0.0;
    for (int j = 0; j <= m.n; ++j) row += b[i * (m.n + 1) + j];
    EXPECT_NEAR(row, 1.0, 1e-12);
    for (int j = 0; j < m.n; ++j)
      EXPECT_NEAR(m.area[i] * units.emissivity[i] * b[i * (m.n + 1) + j],
                  m.area[j] * units.emissivity[j] * b[j * (m.n + 1) + i], 1e-12 * m.area[i]);
  }
}

}  // namespace
}  // namespace hrad::test
