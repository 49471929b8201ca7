// The receiver-grouped parallel gather gives the same bits as the sequential gather in link order.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "hrad/solvers/solver_context.h"
#include "solver_test_scenes.h"

namespace hrad {
namespace {

TEST(GatherPlan, SameBitsAsTheSequentialGatherAtAnyThreadCount) {
  const Scene s = test::make_box(3, 2, 4, {{"m", Rgb(0.5, 0.4, 0.3), Rgb(1.0, 2.0, 3.0)}}, {0, 0, 0, 0, 0, 0});
  ElementHierarchy h(s);
  h.subdivide_uniform(0.05);
  std::uint64_t state = 3;
  auto next = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 11;
  };
  for (std::size_t i = 0; i < h.size(); ++i)
    h.node(static_cast<NodeId>(i)).radiosity = Rgb(next() % 1000 * 1e-3, next() % 997 * 1e-2, next() % 991 * 0.1);
  std::vector<Link> links(200000);
  for (Link& l : links) {
    l.receiver = static_cast<NodeId>(next() % h.size());
    l.source = static_cast<NodeId>(next() % h.size());
    l.form_factor = static_cast<double>(next() % 1000003) * 1e-7;
  }
  gather(h, links);
  std::vector<Rgb> reference;
  for (std::size_t i = 0; i < h.size(); ++i) reference.push_back(h.node(static_cast<NodeId>(i)).gathered);
  const GatherPlan plan(h.size(), links);
  EXPECT_EQ(plan.links(), links.size());
  EXPECT_LE(plan.bytes(), links.size() * 12 + (h.size() + 1) * 8 + 64);
  for (const int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    for (std::size_t i = 0; i < h.size(); ++i) h.node(static_cast<NodeId>(i)).gathered = Rgb::Constant(-1.0);
    gather(h, plan);
    for (std::size_t i = 0; i < h.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(h.node(static_cast<NodeId>(i)).gathered[c], reference[i][c]) << i;
  }
}

}  // namespace
}  // namespace hrad
