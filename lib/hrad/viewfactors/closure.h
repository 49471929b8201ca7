// Enforcing closure on a closed model's matrix without breaking reciprocity.
//
// The exchange areas E_uv = A_u F_uv are moved as little as possible, in the weighted least-squares
// sense min sum_{u,v} (E'_uv - E_uv)^2 / E_uv, subject to E' symmetric and sum_v E'_uv = A_u for
// every row: the equality-constrained least-squares problem (Lawson & Hanson 1974, "Solving Least
// Squares Problems", ch. 20), applied to view factors by van Leersum 1989 ("A method for determining
// a consistent set of radiation view factors from a set of generated values", Int. J. Numer.
// Methods Eng. 28, 2045-2062). Its stationarity conditions give E'_uv = E_uv (1 + l_u + l_v) with
// one multiplier per row, and the rows' constraints the symmetric positive semi-definite system
//   (D + E) l = A - E 1,   D = diag(E 1),
// solved here by sparse LDL^T (Eigen). The weight 1 / E_uv keeps zeros at zero (a hidden pair stays
// hidden) and moves each factor in proportion to itself. A row that sees nothing cannot be closed
// and is left as it is; a factor the adjustment would make negative is set to 0 (both counted).
#pragma once

#include "hrad/viewfactors/view_factor_matrix.h"

namespace hrad {

struct ClosureReport {
  double max_row_error_before = 0.0;  ///< max_u |1 - sum_v F_uv| before
  double max_row_error_after = 0.0;
  double max_factor_change = 0.0;  ///< max |F'_uv - F_uv|
  double relative_change = 0.0;    ///< sum |E' - E| / sum E
  int rows_not_closable = 0;       ///< rows with no exchange at all
  int clamped = 0;                 ///< entries that would have become negative
};

/// Adjusts `m` in place (exchange stays symmetric and bit-identical in both rows).
ClosureReport enforce_closure(ViewFactorMatrix& m);

}  // namespace hrad
