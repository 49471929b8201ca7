// Final gather: a solved radiosity field turned into light at points, by one more bounce,
//   H(x) = sum_j F(x -> j) V(x, j) B_j,     B(x) = E(x) + rho(x) H(x),
// over source elements j of a solution, with the exact point-to-polygon factor and visibility
// decided from the point itself. The element values B_j enter only through an integral, so the
// gathered field is far smoother and more accurate than B_j, and shadow boundaries are resolved at
// the points, not at the elements (Reichert 1992; Lischinski, Tampieri & Greenberg 1993, separate
// computational and display meshes; Smits, Arvo & Greenberg 1994, sec. 6; Cohen & Wallace 1993,
// sec. 9.3). H is the irradiance in exitance units (what a reflectance multiplies; W/m^2 when the
// scene's emission is, lm/m^2 = lux when it is luminous exitance).
//
// FinalGather is the small interface the image, the probes and the sweep ask; how the sources are
// chosen is the implementation's (leaf_gather.h: the solution's leaves, grouped by patch under a
// Barnes-Hut hierarchy).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hrad/core/progress.h"
#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

/// A point where light is gathered.
struct GatherPoint {
  Vec3 position = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  ///< unit vector: the side it receives light from
  /// The patch whose front the point lies on (its own patch never lights it, and its pair's
  /// visibility may be reused), or -1 for a point in space.
  int patch = -1;
};

/// Work a gather did, counted where it is done (summed over every call so far).
struct GatherWork {
  std::uint64_t points = 0;
  std::uint64_t patch_visits = 0;     ///< (point, source patch) pairs considered
  std::uint64_t node_visits = 0;      ///< source nodes whose point factor was evaluated
  std::uint64_t nodes_gathered = 0;   ///< nodes that contributed as one polygon (a leaf or a collapsed node)
  std::uint64_t leaves_covered = 0;   ///< leaves under the gathered nodes (what a leaf-by-leaf gather would evaluate)
  std::uint64_t classifications = 0;  ///< from-point visibility classifications (shaft tests)
  std::uint64_t rays = 0;             ///< segment queries for partly visible nodes
  std::uint64_t exact_regions = 0;    ///< exact visible regions computed (VisibilityMode::exact)
  std::uint64_t uncovered = 0;        ///< link gather: source nodes no link on the point's path covers
  /// One number for cost fits: point factors, classifications and rays.
  std::uint64_t total() const { return node_visits + classifications + rays + exact_regions; }
  GatherWork& operator+=(const GatherWork& o);
  /// The work done between two readings of work(): later - earlier.
  friend GatherWork operator-(GatherWork later, const GatherWork& earlier);
};

class FinalGather {
 public:
  virtual ~FinalGather() = default;

  /// The irradiance H at each point (see above), in parallel. Deterministic: a point's value
  /// depends only on the point, the solution and the options, not on the other points, their order
  /// or the thread count. `progress`, when given, advances by one per point done.
  virtual std::vector<Rgb> gather(std::span<const GatherPoint> points, ProgressReporter* progress = nullptr) const = 0;

  /// The work of every gather() so far.
  virtual GatherWork work() const = 0;

  /// The scene the points lie in.
  virtual const Scene& scene() const = 0;

  /// B = E + rho H for a point on `patch` (>= 0) that gathered `irradiance`.
  Rgb radiosity(int patch, const Rgb& irradiance) const;
};

}  // namespace hrad
