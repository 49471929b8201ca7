// Scenes for the view-factor tests: boxes whose walls are cut at random into rectangles (T-junctions,
// coplanar neighbours, slivers), a box split by a partition, a room with an obstacle.
#pragma once

#include <algorithm>
#include <vector>

#include "../solvers/solver_test_scenes.h"
#include "hrad/core/rng.h"
#include "hrad/viewfactors/radiant_exchange.h"
#include "hrad/viewfactors/view_factor_matrix.h"

namespace hrad::test {

/// Cuts the rectangle origin + [0,1] u + [0,1] v into pieces by `cuts` random guillotine cuts; one
/// cut in four is a sliver (`sliver` of the side). Each piece faces `towards`.
inline void add_cut_rectangle(Scene& s, const Vec3& origin, const Vec3& u, const Vec3& v, const Vec3& towards, int cuts,
                              detail::Rng& rng, double sliver = 1e-4) {
  struct Rect {
    double u0, u1, v0, v1;
  };
  std::vector<Rect> pieces = {{0, 1, 0, 1}};
  for (int k = 0; k < cuts; ++k) {
    const std::size_t i = rng.below(pieces.size());
    Rect r = pieces[i];
    const bool along_u = rng.uniform() < 0.5;
    const double t = rng.uniform() < 0.25 ? sliver : 0.2 + 0.6 * rng.uniform();
    Rect a = r, b = r;
    if (along_u)
      a.u1 = b.u0 = r.u0 + t * (r.u1 - r.u0);
    else
      a.v1 = b.v0 = r.v0 + t * (r.v1 - r.v0);
    pieces[i] = a;
    pieces.push_back(b);
  }
  for (const Rect& r : pieces)
    add_polygon(s,
                {origin + r.u0 * u + r.v0 * v, origin + r.u1 * u + r.v0 * v, origin + r.u1 * u + r.v1 * v,
                 origin + r.u0 * u + r.v1 * v},
                towards, 0);
}

/// The closed box [0,a] x [0,b] x [0,c], each wall cut into `cuts` + 1 rectangles, facing in.
inline Scene make_cut_box(double a, double b, double c, int cuts, std::uint64_t seed, double sliver = 1e-4) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  detail::Rng rng(seed);
  const Vec3 X(a, 0, 0), Y(0, b, 0), Z(0, 0, c), O = Vec3::Zero();
  add_cut_rectangle(s, O, X, Z, Y, cuts, rng, sliver);   // floor y = 0
  add_cut_rectangle(s, Y, X, Z, -Y, cuts, rng, sliver);  // ceiling
  add_cut_rectangle(s, O, Y, Z, X, cuts, rng, sliver);   // x = 0
  add_cut_rectangle(s, X, Y, Z, -X, cuts, rng, sliver);  // x = a
  add_cut_rectangle(s, O, X, Y, Z, cuts, rng, sliver);   // z = 0
  add_cut_rectangle(s, Z, X, Y, -Z, cuts, rng, sliver);  // z = c
  return s;
}

/// Options for exact-only matrices (no threshold, all threads).
inline ViewFactorOptions plain_options() { return ViewFactorOptions{}; }

/// Concentric faceted spheres (6 rings, 8 sectors each) as two groups: "outer" (radius r2, facing in,
/// reflectance 1 - e2) and "inner" (radius r1, facing out, reflectance 1 - e1), the gray two-surface
/// enclosure of the radiant-exchange tests.
inline Scene make_concentric_spheres(double r1, double r2, double e1, double e2) {
  Scene s = make_faceted_sphere(r2, 6, 8, material(Rgb::Constant(1 - e2), Rgb::Zero()),
                                material(Rgb::Constant(1 - e2), Rgb::Zero()));
  const Scene inner = make_faceted_sphere(r1, 6, 8, material(Rgb::Constant(1 - e1), Rgb::Zero()),
                                          material(Rgb::Constant(1 - e1), Rgb::Zero()));
  const std::size_t outer_faces = s.faces.size();
  s.materials.push_back(material(Rgb::Constant(1 - e1), Rgb::Zero()));
  for (const Patch& p : inner.patches) add_polygon(s, p.vertices, polygon_centroid(p.vertices), 2);  // outward
  for (std::size_t f = 0; f < s.faces.size(); ++f) s.faces[f].group = f < outer_faces ? "outer" : "inner";
  return s;
}

// Black-body emissive power sigma T^4 (Stefan-Boltzmann law), W/m^2 at temperature t in K.
inline double black(double t) { return kStefanBoltzmann * t * t * t * t; }

}  // namespace hrad::test
