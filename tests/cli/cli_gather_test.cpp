// The gathered outputs as a user gets them: `hrad render --final-gather` (PNG and OpenEXR, the
// same at any thread count, the time printed).
#include <gtest/gtest.h>

#include <string>

#include "hrad/io/exr_writer.h"
#include "run_hrad.h"

namespace hrad::test {
namespace {

const std::string kRoom = "notebooks_data/scenes/simple_room.obj";

TEST(CliRender, FinalGatherWritesPngAndExrTheSameAtAnyThreadCount) {
  TempDir dir;
  ASSERT_EQ(run_hrad("solve " + kRoom + " --quiet --out " + dir.path("s.ply"), dir).exit_code, 0);
  const std::string base = "render " + dir.path("s.ply") + " --scene " + kRoom +
                           " --final-gather --width 48 --height 36 --samples-per-pixel 2 --quiet ";
  const RunResult one = run_hrad(base + "--threads 1 --out " + dir.path("a.png") + " --exr " + dir.path("a.exr"), dir);
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_TRUE(one.err.empty()) << one.err;  // --quiet
  EXPECT_NE(one.out.find("final gather: 48x36 pixels, 2 samples per pixel"), std::string::npos) << one.out;
  EXPECT_NE(one.out.find(" s ("), std::string::npos) << one.out;  // the image's time
  const RunResult two = run_hrad(base + "--threads 2 --out " + dir.path("b.png") + " --exr " + dir.path("b.exr"), dir);
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const std::string png = slurp(dir.path("a.png"));
  EXPECT_EQ(png.substr(0, 8), "\x89PNG\r\n\x1a\n");
  EXPECT_TRUE(png == slurp(dir.path("b.png")));
  const HdrImage a = read_exr(dir.path("a.exr")), b = read_exr(dir.path("b.exr"));
  ASSERT_EQ(a.width, 48);
  ASSERT_EQ(a.height, 36);
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    EXPECT_TRUE((a.pixels[i] == b.pixels[i]).all()) << i;
    sum += a.pixels[i].sum();
  }
  EXPECT_GT(sum, 0.0);
  // --out NAME.exr writes the same linear values instead of a PNG.
  ASSERT_EQ(run_hrad(base + "--out " + dir.path("c.exr"), dir).exit_code, 0);
  const HdrImage c = read_exr(dir.path("c.exr"));
  for (std::size_t i = 0; i < a.pixels.size(); ++i) EXPECT_TRUE((a.pixels[i] == c.pixels[i]).all()) << i;
  // A scene that is not the solution's is refused, naming the solution.
  const RunResult wrong = run_hrad("render " + dir.path("s.ply") + " --scene notebooks_data/scenes/two_far_surfaces.obj "
                                   "--final-gather --quiet --out " + dir.path("w.png"), dir);
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find(dir.path("s.ply") + ": patch id"), std::string::npos) << wrong.err;
}

}  // namespace
}  // namespace hrad::test
