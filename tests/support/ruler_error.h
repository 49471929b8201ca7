// A solution's per-polygon error against the Monte Carlo ruler's face means (reference.h,
// reference_faces), scored as `hrad compare` scores it (analysis/face_error.h): the area-weighted
// relative L2 of each input face's reflected radiosity B - E, with the ruler's own noise in the
// same norm. Emitters count by what they reflect.
#pragma once

#include <utility>
#include <vector>

#include "hrad/analysis/face_error.h"
#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/reference/reference.h"
#include "hrad/solvers/solve.h"

namespace hrad::test {

/// `ruler` holds one estimate per input face of `scene`, in order.
FaceErrors errors_against_ruler(const Scene& scene, const Solution& solution, const std::vector<FaceEstimate>& ruler);

/// Solves `scene` with `options` (hierarchical on two threads, the rest as given) and scores it
/// against `ruler` as errors_against_ruler(); throws hrad::Error when the solve does not converge.
FaceErrors solve_against_ruler(const Scene& scene, const std::vector<FaceEstimate>& ruler, SolveOptions options);

/// The ruler's mean radiosity (channel 0) over point estimates at `points` (`samples` paths each),
/// with its standard error; every point must lie on patch `patch` (hrad::Error otherwise).
std::pair<double, double> ruler_mean(const Scene& scene, const std::vector<ProbePoint>& points, int patch, int samples);

}  // namespace hrad::test
