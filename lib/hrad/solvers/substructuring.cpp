#include "hrad/solvers/substructuring.h"

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

  // Shooting patches: the input polygons or their uniform subdivision; elements below them.
  std::vector<NodeId> patches;
  std::vector<std::vector<NodeId>> elements_of;
  {
    auto phase = ctx.phase("mesh");
    h.subdivide_uniform(patch_area);
    patches = h.all_leaves();
    for (NodeId p : patches) {
      h.subdivide_uniform(p, max_area);
      elements_of.push_back(h.leaves_below(p));
    }
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
  const std::size_t links = static_cast<std::size_t>(n) * static_cast<std::size_t>(big_n);
  if (!ctx.effects().bounces) {
    ctx.set_direct("nothing reflects: B = E");
    return ctx.finish(h, 0, out);
  }
  ctx.progress(fmt::format("substructure: {} elements receive from {} patches ({} form factors)", n, big_n, links));

  // F(i -> P) for element i and shooting patch P: row i of an n x N matrix; rows are independent.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> f(n, big_n);
  {
    auto phase = ctx.phase("form_factors");
    const FormFactorEvaluator& evaluator = ctx.evaluator();
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 4), [&](const tbb::blocked_range<int>& range) {
      for (int i = range.begin(); i < range.end(); ++i) {
        const ElementNode& a = h.node(elements[static_cast<std::size_t>(i)]);
        for (int p = 0; p < big_n; ++p) {
          const ElementNode& s = h.node(patches[static_cast<std::size_t>(p)]);
          f(i, p) = p == element_patch[static_cast<std::size_t>(i)]
                        ? 0.0
                        : evaluator.estimate(a.polygon(), a.patch, s.polygon(), s.patch).value;
        }
      }
    });
  }

  const int channels = ctx.channels();
  // Patch radiosity as an N x channels matrix, the area average of its elements.
  Eigen::MatrixXd patch_b(big_n, channels);
  auto average = [&](int p) {
    Rgb sum = Rgb::Zero();
    double area = 0.0;
    for (NodeId e : elements_of[static_cast<std::size_t>(p)]) {
      sum += h.node(e).area * h.node(e).radiosity;
      area += h.node(e).area;
    }
    for (int c = 0; c < channels; ++c) patch_b(p, c) = sum[c] / area;
  };
  for (int p = 0; p < big_n; ++p) average(p);
  {
    auto phase = ctx.phase("solve");
    // Gauss-Seidel over patches: a patch's elements gather from the newest patch radiosities,
    // then its own radiosity is updated before the next patch gathers.
    int row = 0;
    while (true) {
      double change = 0.0, largest = 0.0;
      row = 0;
      for (int p = 0; p < big_n; ++p) {
        for (NodeId id : elements_of[static_cast<std::size_t>(p)]) {
          ElementNode& e = h.node(id);
          for (int c = 0; c < channels; ++c) {
            const double value = e.emission[c] + e.reflectance[c] * f.row(row).dot(patch_b.col(c));
            change = std::max(change, std::abs(value - e.radiosity[c]));
            largest = std::max(largest, std::abs(value - e.emission[c]));
            e.radiosity[c] = value;
          }
          ++row;
        }
        average(p);
      }
      if (ctx.record_iteration(stopping_change(change, largest))) break;
    }
  }
  if (channels == 1)
    for (NodeId id : elements) copy_gray(h.node(id).radiosity);
  h.pull_radiosity();
  return ctx.finish(h, links, out);
}

}  // namespace hrad
