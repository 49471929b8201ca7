// Closed boxes of zero-thickness walls, built in code for the leak tests: each wall a jittered grid
// of triangles with random diagonals and its own cuts along the box's edges (T-junctions where
// walls meet), every inside triangle with a back-to-back outside twin (the same three vertices in
// the opposite order), the whole scene in a tilted frame. The frame is a scaled rotation with
// integer entries (Pythagorean triples) and every local coordinate a short dyadic fraction, so the
// input is closed in exact arithmetic: each T-vertex lies exactly on the edge it splits. The
// walls' planes are tilted, so the elements' rounded midpoints and every sample point lie off
// their planes by rounding: what the leak tests are about.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/geometry/polygon.h"

namespace hrad::test {

/// Materials of the leak scenes.
enum LeakMaterial { kGround = 0, kInside = 1, kOutside = 2, kLight = 3 };

struct LeakScene {
  Scene scene;
  std::vector<int> inside;   ///< the box's inside faces (fronts into the box)
  std::vector<int> outside;  ///< their back-to-back twins (fronts out of the box)
  std::vector<int> around;   ///< patches outside the box that are not its walls (ground, room)
};

/// p -> m p + shift with m an integer matrix whose rows are orthogonal and of one length (a
/// rotation times that length): exact on short dyadic coordinates.
struct LeakFrame {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  Vec3 shift = Vec3::Zero();
  Vec3 operator()(const Vec3& p) const { return m * p + shift; }
};

/// Frame 0: axis-aligned; 1: turned about z by atan(4/3) (rows (3, -4, 0), (4, 3, 0), (0, 0, 5));
/// 2: tilted about every axis (rows (2, -1, 2), (2, 2, -1), (-1, 2, 2)).
inline LeakFrame leak_frame(int kind, const Vec3& shift) {
  LeakFrame f;
  if (kind == 1) f.m << 3, -4, 0, 4, 3, 0, 0, 0, 5;
  if (kind == 2) f.m << 2, -1, 2, 2, 2, -1, -1, 2, 2;
  f.shift = shift;
  return f;
}

/// x rounded to a multiple of 2^-10: a short dyadic fraction.
inline double dyadic(double x) { return std::ldexp(std::round(std::ldexp(x, 10)), -10); }

inline int add_leak_patch(Scene& s, std::vector<Vec3> v, int material) {
  Patch p;
  p.vertices = std::move(v);
  const Vec3 n = newell_normal(p.vertices);
  p.normal = n.normalized();
  p.area = 0.5 * n.norm();
  p.material = material;
  p.face = static_cast<int>(s.faces.size());
  InputFace f;
  f.material = material;
  f.area = p.area;
  f.patches.push_back(static_cast<int>(s.patches.size()));
  s.faces.push_back(f);
  s.patches.push_back(std::move(p));
  return static_cast<int>(s.patches.size()) - 1;
}

/// Cuts of [0, length]: exact ends, `cells - 1` random dyadic interior points at least 5% apart.
inline std::vector<double> leak_cuts(int cells, double length, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, length);
  std::vector<double> c{0.0, length};
  while (static_cast<int>(c.size()) < cells + 1) {
    const double x = dyadic(u(rng));
    if (std::none_of(c.begin(), c.end(), [&](double y) { return std::abs(x - y) < 0.05 * length; })) c.push_back(x);
  }
  std::sort(c.begin(), c.end());
  return c;
}

/// Adds the six walls of the box [0, size] (local coordinates, dyadic `size`, then `frame`), each
/// as a jittered grid of `cells` x `cells + 1` quads cut into triangles, inside faces and outside
/// twins.
inline void add_leak_box(LeakScene& out, const Vec3& size, int cells, const LeakFrame& frame, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  std::bernoulli_distribution coin(0.5);
  for (int axis = 0; axis < 3; ++axis)
    for (int high = 0; high < 2; ++high) {
      const int au = (axis + 1) % 3, av = (axis + 2) % 3;
      const std::vector<double> cu = leak_cuts(cells, size[au], rng), cv = leak_cuts(cells + 1, size[av], rng);
      std::vector<std::vector<Vec3>> grid(cu.size(), std::vector<Vec3>(cv.size()));
      for (std::size_t i = 0; i < cu.size(); ++i)
        for (std::size_t j = 0; j < cv.size(); ++j) {
          double u = cu[i], v = cv[j];
          if (i > 0 && i + 1 < cu.size() && j > 0 && j + 1 < cv.size()) {
            u = dyadic(u + jitter(rng) * std::min(cu[i] - cu[i - 1], cu[i + 1] - cu[i]));
            v = dyadic(v + jitter(rng) * std::min(cv[j] - cv[j - 1], cv[j + 1] - cv[j]));
          }
          Vec3 p;
          p[axis] = high ? size[axis] : 0.0;
          p[au] = u;
          p[av] = v;
          grid[i][j] = frame(p);
        }
      // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis, into the box on
      // the low wall.
      auto triangle = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        const std::vector<Vec3> in = high ? std::vector<Vec3>{a, c, b} : std::vector<Vec3>{a, b, c};
        out.inside.push_back(add_leak_patch(out.scene, in, kInside));
        out.outside.push_back(add_leak_patch(out.scene, {in[0], in[2], in[1]}, kOutside));
      };
      for (std::size_t i = 0; i + 1 < cu.size(); ++i)
        for (std::size_t j = 0; j + 1 < cv.size(); ++j) {
          const Vec3 &p00 = grid[i][j], &p10 = grid[i + 1][j], &p11 = grid[i + 1][j + 1], &p01 = grid[i][j + 1];
          if (coin(rng)) {
            triangle(p00, p10, p11);
            triangle(p00, p11, p01);
          } else {
            triangle(p00, p10, p01);
            triangle(p10, p11, p01);
          }
        }
    }
}

