// Sample streams (SolveOptions::seed): every sampled quantity of a hierarchical solve (element
// links' visible fractions and point rays, cluster links' sampled factors) draws from seeds mixed
// with the stream's, so solves at different seeds are independent draws of the same estimator.
// Their mean then averages the sampling noise away: on the Cornell box (clustered, 16 samples, so
// that the noise is large), the mean of 8 streams lies about sqrt(8) times closer to the mean of 16
// further streams than one stream does. A seed that reached only some samplers, or none, or
// streams that were correlated, would leave the mean about as far off as one solve.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hrad/io/obj_reader.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

std::vector<double> patch_radiosity(const Scene& scene, std::uint64_t seed) {
  SolveOptions options;
  options.visibility_samples = 16;
  options.clustering = Clustering::kOn;
  options.seed = seed;
  Solution s;
  solve(scene, options, &s);
  std::vector<double> b;
  for (const Rgb& x : s.patch_radiosity) b.push_back(x.sum());
  return b;
}

// Root mean square of the relative differences over the patches that reflect light.
double rms_relative(const std::vector<double>& a, const std::vector<double>& reference) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(reference[i] > 0.0)) continue;
    const double d = (a[i] - reference[i]) / reference[i];
    sum += d * d;
    ++n;
  }
  return std::sqrt(sum / n);
}

TEST(SampleStreams, MeanOverSeedsAveragesTheSamplingNoiseAway) {
  const Scene scene = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  constexpr int kSeeds = 8, kReferenceSeeds = 16;
  std::vector<std::vector<double>> solves;
  for (int seed = 0; seed < kSeeds; ++seed) solves.push_back(patch_radiosity(scene, static_cast<std::uint64_t>(seed)));
  std::vector<double> reference(solves[0].size(), 0.0), mean(solves[0].size(), 0.0);
  for (int seed = kSeeds; seed < kSeeds + kReferenceSeeds; ++seed) {
    const std::vector<double> b = patch_radiosity(scene, static_cast<std::uint64_t>(seed));
    for (std::size_t i = 0; i < b.size(); ++i) reference[i] += b[i] / kReferenceSeeds;
  }
  double single = 0.0;
  for (const std::vector<double>& b : solves) {
    for (std::size_t i = 0; i < b.size(); ++i) mean[i] += b[i] / kSeeds;
    const double e = rms_relative(b, reference);
    single += e * e / kSeeds;
  }
  single = std::sqrt(single);
  const double averaged = rms_relative(mean, reference);
  // Independent streams: averaged / single = sqrt((1/8 + 1/16) / (1 + 1/16)) = 0.42.
  EXPECT_GT(single, 1e-4) << "the streams do not differ";
  EXPECT_LT(averaged, 0.65 * single) << "one stream " << single << ", the mean of " << kSeeds << " " << averaged;
}

}  // namespace
}  // namespace hrad
