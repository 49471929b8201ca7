#include "hrad/solvers/hierarchical.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "hrad/core/bright_emitters.h"
#include "hrad/geometry/polygon.h"
#include "hrad/solvers/closed_scene.h"
#include "hrad/solvers/cluster_transfer.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/hsa_links.h"
#include "hrad/solvers/iteration.h"
#include "hrad/solvers/leaf_links.h"
#include "hrad/solvers/push_pull.h"
#include "hrad/solvers/refine.h"
#include "hrad/solvers/refinement_oracle.h"
#include "hrad/solvers/send_closure.h"
#include "hrad/solvers/solved_hierarchy.h"
#include "hrad/solvers/solver_context.h"
#include "hrad/visibility/sampling.h"

namespace hrad {
namespace {

// The link operators of one refinement: the HSA operator over every link, or (Push::kLeaf) the
// leaf-resolved operator over links between elements and the HSA operator over cluster links.
struct Operators {
  std::unique_ptr<HsaLinks> hsa;
  std::unique_ptr<LeafLinks> leaf;
  std::vector<const LinkOperator*> all() const {
    std::vector<const LinkOperator*> ops;
    if (leaf) ops.push_back(leaf.get());
    if (hsa) ops.push_back(hsa.get());
    return ops;
  }
};

Operators make_operators(const SolveOptions& options, const ElementHierarchy& h, const ClusterTree* tree,
                         const ClusterTransfer& geometry, const FormFactorEvaluator& evaluator,
                         const LinkVector& links) {
  Operators ops;
  if (options.push == Push::kHsa) {
    ops.hsa = std::make_unique<HsaLinks>(links, h, tree, geometry);
    return ops;
  }
  LinkVector elements, clusters;
  for (const Link& l : links) (is_cluster(l.p) || is_cluster(l.q) ? clusters : elements).push_back(l);
  ops.leaf = std::make_unique<LeafLinks>(h, evaluator, elements, options.basis == Basis::kLinear);
  ops.hsa = std::make_unique<HsaLinks>(clusters, h, tree, geometry);
  return ops;
}

}  // namespace

HierarchicalTolerances hierarchical_tolerances(const Scene& scene, const SolveOptions& options) {
  HierarchicalTolerances t;
  t.feps = options.feps;
  t.bfeps = options.bfeps;
  if (t.feps == 0.0 && t.bfeps == 0.0) t.feps = kAutoFeps;
  t.aeps = options.aeps > 0.0 ? options.aeps : kAutoAepsFraction * scene.total_area();
  return t;
}

bool uses_clustering(const Scene& scene, const SolveOptions& options) {
  switch (options.clustering) {
    case Clustering::kOn:
      return scene.patches.size() > 1;
    case Clustering::kOff:
      return false;
    case Clustering::kAuto:
      return scene.patches.size() >= kAutoClusteringPatches;
  }
  return false;
}

SolveSummary solve_hierarchical(const Scene& scene, const SolveOptions& requested, Solution* out,
                                SolvedHierarchy* kept) {
  // Links join elements of very different sizes at coarse levels (a whole floor to a small light),
  // where a fixed receiver quadrature is neither accurate nor reciprocal: the oracle uses the
  // analytic kernel where its own quadratures disagree.
  SolveOptions options = requested;
  options.kernel = FormFactorKernel::kAnalytic;
  const HierarchicalTolerances t = hierarchical_tolerances(scene, options);
  options.feps = t.feps;
  options.bfeps = t.bfeps;
  options.aeps = t.aeps;
  SolverContext ctx(scene, options, Method::kHierarchical);
  ElementHierarchy h(scene);
  auto& figures = ctx.summary().figures;
  figures["feps"] = t.feps;
  figures["bfeps"] = t.bfeps;
  figures["aeps"] = t.aeps;
  if (!ctx.effects().bounces) {
    ctx.set_direct("nothing reflects: B = E, no links needed");
    if (options.balance) h.balance();
    SolveSummary summary = ctx.finish(h, 0, out);
    if (kept != nullptr) *kept = {std::make_unique<ElementHierarchy>(std::move(h)), nullptr, {}};
    return summary;
  }
  std::unique_ptr<ClusterTree> tree;
  if (uses_clustering(scene, options)) {
    auto phase = ctx.phase("clusters");
    tree = std::make_unique<ClusterTree>(scene);
    figures["clusters"] = static_cast<double>(tree->size());
    ctx.summary().effects.reasons.push_back(
        "clustering: on (a volume hierarchy above the patches, linked from one root self-link)");
  }
  const ClusterTransfer geometry(scene, h, tree.get());
  std::vector<Rgb> cluster_radiosity(tree ? tree->size() : 0, Rgb::Zero());
  OracleTolerances tolerances{t.feps,
                              t.bfeps,
                              t.aeps,
                              options.push == Push::kHsa,
                              options.basis == Basis::kLinear,
                              options.source_levels,
                              {},
                              options.power_noise};
  if (options.source_levels > 0 && options.source_levels_near_lamps) {
    // Sources split below aeps only on the patches near a bright lamp (SolveOptions).
    const std::vector<std::vector<int>> near = near_bright_emitters(scene, kLampReach);
    tolerances.source_patches.resize(near.size());
    for (std::size_t i = 0; i < near.size(); ++i) tolerances.source_patches[i] = near[i].empty() ? 0 : 1;
  }
  ErrorBoundOracle oracle(h, tree.get(), geometry, ctx.evaluator(), tolerances, source_weights(scene, ctx.channels()),
                          ctx.channels(), &cluster_radiosity);

  std::vector<Candidate> work;
  if (tree) {
    work.push_back({.p = tree->root(), .q = tree->root()});
  } else {
    // HSA: every pair of input patches is refined once and its links are gathered both ways.
    const int n = static_cast<int>(scene.patches.size());
    work.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(std::max(0, n - 1)) / 2);
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) work.push_back({.p = h.root(i), .q = h.root(j)});
  }

  const double bound = radiosity_bound(scene);
  LinkVector links;
  LinkVector standing;  // links a re-refinement leaves as they are
  std::size_t last_link_count = 0;
  std::vector<UnseenPair> unseen;  // pairs no sampled ray saw through, so far
  Operators ops;
  std::vector<PointValues> point_radiosity;  // the leaves' radiosity at their points (for display)
  std::uint64_t candidates = 0;
  int passes = 0;
  // Whether the solve's light stays in the scene (closed_scene.h): tested once, after the first
  // converged solve, by rays drawn by its power; then every leaf's sends are closed to 1.
  const bool may_close = options.close_closed_scenes && options.push == Push::kHsa;
  bool tested = false, closed_scene = false;
  std::uint64_t own_rays = 0;  // the test's rays where the solve has no visibility oracle to count them
  while (true) {
    RefineResult refined;
    {
      auto phase = ctx.phase("refine");
      refined = refine(
          h, tree.get(), oracle, std::move(work), [&](std::string_view line) { ctx.progress(line); },
          options.progress_interval_seconds);
    }
    ++passes;
    candidates += refined.candidates;
    unseen.insert(unseen.end(), refined.unseen.begin(), refined.unseen.end());
    // A separate pass after refinement: links stay where refinement put them, and the HSA push
    // carries them down to the new leaves.
    std::size_t balanced = 0;
    if (options.balance) {
      auto phase = ctx.phase("balance");
      balanced = h.balance();
      figures["balance_splits"] += static_cast<double>(balanced);
    }
    // The standing links first, then the new ones (the order the gather sums them in), moved: a
    // copy of millions of links is seconds of one thread.
    if (standing.empty()) {
      standing = std::move(refined.links);
    } else {
      standing.insert(standing.end(), std::make_move_iterator(refined.links.begin()),
                      std::make_move_iterator(refined.links.end()));
    }
    const bool changed = refined.splits > 0 || balanced > 0 || standing.size() != last_link_count;
    links = std::move(standing);
    standing = {};
    last_link_count = links.size();
    {
      auto phase = ctx.phase("links");
      ops = make_operators(options, h, tree.get(), geometry, ctx.evaluator(), links);
    }
    ctx.progress(
        fmt::format("hierarchical: pass {}: {} elements, {} links", passes, h.size(), directed_link_count(links)));
    // A re-refinement that changed nothing leaves the last solution consistent with its links.
    if (passes > 1 && !changed) break;
    PushPull push_pull(scene, h, tree.get(), ctx.channels(), options.basis);
    // The parts of elements split below aeps as sources, linear leaves, and with the HSA push the
    // leaves under cluster links send what their links' closure says (send_closure.h).
    const bool linear = options.basis == Basis::kLinear;
    const bool under_clusters = tree != nullptr && options.push == Push::kHsa && !linear;
    auto close_sends = [&] {
      auto phase = ctx.phase("closure");
      std::size_t unclosed = 0;
      push_pull.set_send_closure(
          send_closures(h, *ops.hsa, push_pull, t.aeps, linear, under_clusters, closed_scene, &unclosed));
      // The leaves of a closed scene whose sends the closure could not bring to 1 (send_closure.h).
      if (closed_scene) figures["closure_unclosed_leaves"] = static_cast<double>(unclosed);
    };
    if ((options.source_levels > 0 || linear || under_clusters || closed_scene) && ops.hsa) close_sends();
    NodeField field = push_pull.make_field();
    const std::vector<const LinkOperator*> all = ops.all();
    bool converged = false;
    {
      auto phase = ctx.phase("solve");
      converged = iterate(ctx, push_pull, all, field, bound);
    }
    if (may_close && !tested && converged && ops.hsa) {
      tested = true;
      LightLoss loss;
      {
        auto phase = ctx.phase("closure test");
        loss = test_light_loss(scene, h, field.radiosity, ctx.visibility(), detail::mix_seed(options.seed, 0x636c6f73));
      }
      closed_scene = loss.closed();
      if (loss.own_visibility) own_rays = loss.rays;
      figures["closure_test_rays"] = static_cast<double>(loss.rays);
      figures["closure_test_lost_rays"] = static_cast<double>(loss.lost);
      figures["closed_scene"] = closed_scene ? 1.0 : 0.0;
      if (closed_scene) {
        ctx.progress(
            fmt::format("hierarchical: {} of {} rays drawn by the power lost (at most {} allowed): the "
                        "scene keeps its light, every leaf's sends closed to 1",
                        loss.lost, loss.rays, loss.allowed_lost));
        close_sends();
        push_pull.pull(field);  // the moments the next gather reads, closed
        auto phase = ctx.phase("solve");
        converged = iterate(ctx, push_pull, all, field, bound);
      }
    }
    push_pull.store(field, h, &cluster_radiosity);
    if (options.push == Push::kHsa || options.basis == Basis::kLinear)
      point_radiosity = std::move(field.point_radiosity);
    if (!converged || passes >= kMaxRefinePasses) break;
    work.clear();
    standing.clear();
    if (t.bfeps > 0.0) {
      // BF refinement: the tolerance depends on B, so refine again with the new radiosity (HSA sec. 4.2).
      for (const Link& l : links) work.push_back({.p = l.p, .q = l.q});
      continue;
    }
    // feps: the links at elements the solve found far brighter than their a-priori weight are
    // decided again with their brightness (ErrorBoundOracle::observe()); the others stand.
    const std::vector<char> raised = oracle.observe();
    // Nothing raised: the links stand as they are (copying a million of them to find that took 4%
    // of a two-thread solve of the 3,726-polygon warehouse, serially).
    if (std::none_of(raised.begin(), raised.end(), [](char r) { return r != 0; })) break;
    auto is_raised = [&](NodeRef r) { return !is_cluster(r) && raised[static_cast<std::size_t>(r)] != 0; };
    for (const Link& l : links)
      if (is_raised(l.p) || is_raised(l.q)) work.push_back({.p = l.p, .q = l.q});
    const std::size_t relinked = work.size();
    // So are the pairs left unlinked because none of their few samples (counted by the a-priori
    // weights) saw through: a wall behind a lamp 1 mm from it is as bright as the lamp and sends
    // ~1% of its power to the room through the slit, which 16 point pairs a pair mostly miss
    // (notebooks_data/scenes/lamp_near_wall.obj cut along the lamp lost 0.6% of its power so).
    std::erase_if(unseen, [&](const UnseenPair& u) {
      if (!is_raised(u.p) && !is_raised(u.q)) return false;
      work.push_back({.p = u.p, .q = u.q});
      return true;
    });
    if (work.empty()) break;
    // The others stand, compacted in place (the next pass's links replace these before they are
    // read again).
    std::erase_if(links, [&](const Link& l) { return is_raised(l.p) || is_raised(l.q); });
    standing = std::move(links);
    ctx.progress(
        fmt::format("hierarchical: {} links and {} unseen pairs at elements brighter than their weight decided again",
                    relinked, work.size() - relinked));
  }

  // Figures of the mesh and the links.
  double min_area = INFINITY;
  int max_depth = 0;
  for (const NodeId leaf : h.all_leaves()) {
    min_area = std::min(min_area, h.node(leaf).area);
    max_depth = std::max(max_depth, h.node(leaf).depth);
  }
  if (ctx.channels() == 1)
    for (std::size_t i = 0; i < h.size(); ++i)
      copy_gray(h.node(static_cast<NodeId>(i)).radiosity), copy_gray(h.node(static_cast<NodeId>(i)).gathered);
  std::size_t partial = 0, with_cluster = 0;
  for (const Link& l : links) {
    partial += l.partial ? 1 : 0;
    with_cluster += (is_cluster(l.p) || is_cluster(l.q)) ? 1 : 0;
  }
  figures["min_element_area"] = std::isfinite(min_area) ? min_area : 0.0;
  figures["max_depth"] = max_depth;
  figures["refine_passes"] = passes;
  figures["link_pairs"] = static_cast<double>(links.size());
  figures["partial_links"] = static_cast<double>(partial);
  figures["cluster_link_pairs"] = static_cast<double>(with_cluster);
  Work& w = ctx.summary().work;
  w.candidate_pairs = candidates;
  for (const LinkOperator* op : ops.all()) {
    w.gather_terms += op->terms();
    w.link_bytes += op->bytes();
  }
  std::vector<std::pair<Vec3, Vec3>> segments;
  if (out != nullptr && options.record_links) {
    // One segment per link, between the centres of the nodes it joins (for figures of the links).
    segments.reserve(links.size());
    for (const Link& l : links) segments.emplace_back(geometry.shape(l.p).centre, geometry.shape(l.q).centre);
  }
  if (ctx.channels() == 1)
    for (PointValues& v : point_radiosity)
      for (Rgb& b : v) copy_gray(b);
  SolveSummary summary = ctx.finish(h, directed_link_count(links), out, point_radiosity);
  summary.work.segment_queries += own_rays;
  if (out != nullptr) out->link_segments = std::move(segments);
  if (kept != nullptr) *kept = {std::make_unique<ElementHierarchy>(std::move(h)), std::move(tree), std::move(links)};
  return summary;
}

}  // namespace hrad
