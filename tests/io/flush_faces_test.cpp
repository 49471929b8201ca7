#include "hrad/io/flush_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <fmt/format.h>

#include "../support/temp_dir.h"
#include "hrad/core/scene_checks.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/scene_reader.h"

namespace hrad {
namespace {

// An OBJ object: one face per rectangle [x0, x1] x [z0, z1] at height y, facing +y (counter-clockwise
// seen from above).
std::string rectangles(const std::string& object, double y, const std::vector<std::array<double, 4>>& rects,
                       int* vertices) {
  std::string s = fmt::format("o {}\nusemtl w\n", object);
  for (const auto& [x0, x1, z0, z1] : rects) {
    s += fmt::format("v {} {} {}\nv {} {} {}\nv {} {} {}\nv {} {} {}\n", x0, y, z1, x1, y, z1, x1, y, z0, x0, y, z0);
    s += fmt::format("f {} {} {} {}\n", *vertices + 1, *vertices + 2, *vertices + 3, *vertices + 4);
    *vertices += 4;
  }
  return s;
}

Scene read(const test::TempDir& dir, const std::string& body, std::vector<std::string>* warnings = nullptr) {
  dir.write("m.mtl", "newmtl w\nKd 0.5 0.5 0.5\n");
  return read_scene(dir.write("s.obj", "mtllib m.mtl\n" + body), warnings);
}

double area_of(const Scene& s, const std::string& group) {
  double a = 0.0;
  for (const Patch& p : s.patches)
    if (p.group == group) a += p.area;
  return a;
}

// Every patch convex with 3 or 4 corners, in its face's plane, and no two patches of different faces
// overlapping in one plane any more.
void expect_sound(const Scene& s) {
  for (const Patch& p : s.patches) {
    ASSERT_GE(p.vertices.size(), 3u);
    ASSERT_LE(p.vertices.size(), 4u);
    EXPECT_TRUE(is_convex(p.vertices, p.normal));
    EXPECT_NEAR(polygon_area(p.vertices), p.area, 1e-12 * p.area);
    EXPECT_GT(newell_normal(p.vertices).normalized().dot(p.normal), 1.0 - 1e-12);
  }
  EXPECT_TRUE(flush_pairs(s).empty());
}

TEST(FlushFaces, APictureIsCutOutOfItsWallAndTheAreasAddUp) {
  test::TempDir dir;
  int v = 0;
  // A 4 x 3 wall and a 1 x 0.5 picture on it at (1.3..2.3, 0.7..1.2).
  std::string body = rectangles("wall", 0.0, {{0, 4, 0, 3}}, &v);
  body += rectangles("picture", 0.0, {{1.3, 2.3, 0.7, 1.2}}, &v);
  std::vector<std::string> warnings;
  const Scene s = read(dir, body, &warnings);
  EXPECT_NEAR(area_of(s, "wall"), 12.0 - 0.5, 1e-12);
  EXPECT_NEAR(area_of(s, "picture"), 0.5, 1e-15);
  EXPECT_NEAR(s.faces[0].area, 11.5, 1e-12);
  EXPECT_NEAR(s.faces[1].area, 0.5, 1e-15);
  expect_sound(s);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("s.obj:15: warning: 1 pair of faces lie flush on each other"), std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[0].find("first: line 15 on line 8"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("(4% of the area)"), std::string::npos) << warnings[0];
}

TEST(FlushFaces, OnlyTheOverlapIsCutWhereTheFaceOnTopReachesPastTheOneBeneath) {
  test::TempDir dir;
  int v = 0;
  // The rug 1.5 x 1 reaches 0.5 past the tile's edge x = 2: the tile loses 1 x 1, the next tile 0.5 x 1.
  std::string body = rectangles("floor", 0.0, {{0, 2, 0, 2}, {2, 4, 0, 2}, {4, 6, 0, 2}}, &v);
  body += rectangles("rug", 0.0, {{1, 2.5, 0.5, 1.5}}, &v);
  const Scene s = read(dir, body);
  EXPECT_NEAR(s.faces[0].area, 3.0, 1e-12);
  EXPECT_NEAR(s.faces[1].area, 3.5, 1e-12);
  EXPECT_NEAR(s.faces[2].area, 4.0, 0.0);  // untouched
  EXPECT_EQ(s.faces[2].patches.size(), 1u);
  EXPECT_NEAR(s.faces[3].area, 1.5, 1e-15);
  expect_sound(s);
}

TEST(FlushFaces, TheSmallerObjectLiesOnTopEvenWhereItsFaceIsTheLarger) {
  test::TempDir dir;
  int v = 0;
  // A 3.5 x 3 rug, declared first, over 1 x 1 tiles of a 6 x 6 tiled floor: each tile is smaller than
  // the rug, but the floor is the larger object, so the rug lies on top: the nine tiles under it vanish
  // and the three it half covers keep their other halves.
  std::vector<std::array<double, 4>> tiles;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 6; ++k) tiles.push_back({double(i), i + 1.0, double(k), k + 1.0});
  std::string body = rectangles("rug", 0.0, {{1, 4.5, 1, 4}}, &v);
  body += rectangles("floor", 0.0, tiles, &v);
  std::vector<std::string> warnings;
  const Scene s = read(dir, body, &warnings);
  EXPECT_NEAR(area_of(s, "rug"), 10.5, 1e-15);
  EXPECT_NEAR(area_of(s, "floor"), 36.0 - 10.5, 1e-12);
  for (const int k : {1, 2, 3}) EXPECT_NEAR(s.faces[static_cast<std::size_t>(1 + 4 * 6 + k)].area, 0.5, 1e-12) << k;
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("9 faces covered entirely"), std::string::npos) << warnings[0];
  expect_sound(s);
}

