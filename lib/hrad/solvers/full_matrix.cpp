#include "hrad/solvers/full_matrix.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Dense>

#include "hrad/core/error.h"
#include "hrad/core/progress.h"
#include "hrad/solvers/dense_links.h"
#include "hrad/solvers/field_links.h"
#include "hrad/solvers/field_solve.h"
#include "hrad/solvers/iteration.h"
#include "hrad/solvers/push_pull.h"
#include "hrad/solvers/solver_context.h"
#include "hrad/solvers/work_estimate.h"

namespace hrad {
namespace {

// F(i, j) = F(element i -> element j). Row i evaluates the pairs (i, j > i), writing F(i, j) and
// F(j, i) from one kernel call: each entry is written by exactly one task, so the result does not
// depend on the schedule.
// `f` views zeroed storage.
void fill_matrix(SolverContext& ctx, const ElementHierarchy& h, const std::vector<NodeId>& leaves,
                 Eigen::Map<DenseLinks::RowMatrix> f) {
  const int n = static_cast<int>(leaves.size());
  const FormFactorEvaluator& evaluator = ctx.evaluator();
  const long long total_pairs = static_cast<long long>(n) * (n - 1) / 2;
  ProgressReporter progress("full: form factors", static_cast<std::uint64_t>(total_pairs), "pairs",
                            ctx.options().progress, ctx.options().progress_interval_seconds);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i < range.end(); ++i) {
      const ElementNode& a = h.node(leaves[static_cast<std::size_t>(i)]);
      for (int j = i + 1; j < n; ++j) {
        const ElementNode& b = h.node(leaves[static_cast<std::size_t>(j)]);
        const FormFactorEstimate e = evaluator.estimate(a.polygon(), a.patch, b.polygon(), b.patch);
        f(i, j) = e.value;
        f(j, i) = e.reverse;
      }
      progress.advance(static_cast<std::uint64_t>(n - 1 - i));
    }
  });
  progress.finish();
}

// Linear elements: both directions of every pair's field links from one evaluation of its points.
void fill_fields(SolverContext& ctx, const ElementHierarchy& h, FieldLinks& links) {
  const std::vector<NodeId>& leaves = links.receivers();
  const int n = static_cast<int>(leaves.size());
  const FormFactorEvaluator& evaluator = ctx.evaluator();
  const int rays = field_rays_per_point(ctx.options().visibility_samples);
  const NearFieldRules rules(evaluator, h, leaves, leaves);
  ctx.summary().figures["near_field_rules"] = static_cast<double>(rules.nodes());
  ProgressReporter progress("full: form factors", static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n - 1) / 2,
                            "pairs", ctx.options().progress, ctx.options().progress_interval_seconds);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i < range.end(); ++i) {
      const ElementNode& a = h.node(leaves[static_cast<std::size_t>(i)]);
      for (int j = i + 1; j < n; ++j)
        pair_fields(evaluator, a, h.node(leaves[static_cast<std::size_t>(j)]), rays,
                    &links.entry(static_cast<std::size_t>(i), static_cast<std::size_t>(j)),
                    &links.entry(static_cast<std::size_t>(j), static_cast<std::size_t>(i)));
      progress.advance(static_cast<std::uint64_t>(n - 1 - i));
    }
  });
  progress.finish();
  apply_near_field_rules(evaluator, h, rules, links);
}

}  // namespace

