// Power conservation of the element links of hierarchical radiosity on closed, cluttered rooms: the
// generated offices and pillar halls (experiments/scene_generator.h) are closed (every front face
// sees only front faces), so everything emitted is absorbed, and absorbed / emitted is 1 exactly.
// Clustering is off, so every link joins two elements and every partly visible link carries a
// visible fraction sampled by rays. Whether a link is kept is decided from one set of samples; its
// fraction comes from another, independent of the decision, so the links kept see neither more nor
// less than the pairs they join (the refinement_oracle.cpp comment says why the decision's own
// samples would not do: a link whose samples missed a thin shadow passes as fully visible, one
// whose samples caught more of it splits).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <tuple>

#include "hrad/analysis/error_metrics.h"
#include "hrad/experiments/scene_generator.h"
#include "hrad/solvers/solve.h"

namespace hrad {
namespace {

// Guarantee: a closed office or pillar hall of about 300 input polygons, solved by hierarchical
// radiosity at the default tolerances without clustering, absorbs what it emits within 1e-3. The
// sampling error that remains is random: over its links it adds up to a few 1e-4 (the README's
// "Limits" gives the spread measured over sample streams).
TEST(ElementPower, ClosedClutteredRoomsBalancePowerWithoutClustering) {
  for (const auto& [layout, seed] :
       {std::tuple{SceneLayout::kOffice, std::uint64_t{4}}, std::tuple{SceneLayout::kOffice, std::uint64_t{5}},
        std::tuple{SceneLayout::kPillars, std::uint64_t{4}}}) {
    SceneGeneratorOptions g;
    g.polygons = 300;
    g.seed = seed;
    g.layout = layout;
    const Scene s = to_scene(generate_scene(g));
    SCOPED_TRACE(::testing::Message() << (layout == SceneLayout::kOffice ? "office" : "pillars") << " seed " << seed
                                      << ", " << s.patches.size() << " patches");
    SolveOptions o;
    o.method = Method::kHierarchical;
    o.clustering = Clustering::kOff;
    Solution sol;
    const SolveSummary sum = solve(s, o, &sol);
    ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
    EXPECT_LT(std::abs(energy_balance(s, sol).closed_scene_residual[0]), 1e-3);
  }
}

}  // namespace
}  // namespace hrad
