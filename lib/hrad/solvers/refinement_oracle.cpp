#include "hrad/solvers/refinement_oracle.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "hrad/formfactor/simpson_rule.h"
#include "hrad/geometry/polygon.h"
#include "hrad/solvers/linear_basis.h"
#include "hrad/solvers/solve.h"
#include "hrad/visibility/sampling.h"

namespace hrad {
namespace {

// The links' unoccluded factors need closure far below any discretisation error, not the full
// matrix's 1e-9 (hard_test's closed rooms at rho = 0.999 tolerate 1e-6): polygon_to_polygon()'s
// far-field quadrature is then ~20% cheaper on the Cornell box, with the same answers. Pairs whose
// elements are both within kGaussSeparation of their gap take Gauss points on both sides instead
// (~1e-8 there, at a tenth of the closed form's cost for such pairs).
constexpr double kLinkTolerance = 1e-7;
constexpr double kGaussSeparation = 0.25;
// Pairs whose points' quadratures put both factors below this keep the quadratures' exchange; and
// the closed form is asked for 1e-9 absolute too: a pair that barely sees itself (one polygon
// grazing the other's plane) would refine its slivers for a fraction of a second to get a factor of
// 1e-12 to 1e-7 relative, which no sum ever notices.
constexpr double kNegligibleFactor = 1e-6;
constexpr double kLinkAbsoluteTolerance = 1e-9;
// The fewest rays each facing patch of a cluster link's end casts for what it sees of the other end
// and sends to it (ErrorBoundOracle::end_rays_per_patch()), and the fewest of an error test.
constexpr int kFacingRays = 4;
// The share of --visibility-samples that the error test of a pair with a cluster end draws (the
// link draws its own). Against the full count: rays -29% and CPU time -25% on the generated
// 4,400-polygon pillar hall, -18% on the 1,040-polygon one, -16% on the 4k city, with the same
// power balance (hrad solve S.obj --threads 1; hard tests unchanged). An eighth against a quarter:
// time -6% on the 4.4k hall, -9% on the 1k one, -5% on the 762-polygon warehouse, with the same
// error per polygon against a 512-sample solve (hall 0.423 / 0.425%, warehouse 0.506 / 0.507%); a
// sixteenth (the kFacingRays floor) gains nothing more.
constexpr int kClusterTestFraction = 8;
// Rays from each of a partly visible pair's points for its shape and error test, at every
// --visibility-samples: the mesh follows the tolerances, and more samples only lower the noise of
// what the links carry. A point's doubt (its visible fraction's sampling error, added to the
// link's error) is what keeps a partly visible link's factor small where its nine points do not
// resolve the shadow; with more rays a point doubts less and such links come out coarser: one ray
// a point per 64 samples left the generated 1k city (hrad scene generate --kind city) with 1198
// elements at 128 samples against 1387 at 64, and its error per polygon against an unclustered
// 1024-sample solve went up from 0.52% to 0.72-0.90% over sample streams; with one ray a point,
// 0.40% at 128 and 0.25% at 256.
constexpr int kPointRays = 1;
// The sample stream of an element link's visible fraction, independent of the test's rays.
constexpr std::uint64_t kLinkedFractionStream = 11;
// With linear elements, the points' visibility that weighs what each side sends through a partly
// visible link is drawn apart from the one that weighs what it receives (streams 5 and 6; the test's
// are 1-4). A leaf keeps each point's value, and a point whose one ray reached the other side both
// gathered more through the link and, from the same ray, sent more back: the round trip weighed
// E[v^2] = v where the truth is v^2, and the generated warehouse (hrad scene generate --kind shelves)
// gained 1.5e-3 to 1.9e-3 of its emitted power. The excess is a round trip's, second order in the
// link's point factors, so only pairs that are not slight (whose largest point factor fails the
// weighted test) draw apart: the warehouse 9.3e-4 for 6% more rays, where drawing apart on every
// partly visible pair gave 8.5e-4 for 24% more, and linear solves of the peers' rooms took 1.16-1.29x
// the constant ones' CPU time (1.02-1.08x with one draw, 1.08-1.27x drawing apart where not slight).
// Constant leaves send their mean, which no point's ray moves.
constexpr std::uint64_t kSendShapeStream = 5;
// The sampling error of an element link's power, as a share of the scene's, that its visible
// fraction's point pairs aim for, and the most pairs it takes for it (times --visibility-samples).
// On the generated 1k office: the balance's spread over sample streams 8e-4 -> 3.5e-4, for 1% more
// rays.
constexpr double kPowerNoise = 2.5e-5;
constexpr int kMostLinkSamples = 16;
// With OracleTolerances::power_noise = sigma: the balance errs by about sum_L share_L^2 / (4 n_L)
// in variance over the element links L (each fraction from n_L pairs errs by at most 1 / (2
// sqrt(n_L)) of its unoccluded share), which for a given total of pairs is least with n_L = share_L
// / (4 sigma^2) (Lagrange); the variance is then sigma^2 sum_L share_L, and the shares of a closed
// scene's partly visible links sum to about 1 (0.6-1.2 in the generated warehouse and the cluttered
// rooms of hard_test). The cluster links' sends err by about kClusterSendNoise at the defaults in
// those rooms; each end casts (kClusterSendNoise / sigma)^2 times the rays (never fewer; at most
// 25 times: SolveOptions accepts sigma >= kLeastPowerNoise).
constexpr double kClusterSendNoise = 5e-4;
// The sampling error of what each end of an element link gathers through it, in units of the
// tolerance, that the linked fraction's point pairs aim for, and the fewest pairs (per 64 of
// --visibility-samples; the kernel-weighted fraction is a ratio, biased by O(1 / pairs): with 4,
// RenderPark's cube came out 0.1% dark). Against 64 pairs for every link: rays -25% on SPLASH-2's
// room at the defaults, -45% at aeps total/2000, -47% on RenderPark's cube at total/4000, errors
// against a converged reference 1.87 -> 1.85%, 0.67 -> 0.72%, 0.25 -> 0.09%.
constexpr double kGatherNoise = 0.1;
constexpr double kLeastLinkSamples = 16.0;
// Never fewer pairs than this, whatever --visibility-samples: from one or two, the ratio is the
// pairs' unweighted visibility, and near pairs whose kernel peaks where they see each other (a
// lamp's trough, its top and sides meeting at shared edges) came out dark: RenderPark's office2 at
// --basis linear --visibility-samples 4 lost 2% of its power, 0.1% with 4 (tests/hard/
// lamp_housing_test.cpp).
constexpr double kFewestLinkSamples = 4.0;
// A slight pair neither of whose sides can split, whose largest point factor weighs at most this
// share of the tolerance, casts no rays from its points: each point takes the link's visible
// fraction. Where the shadow falls across it then errs by at most that factor. The share is small
// because these errors do not average out: a point's visibility weighs both what it gathers through
// the link and what it sends back, and the uniform fraction drops that round trip's correlation
// (mean v^2 >= (mean v)^2) on every slight link of a fine mesh at once. SPLASH-2's room at --basis
// linear --source-levels auto --aeps total/4000, from the Monte Carlo ruler: 0.738% at 0 and at
// 0.03, 0.743% at 0.05, 0.778% at 0.1 (mean bias -0.61% -> -0.65%). RenderPark's office2 at --basis
// linear --aeps total/50 --feps 0.04 --visibility-samples 4: rays -19% at 0.03 (-31% at 0.1), the
// same error.
constexpr double kUniformVisibilityShare = 0.03;

// One side of an element pair: the receiver's points, their unoccluded point factors to the
// source, and their visible fractions of it.
struct Side {
  SimpsonPoints points;
  std::array<double, 9> factor{};
  std::array<double, 9> visible{};  ///< visible fraction of the source from the point
  std::array<double, 9> doubt{};    ///< sampling error of `visible` (0 when classified exactly)
  double unoccluded = 0.0;          ///< sum w f: the side's estimate of the exchange A_p F(p -> q)
  double seen = 0.0;                ///< sum w f v
  /// A lower bound of how far the unoccluded factor strays at the points from any linear field:
  /// a linear field's value at an edge midpoint is its ends' mean (at the centre, the corners'), so
  /// some point's residual is at least half of |F(m) - (F(a) + F(b)) / 2|.
  double linear_residual_bound() const {
    const int corners = points.count == 9 ? 4 : 3;
    double b = 0.0, corner_mean = 0.0;
    for (int i = 0; i < corners; ++i) {
      b = std::max(b, std::abs(factor[corners + i] - 0.5 * (factor[i] + factor[(i + 1) % corners])));
      corner_mean += factor[i] / corners;
    }
    b = std::max(b, std::abs(factor[2 * corners] - corner_mean));
    return 0.5 * b;
  }
  /// The largest unoccluded point factor.
  double largest() const { return *std::max_element(factor.begin(), factor.begin() + points.count); }
  /// The points' spread of the unoccluded factor: some point strays from any constant by half of it.
  double spread() const {
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < points.count; ++i) lo = std::min(lo, factor[i]), hi = std::max(hi, factor[i]);
    return hi - lo;
  }
};

void point_factors(const FormFactorEvaluator& ev, const ElementNode& r, const Vec3& n, const ElementNode& s,
                   bool limits, Side* side) {
  side->points = simpson_points(r.polygon());
  side->unoccluded = 0.0;
  const int centre = side->points.count - 1;
  for (int i = 0; i < side->points.count; ++i) {
    // Points on the element's boundary may lie in the source's plane (a shared edge, a contact):
    // with `limits` their factor is the limit from inside the element, otherwise 0.
    const Vec3& x = side->points.x[i];
    side->factor[i] = i == centre || !limits ? ev.point_factor(x, n, s.polygon())
                                             : ev.point_factor(x, n, Vec3(side->points.x[centre] - x), s.polygon());
    side->visible[i] = 1.0;
    side->doubt[i] = 0.0;
    side->unoccluded += side->points.weight[i] * side->factor[i];
  }
  side->seen = side->unoccluded;
}

// Where s floats close in front of r (every vertex strictly in front of r's plane, within a
// quarter of r's diameter), r's point factors towards s step along s's outline, and the points a
// field is tested and fitted at (corners, edge midpoints, centre) may lie on it: a floor halved
// from a room's corners puts them on the edges of a table modelled on the same grid, where the
// field looks smooth. The largest deviation of the unoccluded factor from the biquadratic through
// the points, at the four points u, v in {1/3, 2/3} of r's bilinear map (never on a halving
// line); 0 elsewhere and on triangles.
double off_grid_deviation(const FormFactorEvaluator& ev, const ElementNode& r, const Vec3& n, const ElementNode& s,
                          const Side& side) {
  if (side.points.count != 9) return 0.0;
  const std::span<const Vec3> pr = r.polygon(), ps = s.polygon();
  double diameter = 0.0;
  for (const Vec3& a : pr)
    for (const Vec3& b : pr) diameter = std::max(diameter, (a - b).norm());
  double lo = INFINITY, hi = -INFINITY;
  for (const Vec3& v : ps) {
    const double h = (v - pr[0]).dot(n);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  if (!(lo > 0.0) || hi > 0.25 * diameter) return 0.0;
  // The biquadratic through the points (kSimpsonQuadUv: (u, v) in {0, 1/2, 1}), by Lagrange's
  // basis on each axis.
  const auto lagrange = [](int k, double t) {
    return k == 0 ? 2.0 * (t - 0.5) * (t - 1.0) : k == 1 ? -4.0 * t * (t - 1.0) : 2.0 * t * (t - 0.5);
  };
  double deviation = 0.0;
  for (const double u : {1.0 / 3.0, 2.0 / 3.0})
    for (const double v : {1.0 / 3.0, 2.0 / 3.0}) {
      const Vec3 x = bilinear_point(pr, u, v);
      double fit = 0.0;
      for (int k = 0; k < 9; ++k)
        fit += lagrange(static_cast<int>(2 * kSimpsonQuadUv[k][0]), u) *
               lagrange(static_cast<int>(2 * kSimpsonQuadUv[k][1]), v) * side.factor[static_cast<std::size_t>(k)];
      deviation = std::max(deviation, std::abs(ev.point_factor(x, n, ps) - fit));
    }
  return deviation;
}

// Visible fractions of the source from each point of a partly visible pair's side, by rays to
// stratified points of the source tested against the pair's occluders only (a segment between
// points of the pair lies in its shaft). Rays, not each point's own shaft: against a short occluder
// list a handful of rays costs a fraction of a shaft's hull and facet tests. A point on the
// element's boundary casts its rays from kRayStart of the way towards the centre: on an edge
// shared with a neighbouring patch the rounded point may lie a hair behind the neighbour's plane,
// and the neighbour would then block every ray leaving it.
constexpr double kRayStart = 1.0 / 16.0;

void point_visibility(const FormFactorEvaluator& ev, const ElementNode& r, const Vec3& n, const ElementNode& s,
                      const std::vector<int>* occluders, int rays, std::uint64_t seed, Side* side) {
  side->seen = 0.0;
  const int centre = side->points.count - 1;
  for (int i = 0; i < side->points.count; ++i) {
    if (!(side->factor[i] > 0.0)) {
      side->visible[i] = 0.0;
      continue;
    }
    const Vec3& c = side->points.x[centre];
    const Vec3 start = i == centre ? c : Vec3(side->points.x[i] + kRayStart * (c - side->points.x[i]));
    const KernelVisibility k = ev.visibility_from_point(start, n, r.patch, s.polygon(), s.patch, occluders, rays,
                                                        detail::mix_seed(seed, static_cast<std::uint64_t>(i)));
    side->visible[i] = k.weight > 0.0 ? k.visible / k.weight : 0.5;
    side->doubt[i] = detail::fraction_error(k.visible_rays, k.rays);
    side->seen += side->points.weight[i] * side->factor[i] * side->visible[i];
  }
}

// What a link's field over a receiver is measured against (OracleTolerances::fields, linear_leaves).
enum class Fit : std::uint8_t {
  kMean,          ///< the link's mean factor
  kCorners,       ///< the linear field through the receiver's corners, moved to the link's mean
  kLeastSquares,  ///< the least-squares linear field of the points (the linear basis's projection), moved to the mean
};

// The largest error of a link's factor if it were the `fit` field over the side, moved to the link's
// mean `mean` (per unit radiosity of the source): how far the visible point factors stray from it,
// plus each point's sampling doubt. With kCorners, a conservative measure of the error of the
// quadratic field the link carries (shape_of()), which passes through the points. With
// kLeastSquares, the part of the link's field that a linear element's projection (linear_basis.h
// linear_projection(), the element's own Simpson inner product) does not keep: what a linear leaf
// loses of the link, which no choice of corner values recovers.
double field_error(const Side& side, double mean, bool with_doubt, Fit fit) {
  const int corners = side.points.count == 9 ? 4 : 3;
  std::array<double, 9> field{};
  if (fit == Fit::kLeastSquares) {
    const LinearProjection projection = linear_projection(side.points);
    std::array<double, 4> corner{};
    for (int a = 0; a < corners; ++a)
      for (int k = 0; k < side.points.count; ++k)
        corner[static_cast<std::size_t>(a)] +=
            projection.weight[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] *
            side.factor[static_cast<std::size_t>(k)] * side.visible[static_cast<std::size_t>(k)];
    // The projection keeps the points' weighted mean; the link's field has the link's mean.
    double area = 0.0, g_mean = 0.0;
    for (int k = 0; k < side.points.count; ++k) {
      area += side.points.weight[k];
      g_mean += side.points.weight[k] * side.factor[k] * side.visible[k];
    }
    const double shift = area > 0.0 ? mean - g_mean / area : 0.0;
    for (int k = 0; k < side.points.count; ++k) {
      double v = shift;
      for (int a = 0; a < corners; ++a) v += corner[static_cast<std::size_t>(a)] * linear_function(corners, a, k);
      field[static_cast<std::size_t>(k)] = v;
    }
  } else {
    const std::array<double, 4> w = corner_mean_weights(side.points);
    std::array<double, 4> g{};
    double g_mean = 0.0;
    for (int i = 0; i < corners; ++i) {
      g[i] = side.factor[i] * side.visible[i];
      g_mean += w[i] * g[i];
    }
    for (int i = 0; i < corners; ++i) g[i] = fit == Fit::kCorners ? g[i] + mean - g_mean : mean;
    double centre = 0.0;
    for (int i = 0; i < corners; ++i) centre += g[i] / corners;
    for (int i = 0; i < side.points.count; ++i)
      field[static_cast<std::size_t>(i)] = i < corners       ? g[i]
                                           : i < 2 * corners ? 0.5 * (g[i - corners] + g[(i - corners + 1) % corners])
                                                             : centre;
  }
  double e = 0.0;
  for (int i = 0; i < side.points.count; ++i)
    e = std::max(e, std::abs(side.factor[i] * side.visible[i] - field[static_cast<std::size_t>(i)]) +
                        (with_doubt ? side.factor[i] * side.doubt[i] : 0.0));
  return e;
}

// How far the visibility at the side's points strays from the link's visible fraction, beyond twice
// each point's sampling doubt, weighted by the point's factor relative to the side's mean factor:
// the relative error of giving the whole side the link's fraction.
double shadow_variation(const Side& side, double fraction) {
  double mean = 0.0, area = 0.0;
  for (int i = 0; i < side.points.count; ++i) {
    mean += side.points.weight[i] * side.factor[i];
    area += side.points.weight[i];
  }
  mean /= area;
  if (!(mean > 0.0)) return 0.0;
  double v = 0.0;
  for (int i = 0; i < side.points.count; ++i)
    v = std::max(v, side.factor[i] / mean * std::max(0.0, std::abs(side.visible[i] - fraction) - 2.0 * side.doubt[i]));
  return v;
}

// The visible fraction about each of a side's points, pooled from its own rays and the link's point
// pairs (FormFactorEvaluator::pair_visibility()): a pair counts for the point nearest its end on the
// side, and a point's cell gives the ratio of its pairs' kernel-weighted outcomes, which joins the
// point's rays as that many more. The points cast one ray each (kPointRays), and a partly visible
// link's shape (shape_of()) scales the points whose ray passed: from one ray, which they are is
// noise that the scaled shape concentrates, where a link's 16 or more pairs already say where its
// receiver sees the source.
void pool_pair_visibility(const std::vector<VisibilityPair>& pairs, bool receiver_side, int point_rays, Side* side) {
  std::array<double, 9> weight{}, visible{};
  std::array<int, 9> count{};
  for (const VisibilityPair& pair : pairs) {
    const Vec3& z = receiver_side ? pair.x : pair.y;
    int nearest = 0;
    double d = INFINITY;
    for (int i = 0; i < side->points.count; ++i) {
      const double e = (side->points.x[static_cast<std::size_t>(i)] - z).squaredNorm();
      if (e < d) d = e, nearest = i;
    }
    const std::size_t k = static_cast<std::size_t>(nearest);
    weight[k] += pair.weight;
    if (pair.visible) visible[k] += pair.weight;
    ++count[k];
  }
  for (std::size_t i = 0; i < static_cast<std::size_t>(side->points.count); ++i)
    if (side->factor[i] > 0.0 && weight[i] > 0.0)
      side->visible[i] = (point_rays * side->visible[i] + count[i] * visible[i] / weight[i]) / (point_rays + count[i]);
}

// The factor's shape over one side: the visible point factors, moved to the link's mean `mean` by
// adding the difference of means (their quadrature is exact for the field): `sends`; and that shape
// pulled towards `mean` as far as needed to keep every point >= 0: `receives`. A triangle's centroid
// value is the quadratic's through the other six (link_operator.h PointValues).
//
// A partly visible link to constant leaves whose mean is above its points' (`partly_visible`): the
// link's own point pairs saw more of the source than the points' rays (one a point), so some points
// whose ray was blocked see part of it, and which ones the rays cannot tell. Added evenly, the
// difference lands on points in the umbra too, and the pull (when the mean is below) scales
// instead: so umbra points got light on average, not 0 (the Cornell box's red wall in the tall
// block's shadow +0.53% above a final gather at 6k elements, mean of seven sample streams). There
// the visible point factors are scaled up to the mean instead, light going where rays passed (a
// penumbra lies beside them), by at most kLargestShapeScale, the rest added evenly: a point alone
// visible would otherwise carry the link, and the quadratic through it and its blocked neighbours
// overshoot (umbra_benchmark at 2k elements, red wall, four seeds: +0.24% added evenly, +0.00%
// scaled by at most 8; scaling only sides whose points saw a shadow, +0.15% by at most 4, +0.06% by
// 8, -0.13% by 16 with single leaves 5% off). The receiving shape's points take their visibility
// pooled with the link's pairs (pool_pair_visibility()): from its one ray a point, the scaled shape
// concentrated noise, and the Cornell box's displayed field at total/10000 and /33333 was 1.63% and
// 1.23% off against 1.40% and 0.97% added evenly (hrad sweep --quick); pooled, 1.41% and 0.97%,
// and the umbras within +0.25% / -0.12% of their final gather at 2k and 6k elements.
//
// The side receives by the nonnegative shape: an irradiance < 0 at a point would make a linear
// leaf's corner < 0, and the pull keeps the mean, so the side gathers the link's exchange either
// way. It sends by the shape as moved: at each of its points the links' point factors sum to the
// closure of that point (1 in a closed scene) and the moves sum to 0 (the links' means and the
// points' quadratures both sum to the exchange), so the side sends all of its power, which a pull
// on some links would not keep. A long leaf whose points see a steep falloff (a corridor's wall
// beside the lit end, refined no further by --aeps) has quadrature means far above the exact ones:
// pulled on both ends, a 1.25 x 0.75 x 1000 corridor's linear solve loses 1.9% of its power
// (tests/hard/long_room_test.cpp).
constexpr double kLargestShapeScale = 8.0;

// A source side that touches its receiver along an edge (a floor under the baseboard standing on
// it: the kernel is singular along the contact) has a quadrature mean over its points far above the
// link's exact mean, and moved by the whole difference its send shape is negative over its far
// side: what the link carries then weighs the source's radiosity there negatively. On RenderPark's
// office2 at --basis linear --aeps total/50 a floor quarter whose radiosity is about 0.4 sent 0.065
// to the 5.5 m baseboard beside it, which came out 36% dark. Where the quadrature mean is more than
// kSendScaleRatio times the link's, the send shape is the point factors scaled down to the link's
// mean: the kernel's shape, peaked at the contact, and nowhere negative. The per-point closure that
// the whole move keeps is given up for that link only; a leaf whose links close it still sends its
// power as closed (send_closure.h). Per polygon against a converged reference, office2's linear
// defaults 0.69-0.72% -> 0.62-0.63% (seeds 0, 1), total/50 2.08-2.24% -> 1.70-1.73%; the generated
// 762-polygon warehouse cut along its near faces 1.09-1.14% -> 0.95-0.97% against the ruler (uncut,
// its uprights' feet 1 cm above the floor gather a lit floor element's field and dominate its
// error: 2.07% -> 2.38%); RenderPark's cube and SPLASH-2's room within 0.01 points. Pulling the
// shape towards the mean instead gives the same figures; a ratio of 2 or 1 makes office2's defaults
// worse (0.77%) (tests/hard/contact_send_test.cpp).
constexpr double kSendScaleRatio = 4.0;

void shape_of(const Side& side, double mean, bool partly_visible, std::array<float, 9>* receives,
              std::array<float, 9>* sends) {
  std::array<double, 9> g{};
  for (int i = 0; i < side.points.count; ++i) g[i] = side.factor[i] * side.visible[i];
  if (side.points.count == 7) g[6] = triangle_quadratic_centre(g);
  double area = 0.0, g_mean = 0.0;
  for (int i = 0; i < side.points.count; ++i) {
    area += side.points.weight[i];
    g_mean += side.points.weight[i] * g[i];
  }
  g_mean = area > 0.0 ? g_mean / area : 0.0;
  double lambda = 1.0;
  for (int i = 0; i < side.points.count; ++i)
    if (mean + (g[i] - g_mean) < 0.0) lambda = std::min(lambda, mean / (g_mean - g[i]));
  // Sends moved by the whole difference, except where the points' quadrature overshoots the link's
  // mean kSendScaleRatio-fold (above): there scaled down to it.
  const double send_scale = g_mean > kSendScaleRatio * mean ? mean / g_mean : 0.0;
  // Scaled (partly visible, mean above the points'): mean = scale g_mean + lift.
  const double scale =
      partly_visible && mean > g_mean && g_mean > 0.0 ? std::min(mean / g_mean, kLargestShapeScale) : 0.0;
  const double lift = mean - scale * g_mean;
  receives->fill(0.0f);
  sends->fill(0.0f);
  for (int i = 0; i < side.points.count; ++i) {
    (*receives)[i] = static_cast<float>(scale > 0.0 ? scale * g[i] + lift : mean + lambda * (g[i] - g_mean));
    (*sends)[i] = static_cast<float>(send_scale > 0.0 ? send_scale * g[i] : mean + (g[i] - g_mean));
  }
}

// What a side sends through the link is the integral of its radiosity against its shape (the
// factor from each of its points to the other side): over the radiosity's moments (link_operator.h
// NodeField::radiosity_moments), the shape's values over the exchange, so that a uniform radiosity
// B sends B. A triangle's quadratic has no basis function at the centroid.
void source_weights_of(const Side& side, const std::array<float, 9>& shape, double exchange,
                       std::array<float, 9>* weights) {
  weights->fill(0.0f);
  const int functions = side.points.count == 9 ? 9 : 6;
  for (int i = 0; i < functions; ++i) (*weights)[i] = static_cast<float>(exchange > 0.0 ? shape[i] / exchange : 0.0);
}

}  // namespace

ErrorBoundOracle::ErrorBoundOracle(const ElementHierarchy& hierarchy, const ClusterTree* tree,
                                   const ClusterTransfer& geometry, const FormFactorEvaluator& evaluator,
                                   const OracleTolerances& tolerances, std::vector<double> patch_weights, int channels,
                                   const std::vector<Rgb>* cluster_radiosity)
    : h_(hierarchy),
      tree_(tree),
      geometry_(geometry),
      evaluator_(evaluator),
      tol_(tolerances),
      patch_weight_(std::move(patch_weights)),
      channels_(channels),
      cluster_radiosity_(cluster_radiosity),
      // The pair's budget of point pairs (--visibility-samples, 64 by default) for the link's visible
      // fraction, whose noise a small face in a penumbra shows (RenderPark's cube: faces 8% off with a
      // quarter of it). The shape and the error test take kPointRays a point whatever the budget.
      pair_samples_(std::max(4, evaluator.visibility_samples())),
      cluster_end_rays_(evaluator.visibility_samples() *
                        (tolerances.power_noise > 0.0
                             ? std::max(1.0, std::pow(kClusterSendNoise / tolerances.power_noise, 2))
                             : 1.0)) {
  for (const Patch& patch : evaluator.scene().patches) total_area_ += patch.area;
  b_mean_ = mean_radiosity(evaluator.scene());
  // Read only by varied(), with source levels.
  if (tol_.source_levels > 0) patch_emitted_.assign(evaluator.scene().patches.size(), 0.0);
  for (std::size_t i = 0; i < patch_emitted_.size(); ++i) {
    const Material& m = evaluator.scene().material_of(evaluator.scene().patches[i]);
    for (int ch = 0; ch < channels_; ++ch)
      if (b_mean_[ch] > 0.0) patch_emitted_[i] = std::max(patch_emitted_[i], std::abs(m.emission[ch]) / b_mean_[ch]);
  }
  if (tree_ != nullptr) {
    // A cluster's weight is its brightest patch's.
    cluster_weight_.assign(tree_->size(), 1.0);
    for (std::size_t c = 0; c < tree_->size(); ++c) {
      double w = 0.0;
      for (const int patch : tree_->patches(static_cast<int>(c)))
        w = std::max(w, patch_weight_[static_cast<std::size_t>(patch)]);
      cluster_weight_[c] = w;
    }
  }
}

bool ErrorBoundOracle::can_split(NodeRef r) const {
  if (is_cluster(r)) return true;
  return h_.node(r).area * 0.25 >= tol_.aeps;
}

bool ErrorBoundOracle::can_split_source(NodeRef r) const {
  if (is_cluster(r) || tol_.source_levels <= 0 || can_split(r)) return false;
  if (!tol_.source_patches.empty() && !tol_.source_patches[static_cast<std::size_t>(h_.node(r).patch)]) return false;
  return h_.node(r).area * 0.25 >= std::ldexp(tol_.aeps, -2 * tol_.source_levels);
}

std::pair<double, double> ErrorBoundOracle::varied(NodeRef p, NodeRef q, double err_p, double err_q) const {
  const auto variation = [&](NodeRef r) {
    return std::max(0.0, weight(r) - patch_emitted_[static_cast<std::size_t>(h_.node(r).patch)]);
  };
  const auto reflected = [&](NodeRef r) {
    const ElementNode& e = h_.node(r);
    double b = 0.0;
    for (int ch = 0; ch < channels_; ++ch) b = std::max(b, std::abs(e.radiosity[ch] - e.emission[ch]));
    return b;
  };
  return weigh(variation, reflected, p, q, err_p, err_q);
}

double ErrorBoundOracle::weight(NodeRef r) const {
  if (is_cluster(r)) return cluster_weight_[static_cast<std::size_t>(cluster_index(r))];
  const double a_priori = patch_weight_[static_cast<std::size_t>(h_.node(r).patch)];
  if (observed_.empty()) return a_priori;
  // Elements split after the observation take their nearest observed ancestor's.
  NodeId id = r;
  while (static_cast<std::size_t>(id) >= observed_.size()) id = h_.node(id).parent;
  return std::max(a_priori, observed_[static_cast<std::size_t>(id)]);
}

std::vector<char> ErrorBoundOracle::observe() {
  const std::size_t n = h_.size();
  if (!(tol_.feps > 0.0) || !(b_mean_.maxCoeff() > 0.0)) return std::vector<char>(n, 0);
  // Each element's brightest leaf, in units of B_mean (children have larger ids than their parent).
  std::vector<double> peak(n, 0.0);
  for (std::size_t i = n; i-- > 0;) {
    const ElementNode& e = h_.node(static_cast<NodeId>(i));
    if (e.is_leaf())
      for (int c = 0; c < channels_; ++c)
        if (b_mean_[c] > 0.0) peak[i] = std::max(peak[i], std::abs(e.radiosity[c]) / b_mean_[c]);
    if (e.parent != kNoNode)
      peak[static_cast<std::size_t>(e.parent)] = std::max(peak[static_cast<std::size_t>(e.parent)], peak[i]);
  }
  std::vector<char> raised(n, 0);
  std::vector<double> observed(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double now = weight(static_cast<NodeRef>(i));
    if (peak[i] > kBrighterThanWeighed * now) {
      observed[i] = peak[i];
      raised[i] = 1;
    } else {
      observed[i] = i < observed_.size() ? observed_[i] : now;
    }
  }
  observed_ = std::move(observed);
  return raised;
}

double ErrorBoundOracle::brightest(NodeRef r) const {
  const Rgb& b =
      is_cluster(r) ? (*cluster_radiosity_)[static_cast<std::size_t>(cluster_index(r))] : h_.node(r).radiosity;
  return channels_ == 1 ? b[0] : b.maxCoeff();
}

std::pair<double, double> ErrorBoundOracle::weighted(NodeRef p, NodeRef q, double err_p, double err_q) const {
  return weigh([&](NodeRef r) { return weight(r); }, [&](NodeRef r) { return brightest(r); }, p, q, err_p, err_q);
}

Decision ErrorBoundOracle::split_choice(NodeRef p, NodeRef q, double e_p, double e_q) const {
  // Split the side whose gather errs more as the test weighs it: only splitting p reduces p's
  // error. Splitting q instead would make each piece's share small enough to pass while the
  // pieces' errors add up on p. On a tie, the larger side (HSA 1991, Refine).
  bool q_first = e_q > e_p;
  if (e_q == e_p) {
    const double ap = is_cluster(p) ? INFINITY : h_.node(p).area, aq = is_cluster(q) ? INFINITY : h_.node(q).area;
    q_first = aq > ap;
  }
  if (q_first) {
    if (can_split(q)) return Decision::kSplitQ;
    if (can_split(p)) return Decision::kSplitP;
  } else {
    if (can_split(p)) return Decision::kSplitP;
    if (can_split(q)) return Decision::kSplitQ;
  }
  return Decision::kLink;  // both at the smallest area: link anyway (HSA)
}

void ErrorBoundOracle::decide(Candidate& c) const {
  c.decision = Decision::kDrop;
  c.f_pq = c.f_qp = 0.0;
  c.partial = false;
  c.hidden_p = c.hidden_q = nullptr;
  c.shadow_p = c.shadow_q = c.share_p = c.share_q = 0.0f;
  if (c.split_p && can_split(c.p)) {
    // Asked to split p (refine.h: the shadow errors below p add up past the tolerance).
    c.decision = Decision::kSplitP;
    return;
  }
  if (c.p == c.q) {
    // A cluster's self-link; a planar element sees nothing of itself.
    c.decision = is_cluster(c.p) ? Decision::kSelf : Decision::kDrop;
    return;
  }
  if (is_cluster(c.p) || is_cluster(c.q)) {
    decide_with_cluster(c);
    return;
  }
  decide_elements(c);
}

void ErrorBoundOracle::decide_elements(Candidate& c) const {
  const ElementNode& p = h_.node(c.p);
  const ElementNode& q = h_.node(c.q);
  if (p.patch == q.patch) return;  // one plane
  if (evaluator_.faces_away(p.polygon(), q.polygon())) return;
  const Scene& scene = evaluator_.scene();
  const Vec3& np = scene.patches[static_cast<std::size_t>(p.patch)].normal;
  const Vec3& nq = scene.patches[static_cast<std::size_t>(q.patch)].normal;
  Side sp, sq;
  // The fields the HSA push carries take the factor's limit on shared edges. The leaf push resolves
  // each link per leaf with a Gauss rule that cannot follow the factor's steep rise towards a shared
  // edge; with 0 there, the spread keeps such pairs refining down to leaves, whose links are exact.
  point_factors(evaluator_, p, np, q, tol_.fields, &sp);
  point_factors(evaluator_, q, nq, p, tol_.fields, &sq);
  if (!(sp.unoccluded > 0.0) && !(sq.unoccluded > 0.0)) return;   // no point of either side sees the other
  const double exchange = 0.5 * (sp.unoccluded + sq.unoccluded);  // A_p F(p -> q) = A_q F(q -> p)
  const double disagreement = 0.5 * std::abs(sp.unoccluded - sq.unoccluded);
  const bool splittable = can_split(c.p) || can_split(c.q);
  const Fit fit = !tol_.fields ? Fit::kMean : tol_.linear_leaves ? Fit::kLeastSquares : Fit::kCorners;

  // Visibility: classify with the parent's occluders; the children inherit what is found. A pair
  // whose largest point factor passes the weighted test is slight: however its visibility falls, its
  // link errs by about that factor at most, within the tolerance, so its class would only spare rays
  // and name their candidate occluders. It goes to the rays below unclassified: they decide exactly
  // among its parent's occluders (a superset of its own) or the whole scene, and cost less than the
  // shaft's hull and facet tests. Most pairs of a furnished room are slight: SPLASH-2's room at
  // --feps 0.04 tests 61% fewer shafts, for 6% more segments.
  c.visible = c.known_visible || !evaluator_.effects().visibility;
  std::vector<int> occluders;
  double largest = 0.0;  // the largest point factor, weighted, in units of the tolerance
  if (!c.visible) {
    const auto [e_p, e_q] = weighted(c.p, c.q, sp.largest(), sq.largest());
    largest = std::max(e_p, e_q);
  }
  const bool classified = !c.visible && !(largest <= 1.0);  // not slight
  if (classified) {
    const PairClass cls =
        evaluator_.classify(p.polygon(), p.patch, q.polygon(), q.patch, c.occluders.get(), &occluders);
    if (cls == PairClass::kFullyHidden || cls == PairClass::kFacingAway) return;
    c.visible = cls == PairClass::kFullyVisible;
    if (!c.visible) c.found_occluders = std::make_shared<const std::vector<int>>(std::move(occluders));
  }
  // The rays' candidate occluders: the pair's own, else its parent's (a superset), else the scene's.
  const std::vector<int>* among = c.found_occluders ? c.found_occluders.get() : c.occluders.get();
  // A fully visible pair whose point factors alone stray from every linear field by more than the
  // tolerance is split without more ado.
  if (c.visible && splittable) {
    const auto [e_p, e_q] = tol_.fields ? weighted(c.p, c.q, sp.linear_residual_bound(), sq.linear_residual_bound())
                                        : weighted(c.p, c.q, 0.5 * sp.spread(), 0.5 * sq.spread());
    if (std::max(e_p, e_q) > 1.0) {
      c.decision = split_choice(c.p, c.q, e_p, e_q);
      return;
    }
  }
  double fraction = 1.0;
  Side sp_send, sq_send;  // with linear elements: the points' visibility for what each side sends
  bool apart = false;
  // Point visibility taken as the link's fraction (kUniformVisibilityShare).
  const bool uniform = !c.visible && !classified && !splittable && largest <= kUniformVisibilityShare;
  if (!c.visible) {
    const std::uint64_t seed = evaluator_.pair_seed(p.polygon(), p.patch, q.polygon(), q.patch);
    auto sample = [&](int rays, std::uint64_t stream) {
      point_visibility(evaluator_, p, np, q, among, rays, detail::mix_seed(seed, stream), &sp);
      point_visibility(evaluator_, q, nq, p, among, rays, detail::mix_seed(seed, stream + 1), &sq);
      const double unoccluded = sp.unoccluded + sq.unoccluded;
      return unoccluded > 0.0 ? (sp.seen + sq.seen) / unoccluded : 0.0;
    };
    if (splittable && classified) {
      // One ray per point first: where the points already disagree by twice the tolerance (a shadow
      // boundary crosses the pair), split without sampling further. Sampling noise can only cause a
      // split here, never a link. Not for a slight pair: its largest point factor passes the test,
      // so its points hardly ever disagree by twice it (2 of the 72.6 k slight pairs of RenderPark's
      // office2 at --basis linear did), and the draw cost it 18 rays for nothing (6% of the rays).
      fraction = sample(1, 1);
      if (fraction > 0.0) {
        const double f_pq = exchange * fraction / p.area, f_qp = exchange * fraction / q.area;
        const auto [e_p, e_q] =
            weighted(c.p, c.q, field_error(sp, f_pq, false, fit), field_error(sq, f_qp, false, fit));
        if (std::max(e_p, e_q) > 2.0) {
          c.decision = split_choice(c.p, c.q, e_p, e_q);
          return;
        }
      }
    }
    // The test reads the fraction the points' own rays give (their quadrature of the visible point
    // factors, which weighs the elements' boundaries as the quadrature does); the link's fraction
    // comes from point pairs of its own below. A uniform pair's test reads its unoccluded factors
    // (neither side can split).
    if (!uniform) fraction = sample(kPointRays, 3);
    c.partial = true;
    if (tol_.linear_leaves && classified) {
      apart = true;
      sp_send = sp;
      sq_send = sq;
      point_visibility(evaluator_, p, np, q, among, kPointRays, detail::mix_seed(seed, kSendShapeStream), &sp_send);
      point_visibility(evaluator_, q, nq, p, among, kPointRays, detail::mix_seed(seed, kSendShapeStream + 1), &sq_send);
    }
  }
  // The link carries the factor's shape over each side (push_pull.h); its error is bounded by how
  // far the visible point factors stray from a linear field.
  const double f_pq = exchange * fraction / p.area, f_qp = exchange * fraction / q.area;
  // Its points may lie on the outline of a side floating close in front of the other
  // (off_grid_deviation()): the deviation at points off them counts too.
  const double field_p = std::max(field_error(sp, f_pq, true, fit), off_grid_deviation(evaluator_, p, np, q, sp));
  const double field_q = std::max(field_error(sq, f_qp, true, fit), off_grid_deviation(evaluator_, q, nq, p, sq));
  const double err_p = field_p + disagreement / p.area;
  const double err_q = field_q + disagreement / q.area;
  auto [e_p, e_q] = weighted(c.p, c.q, err_p, err_q);
  Decision source_split = Decision::kLink;  // a split below aeps, if the link would stand otherwise
  if (tol_.fields) {
    // What p gathers through the link is q's radiosity weighed by the link's field over q (q's
    // factors towards p, sum_i source_q[i] m_i), which stands for the point kernel towards p. Where
    // that kernel is peaked over q (q touches or nearly touches p, as a block's face meets the floor
    // beside it), the field's error relative to its mean, times how far q's radiosity strays from
    // its weighted mean (at most its a-priori weight), is what p's gather errs by: on the Cornell box
    // this, not the receiver's field, made the leaves in the blocks' umbras too bright (a darker
    // strip of q near the contact weighed too little). Only splitting q reduces it.
    const double relative_q = f_qp > 0.0 ? field_q / f_qp : 0.0;
    const double relative_p = f_pq > 0.0 ? field_p / f_pq : 0.0;
    // With source levels, each side's radiosity is weighed by how far it can vary (a lamp's own
    // emission is uniform: splitting it as a source reduces nothing), and a source at aeps may
    // split on (OracleTolerances::source_levels).
    const auto [s_p, s_q] = tol_.source_levels > 0 ? varied(c.p, c.q, f_pq * relative_q, f_qp * relative_p)
                                                   : weighted(c.p, c.q, f_pq * relative_q, f_qp * relative_p);
    if (can_split(c.q)) e_q = std::max(e_q, s_p);
    if (can_split(c.p)) e_p = std::max(e_p, s_q);
    if (s_p > 1.0 && can_split_source(c.q)) source_split = Decision::kSplitQ;
    if (s_q > 1.0 && can_split_source(c.p) && (source_split == Decision::kLink || s_q > s_p))
      source_split = Decision::kSplitP;
  }
  if (c.partial && fraction < 1.0) {
    // What giving the whole receiver the link's visible fraction errs, in units of the tolerance:
    // a shadow errs the same way for every source its occluder hides, so these add up on the
    // leaves below (refine.h sums them and refines where the sum passes the tolerance).
    const auto [s_p, s_q] =
        weighted(c.p, c.q, f_pq * shadow_variation(sp, fraction), f_qp * shadow_variation(sq, fraction));
    c.shadow_p = static_cast<float>(s_p);
    c.shadow_q = static_cast<float>(s_q);
  }
  {
    const auto [w_p, w_q] = weighted(c.p, c.q, f_pq, f_qp);
    c.share_p = static_cast<float>(w_p);
    c.share_q = static_cast<float>(w_q);
  }
  const bool passes = std::max(e_p, e_q) <= 1.0;
  c.decision = passes ? Decision::kLink : split_choice(c.p, c.q, e_p, e_q);
  if (c.decision == Decision::kLink) c.decision = source_split;
  if (c.decision != Decision::kLink) return;
  // The link's unoccluded exchange by the closed form (or Gauss points where the pair is far apart
  // against its size): the Simpson points' quadratures can be off by a percent for large elements
  // even where the two sides agree (a pair symmetric about a plane).
  const auto linked_exchange = [&] {
    if (exchange < kNegligibleFactor * std::min(p.area, q.area)) return exchange;
    const bool far = FormFactorEvaluator::separated(p.polygon(), q.polygon(), kGaussSeparation) &&
                     FormFactorEvaluator::separated(q.polygon(), p.polygon(), kGaussSeparation);
    return p.area * (far ? evaluator_.gauss(p.polygon(), q.polygon())
                         : evaluator_.analytic(p.polygon(), q.polygon(), kLinkTolerance, kLinkAbsoluteTolerance))
                        .from_to;
  };
  double linked = -1.0;  // not yet computed
  // Constant leaves: the linked fraction's pairs pool into the points' visibility for the receiving
  // shapes below.
  thread_local std::vector<VisibilityPair> pairs;
  if (c.partial) {
    // The linked fraction from point pairs of its own. The test above read `fraction`, and keeping
    // it would keep the estimates that happened to pass: a pair whose samples all missed a thin
    // shadow passes as fully visible with no shadow error, one whose samples caught more of it
    // splits, and the links kept see too much. Independent samples are unbiased whatever the test
    // decided, including a pair whose test samples were all blocked.
    // As many point pairs as keep the fraction's sampling error small in two ways. As a share of
    // the scene's power through the link, below kPowerNoise (the balance): the power through a link
    // is about (weight(p) + weight(q)) B_mean times its exchange, the scene emits B_mean (1 -
    // rhobar) times its area (taken as B_mean times its area, which asks for fewer pairs), and a
    // fraction from n pairs errs by at most 1 / (2 sqrt(n)) (a Bernoulli mean; the kernel weights
    // spread it further). The links of lamps to the surfaces beside them carry much of a room's
    // power and are few: 64 pairs there left the generated 1k office's balance spread by 8e-4 over
    // independent sample streams. And as what each end gathers through the link in units of the
    // tolerance (share_p, share_q), below kGatherNoise: a small face in a penumbra gathers most of
    // its light through a few links, whose noise it shows. A link that carries little of what its
    // ends gather needs few pairs. Both per 64 of --visibility-samples.
    const double scale = static_cast<double>(pair_samples_) / kDefaultVisibilitySamples;
    const double share = (weight(c.p) + weight(c.q)) * exchange / total_area_;
    const double gathered = std::max(c.share_p, c.share_q);
    const double budget = tol_.power_noise > 0.0 ? share / (4.0 * tol_.power_noise * tol_.power_noise) : 0.0;
    const double wanted = std::max(scale * std::ceil(std::max(std::pow(share / (2.0 * kPowerNoise), 2),
                                                              std::pow(gathered / (2.0 * kGatherNoise), 2))),
                                   std::ceil(budget));
    const int samples = static_cast<int>(std::clamp(wanted, std::max(kFewestLinkSamples, scale * kLeastLinkSamples),
                                                    static_cast<double>(kMostLinkSamples * pair_samples_)));
    const PairVisibility seen =
        evaluator_.pair_visibility(p.polygon(), p.patch, q.polygon(), q.patch, among, samples, kLinkedFractionStream,
                                   true, tol_.linear_leaves ? nullptr : &pairs);
    if (!(seen.visible() > 0.0)) {
      // Every linked sample was blocked too: nothing to link, as far as these samples know.
      c.decision = Decision::kUnseen;
      return;
    }
    // With the link's exact exchange the fraction is unbiased (PairVisibility::controlled(); the
    // test's fraction, from rays of its own, where a half of the pairs carries no weight). The
    // ratio of sums loses power where the kernel weights and the outcomes correlate, most beside
    // faces a hair in front of others: a generated 700-polygon warehouse as 1,524 triangles, every
    // surface emitting uniformly, lost 8.8e-4 to 1.9e-3 of its power over four sample streams so.
    // A slight pair that every ray crossed keeps its sampled fraction (exactly 1 then) and stays
    // partial. Classifying it, to store it as fully visible when it is, was a shaft test for each
    // such pair (16 k of the 40 k of RenderPark's office2 at its defaults) and moved no error per
    // polygon on the peers' rooms by more than 0.002 points.
    linked = linked_exchange();
    fraction = seen.controlled(linked, fraction);
    if (uniform)
      for (Side* side : {&sp, &sq}) {
        std::fill(side->visible.begin(), side->visible.end(), fraction);
        side->seen = fraction * side->unoccluded;
      }
  }
  if (linked < 0.0) linked = linked_exchange();
  c.f_pq = linked * fraction / p.area;
  c.f_qp = linked * fraction / q.area;
  c.fraction = fraction;
  if (!(c.f_pq > 0.0) && !(c.f_qp > 0.0)) {
    c.decision = Decision::kDrop;
    return;
  }
  c.shaped = true;
  std::array<float, 9> sends_p{}, sends_q{};
  // Constant leaves only: a linear leaf keeps the scaled shape's slope, steep where one point saw
  // the source (SPLASH-2's room: its linear reference at aeps total/16000 went from 0.64% to 1.59%
  // against the Monte Carlo ruler, and its linear solves took up to 11x the iterations' time).
  const bool scaled = c.partial && !tol_.linear_leaves;
  shape_of(sp, c.f_pq, scaled, &c.shape_p, &sends_p);
  shape_of(sq, c.f_qp, scaled, &c.shape_q, &sends_q);
  if (scaled) {
    // What each side receives follows its points' rays pooled with the link's pairs; what it sends
    // stays its points' own (constant leaves send their mean).
    std::array<float, 9> sends{};
    Side pooled = sp;
    pool_pair_visibility(pairs, true, kPointRays, &pooled);
    shape_of(pooled, c.f_pq, scaled, &c.shape_p, &sends);
    pooled = sq;
    pool_pair_visibility(pairs, false, kPointRays, &pooled);
    shape_of(pooled, c.f_qp, scaled, &c.shape_q, &sends);
  }
  if (apart) {
    std::array<float, 9> receives{};  // already in c.shape_p, c.shape_q
    shape_of(sp_send, c.f_pq, scaled, &receives, &sends_p);
    shape_of(sq_send, c.f_qp, scaled, &receives, &sends_q);
  }
  source_weights_of(sp, sends_p, linked * fraction, &c.source_p);
  source_weights_of(sq, sends_q, linked * fraction, &c.source_q);
}

int ErrorBoundOracle::end_rays_per_patch(NodeRef end) const {
  return std::max(kFacingRays, static_cast<int>(std::ceil(cluster_end_rays_ / geometry_.patch_count(end))));
}

double ErrorBoundOracle::near_share_noise(NodeRef end, double largest) const {
  return is_cluster(end) ? largest / std::sqrt(static_cast<double>(end_rays_per_patch(end))) : 0.0;
}

void ErrorBoundOracle::decide_with_cluster(Candidate& c) const {
  if (evaluator_.effects().cull_facing_away && geometry_.facing_away(c.p, c.q)) return;
  const NodeShape sp = geometry_.shape(c.p), sq = geometry_.shape(c.q);
  const double r = (sq.centre - sp.centre).norm(), reach = sp.radius + sq.radius;
  const bool far_apart = r > kClusterSeparation * reach;
  if (r > reach) {  // far_apart implies it (kClusterSeparation > 1)
    // The link's factor is one value for the whole pair, which errs by the change of 1/r^2 across
    // the two spheres (HSA 1991 sec. 4's error of a link, rather than the factor's size): far apart,
    // by about 2 (r_p + r_q) / r of it (first order). Nearer, down to disjoint spheres, the first
    // order understates it (3x at r = 2 (r_p + r_q)): such a pair is judged by the whole range of
    // 1/r^2 over the spheres, and by the noise of each cluster end's shares (near_share_noise()).
    const double variation = far_apart ? 2.0 * reach / r : std::pow((r + reach) / (r - reach), 2) - 1.0;
    const TransferBound most = geometry_.bound(sp, sq);
    const double noise_p = far_apart ? 0.0 : near_share_noise(c.p, most.pq);
    const double noise_q = far_apart ? 0.0 : near_share_noise(c.q, most.qp);
    const FormFactorEstimate far = geometry_.far_field(c.p, sp, c.q, sq);
    // No patch of one side faces the other's centre: dropped only when nothing faces any of the
    // other (dropping pairs that graze would lose their exchange); otherwise split below.
    if (far.facing_away && geometry_.patches_face_away(c.p, c.q)) return;
    const auto [b_p, b_q] = weighted(c.p, c.q, far.value * variation + noise_p, far.reverse * variation + noise_q);
    if (!far.facing_away && std::max(b_p, b_q) <= 1.0) {
      const NodeSurfaces surfaces_p(geometry_, c.p, sp.area), surfaces_q(geometry_, c.q, sq.area);
      const std::uint64_t seed = evaluator_.stream_seed(detail::mix_seed(
          (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.p)) << 32) | static_cast<std::uint32_t>(c.q), 7));
      // The test's factor only decides whether the pair is linked; what a link carries comes from
      // samples of its own (below), as many as --visibility-samples. So the test draws a fraction
      // of them, and the link's sampling error is the test's scaled to the link's count.
      const int link_samples = evaluator_.visibility_samples();
      const int test_samples = std::max(kFacingRays, link_samples / kClusterTestFraction);
      const FormFactorEstimate e = evaluator_.sampled(surfaces_p, surfaces_q, test_samples, seed);
      const double link_error = e.error * std::sqrt(static_cast<double>(test_samples) / std::max(1, link_samples));
      // The link shares its power among each side's patches by their projected areas towards the
      // other's centre (hsa_links.h), as the far-field factor does: where the sampled unoccluded
      // factor strays from it by more than the test's noise, the shares would put that much in the
      // wrong places (patches grazing the centre direction that do face parts of the other side).
      const double stray = std::max(0.0, std::abs(e.unoccluded - far.value) - 2.0 * e.error);
      const double error_pq = std::max(far.value * variation, stray) + link_error;
      const double error_qp = error_pq * sp.area / sq.area;
      const auto [e_p, e_q] = weighted(c.p, c.q, error_pq + noise_p, error_qp + noise_q);
      if (std::max(e_p, e_q) <= 1.0) {
        // What the link carries comes from samples of its own, drawn once the error test (on the
        // test's factor `e`) has passed: values that decided their own link would keep the
        // estimates that came out small (a pair whose rays were all blocked passes, one whose rays
        // found much is split), a loss of power on every link. A cluster end sends by each patch's
        // own sampled factor to the other end (--visibility-samples rays in all, at least
        // kFacingRays a patch: end_rays_per_patch()), an element end by the same estimate (below);
        // each direction is stored, or the pair dropped, by what it carries. Deciding by another
        // estimate loses what the carried one gives where the other found nothing: the generated
        // 4,400-polygon pillar hall lost 1.2e-3 of its emitted power so. The patches of each end
        // that some ray passed to (the other cluster end's own rays) see the other end.
        std::vector<int> seen_p, seen_q;
        auto own = [&](NodeRef end, const NodeSurfaces& from, NodeRef other, const NodeSurfaces& to,
                       std::uint64_t stream, ShadedPatches* s, std::vector<int>* reached) {
          *s = evaluator_.shaded_surfaces(from, to, end_rays_per_patch(end), detail::mix_seed(seed, stream), reached);
          geometry_.drop_idle(end, other, s);
          double exchange = 0.0;  // sum_j A_j q_j: what the end sends per unit radiosity
          for (const ShadedPatch& patch : *s)
            exchange += evaluator_.scene().patches[static_cast<std::size_t>(patch.patch)].area *
                        static_cast<double>(patch.factor);
          return exchange;
        };
        // An element end sends what the cluster end's rays found it gets (A_p F_pq = A_q F_qp): the
        // link's two directions balance exactly, and the element casts no rays of its own. Against
        // point pairs of the element's own: rays -15% and time -11% on the generated 4,400-polygon
        // pillar hall, -10% on the 16.5k one, with the same error per polygon against a 512-sample
        // solve of the 1k hall (hrad solve S.obj --threads 1).
        ShadedPatches shaded_p, shaded_q;
        double sends_q = 0.0, sends_p = 0.0;
        const bool both = is_cluster(c.p) && is_cluster(c.q);
        if (is_cluster(c.q)) sends_q = own(c.q, surfaces_q, c.p, surfaces_p, 5, &shaded_q, both ? &seen_p : nullptr);
        if (is_cluster(c.p)) sends_p = own(c.p, surfaces_p, c.q, surfaces_q, 4, &shaded_p, both ? &seen_q : nullptr);
        if (!is_cluster(c.p)) sends_p = sends_q;
        if (!is_cluster(c.q)) sends_q = sends_p;
        if (!(sends_p > 0.0) && !(sends_q > 0.0)) return;
        // Each cluster end shares what the link brings among its patches by their own factors to
        // the other end (by the part of it each sees and its factor to the other end's bounding
        // sphere where its rays found nothing, ClusterTransfer::link_weights()): a patch that sees
        // nothing of it (the inside of a closed box lit from outside) gets nothing. Nor may a patch
        // get more through the link than any point of it can see of the other side (TransferBound):
        // such pairs are split. That test reads the carried rays: it splits 0.2-0.4% of the pairs
        // that reach it on the generated 1k scenes, and rays of its own (kFacingRays a patch) cost
        // the generated 3,726-polygon warehouse a seventh of its time.
        // Between two clusters, an end whose own rays all missed the other end still gets what the
        // link brings: among its patches that the other end's own rays reached (some did when that
        // end sends anything). Opposite an element, the cluster end's own rays found the exchange,
        // and it shares by them (hsa_links.cpp reads what each patch saw only where its own rays
        // found nothing).
        auto largest_share = [&](NodeRef end, NodeRef other, std::vector<int>& seen, ShadedPatches* s) {
          const double largest = geometry_.largest_share(end, other, s);
          if (!both || std::isfinite(largest)) return largest;
          std::sort(seen.begin(), seen.end());
          for (ShadedPatch& patch : *s)
            patch.visible = std::binary_search(seen.begin(), seen.end(), patch.patch) ? 1.0f : 0.0f;
          return geometry_.largest_share(end, other, s);
        };
        const double share_p = largest_share(c.p, c.q, seen_p, &shaded_p);
        const double share_q = largest_share(c.q, c.p, seen_q, &shaded_q);
        if (!(sends_q * share_p > most.pq) && !(sends_p * share_q > most.qp)) {
          c.decision = Decision::kLink;
          c.f_pq = sends_q / sp.area;  // F(p -> q) as carried
          c.f_qp = sends_p / sq.area;
          c.partial = true;
          if (!shaded_p.empty()) c.hidden_p = std::make_shared<const ShadedPatches>(std::move(shaded_p));
          if (!shaded_q.empty()) c.hidden_q = std::make_shared<const ShadedPatches>(std::move(shaded_q));
          return;
        }
      }
    }
  }
  // Split the node with the larger bounding sphere (Smits et al. 1994 split the larger side).
  const bool p_can = can_split(c.p), q_can = can_split(c.q);
  if (!is_cluster(c.p) && !is_cluster(c.q)) {
    decide_elements(c);
    return;
  }
  if (is_cluster(c.p) && (!is_cluster(c.q) || sp.radius >= sq.radius || !q_can))
    c.decision = Decision::kSplitP;
  else if (q_can)
    c.decision = Decision::kSplitQ;
  else
    c.decision = p_can ? Decision::kSplitP : Decision::kLink;
}

std::vector<double> source_weights(const Scene& scene, int channels) {
  std::vector<double> weights(scene.patches.size(), 1.0);
  const Rgb b_mean = mean_radiosity(scene);
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Material& m = scene.material_of(scene.patches[i]);
    double w = 0.0;
    bool any = false;
    for (int c = 0; c < channels; ++c) {
      if (!(b_mean[c] > 0.0)) continue;
      w = std::max(w, std::abs(m.emission[c]) / b_mean[c] + m.reflectance[c]);
      any = true;
    }
    if (any) weights[i] = w;
  }
  return weights;
}

}  // namespace hrad
