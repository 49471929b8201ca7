#include "hrad/render/render.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "../support/temp_dir.h"
#include "hrad/core/error.h"
#include "hrad/io/exr_writer.h"
#include "hrad/io/png_writer.h"
#include "hrad/render/pixel_samples.h"
#include "hrad/render/rasterizer.h"

namespace hrad {
namespace {

// Camera at the origin looking along +z, 90 degree vertical field of view: at depth 10 the image
// spans [-10, 10] in both directions. World +x appears on the LEFT (right = forward x up = -x).
Camera test_camera(int w = 100, int h = 100) {
  Camera c;
  c.position = Vec3::Zero();
  c.target = Vec3(0, 0, 1);
  c.up = Vec3::UnitY();
  c.vfov_deg = 90.0;
  c.width = w;
  c.height = h;
  return c;
}

// A square [-5, 5]^2 at depth 10 whose front (CCW) faces the camera, constant radiosity.
Solution facing_square(double radiosity, bool reversed = false) {
  Solution s;
  s.vertices = {Vec3(-5, -5, 10), Vec3(-5, 5, 10), Vec3(5, 5, 10), Vec3(5, -5, 10)};
  s.vertex_radiosity.assign(4, Rgb::Constant(radiosity));
  s.faces = {{0, 1, 2, 3}};
  if (reversed) s.faces = {{3, 2, 1, 0}};
  s.face_patch = {0};
  s.face_radiosity = {Rgb::Constant(radiosity)};
  s.patch_radiosity = {Rgb::Constant(radiosity)};
  return s;
}

TEST(Camera, ProjectsKnownPointsOfTheCornellCamera) {
  const Camera c = cornell_box_camera(512, 512);
  EXPECT_NEAR(c.vfov_deg, 39.30764812, 1e-7);  // 2 atan(0.0125 / 0.035) in degrees
  const auto centre = project(c, Vec3(278, 273, 0));
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x(), 256.0, 1e-9);
  EXPECT_NEAR(centre->y(), 256.0, 1e-9);
  EXPECT_NEAR(centre->z(), 800.0, 1e-9);
  // Camera space (-100, -50, 1000): x = 0.5 (1 - 100 / (1000 * 0.0125/0.035)) 512 = 184.32,
  // y = 0.5 (1 + 50 / 357.142857) 512 = 291.84. World +x is image left.
  const auto p = project(c, Vec3(378, 223, 200));
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->x(), 184.32, 1e-9);
  EXPECT_NEAR(p->y(), 291.84, 1e-9);
  EXPECT_NEAR(p->z(), 1000.0, 1e-9);
  // The top edge of the film at depth 800: y = 273 + 800 * 0.0125 / 0.035.
  EXPECT_NEAR(project(c, Vec3(278, 273 + 800 * 0.0125 / 0.035, 0))->y(), 0.0, 1e-9);
  EXPECT_FALSE(project(c, Vec3(278, 273, -900)));
}

TEST(Camera, FittedCameraSeesTheWholeBox) {
  const Vec3 lo(-3, 1, 2), hi(7, 4, 20);
  const Camera c = fit_camera(lo, hi, 320, 200);
  double widest = 0.0;  // largest |ndc| over the corners: 0.95 by construction
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
    const auto p = project(c, corner);
    ASSERT_TRUE(p);
    EXPECT_GE(p->x(), 0.0);
    EXPECT_LE(p->x(), 320.0);
    EXPECT_GE(p->y(), 0.0);
    EXPECT_LE(p->y(), 200.0);
    widest = std::max({widest, std::abs(p->x() / 160.0 - 1.0), std::abs(p->y() / 100.0 - 1.0)});
  }
  EXPECT_NEAR(widest, 0.95, 1e-9);
}

TEST(Render, ConstantSquareCoversExactlyItsPixels) {
  RenderOptions o;
  o.camera = test_camera();
  o.exposure = 2.0;
  o.background = {1, 2, 3};
  // 0.09 * 2 = 0.18 -> sRGB 0.4614 -> 118. The square spans pixels [25, 75) in x and y.
  const Image image = render_solution(facing_square(0.09), o);
  int covered = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      const bool inside = x >= 25 && x < 75 && y >= 25 && y < 75;
      EXPECT_EQ(image.at(x, y), inside ? (Rgb8{118, 118, 118}) : (Rgb8{1, 2, 3})) << x << "," << y;
      covered += inside;
    }
  EXPECT_EQ(covered, 2500);
}

