// Closed rooms of uniform emission E and reflectance rho: every surface's radiosity, and the
// irradiance at any point inside facing any way, is B = E / (1 - rho) (the radiosity equation
// B = E + rho B, every direction from every point seeing a wall of radiosity B). The estimator must
// reach it within 4 standard errors, with Russian roulette ending the paths (unbiased), per point
// and per face, and through the shared edges and T-junctions of tessellated walls (a leak would
// bias it low).
#include <gtest/gtest.h>

#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/reference.h"
#include "reference_checks.h"

namespace hrad::test {
namespace {

const Rgb kEmission(1.0, 0.6, 0.3);

// Probes on the walls of the 2 x 1 x 1.5 box (one near an edge, one near a corner) and in space.
std::vector<ProbePoint> box_probes() {
  std::vector<ProbePoint> p;
  auto add = [&p](Vec3 x, Vec3 n) { p.push_back({x, n.normalized(), 0}); };
  add({1.0, 0.0, 0.75}, {0, 1, 0});         // floor centre
  add({0.3, 1.0, 0.2}, {0, -1, 0});         // ceiling
  add({0.0, 0.5, 1.49}, {1, 0, 0});         // x = 0 wall, 1 cm from an edge
  add({2.0, 0.99, 0.01}, {-1, 0, 0});       // x = 2 wall, near a corner
  add({1.7, 0.4, 0.0}, {0, 0, 1});          // z = 0 wall
  add({1.0, 0.5, 0.75}, {0.3, -0.5, 0.8});  // in space, facing a corner
  add({0.05, 0.9, 1.4}, {-1, 0, 0});        // in space, 5 cm from the wall it faces
  return p;
}

Scene uniform_box(const Rgb& rho, bool t_junctions) {
  return make_box(2.0, 1.0, 1.5, {material(rho, kEmission)}, {0, 0, 0, 0, 0, 0}, t_junctions);
}

// Paths of a room with rho = 0.9 are ~13 surfaces long and their estimates spread by ~70% of B
// (the roulette makes the path length geometric), so 8192 paths give a standard error of ~0.8%
// and 4 of them bound a bias of ~3%; at rho = 0.5, ~0.3%.
TEST(ReferenceClosedBox, PointsOnWallsAndInSpaceSeeEOverOneMinusRho) {
  for (const Rgb& rho : {Rgb(0.5, 0.5, 0.5), Rgb(0.9, 0.9, 0.9), Rgb(0.9, 0.5, 0.7)}) {
    const Scene scene = uniform_box(rho, false);
    const Rgb exact = kEmission / (1.0 - rho);
    ReferenceOptions o;
    o.samples = 8192;
    std::vector<PointEstimate> out;
    const std::vector<ProbePoint> probes = box_probes();
    const ReferenceSummary s = reference_points(scene, probes, o, &out);
    ASSERT_EQ(out.size(), probes.size());
    EXPECT_EQ(s.paths, probes.size() * 8192u);
    EXPECT_GT(s.rays(), s.paths);  // at least one bounce and one shadow ray per path
    for (std::size_t i = 0; i < out.size(); ++i) {
      const std::string what =
          "rho " + std::to_string(rho[0]) + "," + std::to_string(rho[1]) + " probe " + std::to_string(i);
      expect_agrees(out[i].irradiance, out[i].irradiance_se, exact, 0.012, what + " irradiance");
      if (i < 5) {
        ASSERT_GE(out[i].patch, 0) << what << " should lie on a wall";
        expect_agrees(out[i].radiosity, out[i].radiosity_se, exact, 0.012, what + " radiosity");
      } else {
        EXPECT_EQ(out[i].patch, -1) << what << " is in space";
      }
    }
  }
}

// Per face, with the walls cut into T-junctions (the floor in two, the x = 0 wall in three strips):
// 4096 stratified points per face.
TEST(ReferenceClosedBox, FaceMeansThroughTJunctionsAreEOverOneMinusRho) {
  for (double r : {0.5, 0.9}) {
    const Rgb rho = Rgb::Constant(r);
    const Scene scene = uniform_box(rho, true);
    ReferenceOptions o;
    o.samples = 4096;
    std::vector<FaceEstimate> out;
    reference_faces(scene, o, &out);
    ASSERT_EQ(out.size(), scene.faces.size());
    for (std::size_t f = 0; f < out.size(); ++f)
      expect_agrees(out[f].radiosity, out[f].radiosity_se, kEmission / (1.0 - rho), 0.012,
                    "rho " + std::to_string(r) + " face " + std::to_string(f));
  }
}

// A sphere faceted into 8 x 12 planar facets facing inward (triangles at the poles, trapezoids
// between): closed, curved, every facet seeing most others at varied angles.
TEST(ReferenceFacetedSphere, FacesAndPointsSeeEOverOneMinusRho) {
  const Rgb rho = Rgb::Constant(0.9);
  const Material m = material(rho, kEmission);
  const Scene scene = make_faceted_sphere(1.0, 8, 12, m, m);
  const Rgb exact = kEmission / (1.0 - rho);
  ReferenceOptions o;
  o.samples = 1024;
  std::vector<FaceEstimate> faces;
  reference_faces(scene, o, &faces);
  // The mean over all 96 faces, each with a ~2.3% standard error: ~0.25%.
  Rgb mean = Rgb::Zero(), variance = Rgb::Zero();
  for (const FaceEstimate& f : faces) {
    expect_agrees(f.radiosity, f.radiosity_se, exact, 0.03, "facet");
    mean += f.radiosity / static_cast<double>(faces.size());
    variance += f.radiosity_se.square() / static_cast<double>(faces.size() * faces.size());
  }
  expect_agrees(mean, variance.sqrt(), exact, 0.004, "mean over the facets");

  std::vector<ProbePoint> probes = {{Vec3(0, 0, 0), Vec3(0, 1, 0), 0},
                                    {Vec3(0.2, -0.3, 0.1), Vec3(1, 1, 1).normalized(), 0},
                                    {Vec3(0, 0.9, 0), Vec3(0, -1, 0), 0}};
  o.samples = 8192;
  std::vector<PointEstimate> points;
  reference_points(scene, probes, o, &points);
  for (const PointEstimate& p : points) expect_agrees(p.irradiance, p.irradiance_se, exact, 0.012, "sphere probe");
}

}  // namespace
}  // namespace hrad::test
