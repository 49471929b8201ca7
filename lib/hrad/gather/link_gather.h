// The final gather (final_gather.h) through a hierarchical solution's links: a point x on leaf L
// gathers over the sources of the links of L and of every ancestor of L (its elements up to the
// patch's root, then the clusters above the patch), the sources of one receiver-to-patch pair's
// links tiling that patch (refinement splits a pair into pairs that tile it, and drops only pairs
// that exchange nothing). Each source is gathered with Lambert's exact point-to-polygon factor
// from x over its polygon (a cluster source: over each of its patches), times its radiosity (an
// interior element's: the area mean of its leaves), so the point's cost is the links on its path,
// not the scene (Smits, Arvo & Greenberg 1994 sec. 6: the gather at a point reuses the links'
// visibility; Lischinski, Tampieri & Greenberg 1993).
//
// Visibility by the link's class: a link between elements that the refinement did not mark partial
// is classified once for the whole pair (receiver polygon against source polygon, by shaft culling,
// on first use; the refinement leaves a link unmarked also when it sampled the pair and every ray
// passed, which a point near an occluder need not share): fully visible needs no ray, hidden
// nothing. A partial link's source (and every link with a cluster end) is classified from x's leaf,
// once for all the leaf's points (gather() groups the points by leaf; the shaft from the leaf holds
// the shaft from each of its points, so a leaf that sees all or none of a source decides it for
// every point on it), among the occluders of the two patches' pair (classified once per pair).
// Where the leaf sees part of it, it is opened down to its leaves (open_partly_visible), each
// classified from the leaf among its parent's occluders, and a leaf still partly visible is sampled
// from x among those occluders: by default with rays shared by all of x's partly visible sources,
// each source's share proportional to its unoccluded contribution F(x -> N) B_N (systematic
// sampling; PartialSampling::shared, as leaf_gather.h), or with `visibility_samples` stratified
// points on each (per_node), the kernel-weighted visible fraction multiplying the factor.
// classify_points adds a shaft test from x itself before sampling (no ray where x sees all or none
// of the source): ~15 rays' cost per test, for less noise per ray. With `visibility_samples` points
// on each partly visible source (per_node), the leaf's test then only saves point tests, which pays
// where the leaf holds several points: a leaf with fewer than `leaf_first_points` of the batch's
// points classifies from each point straight away (among the patch pair's occluders, then each
// opened node's). The values are the same either way, so they do not depend on the batch: a leaf
// that sees all or none of a source decides it for each of its points (the shaft from the leaf
// holds the shaft from each point), where the point's own test may only find the source possibly
// partly visible (shaft culling is conservative), and then its samples all pass, or all are
// blocked, and the fraction is exactly 1 or 0; where the leaf sees part of the source the point's
// test decides in both cases, and a ray meets only occluders that both candidate lists hold. With
// shared rays the sources flagged partly visible share a point's rays, so such a flag would move
// the others' rays: there the leaf always classifies first. A cluster link lists the patches
// of either end that see nothing of the other: those neither gather nor are gathered through it.
//
// Accuracy: a coarse link's source, taken whole, enters with its mean radiosity B_N; over its
// leaves j that differs from gathering them one by one by
//   sum_j (F_j - F_N A_j / A_N)(B_j - B_N)  <=  A_N / pi * (k_max - k_min) * D_N,
// k_min, k_max bounding the point-to-area kernel over N from x and D_N the area-weighted mean
// absolute deviation of N's leaves from B_N (the Barnes-Hut bound of leaf_gather.h, with the
// link's source as the node). The refinement kept the kernel's variation small from the
// receiver's side, not the radiosity's below the source, so the gather walks down a source's
// subtree until that bound is within `tolerance` times the mean radiosity times the node's factor,
// as leaf_gather.h does below a patch: its cost per point is the links on the path plus the nodes it
// opens below coarse sources whose radiosity varies. tolerance = infinity gathers every source
// whole (exactly one point factor per link and source patch).

// What no link covers: refinement drops a pair whose rays were all blocked when what may pass
// unseen is within its tolerance for the pair as a whole (refinement_oracle.h), and such light can
// be a large part of what a point near the occluder receives (on the Cornell box's floor beside
// the tall block, a fifth of what one point gets from the back wall). So each source patch in
// front of x is walked from its root, skipping the link sources on the path, and every node that
// no source covers or lies in is gathered as partly visible: classified from x's leaf (a shaft
// test per leaf; fully hidden ones, usually all, cost nothing more), opened and sampled where
// partly visible. This adds one plane test per patch to a point's cost.
//
// Points that lie on no patch have no leaf and no links: the gather hands them to `in_space`
// (an all-patches LeafGather) when given, and refuses them otherwise.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include <tbb/concurrent_unordered_map.h>

#include "hrad/core/scene.h"
#include "hrad/gather/final_gather.h"
#include "hrad/gather/leaf_gather.h"
#include "hrad/solvers/solved_hierarchy.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

