// Solutions made in code for the gather tests: a scene's patches cut into leaves by the element
// hierarchy's own splits (as every solver does), each leaf given a radiosity by a function of its
// centroid, so that a test knows the B_j it gathers from.
#pragma once

#include <functional>

#include "../solvers/solver_test_scenes.h"
#include "hrad/geometry/polygon.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/solved_hierarchy.h"

namespace hrad::test {

/// The leaves of `scene` split uniformly to at most `max_area` (patch p to at most
/// max_area * area_scale(p) when given, for trees of different depths), with face_radiosity
/// B(centroid, patch) (patch_radiosity and vertex_radiosity are left as the hierarchy made them:
/// a gather reads only the leaves).
inline Solution leaves_with(const Scene& scene, double max_area, const std::function<Rgb(const Vec3&, int)>& radiosity,
                            const std::function<double(int)>& area_scale = {}) {
  ElementHierarchy h(scene);
  for (int p = 0; p < static_cast<int>(scene.patches.size()); ++p)
    h.subdivide_uniform(h.root(p), max_area * (area_scale ? area_scale(p) : 1.0));
  Solution s = h.to_solution();
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    std::vector<Vec3> polygon;
    for (int v : s.faces[f]) polygon.push_back(s.vertices[static_cast<std::size_t>(v)]);
    s.face_radiosity[f] = radiosity(polygon_centroid(polygon), s.face_patch[f]);
  }
  return s;
}

/// A square emitter [0, a]^2 at height c facing down (emission (e, 2e, e/2), no reflection) over a
/// floor patch facing up (reflectance 0.5); nothing occludes, so a point on the floor sees the
/// square with Howell's factor (B-3 summed over the four rectangles meeting at its foot).
inline Scene square_emitter_over_floor(double a, double c, double e) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero(), "floor"),
                 material(Rgb::Zero(), Rgb(e, 2 * e, 0.5 * e), "light")};
  add_polygon(s, {{-3, 0, -3}, {5, 0, -3}, {5, 0, 5}, {-3, 0, 5}}, Vec3::UnitY(), 0);
  add_polygon(s, {{0, c, 0}, {a, c, 0}, {a, c, a}, {0, c, a}}, -Vec3::UnitY(), 1);
  return s;
}

/// A hierarchical solve of `scene` with its hierarchy and links kept.
inline SolvedHierarchy solve_keeping(const Scene& scene, SolveOptions o, Solution* out) {
  SolvedHierarchy kept;
  o.method = Method::kHierarchical;
  solve(scene, o, out, &kept);
  return kept;
}

/// square_emitter_over_floor(a, c, e) solved hierarchically (feps 0.001), its links kept.
struct SolvedSquareEmitter {
  double a = 2.0, c = 0.75, e = 3.0;
  Scene scene;
  Solution solution;
  SolvedHierarchy kept;
};
inline SolvedSquareEmitter solved_square_emitter() {
  SolvedSquareEmitter out;
  out.scene = square_emitter_over_floor(out.a, out.c, out.e);
  SolveOptions o;
  o.feps = 0.001;
  out.kept = solve_keeping(out.scene, o, &out.solution);
  return out;
}

/// A uniform field: every leaf at `b`.
inline Solution uniform_leaves(const Scene& scene, double max_area, const Rgb& b) {
  return leaves_with(scene, max_area, [&](const Vec3&, int) { return b; });
}

}  // namespace hrad::test