TEST(Render, BackFacesAreCulledUnlessAsked) {
  RenderOptions o;
  o.camera = test_camera();
  EXPECT_EQ(render_solution(facing_square(1.0, /*reversed=*/true), o).at(50, 50), (Rgb8{0, 0, 0}));
  o.cull_back_faces = false;
  EXPECT_EQ(render_solution(facing_square(1.0, true), o).at(50, 50), (Rgb8{255, 255, 255}));
}

TEST(Rasterizer, GouraudIsPerspectiveCorrect) {
  // A triangle receding in depth carrying f(p) = 0.01 x + 0.02 z + 0.3 y, linear in world space.
  // At each covered pixel the value must be f at the point where the pixel's centre ray meets
  // the triangle's plane; screen-linear interpolation would be off by up to ~20% here.
  const Camera c = test_camera(64, 48);
  Rasterizer r(c);
  const Vec3 pts[3] = {Vec3(-8, -3, 4), Vec3(6, -3, 4), Vec3(0, 2, 40)};
  auto f = [](const Vec3& p) { return 0.01 * p.x() + 0.02 * p.z() + 0.3 * p.y(); };
  const Rgb vals[3] = {Rgb::Constant(f(pts[0])), Rgb::Constant(f(pts[1])), Rgb::Constant(f(pts[2]))};
  r.fill_polygon(pts, vals);
  const Vec3 n = (pts[1] - pts[0]).cross(pts[2] - pts[0]);
  const double tan_half = 1.0, aspect = 64.0 / 48.0;
  int checked = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      if (!r.covered(x, y)) continue;
      const double ndc_x = 2.0 * (x + 0.5) / 64 - 1.0, ndc_y = 1.0 - 2.0 * (y + 0.5) / 48;
      const Vec3 dir(-ndc_x * tan_half * aspect, ndc_y * tan_half, 1.0);  // right = -x
      const double t = n.dot(pts[0]) / n.dot(dir);
      const Vec3 hit = t * dir;
      EXPECT_NEAR(r.depth(x, y), hit.z(), 1e-9 * hit.z());
      EXPECT_NEAR(r.value(x, y)[0], f(hit), 1e-9);
      ++checked;
    }
  EXPECT_GT(checked, 200);
}

TEST(Rasterizer, NearerPolygonWinsWhateverTheOrder) {
  const Camera c = test_camera(20, 20);
  const Vec3 near_sq[4] = {Vec3(-5, -5, 10), Vec3(-5, 5, 10), Vec3(5, 5, 10), Vec3(5, -5, 10)};
  const Vec3 far_sq[4] = {Vec3(-9, -9, 12), Vec3(-9, 9, 12), Vec3(9, 9, 12), Vec3(9, -9, 12)};
  const Rgb a[4] = {Rgb::Constant(1), Rgb::Constant(1), Rgb::Constant(1), Rgb::Constant(1)};
  const Rgb b[4] = {Rgb::Constant(2), Rgb::Constant(2), Rgb::Constant(2), Rgb::Constant(2)};
  for (int order = 0; order < 2; ++order) {
    Rasterizer r(c);
    if (order == 0) {
      r.fill_polygon(near_sq, a);
      r.fill_polygon(far_sq, b);
    } else {
      r.fill_polygon(far_sq, b);
      r.fill_polygon(near_sq, a);
    }
    EXPECT_EQ(r.value(10, 10)[0], 1.0);
    EXPECT_NEAR(r.depth(10, 10), 10.0, 1e-12);
    EXPECT_EQ(r.value(2, 10)[0], 2.0);  // only the far square reaches x = 2 (ndc -0.75 -> 9 at depth 12)
  }
}

