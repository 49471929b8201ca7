#include "hrad/solvers/hierarchical.h"

#include "hrad/geometry/polygon.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hrad/solvers/hierarchical_leaf_factors.h"
#include "hrad/solvers/hierarchical_refine.h"
#include "hrad/solvers/solver_context.h"

namespace hrad {
namespace {


/// Jacobi iterations of gather and push-pull (HSA 1991 sec. 4, "SolveSystem"). Returns false when
/// the iteration stopped without converging.
///
/// Every link is resolved to leaves (hierarchical_leaf_factors.h), whose factors sum to at most 1
/// up to quadrature and visibility sampling, so rho * K contracts for rho < 1. Sampled visibility
/// or quadrature could still push a row sum above 1 as rho -> 1; that is reported as a failure
/// (twice the physical bound E_max / (1 - rho_max) is never reached by a contracting iteration
/// started at B = E), before any overflow.
bool solve_links(SolverContext& ctx, ElementHierarchy& h, const detail::LeafLinks& links, double bound) {
  auto phase = ctx.phase("solve");
  h.pull_radiosity();  // interior nodes hold their leaves' area average (for the output)
  while (true) {
    detail::gather_leaf_links(h, links);
    const double change = push_pull(h, ctx.channels());
    if (ctx.record_iteration(change)) break;
    double largest = 0.0;
    for (int p = 0; p < h.patch_count(); ++p) largest = std::max(largest, h.node(h.root(p)).radiosity.maxCoeff());
    if (largest > 2.0 * bound) {
      ctx.set_failed("diverging: the mean radiosity of a patch (" + std::to_string(largest) +
                     ") passed twice the bound E_max / (1 - rho_max) = " + std::to_string(bound) +
                     " after " + std::to_string(ctx.summary().iterations) +
                     " iterations; the links' factors sum above 1 on some elements (try a smaller --feps or more --visibility-samples)");
      break;
    }
  }
  return ctx.summary().termination == Termination::kConverged;
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

std::optional<SolveSummary> start_hierarchical(SolverContext& ctx, const ElementHierarchy& h,
                                              const HierarchicalTolerances& t, Solution* out) {
  auto& figures = ctx.summary().figures;
  figures["feps"] = t.feps;
  figures["bfeps"] = t.bfeps;
  figures["aeps"] = t.aeps;
  if (ctx.effects().bounces) return std::nullopt;
  ctx.set_direct("nothing reflects: B = E, no links needed");
  figures["refine_passes"] = 0;
  figures["link_pairs"] = 0;
  return ctx.finish(h, 0, out);
}

double radiosity_bound(const Scene& scene) {
  double e = 0.0, rho = 0.0;
  for (const Material& m : scene.materials) {
    e = std::max(e, m.emission.maxCoeff());
    rho = std::max(rho, m.reflectance.maxCoeff());
  }
  return e / (1.0 - rho);
}

void end_hierarchical(SolverContext& ctx, ElementHierarchy& h) {
  double min_area = INFINITY;
  int max_depth = 0;
  for (const NodeId leaf : h.all_leaves()) {
    const ElementNode& node = h.node(leaf);
    min_area = std::min(min_area, node.area);
    max_depth = std::max(max_depth, node.depth);
  }
  if (ctx.channels() == 1)
    for (std::size_t i = 0; i < h.size(); ++i) copy_gray(h.node(static_cast<NodeId>(i)).radiosity);
  ctx.summary().figures["min_element_area"] = std::isfinite(min_area) ? min_area : 0.0;
  ctx.summary().figures["max_depth"] = max_depth;
}

SolveSummary solve_hierarchical(const Scene& scene, const SolveOptions& requested, Solution* out) {
  // Always the analytic kernel: HSA's links join elements of very different sizes at coarse levels
  // (a whole floor to a small light), where a fixed receiver quadrature is inaccurate and not
  // reciprocal (the Cornell box's floor came out 8% dark with it); the closed form is exact at any
  // size and distance, and reciprocal, which the two-way links rely on.
  SolveOptions options = requested;
  options.kernel = FormFactorKernel::kAnalytic;
  SolverContext ctx(scene, options, Method::kHierarchical);
  ElementHierarchy h(scene);
  const HierarchicalTolerances t = hierarchical_tolerances(scene, options);
  ctx.summary().effects.reasons.push_back("kernel: analytic (hierarchical links need exact, reciprocal factors at every size)");
  if (auto done = start_hierarchical(ctx, h, t, out)) return *done;
  auto& figures = ctx.summary().figures;

  const detail::RefineTolerances tol{t.feps, t.bfeps, t.aeps, detail::source_weights(scene, ctx.channels())};
  const int channels = ctx.channels();
  // Initial candidates: every pair of input patches (HSA: "for all patches p, q"); each pair is
  // refined once and its links are gathered both ways.
  std::vector<detail::RefineCandidate> work;
  const int n = static_cast<int>(scene.patches.size());
  work.reserve(static_cast<std::size_t>(n) * static_cast<std::size_t>(n - 1) / 2);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) work.push_back(detail::candidate(h.root(i), h.root(j)));

  std::vector<detail::LinkPair> pairs;
  detail::LeafLinks links;
  const double bound = radiosity_bound(scene);
  int passes = 0;
  while (true) {
    detail::RefineResult refined;
    {
      auto phase = ctx.phase("refine");
      refined = detail::refine_pairs(h, ctx.evaluator(), std::move(work), tol, channels);
    }
    ++passes;
    const bool changed = refined.splits > 0;
    pairs = std::move(refined.links);
    {
      auto phase = ctx.phase("leaf_factors");
      links = detail::leaf_links(h, pairs);
    }
    ctx.progress("hierarchical: pass " + std::to_string(passes) + ": " + std::to_string(h.size()) + " nodes, " +
                 std::to_string(detail::directed_link_count(pairs)) + " links, " + std::to_string(links.size()) +
                 " leaf factors");
    // A re-refinement that changed nothing leaves the last solution consistent with its links.
    if (passes > 1 && !changed) break;
    if (!solve_links(ctx, h, links, bound)) break;
    // BF refinement: the tolerance depends on B, so refine again with the new radiosity (HSA sec. 4.2).
    if (t.bfeps <= 0.0 || passes >= kMaxRefinePasses) break;
    work = pairs;
  }

  end_hierarchical(ctx, h);
  figures["refine_passes"] = passes;
  figures["link_pairs"] = static_cast<double>(pairs.size());
  figures["leaf_links"] = static_cast<double>(links.size());
  SolveSummary summary = ctx.finish(h, detail::directed_link_count(pairs), out);
  if (out != nullptr && options.record_links) {
    // One segment per link pair, between the elements' centroids (for figures of the links).
    out->link_segments.clear();
    out->link_segments.reserve(pairs.size());
    for (const detail::LinkPair& pair : pairs)
      out->link_segments.emplace_back(polygon_centroid(h.node(pair.p).polygon()), polygon_centroid(h.node(pair.q).polygon()));
  }
  return summary;
}

}  // namespace hrad