TEST(FlushFaces, WithinOneObjectTheSmallerFaceThenTheLaterLiesOnTop) {
  test::TempDir dir;
  int v = 0;
  Scene s = read(dir, rectangles("one", 0.0, {{0, 2, 0, 2}, {0.5, 1, 0.5, 1}}, &v));
  EXPECT_NEAR(s.faces[0].area, 4.0 - 0.25, 1e-12);
  EXPECT_NEAR(s.faces[1].area, 0.25, 1e-15);
  // Two equal faces, offset: the later one keeps all of itself.
  v = 0;
  s = read(dir, rectangles("one", 0.0, {{0, 2, 0, 2}, {1, 3, 0, 2}}, &v));
  EXPECT_NEAR(s.faces[0].area, 2.0, 1e-12);
  EXPECT_NEAR(s.faces[1].area, 4.0, 1e-15);
  expect_sound(s);
}

TEST(FlushFaces, ALabelOnAPictureOnAWallCutsEachLayerOnce) {
  test::TempDir dir;
  int v = 0;
  std::string body = rectangles("wall", 0.0, {{0, 4, 0, 4}}, &v);
  body += rectangles("picture", 0.0, {{1, 3, 1, 3}}, &v);
  body += rectangles("label", 0.0, {{1.5, 2, 1.5, 1.75}}, &v);
  const Scene s = read(dir, body);
  EXPECT_NEAR(s.faces[0].area, 16.0 - 4.0, 1e-12);
  EXPECT_NEAR(s.faces[1].area, 4.0 - 0.125, 1e-12);
  EXPECT_NEAR(s.faces[2].area, 0.125, 1e-15);
  expect_sound(s);
}

TEST(FlushFaces, FacesBackToBackLiftedOrBesideEachOtherAreLeftAlone) {
  test::TempDir dir;
  for (const std::string& second : {std::string("v 1 0.001 1\nv 2 0.001 1\nv 2 0.001 0\nv 1 0.001 0\n"),  // lifted
                                    std::string("v 1 0 0\nv 2 0 0\nv 2 0 1\nv 1 0 1\n"),                  // facing down
                                    std::string("v 4 0 1\nv 5 0 1\nv 5 0 0\nv 4 0 0\n")}) {               // beside
    int v = 0;
    std::vector<std::string> warnings;
    const Scene s = read(
        dir, rectangles("floor", 0.0, {{0, 4, 0, 4}}, &v) + "o other\nusemtl w\n" + second + "f 5 6 7 8\n", &warnings);
    EXPECT_EQ(s.patches.size(), 2u);
    EXPECT_NEAR(s.faces[0].area, 16.0, 0.0);
    EXPECT_TRUE(warnings.empty()) << warnings[0];
  }
}

