// The urban generator: about the requested facets, the same bits for the same seed, every facet a
// planar quad facing out of its building (walls sideways, roofs and ground up).
#include <gtest/gtest.h>

#include "hrad/experiments/urban_generator.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

TEST(UrbanGenerator, CountSeedAndOrientation) {
  const GeneratedScene a = generate_urban({3000, 7});
  const GeneratedScene b = generate_urban({3000, 7});
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t i = 0; i < a.faces.size(); ++i) EXPECT_EQ(a.faces[i].vertices, b.faces[i].vertices);
  // Walls are rounded to whole cuts per side, so the count is near, not exact.
  EXPECT_NEAR(static_cast<double>(a.faces.size()), 3000.0, 0.15 * 3000.0);
  for (const auto& f : a.faces) {
    const Vec3 n = newell_normal(f.vertices).normalized();
    if (f.material != 1) {
      EXPECT_GT(n.y(), 0.999);  // ground and roofs face up
      continue;
    }
    EXPECT_NEAR(n.y(), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace hrad
