// The reference's numbers are reproducible and its standard errors are honest: the same seed gives
// the same bits at any thread count, another seed other numbers, and the reported standard error
// is the spread of the estimate (it falls as 1/sqrt(N) and matches the scatter across seeds).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "hrad/reference/reference.h"

namespace hrad::test {
namespace {

// A room with an occluding block and a small light: shadows, several bounces, colour.
Scene test_room() {
  Scene s = make_box(2.0, 1.5, 1.0,
                     {material(Rgb(0.7, 0.5, 0.3), Rgb::Zero(), "wall"),
                      material(Rgb(0.2, 0.6, 0.8), Rgb::Zero(), "floor"), material(Rgb::Zero(), Rgb(5, 5, 4), "light")},
                     {1, 0, 0, 0, 0, 0});
  add_block(s, 0.6, 1.2, 0.0, 0.7, 0.3, 0.7, 0);
  add_polygon(s, {{0.8, 1.49, 0.4}, {1.2, 1.49, 0.4}, {1.2, 1.49, 0.6}, {0.8, 1.49, 0.6}}, -Vec3::UnitY(), 2);
  return s;
}

std::vector<ProbePoint> test_probes() {
  return {{Vec3(0.3, 0.0, 0.5), Vec3::UnitY(), 0},   // floor, beside the block
          {Vec3(1.5, 0.0, 0.5), Vec3::UnitY(), 0},   // floor, in the block's shadow
          {Vec3(1.0, 0.8, 0.5), -Vec3::UnitY(), 0},  // in space above the block, facing it
          {Vec3(0.0, 0.7, 0.5), Vec3::UnitX(), 0}};  // a wall
}

bool same_bits(const Rgb& a, const Rgb& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

TEST(ReferenceDeterminism, SameSeedSameBitsAtOneAndTwoThreads) {
  const Scene scene = test_room();
  const std::vector<ProbePoint> probes = test_probes();
  ReferenceOptions o;
  o.samples = 300;  // not a multiple of the block size: a partial last block
  o.seed = 42;
  std::vector<PointEstimate> one, two;
  o.threads = 1;
  const ReferenceSummary s1 = reference_points(scene, probes, o, &one);
  o.threads = 2;
  const ReferenceSummary s2 = reference_points(scene, probes, o, &two);
  EXPECT_EQ(s1.rays(), s2.rays());
  EXPECT_EQ(s1.paths, s2.paths);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    EXPECT_TRUE(same_bits(one[i].irradiance, two[i].irradiance)) << i;
    EXPECT_TRUE(same_bits(one[i].irradiance_se, two[i].irradiance_se)) << i;
    EXPECT_TRUE(same_bits(one[i].radiosity, two[i].radiosity)) << i;
  }
  std::vector<FaceEstimate> f1, f2;
  o.samples = 100;
  o.threads = 1;
  reference_faces(scene, o, &f1);
  o.threads = 2;
  reference_faces(scene, o, &f2);
  for (std::size_t f = 0; f < f1.size(); ++f) {
    EXPECT_TRUE(same_bits(f1[f].radiosity, f2[f].radiosity)) << f;
    EXPECT_TRUE(same_bits(f1[f].radiosity_se, f2[f].radiosity_se)) << f;
  }
}

TEST(ReferenceDeterminism, AnotherSeedGivesOtherNumbers) {
  const Scene scene = test_room();
  const std::vector<ProbePoint> probes = test_probes();
  ReferenceOptions o;
  o.samples = 256;
  std::vector<PointEstimate> a, b;
  o.seed = 1;
  reference_points(scene, probes, o, &a);
  o.seed = 2;
  reference_points(scene, probes, o, &b);
  for (std::size_t i = 0; i < probes.size(); ++i) EXPECT_NE(a[i].irradiance[0], b[i].irradiance[0]) << i;
}

// 16 times the paths, a quarter of the standard error. The estimate of a standard error from N
// paths is itself uncertain by ~sqrt(kurtosis / 4N), a few percent here; a formula with the wrong
// power of N (1/N: 16, none: 1, 1/N^(1/4): 2) is far outside [3.4, 4.6].
TEST(ReferenceStandardError, FallsAsOneOverSquareRootOfPaths) {
  const Scene scene = test_room();
  const std::vector<ProbePoint> probes = test_probes();
  ReferenceOptions o;
  std::vector<PointEstimate> few, many;
  o.samples = 1024;
  reference_points(scene, probes, o, &few);
  o.samples = 16384;
  o.seed = 7;
  reference_points(scene, probes, o, &many);
  for (std::size_t i = 0; i < probes.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double ratio = few[i].irradiance_se[c] / many[i].irradiance_se[c];
      EXPECT_GT(ratio, 3.4) << "probe " << i << " channel " << c;
      EXPECT_LT(ratio, 4.6) << "probe " << i << " channel " << c;
    }
}

// The reported standard error is the spread of the estimate: over 64 seeds, the standard deviation
// of the 64 estimates matches the root-mean-square reported error within [0.75, 1.3] (the spread of
// 64 numbers is uncertain by ~9%; a variance divided by N twice, or the spread of single paths
// reported as the error, is off by a factor sqrt(N) = 16).
TEST(ReferenceStandardError, MatchesTheScatterAcrossSeeds) {
  const Scene scene = test_room();
  const std::vector<ProbePoint> probes = test_probes();
  constexpr int kSeeds = 64;
  ReferenceOptions o;
  o.samples = 256;
  std::vector<std::vector<PointEstimate>> runs(kSeeds);
  for (int k = 0; k < kSeeds; ++k) {
    o.seed = 1000 + static_cast<std::uint64_t>(k);
    reference_points(scene, probes, o, &runs[static_cast<std::size_t>(k)]);
  }
  for (std::size_t i = 0; i < probes.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double mean = 0.0, reported = 0.0;
      for (const auto& run : runs) {
        mean += run[i].irradiance[c] / kSeeds;
        reported += run[i].irradiance_se[c] * run[i].irradiance_se[c] / kSeeds;
      }
      double scatter = 0.0;
      for (const auto& run : runs) scatter += std::pow(run[i].irradiance[c] - mean, 2) / (kSeeds - 1);
      const double ratio = std::sqrt(scatter / reported);
      EXPECT_GT(ratio, 0.75) << "probe " << i << " channel " << c;
      EXPECT_LT(ratio, 1.3) << "probe " << i << " channel " << c;
    }
}

}  // namespace
}  // namespace hrad::test
