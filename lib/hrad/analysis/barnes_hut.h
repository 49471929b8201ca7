// A small Barnes-Hut N-body force calculation (Barnes & Hut 1986, "A hierarchical O(N log N)
// force-calculation algorithm", Nature 324), the lecture's analogy for hierarchical radiosity:
// far-away groups of bodies act as one (their centre of mass), as far-away groups of elements
// interact through one link. Used to count interactions per body against n and theta.
//
// Gravity with G = 1 and Plummer softening eps: a_i = sum_j m_j (x_j - x_i) / (|x_j - x_i|^2 + eps^2)^(3/2).
// Octree: a cube around all bodies split into octants until each leaf holds one body (or a depth
// limit of 40 is reached, for coincident bodies). Walk for body i from the root: a cell of side s
// whose centre of mass is at distance d from x_i, and which does not contain x_i, acts as one
// body of its total mass if s / d < theta (Barnes & Hut's opening criterion); otherwise its
// children are visited; the bodies of a leaf act one by one. Each accepted cell or body is one
// interaction. theta = 0 opens every cell, so it reproduces the direct sum with n - 1
// interactions per body; for fixed theta > 0 the count per body grows like log n.
#pragma once

#include <cstddef>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

struct Body {
  Vec3 position = Vec3::Zero();
  double mass = 1.0;
};

/// n bodies uniform in the unit cube with masses uniform in [0.5, 1.5], from std::mt19937(seed).
std::vector<Body> random_bodies(int n, unsigned seed);

struct BarnesHutOptions {
  double theta = 0.5;
  double softening = 1e-3;  ///< eps above (same for the direct sum)
};

struct BarnesHutResult {
  std::vector<Vec3> acceleration;
  std::vector<std::size_t> interactions;  ///< per body: accepted cells + leaf bodies
  std::size_t cells = 0;                  ///< octree nodes
  double mean_interactions() const;
};

BarnesHutResult barnes_hut(const std::vector<Body>& bodies, const BarnesHutOptions& options);

/// The n(n-1) pairwise sum, the reference.
std::vector<Vec3> direct_accelerations(const std::vector<Body>& bodies, double softening);

/// sqrt(sum_i |a_i - ref_i|^2 / sum_i |ref_i|^2).
double relative_rms_error(const std::vector<Vec3>& approx, const std::vector<Vec3>& reference);

struct BarnesHutSample {
  int n = 0;
  double theta = 0.0;
  double mean_interactions = 0.0;
  std::size_t max_interactions = 0;
  double naive_interactions = 0.0;   ///< n - 1 per body
  double relative_force_error = -1;  ///< against the direct sum; -1 when n > direct_limit
  double seconds = 0.0;              ///< tree build + walk
};

/// For every n and theta: bodies from random_bodies(n, seed), interaction counts and (for
/// n <= direct_limit) the force error against the direct sum.
std::vector<BarnesHutSample> barnes_hut_sweep(const std::vector<int>& ns, const std::vector<double>& thetas,
                                              unsigned seed = 1, int direct_limit = 20000);

}  // namespace hrad
