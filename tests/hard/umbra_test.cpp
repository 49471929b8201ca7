// Umbras are not too bright: on the bundled Cornell box, at about 2k elements, the leaves that see
// none of the light (beside and behind the blocks, on the red wall in the tall block's shadow) are
// compared with the final gather of the same solution at points across each leaf, an independent
// one-bounce estimate with exact point factors and visibility from each point
// (tests/support/umbra_bias.h). The HSA push bounds both the receiver's field and the weighting of
// the source's radiosity, and a partly visible link puts what its points' rays missed where they
// passed (refinement_oracle.cpp shape_of()), so no surface's umbra is more than 0.5% brighter on
// average, nor more than 1% darker. The links' visible fractions are sampled: the bias is the mean
// over two sample streams (SolveOptions::seed), whose noise on the red wall is about 0.15% a solve
// (umbra_benchmark).
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <string>

#include "hrad/io/obj_reader.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"
#include "support/umbra_bias.h"

namespace hrad {
namespace {

TEST(Umbra, CornellBoxUmbrasAreWithinHalfAPercentOfTheirFinalGather) {
  const Scene scene = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  SolveOptions options;
  options.aeps = scene.total_area() / 4000.0;
  constexpr int kSeeds = 2;
  std::map<std::string, test::UmbraBias> groups;
  for (int seed = 0; seed < kSeeds; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    Solution s;
    solve(scene, options, &s);
    for (const auto& [name, g] : test::umbra_bias(scene, s)) {
      groups[name].bias += g.bias / kSeeds;
      groups[name].leaves += g.leaves;
    }
  }
  // The floor beside both blocks, the red wall behind the tall one and the blocks' own faces have
  // umbras in this scene; each must be found and measured.
  for (const char* name : {"floor", "left_wall_red", "short_block", "tall_block"}) {
    ASSERT_TRUE(groups.count(name)) << name << " has no umbra leaves";
    EXPECT_GT(groups.at(name).leaves, 10 * kSeeds) << name;
  }
  for (const auto& [name, g] : groups) {
    EXPECT_LE(g.bias, 0.005) << name << ": " << g.leaves << " umbra leaves";
    EXPECT_GE(g.bias, -0.01) << name << ": " << g.leaves << " umbra leaves";
  }
}

}  // namespace
}  // namespace hrad
