// A probe facing a rectangular emitter in an otherwise empty scene: the irradiance is E times the
// point-to-rectangle configuration factor, H = (1/pi) int_A E cos_x cos_y / r^2 dA = E F. F from
// Howell's catalogue (tests/formfactor/howell.h): B-3, a plane element parallel to a rectangle with
// its normal through a corner, by superposition for other positions; and the element whose plane
// is perpendicular to the rectangle. Light leaves only the emitter's front.
#include <gtest/gtest.h>

#include <vector>

#include "../formfactor/howell.h"
#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/reference.h"
#include "reference_checks.h"

namespace hrad::test {
namespace {

const Rgb kHowellEmission(3.0, 2.0, 1.0);

// The emitter [0, a] x [0, b] in the plane z = 0, its front facing +z; nothing else.
Scene emitter_rectangle(double a, double b) {
  Scene s;
  s.materials = {material(Rgb::Zero(), kHowellEmission)};
  add_polygon(s, {{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}}, Vec3::UnitZ(), 0);
  return s;
}

PointEstimate probe(const Scene& scene, const Vec3& x, const Vec3& n, int samples = 16384) {
  ReferenceOptions o;
  o.samples = samples;
  std::vector<PointEstimate> out;
  const std::vector<ProbePoint> points = {{x, n.normalized(), 0}};
  reference_points(scene, points, o, &out);
  EXPECT_EQ(out[0].patch, -1);
  return out[0];
}

// With one emitter and nothing to bounce from, a path is one light sample and one bounce. Far from
// the emitter the light sample carries the answer (standard errors ~0.05% with 16384 paths); close
// to it the power heuristic hands it to the bounce, which hits the emitter with probability ~F: at
// 0.05 above a corner (F ~ 0.25) that is a Bernoulli spread of sqrt((1 - F) / F) ~ 1.7 per path,
// a 1.3% standard error; elsewhere 0.2-1.1%.
TEST(ReferenceHowell, ProbeParallelToARectangleSeesEmissionTimesB3) {
  const double a = 0.7, b = 1.3;
  const Scene scene = emitter_rectangle(a, b);
  for (double c : {0.05, 0.9, 4.0}) {
    // Under a corner: B-3 itself.
    PointEstimate e = probe(scene, {0, 0, c}, -Vec3::UnitZ());
    expect_agrees(e.irradiance, e.irradiance_se, kHowellEmission * howell_b3(a, b, c), 0.015,
                  "corner, c " + std::to_string(c));
    // Under an inner point: four rectangles meeting there.
    const double x = 0.2, y = 0.9;
    const double inner =
        howell_b3(x, y, c) + howell_b3(a - x, y, c) + howell_b3(x, b - y, c) + howell_b3(a - x, b - y, c);
    e = probe(scene, {x, y, c}, -Vec3::UnitZ());
    expect_agrees(e.irradiance, e.irradiance_se, kHowellEmission * inner, 0.01, "inner, c " + std::to_string(c));
    // Beside the rectangle (x = -0.4): the rectangle [-0.4, a] minus [-0.4, 0], both halves in y.
    const double d = 0.4, y2 = 0.5;
    const double outside =
        howell_b3(a + d, y2, c) - howell_b3(d, y2, c) + howell_b3(a + d, b - y2, c) - howell_b3(d, b - y2, c);
    e = probe(scene, {-d, y2, c}, -Vec3::UnitZ());
    expect_agrees(e.irradiance, e.irradiance_se, kHowellEmission * outside, 0.015, "beside, c " + std::to_string(c));
  }
}

// Probe at the origin facing +x; the emitter in the plane z = c spans a along y and b along x,
// facing the probe (-z): Howell's perpendicular element.
TEST(ReferenceHowell, ProbePerpendicularToARectangleSeesEmissionTimesItsFactor) {
  for (const auto& [a, b, c] : {std::tuple{1.0, 0.5, 0.3}, std::tuple{0.4, 2.0, 1.5}}) {
    Scene s;
    s.materials = {material(Rgb::Zero(), kHowellEmission)};
    add_polygon(s, {{0, 0, c}, {b, 0, c}, {b, a, c}, {0, a, c}}, -Vec3::UnitZ(), 0);
    const PointEstimate e = probe(s, Vec3::Zero(), Vec3::UnitX());
    expect_agrees(e.irradiance, e.irradiance_se, kHowellEmission * howell_perpendicular_element(a, b, c), 0.012,
                  "perpendicular");
  }
}

// Only fronts emit and receive: behind the emitter, or facing away from it, the irradiance is
// exactly 0 with standard error 0 (no path can carry light).
TEST(ReferenceHowell, NothingBehindTheEmitterOrFacingAway) {
  const Scene scene = emitter_rectangle(1.0, 1.0);
  PointEstimate e = probe(scene, {0.5, 0.5, -0.5}, Vec3::UnitZ(), 256);  // sees the back
  EXPECT_EQ(e.irradiance.maxCoeff(), 0.0);
  EXPECT_EQ(e.irradiance_se.maxCoeff(), 0.0);
  e = probe(scene, {0.5, 0.5, 0.5}, Vec3::UnitZ(), 256);  // above it, facing up
  EXPECT_EQ(e.irradiance.maxCoeff(), 0.0);
  EXPECT_EQ(e.irradiance_se.maxCoeff(), 0.0);
}

}  // namespace
}  // namespace hrad::test