inline Scene leak_materials() {
  Scene s;
  s.path = "<leak scene>";
  s.materials = {{"ground", Rgb::Constant(0.5), Rgb::Zero()},
                 {"inside", Rgb::Constant(0.5), Rgb::Zero()},
                 {"outside", Rgb::Constant(0.5), Rgb::Zero()},
                 {"light", Rgb::Zero(), Rgb::Constant(10.0)}};
  return s;
}

/// A closed box of size `size` standing `lift` above a ground `ground` times its size across,
/// lit from outside by a quad emitter above and to the side of it (so the ground's light reaches
/// the box's walls at grazing angles too); the whole scene in `frame`.
inline LeakScene box_above_ground(const Vec3& size, double lift, double ground, int cells, const LeakFrame& frame,
                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  LeakScene s;
  s.scene = leak_materials();
  const double g = dyadic(ground * size.maxCoeff());
  const Vec3 c(0.5 * size.x(), 0.5 * size.y(), -dyadic(lift));
  s.around.push_back(add_leak_patch(
      s.scene,
      {frame(c + Vec3(-g, -g, 0)), frame(c + Vec3(g, -g, 0)), frame(c + Vec3(g, g, 0)), frame(c + Vec3(-g, g, 0))},
      kGround));
  add_leak_box(s, size, cells, frame, rng);
  const double h = dyadic(2.0 * size.maxCoeff());
  add_leak_patch(
      s.scene,
      {frame(Vec3(-h, -h, 2 * h)), frame(Vec3(-h, dyadic(0.3 * h), dyadic(2.2 * h))),
       frame(Vec3(dyadic(0.2 * h), dyadic(0.3 * h), dyadic(2.2 * h))), frame(Vec3(dyadic(0.2 * h), -h, 2 * h))},
      kLight);
  return s;
}

/// An emitter inside a closed crate of size `size`, the crate standing in a closed room (one-sided
/// walls facing in) `room` times its size across; the whole scene in `frame`.
inline LeakScene crate_in_room(const Vec3& size, double room, int cells, const LeakFrame& frame, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  LeakScene s;
  s.scene = leak_materials();
  const double r = dyadic(room * size.maxCoeff());
  const Vec3 lo(0.5 * size.x() - r, 0.5 * size.y() - r, -0.5 * size.z()),
      hi(0.5 * size.x() + r, 0.5 * size.y() + r, 2 * r);
  const Vec3 centre = 0.5 * (lo + hi);
  auto wall = [&](std::vector<Vec3> v) {
    const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    if (n.dot(centre - v[0]) < 0) std::reverse(v.begin(), v.end());
    for (Vec3& x : v) x = frame(x);
    s.around.push_back(add_leak_patch(s.scene, v, kGround));
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int high = 0; high < 2; ++high) {
      const int au = (axis + 1) % 3, av = (axis + 2) % 3;
      std::vector<Vec3> v(4);
      for (int k = 0; k < 4; ++k) {
        v[k][axis] = high ? hi[axis] : lo[axis];
        v[k][au] = (k == 1 || k == 2) ? hi[au] : lo[au];
        v[k][av] = (k >= 2) ? hi[av] : lo[av];
      }
      wall(v);
    }
  add_leak_box(s, size, cells, frame, rng);
  // The lamp: a small quad under the crate's lid, facing down.
  const Vec3 m = 0.5 * size;
  const double e = dyadic(0.2 * size.minCoeff()), z = dyadic(0.8 * size.z());
  add_leak_patch(s.scene,
                 {frame(Vec3(m.x() - e, m.y() - e, z)), frame(Vec3(m.x() - e, m.y() + e, z)),
                  frame(Vec3(m.x() + e, m.y() + e, z)), frame(Vec3(m.x() + e, m.y() - e, z))},
                 kLight);
  return s;
}

/// Removes the inside face `index` of s.inside and its outside twin (moves both far away as
/// slivers would change nothing else): the box gets a real opening.
inline void open_box(LeakScene& s, std::size_t index) {
  for (int p : {s.inside[index], s.outside[index]}) {
    Patch& patch = s.scene.patches[static_cast<std::size_t>(p)];
    const Vec3 far = Vec3::Constant(1e3) + 0.001 * Vec3::Constant(p);
    patch.vertices = {far, far + Vec3(1e-3, 0, 0), far + Vec3(0, 1e-3, 0)};
    patch.normal = newell_normal(patch.vertices).normalized();
    patch.area = polygon_area(patch.vertices);
    s.scene.faces[static_cast<std::size_t>(patch.face)].area = patch.area;
  }
}

}  // namespace hrad::test
