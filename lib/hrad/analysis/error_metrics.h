// Error of a radiosity Solution against a reference Solution or an analytic field, measured on
// one fixed set of sample points per patch so that solutions on different meshes compare fairly.
//
// Sampling (patch_samples): with m = max(1, round(sqrt(samples_per_patch))), one point per cell
// of an m x m stratification of each patch, standing for the cell's area:
//   * a quad patch v0 v1 v2 v3: the cells [i/m, (i+1)/m] x [j/m, (j+1)/m] of its bilinear map
//     x(u, v) = (1-u)(1-v) v0 + u(1-v) v1 + uv v2 + (1-u)v v3, weight |x_u x x_v| at the cell's
//     centre / m^2 (for a planar quad the Jacobian is linear in (u, v), so that is the cell's area
//     and the weights add up to the patch's area exactly);
//   * a triangle: m^2 congruent triangles (m per side), each weighing area / m^2; a polygon with
//     more vertices is fanned into triangles.
// SampleLayout::jittered (the default) takes a uniform point in each cell, from a random stream
// fixed by (patch, cell), so the set is the same for every run (stratified sampling; Cook 1986,
// "Stochastic sampling in computer graphics"). SampleLayout::centres takes the cells' centres.
// The centres alias with hrad's meshes: quadtree leaves split a quad patch at the same bilinear
// midpoints, so with m = 16 the leaves of depth 4 have one sample each at their centre, where a
// constant element is second-order exact, and the leaves of depth 5 have the samples on their
// corners, where it is worst. On the Cornell box (hierarchical, aeps total/40000 against total/
// 80000) the tall block's top read 0.04% at depth 4 and 1.38% at depth 5, while the leaves'
// values matched an exact gather at their centroids; that made the element field's error rise
// with refinement. Jittered samples see every leaf at a random place.
// The value of a Solution at a sample of patch p comes from the leaf of patch p that contains the
// point: with Field::constant it is the leaf's own field (the unknowns: face_radiosity, piecewise
// constant, or with the linear basis the leaf's linear field, Solution::face_field);
// with Field::interpolated it is the displayed field, the vertex_radiosity interpolated linearly
// over the leaf's polygon fanned from its first vertex into triangles, as the rasterizer draws it
// (Gouraud). The leaf is found (point in convex polygon in the patch's plane, with a relative
// tolerance of 1e-6 of the patch size, which covers float-rounded PLY vertices); when none does (a gap in the mesh),
// the leaf whose nearest edge is least violated is used and the sample counts as `unmatched`.
//
// Definitions (|.| is the Euclidean norm over the three channels, w_k the sample areas):
//   relative_l2   = sqrt( sum_k w_k |B(x_k) - Bref(x_k)|^2 / sum_k w_k |Bref(x_k)|^2 )
//   relative_linf = max_k |B(x_k) - Bref(x_k)| / max_k |Bref(x_k)|
//   patch_relative_l2[p], face_relative_l2[f]: relative_l2 restricted to the samples of patch p,
//     or to the samples falling in leaf f of the evaluated solution (a leaf that no sample falls
//     in is compared at its centroid). 0/0 is 0; x/0 with x > 0 is +infinity.
// With Emitters::exclude the samples of emitting patches are left out of every sum (their
// radiosity is mostly the given emission, which would dominate the norms); their
// patch_relative_l2 and face_relative_l2 are NaN ("not measured").
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"

