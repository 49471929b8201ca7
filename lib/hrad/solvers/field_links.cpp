#include "hrad/solvers/field_links.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/formfactor/simpson_rule.h"
#include "hrad/solvers/linear_basis.h"
#include "hrad/solvers/near_field_rule.h"
#include "hrad/visibility/sampling.h"

namespace hrad {
namespace {

// Visibility sample streams of a near-field rule's moments (apply_near_field_rules()), apart from
// pair_fields()' 1 and 2.
constexpr std::uint64_t kGatherStream = 5, kSendStream = 6;

// A boundary point casts its rays from this fraction of the way towards the element's centre: from
// the boundary itself a ray can graze a neighbouring patch that meets it there.
constexpr double kRayStart = 1.0 / 16.0;

void visible_fractions(const FormFactorEvaluator& ev, const ElementNode& r, const ElementNode& s,
                       const std::vector<int>* occluders, int rays, std::uint64_t seed, PointFactors* side) {
  const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
  const int centre = side->points.count - 1;
  const Vec3& c = side->points.x[static_cast<std::size_t>(centre)];
  for (int i = 0; i < side->points.count; ++i) {
    double& f = side->factor[static_cast<std::size_t>(i)];
    if (!(f > 0.0)) continue;
    const Vec3& x = side->points.x[static_cast<std::size_t>(i)];
    const Vec3 start = i == centre ? x : Vec3(x + kRayStart * (c - x));
    const KernelVisibility k = ev.visibility_from_point(start, n, r.patch, s.polygon(), s.patch, occluders, rays,
                                                        detail::mix_seed(seed, static_cast<std::uint64_t>(i)));
    // No ray carried weight (the point sees the source edge-on): half, the least biased guess.
    f *= k.weight > 0.0 ? k.visible / k.weight : 0.5;
  }
}

// The source's weights over its moments: its points' factors in the Bernstein form (a positive
// average of its radiosity, linear_basis.h bernstein_weighting()) over their integral against its
// basis (basis_integrals()), so a uniform radiosity sends itself. A source none of whose points sees
// the receiver sends its mean.
std::array<double, 9> source_weights(const PointFactors& source, double area) {
  const int functions = basis_functions(source.points);
  const std::array<double, 9> basis = basis_integrals(source.points, area);
  const std::array<double, 9> g = bernstein_weighting(source.factor, source.points.count);
  double integral = 0.0;
  for (int m = 0; m < functions; ++m) integral += basis[static_cast<std::size_t>(m)] * g[static_cast<std::size_t>(m)];
  std::array<double, 9> w{};
  for (int m = 0; m < functions; ++m)
    w[static_cast<std::size_t>(m)] = integral > 0.0 ? g[static_cast<std::size_t>(m)] / integral : 1.0 / area;
  return w;
}

}  // namespace

PointFactors point_factors(const FormFactorEvaluator& ev, const ElementNode& r, std::span<const Vec3> source) {
  PointFactors side;
  side.points = simpson_points(r.polygon());
  const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
  const int centre = side.points.count - 1;
  const Vec3& c = side.points.x[static_cast<std::size_t>(centre)];
  for (int i = 0; i < side.points.count; ++i) {
    const Vec3& x = side.points.x[static_cast<std::size_t>(i)];
    side.factor[static_cast<std::size_t>(i)] =
        i == centre ? ev.point_factor(x, n, source) : ev.point_factor(x, n, Vec3(c - x), source);
  }
  return side;
}

void pair_fields(const FormFactorEvaluator& ev, const ElementNode& a, const ElementNode& b, int rays,
                 FieldEntry* a_from_b, FieldEntry* b_from_a) {
  *a_from_b = FieldEntry{};
  *b_from_a = FieldEntry{};
  if (a.patch == b.patch || ev.faces_away(a.polygon(), b.polygon())) return;
  PointFactors sa = point_factors(ev, a, b.polygon()), sb = point_factors(ev, b, a.polygon());
  if (ev.effects().visibility) {
    std::vector<int> occluders;
    const PairClass cls = ev.classify(a.polygon(), a.patch, b.polygon(), b.patch, nullptr, &occluders);
    if (cls == PairClass::kFullyHidden || cls == PairClass::kFacingAway) return;
    if (cls == PairClass::kPartial) {
      const std::uint64_t seed = ev.pair_seed(a.polygon(), a.patch, b.polygon(), b.patch);
      visible_fractions(ev, a, b, &occluders, rays, detail::mix_seed(seed, 1), &sa);
      visible_fractions(ev, b, a, &occluders, rays, detail::mix_seed(seed, 2), &sb);
    }
  }
  a_from_b->factor = sa.factor;
  b_from_a->factor = sb.factor;
  a_from_b->weight = source_weights(sb, b.area);
  b_from_a->weight = source_weights(sa, a.area);
}

NearFieldRules::NearFieldRules(const FormFactorEvaluator& ev, const ElementHierarchy& h,
                               std::span<const NodeId> receivers, std::span<const NodeId> sources) {
  // The near pairs whose points stray, each end's list of such partners.
  std::unordered_map<NodeId, std::vector<NodeId>> partners;
  // As for the contour kernel's graded cells: only polygons floating in front of each other, no
  // vertex on the other's plane. Pairs that touch (a block on a floor, walls at a corner) keep their
  // nine points, whose quadrature there errs by a few percent, not by the factor's whole size.
  auto floats_in_front = [&](const ElementNode& r, const ElementNode& s) {
    const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
    const std::span<const Vec3> rv = r.polygon();
    double size = 0.0;
    for (const Vec3& v : rv) size = std::max(size, (v - rv[0]).norm());
    for (const Vec3& v : s.polygon())
      if (!((v - rv[0]).dot(n) > kContactTolerance * size)) return false;
    return true;
  };
  auto strays = [&](const ElementNode& r, const ElementNode& s) {
    const PointFactors p = point_factors(ev, r, s.polygon());
    double area = 0.0, mean = 0.0;
    for (int i = 0; i < p.points.count; ++i) {
      area += p.points.weight[static_cast<std::size_t>(i)];
      mean += p.points.weight[static_cast<std::size_t>(i)] * p.factor[static_cast<std::size_t>(i)];
    }
    const double exact = ev.analytic(r.polygon(), s.polygon()).from_to;
    return std::abs(mean / area - exact) > kNearFieldStray * exact;
  };
  // The test is symmetric: where the receivers are the sources (the full matrix), each pair once.
  const bool same = receivers.data() == sources.data() && receivers.size() == sources.size();
  for (std::size_t x = 0; x < receivers.size(); ++x)
    for (std::size_t y = same ? x + 1 : 0; y < sources.size(); ++y) {
      const NodeId i = receivers[x], j = sources[y];
      const ElementNode& a = h.node(i);
      const ElementNode& b = h.node(j);
      if (i == j || a.patch == b.patch || ev.faces_away(a.polygon(), b.polygon())) continue;
      if (FormFactorEvaluator::separated(a.polygon(), b.polygon(), 1.0) &&
          FormFactorEvaluator::separated(b.polygon(), a.polygon(), 1.0))
        continue;
      if (!floats_in_front(a, b) && !floats_in_front(b, a)) continue;
      if (!strays(a, b) && !strays(b, a)) continue;
      partners[i].push_back(j);
      partners[j].push_back(i);
    }
  std::vector<std::pair<NodeId, std::vector<NodeId>>> work(partners.begin(), partners.end());
  std::sort(work.begin(), work.end());
  std::vector<std::vector<RulePoint>> rules(work.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const ElementNode& r = h.node(work[k].first);
                        std::vector<NodeId>& list = work[k].second;
                        std::sort(list.begin(), list.end());
                        list.erase(std::unique(list.begin(), list.end()), list.end());
                        std::vector<std::vector<Vec3>> near;
                        for (const NodeId s : list)
                          near.emplace_back(h.node(s).polygon().begin(), h.node(s).polygon().end());
                        const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
                        rules[k] = near_field_rule(ev, r.polygon(), n, near, kNearFieldRuleTolerance * r.area);
                      }
                    });
  for (std::size_t k = 0; k < work.size(); ++k) rules_.emplace(work[k].first, std::move(rules[k]));
}