struct LinkGatherOptions {
  /// The bound on opening a source (see above), relative to the mean radiosity; 0 gathers each
  /// source's leaves one by one, infinity each source whole.
  double tolerance = 1e-2;
  /// per_node: `visibility_samples` stratified points on each partly visible source; shared:
  /// `visibility_samples` rays per point over all of them, each source's share proportional to its
  /// unoccluded contribution (as LeafGatherOptions::partial).
  PartialSampling partial = PartialSampling::shared;
  /// Stratified points per partly visible source, or rays per point (see `partial`). Shared, 512
  /// keep the Cornell box's default solve as close to the sweep's reference as 64 points a source
  /// (~3100 rays a point) do (README, "Gathering through the links").
  int visibility_samples = 512;
  /// A split source still partly visible from the point is opened and its children classified
  /// (as leaf_gather.h per node): k points over a large source resolve a shadow edge across it
  /// far more coarsely than k points on each of its leaves. Off: sampled whole.
  bool open_partly_visible = true;
  /// Also gather what no link on the path covers (see the header). Off: the links' sources only.
  bool gather_uncovered = true;
  /// A source partly visible from the point's leaf is classified again from the point before it is
  /// sampled (fewer rays where the point sees all or none of it). Off: sampled among the leaf's
  /// occluders, a shaft test saved per point and source.
  bool classify_points = false;
  /// With classify_points and per_node, a leaf holding fewer of gather()'s points than this
  /// classifies each partly visible source from each point straight away, without the polygon-sized
  /// shaft test from the leaf first (see the header); 1: always from the leaf first.
  int leaf_first_points = 4;
  std::uint64_t seed = 1;
};

class LinkGather final : public FinalGather {
 public:
  /// `scene` and `solved` (a hierarchical solve's, with every node's radiosity) must outlive the
  /// gather, as must `in_space` when given.
  LinkGather(const Scene& scene, const SolvedHierarchy& solved, const LinkGatherOptions& options = {},
             const FinalGather* in_space = nullptr);
  ~LinkGather() override;

  std::vector<Rgb> gather(std::span<const GatherPoint> points, ProgressReporter* progress = nullptr) const override;
  /// Its own work (points on patches) plus `in_space`'s.
  GatherWork work() const override;
  const Scene& scene() const override { return scene_; }

  /// The leaf of patch `patch` whose polygon holds x (the deepest node whose polygon holds x up to
  /// rounding; x is taken to lie in the patch's plane).
  NodeId leaf_at(int patch, const Vec3& x) const;
  /// The directed links whose receiver is on the path of `leaf` (itself, its ancestors and the
  /// clusters above its patch): what a point on it gathers through.
  std::size_t links_on_path(NodeId leaf) const;
  /// The source polygons of those links (an element: one; a cluster: its patches): the most point
  /// factors a point on `leaf` evaluates with tolerance = infinity.
  std::size_t sources_on_path(NodeId leaf) const;

 private:
  struct Source;
  struct Scratch;
  /// A point on leaf s.leaf.
  Rgb gather_point(const GatherPoint& p, Scratch& s, GatherWork& w) const;
  /// The class of the pair (s.leaf, element `id`), classified once per leaf's turn among
  /// `candidates` (an enclosing pair's occluders; null: every patch); its occluders are kept in s.
  PairClass leaf_class(NodeId id, const std::vector<int>* candidates, Scratch& s, GatherWork& w) const;
  /// The class of directed link k between elements (at dense receiver `receiver`): partial links are
  /// partial; the others are classified once, receiver polygon against source polygon, on first use
  /// (a link the refinement sampled and found unoccluded at every ray is not partial, yet may be).
  PairClass pair_class(std::size_t receiver, std::uint64_t k, GatherWork& w) const;
  static constexpr std::uint8_t kUnclassified = 0xff;
  /// A pair of patches classified by shaft culling, with its occluders: complete candidates for
  /// every pair of their elements.
  struct PatchPair {
    PairClass cls = PairClass::kPartial;
    std::vector<int> occluders;
  };
  /// The pair (patch p, patch q), classified on first use.
  const PatchPair& patch_pair(int p, int q, GatherWork& w) const;
  /// The pair (s.leaf's patch, patch q), looked up once per patch's turn.
  const PatchPair& patch_pair_of(int q, Scratch& s, GatherWork& w) const;
  /// The receiver nodes on `leaf`'s path, as dense indices (elements, then clusters after them).
  void path(NodeId leaf, std::vector<std::size_t>* out) const;

  const Scene& scene_;
  const SolvedHierarchy& solved_;
  LinkGatherOptions options_;
  const FinalGather* in_space_ = nullptr;
  std::unique_ptr<Visibility> visibility_;
  bool occlusion_ = true;
  // Per dense receiver, its directed links' sources: [offsets_[r], offsets_[r + 1]) of sources_.
  std::vector<std::uint64_t> offsets_;
  std::vector<Source> sources_;
  mutable tbb::concurrent_unordered_map<std::uint64_t, PatchPair> patch_pairs_;  ///< by p << 32 | q
  mutable std::unique_ptr<std::atomic<std::uint8_t>[]> pair_class_;  ///< per directed link: PairClass or kUnclassified
  std::vector<double> deviation_;          ///< per element: D_N (largest channel; 0 for a leaf)
  std::vector<std::uint32_t> leaf_count_;  ///< per element: the leaves below it (1 for a leaf)
  double mean_radiosity_ = 0.0;            ///< area-weighted over all patches, largest channel
  mutable std::mutex work_mutex_;
  mutable GatherWork work_;
};

}  // namespace hrad
