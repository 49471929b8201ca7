// Classical radiosity (Goral, Torrance, Greenberg & Battaile 1984; Cohen & Greenberg 1985): every
// patch meshed uniformly into elements of area <= max_area, the n x n form-factor matrix filled in
// parallel (each unordered pair evaluated once, both directions from that one evaluation), and
// (I - rho F) B = E solved per channel by LU (the reference), Jacobi or Gauss-Seidel. With linear
// elements (SolveOptions::basis) the pairs' field links (field_links.h) replace F and the corner
// values are iterated by Jacobi (field_solve.h).
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// Summary: links = n^2; figures "max_area". options.method is ignored.
SolveSummary solve_full_matrix(const Scene& scene, const SolveOptions& options, Solution* out);

}  // namespace hrad