TEST(Rasterizer, PolygonCrossingTheCameraPlaneIsClipped) {
  // A floor y = -1 from behind the camera to far ahead: it must fill the lower half only.
  const Camera c = test_camera(40, 40);
  Rasterizer r(c);
  const Vec3 floor[4] = {Vec3(50, -1, -10), Vec3(-50, -1, -10), Vec3(-50, -1, 100), Vec3(50, -1, 100)};
  const Rgb v[4] = {Rgb::Ones(), Rgb::Ones(), Rgb::Ones(), Rgb::Ones()};
  r.fill_polygon(floor, v);
  EXPECT_FALSE(r.covered(20, 5));
  EXPECT_TRUE(r.covered(20, 35));
  // Pixel row 39: ndc_y = -0.975 -> the ray meets y = -1 at depth 1/0.975.
  EXPECT_NEAR(r.depth(20, 39), 1.0 / 0.975, 1e-9);
}

TEST(Render, WireframeDrawsEdgesOverFlatShading) {
  RenderOptions o;
  o.camera = test_camera();
  Solution s = facing_square(0.5);
  s.vertex_radiosity[0] = Rgb::Constant(1.0);  // flat shading must ignore vertex values
  WireframeOptions w;
  w.edge_colour = {255, 0, 0};
  w.links = {{Vec3(0, -2, 9), Vec3(0, 2, 9)}};  // in front of the square, vertical at the centre
  w.link_colour = {0, 255, 0};
  const Image image = render_wireframe(s, o, w);
  EXPECT_EQ(image.at(40, 40), (Rgb8{188, 188, 188}));  // sRGB(0.5)
  // The left and top edges lie on the pixel boundary 25: either neighbour may take them.
  const Rgb8 red{255, 0, 0};
  EXPECT_TRUE(image.at(25, 40) == red || image.at(24, 40) == red);
  EXPECT_TRUE(image.at(40, 25) == red || image.at(40, 24) == red);
  EXPECT_NE(image.at(26, 40), red);
  EXPECT_EQ(image.at(50, 50), (Rgb8{0, 255, 0}));  // link
  EXPECT_EQ(image.at(10, 10), (Rgb8{0, 0, 0}));
  // A link hidden behind the square is not drawn.
  w.links = {{Vec3(0, -2, 20), Vec3(0, 2, 20)}};
  EXPECT_EQ(render_wireframe(s, o, w).at(50, 50), (Rgb8{188, 188, 188}));
}

TEST(Render, FalseColourMapsValuesAndAddsLegend) {
  EXPECT_EQ(error_colormap(0.0), (Rgb8{59, 76, 192}));
  EXPECT_EQ(error_colormap(0.5), (Rgb8{221, 221, 221}));
  EXPECT_EQ(error_colormap(1.0), (Rgb8{180, 4, 38}));
  EXPECT_EQ(error_colormap(0.25), (Rgb8{140, 149, 207}));  // halfway blue -> white
  EXPECT_EQ(error_colormap(INFINITY), (Rgb8{180, 4, 38}));
  EXPECT_EQ(error_colormap(NAN), (Rgb8{128, 128, 128}));
  RenderOptions o;
  o.camera = test_camera();
  FalseColourOptions fc;
  fc.lo = 0.0;
  fc.hi = 0.2;
  Image image = render_false_colour(facing_square(1.0), {0.1}, o, fc);
  EXPECT_EQ(image.width, 100 + 64);
  EXPECT_EQ(image.at(50, 50), (Rgb8{221, 221, 221}));
  fc.log_scale = true;
  fc.lo = 1e-3;
  fc.hi = 1e-1;
  fc.legend = false;
  image = render_false_colour(facing_square(1.0), {1e-2}, o, fc);  // log midpoint
  EXPECT_EQ(image.width, 100);
  EXPECT_EQ(image.at(50, 50), (Rgb8{221, 221, 221}));
}

TEST(Png, RoundTripAndErrors) {
  test::TempDir dir;
  Image image(7, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 7; ++x)
      image.at(x, y) = {static_cast<std::uint8_t>(30 * x), static_cast<std::uint8_t>(80 * y), 7};
  write_png(dir.path("a.png"), image);
  EXPECT_EQ(dir.entries(), 1u);
  const Image back = read_png(dir.path("a.png"));
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_THROW(read_png(dir.path("missing.png")), Error);
  EXPECT_THROW(read_png(dir.write("bad.png", "\x89PNG\r\n\x1a\ntruncated")), Error);
  EXPECT_THROW(write_png(dir.path("empty.png"), Image()), Error);
}

