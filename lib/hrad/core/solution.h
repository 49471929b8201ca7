// A solved radiosity field: the leaf elements as one polygon mesh with constant radiosity per
// element, plus per-vertex radiosity for smooth display. Solvers write it; io, render and
// analysis read it. Plain arrays: no OpenMesh or CGAL types cross this boundary.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

/// A leaf's radiosity under the linear basis: its values at the element's own corners (3: linear
/// on the triangle; 4: bilinear on the quad's map x(u, v) = (1-u)(1-v) x0 + u(1-v) x1 + uv x2 +
/// (1-u)v x3), counter-clockwise.
struct ElementField {
  int corners = 0;
  std::array<Vec3, 4> x{};
  std::array<Rgb, 4> radiosity{};
};

/// The field of `e` at a point x of its plane (on the element or near it): the triangle's linear
/// function of x's barycentric coordinates, or the quad's bilinear function of x's (u, v) (the
/// bilinear map inverted by Newton's method in the element's plane).
Rgb element_field_at(const ElementField& e, const Vec3& x);

struct Solution {
  std::vector<Vec3> vertices;           ///< leaf-mesh vertex positions
  std::vector<Rgb> vertex_radiosity;    ///< per vertex, for display (anchored at T-vertices, no cracks)
  std::vector<std::vector<int>> faces;  ///< leaf elements, counter-clockwise vertex ids (T-vertices included)
  std::vector<int> face_patch;          ///< the patch (index into Scene::patches) each leaf lies on
  std::vector<Rgb> face_radiosity;      ///< constant radiosity of each leaf element (the unknowns), or its mean
  /// The irradiance H each leaf gathered in the last gather (B = E + rho H there); its net outgoing
  /// flux is face_radiosity - face_irradiance.
  std::vector<Rgb> face_irradiance;
  /// Per face, the linear basis's field (its mean is face_radiosity); empty with the constant basis.
  std::vector<ElementField> face_field;
  std::vector<Rgb> patch_radiosity;  ///< area-weighted mean radiosity of each patch
  /// The scene's faces were cut along the outlines of faces near them before solving (io/near_faces.h, as
  /// read_scene() does by default; false after `hrad solve --no-cut-near-faces`): read the scene alike to use
  /// it with this solution.
  bool near_faces_cut = true;
  /// Optional, for figures: each link of a hierarchical solve as the segment between the centroids
  /// of its receiver and source elements (empty unless SolveOptions::record_links).
  std::vector<std::pair<Vec3, Vec3>> link_segments;
};

struct Scene;

/// The area-weighted mean radiosity of each input face of `scene` (Scene::faces, over its patches):
/// what the solve report lists per face and what per-face errors are scored on. A face with no
/// solved patch or no area reads 0.
std::vector<Rgb> face_radiosity(const Scene& scene, const Solution& solution);

}  // namespace hrad