SolveSummary solve_full_matrix(const Scene& scene, const SolveOptions& options, Solution* out) {
  SolverContext ctx(scene, options, Method::kFull);
  ElementHierarchy h(scene);
  const double max_area = ctx.max_area();
  ctx.summary().figures["max_area"] = max_area;
  ctx.summary().used.max_area = max_area;
  // The dense F and, for LU, one system matrix at a time: refuse up front what cannot fit rather
  // than fail in the allocator halfway through. Elements before meshing: a patch of area A splits
  // into quarters until they are <= max_area (about: quads that are not parallelograms split unevenly).
  // Linear elements hold a field entry per ordered pair instead (field_links.h).
  const bool linear = options.basis == Basis::kLinear;
  const double estimate = uniform_elements(scene, max_area);
  const double needed = estimate * estimate * (linear ? sizeof(FieldEntry) : 2.0 * sizeof(double));
  const double physical = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  if (physical > 0.0 && needed > 0.8 * physical)
    throw Error(
        fmt::format("full matrix: about {:.0f} elements need {} ({:.1f} GB) and "
                    "this machine has {:.1f} GB: raise --max-area (now {:g}) or use --method hierarchical",
                    estimate,
                    linear ? fmt::format("{} bytes of field links per ordered pair", sizeof(FieldEntry))
                           : fmt::format("two dense {:.0f} x {:.0f} matrices", estimate, estimate),
                    needed / 1e9, physical / 1e9, max_area));
  {
    auto phase = ctx.phase("mesh");
    h.subdivide_uniform(max_area);
    if (options.balance) ctx.summary().figures["balance_splits"] = static_cast<double>(h.balance());
  }
  const std::vector<NodeId> leaves = h.all_leaves();
  const int n = static_cast<int>(leaves.size());
  const std::size_t factors = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  if (!ctx.effects().bounces) {
    ctx.set_direct("nothing reflects: B = E");
    return ctx.finish(h, 0, out);
  }
  ctx.progress(fmt::format("full: {} elements, {} form factors", n, factors));
  if (linear) {
    FieldLinks fields(leaves, leaves);
    {
      auto phase = ctx.phase("form_factors");
      fill_fields(ctx, h, fields);
    }
    return solve_linear_field(ctx, h, fields, factors, out);
  }

  DenseLinks links(leaves, leaves);
  {
    auto phase = ctx.phase("form_factors");
    ctx.set_sources(h, leaves);
    fill_matrix(ctx, h, leaves, links.matrix());
  }
  const Eigen::Map<const DenseLinks::RowMatrix> f = std::as_const(links).matrix();
  ctx.summary().work.gather_terms = links.terms();
  ctx.summary().work.link_bytes = links.bytes();

  const int channels = ctx.channels();
  Eigen::MatrixXd e(n, channels), rho(n, channels);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < channels; ++c) {
      e(i, c) = h.node(leaves[static_cast<std::size_t>(i)]).emission[c];
      rho(i, c) = h.node(leaves[static_cast<std::size_t>(i)]).reflectance[c];
    }
  Eigen::MatrixXd b = e;
  Eigen::MatrixXd gathered;  // H = F B, what B = E + rho H reflects
  {
    auto phase = ctx.phase("solve");
    switch (options.linear_solver) {
      case LinearSolver::kLu: {
        // (I - diag(rho_c) F) B_c = E_c: one factorization per channel (rho differs per channel).
        for (int c = 0; c < channels; ++c) {
          Eigen::MatrixXd m = -(rho.col(c).asDiagonal() * f);
          m.diagonal().array() += 1.0;
          b.col(c) = m.partialPivLu().solve(e.col(c));
        }
        if (!b.allFinite()) {
          ctx.set_failed("LU solve gave non-finite radiosity (singular system: is some reflectance 1?)");
        } else {
          ctx.set_direct(
              fmt::format("direct LU solve of {} x {} ({} channel{})", n, n, channels, channels == 1 ? "" : "s"));
        }
        break;
      }
      case LinearSolver::kJacobi: {
        const PushPull push_pull(scene, h, nullptr, channels);
        NodeField field = push_pull.make_field();
        const LinkOperator* ops[] = {&links};
        iterate(ctx, push_pull, ops, field, radiosity_bound(scene));
        gathered.resize(n, channels);
        for (int i = 0; i < n; ++i)
          for (int c = 0; c < channels; ++c) {
            const auto id = static_cast<std::size_t>(leaves[static_cast<std::size_t>(i)]);
            b(i, c) = field.radiosity[id][c];
            gathered(i, c) = field.leaf_irradiance[id][c];
          }
        break;
      }
      case LinearSolver::kGaussSeidel: {
        while (true) {
          LeafChange change;
          for (int i = 0; i < n; ++i) {
            double moved = 0.0, reflected = 0.0;
            for (int c = 0; c < channels; ++c) {
              const double value = e(i, c) + rho(i, c) * f.row(i).dot(b.col(c));
              moved = std::max(moved, std::abs(value - b(i, c)));
              reflected = std::max(reflected, std::abs(value - e(i, c)));
              b(i, c) = value;
            }
            change.add_leaf(h.node(leaves[static_cast<std::size_t>(i)]).area, moved, reflected);
          }
          if (ctx.record_iteration(stopping_change(change))) break;
        }
        break;
      }
    }
  }
  // The direct solves gather once more from their answer: H = F B.
  if (gathered.size() == 0) gathered = f * b;
  for (int i = 0; i < n; ++i) {
    ElementNode& node = h.node(leaves[static_cast<std::size_t>(i)]);
    for (int c = 0; c < channels; ++c) node.radiosity[c] = b(i, c), node.gathered[c] = gathered(i, c);
    if (channels == 1) copy_gray(node.radiosity), copy_gray(node.gathered);
  }
  h.pull_radiosity();
  return ctx.finish(h, factors, out);
}

}  // namespace hrad