// Random convex faces (triangles and quadrilaterals, in three objects) overlapping in one plane, turned
// off the axes: after the cut, every point of the plane that some face covered is covered by exactly
// one patch, of the face the rule puts on top there (the smallest object, then the smallest face,
// then the latest), and no other point is covered. Checked at random points against the faces as
// given, away from every edge by 1e-7.
TEST(FlushFaces, RandomOverlapsLeaveExactlyTheFaceOnTopAtEveryPoint) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  using P2 = Eigen::Vector2d;
  const auto inside = [](const std::vector<P2>& poly, const P2& x, double margin) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const P2 a = poly[i], d = poly[(i + 1) % poly.size()] - a;
      if ((d.x() * (x.y() - a.y()) - d.y() * (x.x() - a.x())) / d.norm() < margin) return false;
    }
    return true;
  };
  const auto near_edge = [](const std::vector<P2>& poly, const P2& x, double margin) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const P2 a = poly[i], d = poly[(i + 1) % poly.size()] - a;
      const double t = std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((a + t * d - x).norm() < margin) return true;
    }
    return false;
  };
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Matrix3d turn =
        (Eigen::AngleAxisd(6.3 * u(rng), Vec3::UnitX()) * Eigen::AngleAxisd(6.3 * u(rng), Vec3::UnitY()))
            .toRotationMatrix();
    const Vec3 shift(u(rng), u(rng), u(rng));
    Scene s;
    s.materials.push_back({"w", Rgb::Constant(0.5), Rgb::Zero()});
    std::vector<std::vector<P2>> given;
    const int faces = 2 + static_cast<int>(u(rng) * 4);
    for (int f = 0; f < faces; ++f) {
      const int n = u(rng) < 0.5 ? 3 : 4;
      std::vector<double> angle(static_cast<std::size_t>(n));
      for (double& a : angle) a = 6.283185307179586 * u(rng);
      std::sort(angle.begin(), angle.end());
      const P2 c(u(rng), u(rng));
      const double r = 0.2 + 0.5 * u(rng);
      std::vector<P2> poly;
      for (const double a : angle) poly.push_back(c + r * P2(std::cos(a), std::sin(a)));
      Patch p;
      for (const P2& v : poly) p.vertices.push_back(turn * Vec3(v.x(), v.y(), 0.0) + shift);
      p.normal = turn * Vec3::UnitZ();
      p.area = polygon_area(p.vertices);
      if (!(p.area > 1e-3)) continue;  // a sliver of a draw: redrawn as nothing
      p.material = 0;
      p.face = static_cast<int>(s.faces.size());
      p.group = std::string(1, static_cast<char>('a' + static_cast<int>(u(rng) * 3)));
      s.faces.push_back(
          {p.group, 0, static_cast<std::size_t>(p.face + 1), p.area, {static_cast<int>(s.patches.size())}});
      s.patches.push_back(p);
      given.push_back(poly);
    }
    std::map<std::string, double> object_area;
    for (const Patch& p : s.patches) object_area[p.group] += p.area;
    const std::vector<InputFace> as_given = s.faces;
    const auto below = [&](int a, int b) {  // whether face a lies beneath face b
      const InputFace& fa = as_given[static_cast<std::size_t>(a)];
      const InputFace& fb = as_given[static_cast<std::size_t>(b)];
      if (object_area[fa.group] != object_area[fb.group]) return object_area[fa.group] > object_area[fb.group];
      if (fa.area != fb.area) return fa.area > fb.area;
      return a < b;
    };
    cut_flush_faces(s);
    std::vector<std::vector<P2>> pieces;
    for (const Patch& p : s.patches) {
      std::vector<P2> poly;
      for (const Vec3& v : p.vertices) {
        const Vec3 back = turn.transpose() * (v - shift);
        poly.push_back(P2(back.x(), back.y()));
      }
      pieces.push_back(poly);
    }
    for (int k = 0; k < 1000; ++k) {
      const P2 x(-0.7 + 2.4 * u(rng), -0.7 + 2.4 * u(rng));
      bool edge = false;
      for (const auto& g : given) edge = edge || near_edge(g, x, 1e-7);
      for (const auto& q : pieces) edge = edge || near_edge(q, x, 1e-7);
      if (edge) continue;
      int top = -1;
      for (int f = 0; f < static_cast<int>(given.size()); ++f)
        if (inside(given[static_cast<std::size_t>(f)], x, 0.0) && (top < 0 || below(top, f))) top = f;
      std::vector<int> covering;
      for (std::size_t i = 0; i < pieces.size(); ++i)
        if (inside(pieces[i], x, 0.0)) covering.push_back(s.patches[i].face);
      if (top < 0) {
        EXPECT_TRUE(covering.empty()) << "trial " << trial;
      } else {
        ASSERT_EQ(covering.size(), 1u) << "trial " << trial << " at " << x.transpose();
        EXPECT_EQ(covering[0], top) << "trial " << trial;
        ++checked;
      }
    }
    for (const Patch& p : s.patches) {
      EXPECT_LE(p.vertices.size(), 4u);
      EXPECT_TRUE(is_convex(p.vertices, p.normal));
    }
  }
  EXPECT_GT(checked, 10000);  // points some face covers, of the 200000 drawn
}

}  // namespace
}  // namespace hrad
