// Images by final gather (gather/gathered_image.h): a furnace (a closed room of uniform emission
// and reflectance looks the same, B = E / (1 - rho), from anywhere; pbrt-v4's integrator tests,
// src/pbrt/cpu/integrators_test.cpp, check the image mean of such scenes against the closed form),
// antialiased edges with the exact coverage the stratified samples give, the same bits at any
// thread count, and probes at the points the pixels see that get the pixels' values.
#include "hrad/gather/gathered_image.h"

#include <optional>

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include "gather_test_scenes.h"
#include "hrad/gather/leaf_gather.h"
#include "hrad/gather/probes.h"
#include "hrad/render/camera.h"

namespace hrad {
namespace {

using test::add_polygon;
using test::make_box;
using test::material;
using test::uniform_leaves;

Camera inside_camera(int w, int h) {
  Camera c;
  c.position = Vec3(2.6, 1.9, 0.4);
  c.target = Vec3(0.3, 0.2, 3.7);  // towards a corner: floor and three walls in view
  c.up = Vec3::UnitY();
  c.vfov_deg = 80.0;
  c.width = w;
  c.height = h;
  return c;
}

LeafGatherOptions image_options() {
  LeafGatherOptions o;
  o.partial = PartialSampling::shared;
  o.classify_points = false;
  o.visibility_samples = 16;
  return o;
}

// Every sample of every pixel sees a wall of the closed room, whose gathered radiosity is the
// closed form: each pixel, and so the image's mean, is E / (1 - rho) to rounding.
TEST(GatheredImage, FurnaceRoomIsUniformAtTheClosedForm) {
  const double rho = 0.7, e = 0.4, b = e / (1 - rho);
  const Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0}, true);
  const Solution leaves = uniform_leaves(box, 0.3, Rgb::Constant(b));
  const LeafGather gather(box, leaves, image_options());
  RenderOptions o;
  o.camera = inside_camera(40, 30);
  o.samples_per_pixel = 4;
  o.exposure = 1.0;
  const GatheredImage image = render_gathered(leaves, gather, o);
  EXPECT_EQ(image.points, 40u * 30u * 4u);
  double mean = 0.0;
  for (const Rgb& v : image.radiosity.pixels) {
    EXPECT_LT(std::abs(v[1] - b) / b, 1e-9);
    mean += v[1] / static_cast<double>(image.radiosity.pixels.size());
  }
  EXPECT_LT(std::abs(mean - b) / b, 1e-9);
  // exposure * b = 1.333 clamps to 1: white.
  EXPECT_EQ(image.display.at(20, 15), (Rgb8{255, 255, 255}));
}

// A square facing the camera whose left and right edges cross pixel columns at their middle: with
// 2 x 2 stratified samples, exactly two of a column's pixel's four samples fall inside, so the
// edge pixels hold half the value (linear) and the background elsewhere.
TEST(GatheredImage, EdgesAreAntialiasedByTheStrata) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Constant(0.2), "square")};
  // Camera at the origin looking along +z, 90 degrees: at depth 10 the image spans [-10, 10]; 100
  // pixels, so x = -4.9 and 4.9 fall in the middle of pixels 25 and 74 (world +x is image left).
  add_polygon(s, {{-4.9, -5, 10}, {4.9, -5, 10}, {4.9, 5, 10}, {-4.9, 5, 10}}, -Vec3::UnitZ(), 0);
  const Solution leaves = uniform_leaves(s, 100.0, Rgb::Constant(0.2));
  const LeafGather gather(s, leaves, image_options());
  RenderOptions o;
  o.camera.position = Vec3::Zero();
  o.camera.target = Vec3::UnitZ();
  o.camera.up = Vec3::UnitY();
  o.camera.vfov_deg = 90.0;
  o.camera.width = o.camera.height = 100;
  o.samples_per_pixel = 4;
  const GatheredImage image = render_gathered(leaves, gather, o);
  // Nothing else in the scene: the gathered radiosity is the emission.
  EXPECT_DOUBLE_EQ(image.radiosity.at(50, 50)[0], 0.2);
  EXPECT_DOUBLE_EQ(image.radiosity.at(25, 50)[0], 0.1);
  EXPECT_DOUBLE_EQ(image.radiosity.at(74, 50)[0], 0.1);
  EXPECT_DOUBLE_EQ(image.radiosity.at(24, 50)[0], 0.0);
  EXPECT_DOUBLE_EQ(image.radiosity.at(75, 50)[0], 0.0);
  // Display: half of clamp(0.2) and half of black, averaged in linear light, sRGB-encoded.
  EXPECT_EQ(image.display.at(25, 50)[0], static_cast<std::uint8_t>(std::lround(255 * srgb_encode(0.1))));
  // The Gouraud image antialiases the same edge the same way.
  const Image gouraud = render_solution(leaves, o);
  EXPECT_EQ(gouraud.at(25, 50), image.display.at(25, 50));
  EXPECT_EQ(gouraud.at(50, 50), image.display.at(50, 50));
}

