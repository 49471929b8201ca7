#include "hrad/viewfactors/closure.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <vector>

#include "hrad/core/error.h"

namespace hrad {

ClosureReport enforce_closure(ViewFactorMatrix& m) {
  ClosureReport report;
  const int n = m.n;
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(n);
  for (int u = 0; u < n; ++u) {
    for (std::int64_t k = m.row_begin[static_cast<std::size_t>(u)]; k < m.row_begin[static_cast<std::size_t>(u) + 1];
         ++k)
      sums[u] += m.exchange[static_cast<std::size_t>(k)];
    report.max_row_error_before =
        std::max(report.max_row_error_before, std::abs(1.0 - sums[u] / m.area[static_cast<std::size_t>(u)]));
  }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(m.nonzeros() + static_cast<std::size_t>(n));
  Eigen::VectorXd rhs(n);
  for (int u = 0; u < n; ++u) {
    if (!(sums[u] > 0.0)) {
      ++report.rows_not_closable;
      triplets.emplace_back(u, u, 1.0);
      rhs[u] = 0.0;
      continue;
    }
    triplets.emplace_back(u, u, sums[u]);
    for (std::int64_t k = m.row_begin[static_cast<std::size_t>(u)]; k < m.row_begin[static_cast<std::size_t>(u) + 1];
         ++k)
      triplets.emplace_back(u, m.column[static_cast<std::size_t>(k)], m.exchange[static_cast<std::size_t>(k)]);
    rhs[u] = m.area[static_cast<std::size_t>(u)] - sums[u];
  }
  Eigen::SparseMatrix<double> system(n, n);
  system.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
  if (solver.info() != Eigen::Success) throw Error("--enforce-closure: the adjustment's system could not be factored");
  const Eigen::VectorXd l = solver.solve(rhs);
  double moved = 0.0, total = 0.0;
  for (int u = 0; u < n; ++u)
    for (std::int64_t k = m.row_begin[static_cast<std::size_t>(u)]; k < m.row_begin[static_cast<std::size_t>(u) + 1];
         ++k) {
      const int v = m.column[static_cast<std::size_t>(k)];
      double& e = m.exchange[static_cast<std::size_t>(k)];
      // l_u + l_v in a fixed order so both rows get the same bits.
      const double scale = 1.0 + (u < v ? l[u] + l[v] : l[v] + l[u]);
      double adjusted = e * scale;
      if (adjusted < 0.0) {
        ++report.clamped;
        adjusted = 0.0;
      }
      moved += std::abs(adjusted - e);
      total += e;
      report.max_factor_change =
          std::max(report.max_factor_change, std::abs(adjusted - e) / m.area[static_cast<std::size_t>(u)]);
      e = adjusted;
    }
  report.relative_change = total > 0.0 ? moved / total : 0.0;
  for (int u = 0; u < n; ++u)
    report.max_row_error_after = std::max(report.max_row_error_after, std::abs(1.0 - m.row_sum(u)));
  return report;
}

}  // namespace hrad
