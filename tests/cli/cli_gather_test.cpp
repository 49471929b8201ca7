// The gathered outputs as a user gets them: `hrad render --final-gather` (PNG and OpenEXR, the
// same at any thread count, the time printed, the closed form of a furnace room through the whole
// chain solve -> PLY -> gather -> OpenEXR).
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
  const RunResult wrong = run_hrad("render " + dir.path("s.ply") +
                                       " --scene notebooks_data/scenes/two_far_surfaces.obj "
                                       "--final-gather --quiet --out " +
                                       dir.path("w.png"),
                                   dir);
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find(dir.path("s.ply") + ": patch id"), std::string::npos) << wrong.err;
}

// A closed cube of uniform emission E and reflectance rho has B = E / (1 - rho) everywhere (the
// furnace: every point's factors to the closed surface sum to 1). Solved by the full matrix with LU
// (exact to rounding in a closed convex room), written to the PLY in doubles, gathered at every
// sample from inside the room: every pixel of the OpenEXR (32-bit floats) is the closed form to float
// rounding. A gather that lost or double-counted a leaf, a camera ray that hit no wall, or a pixel
// average that dropped a sample would show.
TEST(CliRender, FinalGatherOfAFurnaceRoomIsTheClosedFormAtEveryPixel) {
  TempDir dir;
  const double rho = 0.6, e = 2.0, b = e / (1.0 - rho);
  dir.write("cube.mtl", "newmtl wall\nKd 0.6 0.6 0.6\nKe 2 2 2\n");
  // The cube [0, 2]^3, each face's front towards the inside; the floor cut in two so that leaves
  // of different patches meet along a T-junction.
  dir.write("cube.obj",
            "mtllib cube.mtl\nusemtl wall\n"
            "v 0 0 0\nv 2 0 0\nv 2 0 2\nv 0 0 2\nv 0 2 0\nv 2 2 0\nv 2 2 2\nv 0 2 2\nv 1 0 0\nv 1 0 2\n"
            "f 1 4 10 9\nf 9 10 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
  const RunResult solve = run_hrad("solve " + dir.path("cube.obj") +
                                       " --method full --linear-solver lu --max-area 0.3 "
                                       "--quiet --out " +
                                       dir.path("s.ply"),
                                   dir);
  ASSERT_EQ(solve.exit_code, 0) << solve.err;
  // Default grouping (a uniform field: whole patches gathered as one polygon each) and leaf by leaf.
  for (const std::string tolerance : {"", " --gather-tolerance 0"}) {
    const RunResult r = run_hrad("render " + dir.path("s.ply") + " --scene " + dir.path("cube.obj") +
                                     " --final-gather --camera 1.7,1.5,0.3,0.2,0.4,1.8,0,1,0,90 --width 24 --height 18"
                                     " --samples-per-pixel 2 --quiet --out " +
                                     dir.path("f.exr") + tolerance,
                                 dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const HdrImage image = read_exr(dir.path("f.exr"));
    ASSERT_EQ(image.pixels.size(), 24u * 18u);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(image.pixels[i][c], b, 1e-6 * b) << tolerance << ", pixel " << i << " channel " << c;
  }
}

}  // namespace
}  // namespace hrad::test