void apply_near_field_rules(const FormFactorEvaluator& ev, const ElementHierarchy& h, const NearFieldRules& rules,
                            FieldLinks& links) {
  std::unordered_map<NodeId, std::size_t> source_index;
  for (std::size_t j = 0; j < links.sources().size(); ++j) source_index.emplace(links.sources()[j], j);
  std::vector<std::size_t> ruled;  // receivers with a rule
  for (std::size_t i = 0; i < links.receivers().size(); ++i)
    if (rules.rule(links.receivers()[i]) != nullptr) ruled.push_back(i);
  // A pair's class and occluders, once for both of its directions.
  struct Shaft {
    bool partial = false;
    std::vector<int> occluders;
  };
  // The moments of the factor from r to q by r's rule, its visibility by one ray a point where the
  // pair is partly visible.
  auto by_rule = [&](NodeId r_id, NodeId q_id, std::uint64_t stream, std::unordered_map<NodeId, Shaft>& shafts) {
    const ElementNode& r = h.node(r_id);
    const ElementNode& q = h.node(q_id);
    const auto [it, fresh] = shafts.try_emplace(q_id);
    if (fresh && ev.effects().visibility)
      it->second.partial = ev.classify(r.polygon(), r.patch, q.polygon(), q.patch, nullptr, &it->second.occluders) ==
                           PairClass::kPartial;
    const Vec3& n = ev.scene().patches[static_cast<std::size_t>(r.patch)].normal;
    return rule_moments(ev, *rules.rule(r_id), n, r.patch, q.polygon(), q.patch, &it->second.occluders,
                        it->second.partial,
                        detail::mix_seed(ev.pair_seed(r.polygon(), r.patch, q.polygon(), q.patch), stream));
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ruled.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const std::size_t i = ruled[k];
                        const NodeId r = links.receivers()[i];
                        const SimpsonPoints points = simpson_points(h.node(r).polygon());
                        std::unordered_map<NodeId, Shaft> shafts;
                        // What r gathers from each source it sees.
                        for (std::size_t j = 0; j < links.sources().size(); ++j) {
                          FieldEntry& e = links.entry(i, j);
                          if (e.factor == std::array<double, 9>{}) continue;  // coplanar, facing away or hidden
                          match_linear_moments(points, by_rule(r, links.sources()[j], kGatherStream, shafts), &e.factor);
                        }
                        // What r sends to each receiver that sees it: weights shaped as the rule's moments, summing to
                        // 1 (a uniform radiosity still sends itself).
                        const auto as_source = source_index.find(r);
                        if (as_source == source_index.end()) continue;
                        for (std::size_t m = 0; m < links.receivers().size(); ++m) {
                          FieldEntry& e = links.entry(m, as_source->second);
                          if (e.weight == std::array<double, 9>{}) continue;
                          std::array<double, 4> t = by_rule(r, links.receivers()[m], kSendStream, shafts);
                          double sum = 0.0;
                          for (const double v : t) sum += v;
                          if (!(sum > 0.0)) continue;
                          for (double& v : t) v /= sum;
                          match_linear_moments(points, t, &e.weight);
                          if (points.count == 7) e.weight[6] = 0.0;  // not a basis function
                        }
                      }
                    });
}

