// FormFactorEvaluator's contract on the sources it grades receivers towards (set_sources()): the
// receivers' points are fixed by the first factor, so sources given later are refused, not ignored.
#include <gtest/gtest.h>

#include <span>
#include <stdexcept>
#include <vector>

#include "hrad/io/obj_reader.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

TEST(FormFactorEvaluator, SourcesGivenAfterTheFirstFactorAreRefused) {
  const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  Effects effects;
  effects.visibility = false;
  FormFactorEvaluator ev(s, effects, nullptr, 16, FormFactorKernel::kPointContour);
  std::vector<std::span<const Vec3>> polygons;
  std::vector<int> patches;
  for (std::size_t i = 0; i < s.patches.size(); ++i) {
    polygons.emplace_back(s.patches[i].vertices);
    patches.push_back(static_cast<int>(i));
  }
  EXPECT_NO_THROW(ev.set_sources(polygons, patches));
  // The first pair that exchanges light (the contour kernel runs, and fixes the receivers' points).
  double f = 0.0;
  for (std::size_t j = 1; j < s.patches.size() && !(f > 0.0); ++j)
    f = ev.estimate(s.patches[0].vertices, 0, s.patches[j].vertices, static_cast<int>(j)).value;
  ASSERT_GT(f, 0.0);
  EXPECT_THROW(ev.set_sources(polygons, patches), std::logic_error);
}

}  // namespace
}  // namespace hrad