// OpenEXR keeps what a PNG throws away: values above 1 and below 1/255, to float precision.
TEST(Exr, RoundTripKeepsLinearValues) {
  test::TempDir dir;
  HdrImage image(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) image.at(x, y) = Rgb(17.25 * x, 1e-4 * y, 0.5 + x * y);
  write_exr(dir.path("a.exr"), image);
  EXPECT_EQ(dir.entries(), 1u);
  const HdrImage back = read_exr(dir.path("a.exr"));
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(back.pixels[i][c], static_cast<double>(static_cast<float>(image.pixels[i][c]))) << i;
  EXPECT_THROW(read_exr(dir.path("missing.exr")), Error);
  EXPECT_THROW(read_exr(dir.write("bad.exr", "v/1\x01truncated")), Error);
  EXPECT_THROW(write_exr(dir.path("empty.exr"), HdrImage()), Error);
}

// Jittered pixel samples: inside their pixel, one in each stratum (a 2 x 2 grid for 4 passes, rows
// and columns for 3), the same for the same pixel and seed, different for another seed.
TEST(PixelSamples, StratifiedInsideThePixel) {
  for (int passes : {3, 4}) {
    std::vector<int> columns, rows;
    for (int k = 0; k < passes; ++k) {
      const Vec2 p = pixel_sample(7, 11, k, passes, 5);
      ASSERT_GE(p.x(), 7.0);
      ASSERT_LT(p.x(), 8.0);
      ASSERT_GE(p.y(), 11.0);
      ASSERT_LT(p.y(), 12.0);
      const int m = passes == 4 ? 2 : 3;
      columns.push_back(static_cast<int>((p.x() - 7) * m));
      rows.push_back(static_cast<int>((p.y() - 11) * m));
      EXPECT_EQ(p, pixel_sample(7, 11, k, passes, 5));
      EXPECT_NE(p, pixel_sample(7, 11, k, passes, 6));
    }
    std::vector<int> cells;
    for (int k = 0; k < passes; ++k) cells.push_back(passes == 4 ? columns[k] + 2 * rows[k] : columns[k]);
    std::sort(cells.begin(), cells.end());
    for (int k = 0; k < passes; ++k) EXPECT_EQ(cells[k], k);
    if (passes == 3) {
      std::sort(rows.begin(), rows.end());
      EXPECT_EQ(rows, (std::vector<int>{0, 1, 2}));
    }
  }
}

// Antialiased Gouraud: with one sample a pixel is the old tone_map of its centre; with four, a
// square's edge through the middle of a pixel column gives those pixels half the coverage.
TEST(Render, SamplesPerPixelAntialiasEdges) {
  RenderOptions o;
  o.camera = test_camera();
  o.exposure = 1.0;
  Solution s = facing_square(0.5);
  for (Vec3& v : s.vertices) v.x() *= 0.98;  // x = +-4.9: the middle of pixel columns 25 and 74
  const Image one = render_solution(s, o);
  EXPECT_EQ(one.at(25, 50), tone_map(Rgb::Constant(0.5), 1.0));  // centre 25.5 is on the edge: inside
  o.samples_per_pixel = 4;
  const RenderedImage four = render_solution_with_linear(s, o);
  EXPECT_DOUBLE_EQ(four.linear.at(25, 50)[0], 0.25);
  EXPECT_DOUBLE_EQ(four.linear.at(50, 50)[0], 0.5);
  EXPECT_DOUBLE_EQ(four.linear.at(24, 50)[0], 0.0);
  EXPECT_EQ(four.display.at(25, 50)[0], static_cast<std::uint8_t>(std::lround(255 * srgb_encode(0.25))));
  EXPECT_EQ(four.display.at(50, 50), one.at(50, 50));
}

}  // namespace
}  // namespace hrad
