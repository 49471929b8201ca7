#include "hrad/solvers/substructuring.h"

#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Dense>

#include "hrad/core/progress.h"
#include "hrad/solvers/dense_links.h"
#include "hrad/solvers/field_links.h"
#include "hrad/solvers/field_solve.h"
#include "hrad/solvers/iteration.h"
#include "hrad/solvers/push_pull.h"
#include "hrad/solvers/solver_context.h"

namespace hrad {

SolveSummary solve_substructuring(const Scene& scene, const SolveOptions& options, Solution* out) {
  SolverContext ctx(scene, options, Method::kSubstructure);
  ElementHierarchy h(scene);
  const double max_area = ctx.max_area();
  auto& figures = ctx.summary().figures;
  figures["max_area"] = max_area;
  const double patch_area = options.patch_area > 0.0 ? options.patch_area : kAutoPatchAreaFraction * scene.total_area();
  figures["patch_area"] = patch_area;
  ctx.summary().used.max_area = max_area;
  ctx.summary().used.patch_area = patch_area;

  // Shooting patches: the input polygons or their uniform subdivision; elements below them.
  std::vector<NodeId> patches;
  std::vector<std::vector<NodeId>> elements_of;
  {
    auto phase = ctx.phase("mesh");
    h.subdivide_uniform(patch_area);
    patches = h.all_leaves();
    for (NodeId p : patches) h.subdivide_uniform(p, max_area);
    if (options.balance) figures["balance_splits"] = static_cast<double>(h.balance());
    for (NodeId p : patches) elements_of.push_back(h.leaves_below(p));
  }
  const int big_n = static_cast<int>(patches.size());
  std::vector<NodeId> elements;  // in patch order
  std::vector<int> element_patch;
  for (int p = 0; p < big_n; ++p)
    for (NodeId e : elements_of[static_cast<std::size_t>(p)]) {
      elements.push_back(e);
      element_patch.push_back(p);
    }
  const int n = static_cast<int>(elements.size());
  figures["shooting_patches"] = big_n;
  const std::size_t factors = static_cast<std::size_t>(n) * static_cast<std::size_t>(big_n);
  if (!ctx.effects().bounces) {
    ctx.set_direct("nothing reflects: B = E");
    return ctx.finish(h, 0, out);
  }
  ctx.progress(fmt::format("substructure: {} elements receive from {} patches ({} form factors)", n, big_n, factors));

  if (options.basis == Basis::kLinear) {
    // Linear elements: element i gathers a field from each patch P (field_links.h), reading P's
    // radiosity moments, which push-pull pulls up from P's elements.
    FieldLinks fields(elements, patches);
    {
      auto phase = ctx.phase("form_factors");
      const FormFactorEvaluator& evaluator = ctx.evaluator();
      const int rays = field_rays_per_point(options.visibility_samples);
      ProgressReporter progress("substructure: form factors", static_cast<std::uint64_t>(factors), "factors",
                                options.progress, options.progress_interval_seconds);
      tbb::parallel_for(tbb::blocked_range<int>(0, n, 4), [&](const tbb::blocked_range<int>& range) {
        FieldEntry unused;
        for (int i = range.begin(); i < range.end(); ++i) {
          const ElementNode& a = h.node(elements[static_cast<std::size_t>(i)]);
          for (int p = 0; p < big_n; ++p)
            if (p != element_patch[static_cast<std::size_t>(i)])
              pair_fields(evaluator, a, h.node(patches[static_cast<std::size_t>(p)]), rays,
                          &fields.entry(static_cast<std::size_t>(i), static_cast<std::size_t>(p)), &unused);
          progress.advance(static_cast<std::uint64_t>(big_n));
        }
      });
      progress.finish();
    }
    return solve_linear_field(ctx, h, fields, factors, out);
  }
  // F(i -> P) for element i and shooting patch P: row i of an n x N matrix; rows are independent.
  DenseLinks links(elements, patches);
  {
    auto phase = ctx.phase("form_factors");
    ctx.set_sources(h, patches);
    const FormFactorEvaluator& evaluator = ctx.evaluator();
    Eigen::Map<DenseLinks::RowMatrix> f = links.matrix();
    // n N kernel calls: minutes for a fine mesh, so its rows done with an estimate of the time left.
    ProgressReporter progress("substructure: form factors", static_cast<std::uint64_t>(factors), "factors",
                              options.progress, options.progress_interval_seconds);
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 4), [&](const tbb::blocked_range<int>& range) {
      for (int i = range.begin(); i < range.end(); ++i) {
        const ElementNode& a = h.node(elements[static_cast<std::size_t>(i)]);
        for (int p = 0; p < big_n; ++p) {
          const ElementNode& s = h.node(patches[static_cast<std::size_t>(p)]);
          f(i, p) = p == element_patch[static_cast<std::size_t>(i)]
                        ? 0.0
                        : evaluator.estimate(a.polygon(), a.patch, s.polygon(), s.patch, false).value;
        }
        progress.advance(static_cast<std::uint64_t>(big_n));
      }
    });
    progress.finish();
  }
  ctx.summary().work.gather_terms = links.terms();
  ctx.summary().work.link_bytes = links.bytes();

  const int channels = ctx.channels();
  {
    // Jacobi iterations: elements gather from the patches, whose radiosity push-pull pulls as the
    // area mean of their elements.
    auto phase = ctx.phase("solve");
    const PushPull push_pull(scene, h, nullptr, channels);
    NodeField field = push_pull.make_field();
    const LinkOperator* ops[] = {&links};
    iterate(ctx, push_pull, ops, field, radiosity_bound(scene));
    push_pull.store(field, h, nullptr);
  }
  if (channels == 1)
    for (std::size_t i = 0; i < h.size(); ++i) copy_gray(h.node(static_cast<NodeId>(i)).radiosity), copy_gray(h.node(static_cast<NodeId>(i)).gathered);
  return ctx.finish(h, factors, out);
}

}  // namespace hrad
