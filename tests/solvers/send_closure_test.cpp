// The closure of what the parts of an element split below aeps send (solvers/send_closure.h), on
// the hierarchy and links a solve leaves: in a closed room the whole closure of every element is 1,
// so the parts' mean is too, while what each part sends strays from it (what the closure takes
// out); where light leaves the element, its parts are left as they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hrad/solvers/cluster_transfer.h"
#include "hrad/solvers/hsa_links.h"
#include "hrad/solvers/push_pull.h"
#include "hrad/solvers/send_closure.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/solved_hierarchy.h"
#include "solver_test_scenes.h"

namespace hrad {
namespace {

// A 25 cm lamp 1 mm from the wall x = 0, a thin closed housing whose face towards the wall emits;
// in a closed room, or with only that wall and a floor around it (open).
Scene lamp_by_wall(bool closed) {
  std::vector<Material> materials{test::material(Rgb::Constant(0.7), Rgb::Zero(), "wall"),
                                  test::material(Rgb::Constant(0.5), Rgb::Zero(), "housing"),
                                  test::material(Rgb::Constant(0.5), Rgb::Constant(50.0), "light")};
  Scene s;
  if (closed) {
    s = test::make_box(3.6, 2.7, 3.1, materials, {0, 0, 0, 0, 0, 0});
  } else {
    s.materials = materials;
    test::add_polygon(s, {{0, 0, 0}, {0, 2.7, 0}, {0, 2.7, 3.1}, {0, 0, 3.1}}, Vec3::UnitX(), 0);
    test::add_polygon(s, {{0, 0, 0}, {3.6, 0, 0}, {3.6, 0, 3.1}, {0, 0, 3.1}}, Vec3::UnitY(), 0);
  }
  const std::size_t first = s.patches.size();
  test::add_block(s, 1e-3, 1e-3 + 0.01, 1.3, 1.55, 1.7, 1.95, 1);
  for (std::size_t i = first; i < s.patches.size(); ++i)
    if (s.patches[i].normal.x() < -0.5)
      s.patches[i].material = s.faces[static_cast<std::size_t>(s.patches[i].face)].material = 2;
  return s;
}

std::vector<SendClosure> closures_after_solve(const Scene& s, SolvedHierarchy* kept, double* aeps = nullptr) {
  SolveOptions o;
  o.method = Method::kHierarchical;
  o.source_levels = 2;
  Solution sol;
  const SolveSummary sum = solve(s, o, &sol, kept);
  EXPECT_EQ(sum.termination, Termination::kConverged) << sum.message;
  const ClusterTransfer geometry(s, *kept->hierarchy, kept->tree.get());
  const HsaLinks links(kept->links, *kept->hierarchy, kept->tree.get(), geometry);
  const PushPull push_pull(s, *kept->hierarchy, kept->tree.get(), 1, Basis::kConstant);
  if (aeps != nullptr) *aeps = sum.used.aeps;
  return send_closures(*kept->hierarchy, links, push_pull, sum.used.aeps, false);
}

// Guarantee: in a closed room the parts below aeps are closed to their element's mean of what a
// unit radiosity sends through the links between elements, and that mean is the room's closure, 1
// (within 5%: the links' visible fractions are sampled); the parts' own sums stray from it by more
// than 5% (beside the lamp, the defect the closure takes out).
TEST(SendClosure, PartsInAClosedRoomAreClosedToOne) {
  const Scene s = lamp_by_wall(true);
  SolvedHierarchy kept;
  const std::vector<SendClosure> closures = closures_after_solve(s, &kept);
  ASSERT_FALSE(closures.empty());  // some element split below aeps
  int parts = 0;
  double stray = 0.0;
  for (const SendClosure& c : closures) {
    if (!(c.closed > 0.0)) continue;
    ++parts;
    EXPECT_NEAR(c.closed, 1.0, 0.05);
    stray = std::max(stray, std::abs(c.sigma - c.closed));
  }
  EXPECT_GT(parts, 16);
  EXPECT_GT(stray, 0.05);
}

// Guarantee: with the room's other walls and ceiling gone, the wall's elements beside the lamp send
// much of their light out of the scene, their parts' closures differ by what each sees of the
// opening, and none of the wall's parts 5 cm or more beside the lamp is closed (an element under
// the lamp sees nothing but the lamp 1 mm away, and its parts may be).
TEST(SendClosure, PartsOfElementsThatLightLeavesAreLeftAsTheyAre) {
  const Scene s = lamp_by_wall(false);
  SolvedHierarchy kept;
  double aeps = 0.0;
  const std::vector<SendClosure> closures = closures_after_solve(s, &kept, &aeps);
  ASSERT_FALSE(closures.empty());  // some element split below aeps
  int wall_parts = 0;
  for (std::size_t i = 0; i < closures.size(); ++i) {
    const ElementNode& e = kept.hierarchy->node(static_cast<NodeId>(i));
    if (e.patch != 0 || !e.is_leaf() || e.area >= aeps) continue;  // the wall's parts below aeps
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < e.vertex_count; ++k) c += e.vertices[static_cast<std::size_t>(k)] / e.vertex_count;
    const double outside = std::max({1.3 - c.y(), c.y() - 1.55, 1.7 - c.z(), c.z() - 1.95});
    if (outside < 0.05) continue;  // under the lamp or at its edge: its element may see only the lamp
    ++wall_parts;
    EXPECT_EQ(closures[i].closed, 0.0);
  }
  EXPECT_GT(wall_parts, 0);
}

}  // namespace
}  // namespace hrad
