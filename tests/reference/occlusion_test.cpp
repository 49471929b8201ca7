// A shadow and one bounce with a closed form. The emitter A = [0, 1] x [0, l] in the plane z = 0
// (front +z, reflects nothing); the receiver R in the plane x = 0, y in [0, l], z in [0, h] (front
// +x, reflectance rho); a black barrier in the plane x = s = 1/2, y in [0, l], z in [0, H >= h],
// its front towards R. A segment from a point of A beyond the barrier (x_a > s) to a point of R
// (0, z_r) crosses x = s at height z_r (x_a - s) / x_a < z_r <= h <= H: the barrier hides that
// half of A from all of R, through its black back. So R receives the near half A_s = [0, s] x [0, l]
// exactly, and reflects it once:
//   at a point (0, y0, z0) of R:  B = rho E [P(y0, s, z0) + P(l - y0, s, z0)],
//     P = Howell's element-to-perpendicular-rectangle factor (the rectangle split at y = y0);
//   over R:  mean B = rho E F(R -> A_s) = rho E (A_s / A_R) F(A_s -> R),
//     F(A_s -> R) = Howell C-14 (perpendicular rectangles with the common edge l, widths s and h).
// Without the barrier the same formulas hold with s = 1: the control shows the barrier matters.
#include <gtest/gtest.h>

#include <vector>

#include "../formfactor/howell.h"
#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/reference.h"
#include "reference_checks.h"

namespace hrad::test {
namespace {

constexpr double kL = 1.0, kH = 0.8, kBarrier = 1.0, kS = 0.5;
const Rgb kOcclusionEmission(2.0, 1.0, 0.5);
const Rgb kRho(0.6, 0.3, 0.9);

Scene barrier_scene(bool with_barrier) {
  Scene s;
  s.materials = {material(Rgb::Zero(), kOcclusionEmission, "light"), material(kRho, Rgb::Zero(), "receiver"),
                 material(Rgb::Zero(), Rgb::Zero(), "black")};
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, kL, 0}, {0, kL, 0}}, Vec3::UnitZ(), 0);
  add_polygon(s, {{0, 0, 0}, {0, kL, 0}, {0, kL, kH}, {0, 0, kH}}, Vec3::UnitX(), 1);
  if (with_barrier) add_polygon(s, {{kS, 0, 0}, {kS, kL, 0}, {kS, kL, kBarrier}, {kS, 0, kBarrier}}, -Vec3::UnitX(), 2);
  return s;
}

double point_factor(double y0, double z0, double width) {
  return howell_perpendicular_element(y0, width, z0) + howell_perpendicular_element(kL - y0, width, z0);
}

double face_factor(double width) { return (width * kL) / (kL * kH) * howell_c14(kL, width, kH); }

// Points of R: a path from R ends at its first bounce (A and the barrier are black, R is planar),
// so it is one next-event sample and one bounce. Behind the barrier about half of the light samples
// are blocked and a bounce finds A with probability ~F: per-path spreads of 0.6-1.3 times the
// answer, standard errors of 0.5-1% with 16384 paths. The barrier takes 17-54% of the light at
// these points, 17 or more standard errors.
TEST(ReferenceOcclusion, PointsBehindABarrierSeeOnlyTheNearHalfOnce) {
  const std::vector<std::pair<double, double>> yz = {{0.5, 0.4}, {0.1, 0.2}, {0.8, 0.75}};
  std::vector<ProbePoint> probes;
  for (const auto& [y, z] : yz) probes.push_back({Vec3(0, y, z), Vec3::UnitX(), 0});
  ReferenceOptions o;
  o.samples = 16384;
  for (bool barrier : {true, false}) {
    std::vector<PointEstimate> out;
    reference_points(barrier_scene(barrier), probes, o, &out);
    for (std::size_t i = 0; i < probes.size(); ++i) {
      const auto [y, z] = yz[i];
      const double near = point_factor(y, z, kS), whole = point_factor(y, z, 1.0);
      ASSERT_EQ(out[i].patch, 1);
      const Rgb expected = kRho * kOcclusionEmission * (barrier ? near : whole);
      expect_agrees(out[i].radiosity, out[i].radiosity_se, expected, 0.012,
                    (barrier ? "barrier, point " : "no barrier, point ") + std::to_string(i));
      // The barrier's share is far outside the noise: the test would see it missing.
      EXPECT_GT(kOcclusionEmission[0] * (whole - near), 10 * out[i].irradiance_se[0]);
    }
  }
}

// The mean over R, from 65536 stratified points, one path each: ~0.6% standard error
// (conservative: it treats the stratified points as independent).
TEST(ReferenceOcclusion, FaceMeanBehindABarrierIsRhoETimesTheNearFactor) {
  ReferenceOptions o;
  o.samples = 65536;
  for (bool barrier : {true, false}) {
    const Scene scene = barrier_scene(barrier);
    std::vector<FaceEstimate> out;
    reference_faces(scene, o, &out);
    const Rgb expected = kRho * kOcclusionEmission * face_factor(barrier ? kS : 1.0);
    expect_agrees(out[1].radiosity, out[1].radiosity_se, expected, 0.008, barrier ? "barrier" : "no barrier");
    // The emitter and the barrier reflect nothing: their emission, exactly.
    EXPECT_TRUE((out[0].radiosity == kOcclusionEmission).all());
    EXPECT_EQ(out[0].radiosity_se.maxCoeff(), 0.0);
    if (barrier) EXPECT_EQ(out[2].radiosity.maxCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace hrad::test