namespace hrad {

struct SurfaceSample {
  Vec3 position;
  double area = 0.0;  ///< the area the sample stands for
  int patch = -1;
};

/// Where the sample of each cell lies (see above).
enum class SampleLayout { jittered, centres };

/// The fixed samples described above, patch by patch in Scene order.
std::vector<SurfaceSample> patch_samples(const Scene& scene, int samples_per_patch,
                                         SampleLayout layout = SampleLayout::jittered);

enum class Emitters { include, exclude };

/// Which field of a Solution is measured (see above).
enum class Field { constant, interpolated };

struct ErrorMetrics {
  double relative_l2 = 0.0;
  double relative_linf = 0.0;
  double rms_absolute = 0.0;              ///< sqrt(sum w |B - Bref|^2 / sum w)
  std::vector<double> patch_relative_l2;  ///< per Scene patch
  std::vector<double> face_relative_l2;   ///< per face of the evaluated solution
  std::size_t samples = 0;
  std::size_t unmatched = 0;  ///< samples no leaf contained (in either solution)
};

/// Error of `solution` against `reference` (both on `scene`'s patches, any meshes).
/// Both solutions are evaluated as `field`.
ErrorMetrics compare_solutions(const Scene& scene, const Solution& solution, const Solution& reference,
                               int samples_per_patch = 256, Emitters emitters = Emitters::include,
                               Field field = Field::constant, SampleLayout layout = SampleLayout::jittered);

/// Error of `solution` (evaluated as `field`) against an analytic radiosity `reference(position, patch)`.
ErrorMetrics compare_to_function(const Scene& scene, const Solution& solution,
                                 const std::function<Rgb(const Vec3&, int)>& reference, int samples_per_patch = 256,
                                 Emitters emitters = Emitters::include, Field field = Field::constant,
                                 SampleLayout layout = SampleLayout::jittered);

/// Error of values known only at the samples (`values[k]` at `samples[k]`, e.g. a final gather of a
/// solution there) against `reference[k]` at the same samples: relative_l2, relative_linf,
/// rms_absolute and patch_relative_l2 as above (face_relative_l2 is empty: no mesh).
ErrorMetrics compare_at_samples(const Scene& scene, std::span<const SurfaceSample> samples, std::span<const Rgb> values,
                                std::span<const Rgb> reference);

/// Looks up a Solution's radiosity at points of given patches (see above).
class SolutionSampler {
 public:
  SolutionSampler(const Scene& scene, const Solution& solution);
  /// The leaf of `patch` containing `x` (or the nearest, with *matched = false); -1 if the patch has no leaf.
  int leaf_at(const Vec3& x, int patch, bool* matched = nullptr) const;
  Rgb value_at(const Vec3& x, int patch, bool* matched = nullptr, Field field = Field::constant) const;
  /// Leaf `face`'s own field at `x` (Field::constant): its constant, or its linear field.
  Rgb element(int face, const Vec3& x) const;
  /// The vertex radiosity of leaf `face` interpolated at `x` (Field::interpolated).
  Rgb interpolated(int face, const Vec3& x) const;

 private:
  /// Per patch: leaves bucketed on a uniform grid over the patch's 2D bounds (in the plane basis
  /// u, v), so a look-up tests the few leaves whose bounding boxes overlap the point's cell.
  struct PatchIndex {
    Vec3 origin, u, v;
    Vec2 lo, cell;
    int nu = 1, nv = 1;
    double tolerance = 0.0;
    std::vector<std::vector<int>> buckets;
    std::vector<int> leaves;
  };
  const Scene& scene_;
  const Solution& solution_;
  std::vector<PatchIndex> index_;
};

struct EnergyBalance {
  Rgb emitted_power = Rgb::Zero();    ///< sum over patches of A E
  Rgb radiosity_power = Rgb::Zero();  ///< sum over leaves of A B (power leaving all surfaces)
  /// sum over leaves of A (1 - rho)/rho (B - E): the power absorbed, since B = E + rho H gives the
  /// irradiance H = (B - E)/rho and a surface absorbs (1 - rho) H per unit area. NaN in a channel
  /// where some leaf has rho = 0 (its irradiance is then not recoverable from B).
  Rgb absorbed_power = Rgb::Zero();
  /// |emitted - absorbed| / emitted per channel: 0 for an exact solution of a closed scene (all
  /// emitted power is eventually absorbed); NaN where nothing is emitted or absorbed is NaN.
  Rgb closed_scene_residual = Rgb::Zero();
};

/// Power bookkeeping of a Solution of `scene` (materials by Solution::face_patch).
EnergyBalance energy_balance(const Scene& scene, const Solution& solution);

}  // namespace hrad