const std::vector<RulePoint>* NearFieldRules::rule(NodeId n) const {
  const auto it = rules_.find(n);
  return it == rules_.end() ? nullptr : &it->second;
}

FieldLinks::FieldLinks(std::vector<NodeId> receivers, std::vector<NodeId> sources)
    : receivers_(std::move(receivers)),
      sources_(std::move(sources)),
      entries_(receivers_.size() * sources_.size(), FieldEntry{}) {}

void FieldLinks::gather(NodeField& field) const {
  const std::size_t cols = sources_.size();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers_.size(), 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        PointValues& h = field.irradiance[static_cast<std::size_t>(receivers_[i])];
                        const FieldEntry* row = entries_.data() + i * cols;
                        for (std::size_t j = 0; j < cols; ++j) {
                          const FieldEntry& e = row[j];
                          const PointValues& m = field.radiosity_moments[static_cast<std::size_t>(sources_[j])];
                          Rgb b = Rgb::Zero();
                          for (int k = 0; k < 9; ++k)
                            b += e.weight[static_cast<std::size_t>(k)] * m[static_cast<std::size_t>(k)];
                          for (int k = 0; k < 9; ++k)
                            h[static_cast<std::size_t>(k)] += e.factor[static_cast<std::size_t>(k)] * b;
                        }
                      }
                    });
}

}  // namespace hrad
