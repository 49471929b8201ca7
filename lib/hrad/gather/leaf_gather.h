// The final gather over a Solution's leaves (final_gather.h), grouped by patch, under a
// Barnes-Hut hierarchy so that a distant patch whose radiosity varies little is gathered as a few
// polygons rather than leaf by leaf (Barnes & Hut 1986; for radiosity, Hanrahan, Salzman &
// Aupperle 1991 sec. 3 and Smits, Arvo & Greenberg 1994).
//
// For a point x (normal n, on patch P or in space) and each source patch q:
//   1. visibility of q from x: for a point on P, the pair (P, q) classified once for the whole
//      gather by shaft culling (visibility.h; fully visible, hidden, facing away, or partial with
//      the list of patches that may occlude it, complete for every sub-pair); where it is partial,
//      or for a point in space, x itself is classified against q among those occluders
//      (`classify_points`);
//   2. q's quadtree (leaf_quadtree.h) is walked from its root. A node of polygon N, area A, mean
//      radiosity B_N and area-weighted mean absolute deviation D_N of its leaves' radiosity is
//      gathered as one polygon, F(x -> N) V B_N with Lambert's exact point-to-polygon factor, when
//      it is a leaf, or when its leaves tile N and
//          bound(N) = A / pi * (k_max - k_min) * D_N  <=  tolerance * B_mean * F(x -> N),
//      where k_min <= k(y) <= k_max bound the point-to-area kernel k(y) = cos(theta_x) cos(theta_y)
//      / |y - x|^2 over N (from the distances and cosines at N's vertices; k_min = 0 when N is only
//      partly visible) and B_mean is the area-weighted mean radiosity of the whole solution.
//      Otherwise its children are walked.
// Error bound (Barnes-Hut): with the leaves j of N tiling it and sum_j A_j (B_j - B_N) = 0,
//   sum_j F_j V_j B_j - F_N V_N B_N = sum_j (F_j V_j - F_N V_N A_j / A) (B_j - B_N),
// and F_j V_j / A_j, F_N V_N / A both lie in [k_min, k_max] / pi, so the difference is at most
// bound(N). Summed over the gathered nodes, the hierarchical gather differs from the leaf-by-leaf
// one (tolerance 0) by at most tolerance * B_mean * sum_N F(x -> N) <= tolerance * B_mean * the
// sum of the unoccluded factors from x to every patch (1 in a convex room), per channel, where
// visibility is decided exactly (classified, or VisibilityMode::exact); sampled visibility adds
// its sampling error to both. gather_with_bounds() returns the bound each point reached.
//
// Partly visible nodes (neither classification settled them) are sampled:
//   * PartialSampling::per_node: `visibility_samples` stratified points on the node, the
//     visible fraction weighted by the kernel (Wallace, Elmquist & Haines 1989). A partly visible
//     node that is not a leaf is opened (its children classified from x where classify_points),
//     however uniform its radiosity: k points over a whole uniform light resolve a shadow edge
//     across it far more coarsely than k points on each of its leaves, and the grouping's bound
//     speaks of the radiosity only. So per node the sampled gather is the leaf-by-leaf one, wherever
//     visibility is partial;
//   * PartialSampling::shared: `visibility_samples` rays per point shared by all partly visible
//     nodes, node i drawn with probability proportional to its unoccluded contribution
//     c_i = F_i B_i (systematic sampling over their cumulative sum, so node i gets the integer
//     part of its expected count or one more) and a uniform point y on it; each ray adds
//     C / m * vis(y) k(y) / kbar_i with C = sum_i c_i and kbar_i = pi F_i / A_i, an unbiased
//     estimate of sum_i c_i V_i whose cost does not grow with the number of nodes (for images:
//     the pixel's samples average the noise);
//   * VisibilityMode::exact: the exact visible region of the node (visibility/visible_region.h,
//     milliseconds a node): the reference for the sampled estimates.
// Seeds come from the point's coordinates and the options' seed, so a point gets the same value
// in any batch, order and thread count.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/gather/final_gather.h"
#include "hrad/gather/leaf_quadtree.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

enum class PartialSampling { per_node, shared };
enum class VisibilityMode { sampled, exact };

struct LeafGatherOptions {
  /// Barnes-Hut tolerance (see above); 0 gathers every leaf on its own. The default bounds the
  /// grouping's error by 1% of the mean radiosity (the bound is a worst case: the errors of a
  /// node's leaves largely cancel); larger values group more (final_gather_benchmark measures the
  /// factors per point at each setting).
  double tolerance = 1e-2;
  PartialSampling partial = PartialSampling::per_node;
  /// Points per partly visible node (per_node) or rays per point (shared).
  int visibility_samples = 64;
  /// Classify each point against each partly visible patch, and each partly visible node before
  /// sampling or opening it (exact where it settles; a shaft test costs ~10 us). Off: the
  /// patch pairs' classes only, and rays (for points on patches; a point in space is always
  /// classified, having no pair).
  bool classify_points = true;
  VisibilityMode visibility = VisibilityMode::sampled;
  std::uint64_t seed = 1;
};

/// Throws hrad::Error naming the option (--gather-tolerance, --visibility-samples) when out of range.
void validate_leaf_gather_options(const LeafGatherOptions& options);

class LeafGather final : public FinalGather {
 public:
  /// `scene` and `solution` must outlive the gather; solution.face_patch must index scene.patches.
  LeafGather(const Scene& scene, const Solution& solution, const LeafGatherOptions& options = {});
  ~LeafGather() override;

  std::vector<Rgb> gather(std::span<const GatherPoint> points, ProgressReporter* progress = nullptr) const override;
  GatherWork work() const override;
  const Scene& scene() const override { return scene_; }

  /// gather(), and per point the bound on its difference from the leaf-by-leaf gather (largest
  /// channel; see above).
  std::vector<Rgb> gather_with_bounds(std::span<const GatherPoint> points, std::vector<double>* bounds,
                                      ProgressReporter* progress = nullptr) const;

  /// The area-weighted mean radiosity of the solution's leaves (largest channel): the scale of the tolerance.
  double mean_radiosity() const { return mean_radiosity_; }
  const LeafGatherOptions& options() const { return options_; }
  const detail::LeafQuadtrees& trees() const { return trees_; }

 private:
  struct Pair;
  struct Scratch;
  const Pair& pair(int receiver, int source) const;
  Rgb gather_point(const GatherPoint& p, Scratch& s, GatherWork& w, double* bound) const;

  const Scene& scene_;
  const Solution& solution_;
  LeafGatherOptions options_;
  detail::LeafQuadtrees trees_;
  std::unique_ptr<Visibility> visibility_;
  bool occlusion_ = true;
  double mean_radiosity_ = 0.0;
  std::vector<Vec3> patch_normal_;
  std::vector<double> plane_tolerance_;  ///< per patch: heights below this count as in its plane
  // Patch pairs (receiver, source), classified a receiver row at a time on first use.
  mutable std::vector<std::vector<Pair>> pairs_;
  mutable std::unique_ptr<std::once_flag[]> row_once_;
  mutable std::mutex work_mutex_;
  mutable GatherWork work_;
};

}  // namespace hrad
