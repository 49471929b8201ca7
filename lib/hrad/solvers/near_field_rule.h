// Finer integration rules for linear elements beside a near source (the full matrix's field links).
//
// Linear elements gather and send through fields of values at the element's simpson_points()
// (linear_basis.h, field_links.h). Where a source floats closer than the element's size (a lamp 1 mm
// in front of a wall element larger than it), the factor rises within the gap's width around the
// footprint, which nine points cannot follow: their quadrature of the pair's exchange was 2-4x the
// closed form, and a closed room with such a lamp absorbed up to 4.4 times what it emitted. What the
// solve reads of a field is only its moments against the element's linear functions psi_a: the L2
// projection of what a leaf gathers reads those, and a linear radiosity B sends integral g B = sum_a
// B_a integral g psi_a (Zatz 1993 and Gortler et al. 1993 ask the same of a Galerkin kernel). So such
// an element takes an adaptive rule, finer where its factors to the near sources vary, and every one
// of its pairs (not only the near ones) integrates by it: at each of the rule's points the factors to
// sources that tile a closed room still sum to 1, so their moments sum to those of 1 (a uniform room
// stays exact), while the near pair's moments are accurate on both ends, which makes it reciprocal.
// The nine values are then given those moments by adding a linear function (match_linear_moments()).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "hrad/core/types.h"
#include "hrad/formfactor/simpson_rule.h"

namespace hrad {

class FormFactorEvaluator;

/// A point of a rule over an element: where, its weight (an area), and the element's corner
/// functions there (bilinear on a quad's map, barycentric on a triangle; the 4th 0 on a triangle).
struct RulePoint {
  Vec3 x;
  double weight = 0.0;
  std::array<double, 4> psi{};
};

/// An adaptive composite rule on `element` (3 x 3 Gauss points per cell of its map; a triangle as a
/// collapsed square): a cell is cut into four while the four quarters' integral of the summed
/// factors to `sources` differs from the cell's by more than `tolerance` (an area times a factor).
/// The weights sum to the element's area (exactly for parallelograms and triangles).
std::vector<RulePoint> near_field_rule(const FormFactorEvaluator& evaluator, std::span<const Vec3> element,
                                       const Vec3& normal, const std::vector<std::vector<Vec3>>& sources,
                                       double tolerance);

/// integral psi_a(x) F(dA_x -> source) V(x) dA_x by `rule` for each corner a; V by one ray from each
/// point of a partly visible pair (`occluders` as FormFactorEvaluator::classify() listed them).
std::array<double, 4> rule_moments(const FormFactorEvaluator& evaluator, const std::vector<RulePoint>& rule,
                                   const Vec3& normal, int patch, std::span<const Vec3> source, int source_patch,
                                   const std::vector<int>* occluders, bool partial, std::uint64_t seed);

/// Adds to `values` (at the simpson_points() `points`, `points.count` 9 or 7) the linear function
/// whose moments by the points' rule make the field's moments `target`. A triangle's centre value
/// is first set to the quadratic through its six others, so that its rule is exact for the field
/// times a linear function (as a quad's is for its biquadratic field).
void match_linear_moments(const SimpsonPoints& points, const std::array<double, 4>& target,
                          std::array<double, 9>* values);

}  // namespace hrad