// The gathered image is the same, bit for bit, with one thread and with two (each point's rays
// are seeded by the point; each pixel's samples are summed in pass order).
TEST(GatheredImage, SameBitsAtOneAndTwoThreads) {
  Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero()), material(Rgb::Zero(), Rgb::Constant(5))},
                       {0, 1, 0, 0, 0, 0});
  test::add_block(box, 1.0, 2.0, 0.0, 1.2, 1.5, 2.5, 0);
  const Solution leaves = test::leaves_with(box, 0.2, [&](const Vec3& y, int p) {
    return box.material_of(box.patches[static_cast<std::size_t>(p)]).emission + Rgb::Constant(0.3 + 0.1 * y.y());
  });
  const LeafGather gather(box, leaves, image_options());
  RenderOptions o;
  o.camera = inside_camera(32, 24);
  o.samples_per_pixel = 2;
  GatheredImage one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = render_gathered(leaves, gather, o);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = render_gathered(leaves, gather, o);
  }
  ASSERT_EQ(one.radiosity.pixels.size(), two.radiosity.pixels.size());
  for (std::size_t i = 0; i < one.radiosity.pixels.size(); ++i)
    EXPECT_TRUE((one.radiosity.pixels[i] == two.radiosity.pixels[i]).all()) << i;
  EXPECT_EQ(one.display.pixels, two.display.pixels);
  EXPECT_GT(one.work.rays, 0u);  // the block casts shadows: rays were cast and had to agree
}

// A probe (gather/probes.h) at the point a pixel sees gets the value the image gathered there: with
// one sample per pixel each pixel's ray passes through its centre, so the floor point it meets
// is found here by the ray's own intersection with the floor (y = 0), independently of the
// rasterizer, and `gather_probes` at that point facing up must give the pixel's radiosity, in
// light, in the block's shadow and in its penumbra. Exact visible regions make both values
// deterministic functions of the point (sampled rays are seeded by the point's bits, which the
// two paths round differently), so they agree to 1e-9.
TEST(GatheredImage, ProbesAtThePixelsPointsGetThePixelsValues) {
  Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(0.5), Rgb::Zero()), material(Rgb::Zero(), Rgb::Constant(5))},
                       {0, 1, 0, 0, 0, 0});
  const double bx0 = 1.0, bx1 = 2.0, by1 = 1.2, bz0 = 1.5, bz1 = 2.5;
  test::add_block(box, bx0, bx1, 0.0, by1, bz0, bz1, 0);
  const Solution leaves = test::leaves_with(box, 0.25, [&](const Vec3& y, int p) {
    return box.material_of(box.patches[static_cast<std::size_t>(p)]).emission +
           Rgb(0.2 + 0.1 * y.x(), 0.3, 0.1 * y.z());
  });
  LeafGatherOptions go;
  go.visibility = VisibilityMode::exact;
  const LeafGather gather(box, leaves, go);
  RenderOptions o;
  o.camera.position = Vec3(1.5, 2.3, 0.2);
  o.camera.target = Vec3(1.5, 0.0, 2.6);
  o.camera.up = Vec3::UnitY();
  o.camera.vfov_deg = 70.0;
  o.camera.width = 14;
  o.camera.height = 12;
  o.samples_per_pixel = 1;
  const GatheredImage image = render_gathered(leaves, gather, o);
  // Where the ray from the camera through (px, py) meets the floor first (not the block), or nothing.
  auto floor_point = [&](double px, double py) -> std::optional<Vec3> {
    const Vec3 d = pixel_direction(o.camera, px, py), c = o.camera.position;
    if (d.y() >= 0) return std::nullopt;
    const double t = -c.y() / d.y();
    const Vec3 x = c + t * d;
    if (x.x() <= 0 || x.x() >= 3 || x.z() <= 0 || x.z() >= 4) return std::nullopt;
    // Slab test against the block [bx0, bx1] x [0, by1] x [bz0, bz1].
    double t0 = 0.0, t1 = t;
    const double lo[3] = {bx0, 0.0, bz0}, hi[3] = {bx1, by1, bz1};
    for (int k = 0; k < 3; ++k) {
      const double a = (lo[k] - c[k]) / d[k], b = (hi[k] - c[k]) / d[k];
      t0 = std::max(t0, std::min(a, b));
      t1 = std::min(t1, std::max(a, b));
    }
    if (t0 < t1 * (1 - 1e-9)) return std::nullopt;
    return x;
  };
  std::vector<ProbePoint> probes;
  std::vector<std::pair<int, int>> pixel;
  for (int y = 0; y < o.camera.height; ++y)
    for (int x = 0; x < o.camera.width; ++x)
      if (const std::optional<Vec3> at = floor_point(x + 0.5, y + 0.5)) {
        probes.push_back({*at, Vec3::UnitY(), 0});
        pixel.emplace_back(x, y);
      }
  ASSERT_GT(probes.size(), 40u);
  const std::vector<ProbeValue> values = gather_probes(gather, probes);
  double darkest = 1e300, brightest = 0.0;
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const auto [x, y] = pixel[i];
    const Rgb& seen = image.radiosity.pixels[static_cast<std::size_t>(y) * o.camera.width + x];
    ASSERT_EQ(values[i].patch, 0) << "pixel " << x << "," << y;
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(std::abs(values[i].radiosity[c] - seen[c]), 1e-9 * std::abs(seen[c]) + 1e-15)
          << "pixel " << x << "," << y << " channel " << c << ": " << values[i].radiosity[c] << " vs " << seen[c];
    darkest = std::min(darkest, seen[1]);
    brightest = std::max(brightest, seen[1]);
  }
  EXPECT_LT(darkest, 0.8 * brightest);         // the block's shadow is among the pixels compared
  EXPECT_GT(gather.work().exact_regions, 0u);  // and so is its penumbra
}

}  // namespace
}  // namespace hrad
