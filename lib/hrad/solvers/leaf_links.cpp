#include "hrad/solvers/leaf_links.h"

#include <array>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/core/error.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/formfactor/simpson_rule.h"
#include "hrad/geometry/polygon.h"
#include "hrad/solvers/field_links.h"
#include "hrad/solvers/linear_basis.h"
#include "hrad/solvers/push_pull.h"

namespace hrad {
namespace {

// A_p F(p -> q) = A_q F(q -> p) (the links are reciprocal by construction).
double exchange_of(const ElementHierarchy& h, const Link& link) { return h.node(link.p).area * link.f_pq; }

// Leaves this small against their distance to the link's other side take the one-point rule
// (receiver_factor_by_distance()).
constexpr double kLeafCentroidRatio = 0.03;

// A field over node `top` (PointValues order) restricted to its descendant `n`, through the
// children on the way down (push_pull.h restrict_to_child()).
std::array<double, 9> shape_below(const ElementHierarchy& h, NodeId top, NodeId n, const std::array<double, 9>& field) {
  if (n == top) return field;
  const ElementNode& node = h.node(n);
  const ElementNode& parent = h.node(node.parent);
  return restrict_to_child(shape_below(h, top, node.parent, field), node.vertex_count, parent.split,
                           n - parent.first_child);
}

}  // namespace

LeafLinks::LeafLinks(const ElementHierarchy& h, const FormFactorEvaluator& evaluator, std::span<const Link> pairs,
                     bool fields)
    : nodes_(h.size()), fields_(fields) {
  LeafLinks& out = *this;
  out.pairs_.reserve(pairs.size());
  std::vector<std::vector<NodeId>> leaves_of(h.size());  // memoised leaves_below of interior nodes
  auto count = [&](NodeId id) -> std::size_t {
    if (h.node(id).is_leaf()) return 1;
    std::vector<NodeId>& l = leaves_of[static_cast<std::size_t>(id)];
    if (l.empty()) l = h.leaves_below(id);
    return l.size();
  };
  std::size_t total = 0;
  for (const Link& pair : pairs) {
    Pair e;
    e.p_first = total;
    e.p_count = count(pair.p);
    e.q_first = total + e.p_count;
    e.q_count = count(pair.q);
    total += e.p_count + e.q_count;
    out.pairs_.push_back(e);
  }
  if (2 * pairs.size() >= (std::size_t{1} << 32))
    throw Error(fmt::format("hierarchical: {} link pairs exceed the leaf gather's 32-bit side index", pairs.size()));
  // Each entry is written once below, so the arrays are left uninitialised (BigVector) and the
  // scaled factors wait in `weight` until grouped by leaf: 20 bytes per entry at the peak, not 32
  // (201 M entries at aeps = total/50000 on the Cornell box, where first touching memory is slow).
  out.leaf_.resize(total);
  if (fields) {
    out.points_.resize(total);
    out.inverse_integral_.resize(2 * pairs.size());
    out.functions_.resize(h.size());
    for (std::size_t i = 0; i < h.size(); ++i)
      out.functions_[i] = h.node(static_cast<NodeId>(i)).vertex_count == 4 ? 9 : 6;
  } else {
    out.weight_.resize(total);
  }
  std::vector<std::uint8_t> uniform(2 * pairs.size(), 0);  // per side: HSA's uniform push and mean
  // One side with fields: each leaf's exact point factors times the link's visible fraction (so a
  // point's factors to sources that tile a closed room sum to 1), and the side sends its leaves'
  // moments weighed by them over their integral against the basis (a uniform side sends its
  // radiosity). Where none of them sees the other side, every point takes f_rs and the side sends
  // its area-weighted mean. Returns 1 / that integral (0: the side sends nothing).
  auto resolve_fields = [&](const Link& link, bool p_side, std::size_t first) {
    const NodeId r = p_side ? link.p : link.q, s = p_side ? link.q : link.p;
    const double f_rs = p_side ? link.f_pq : link.f_qp;
    const bool leaf = h.node(r).is_leaf();
    const std::span<const NodeId> l =
        leaf ? std::span<const NodeId>(&r, 1) : std::span<const NodeId>(leaves_of[static_cast<std::size_t>(r)]);
    const std::span<const Vec3> source = h.node(s).polygon();
    std::array<double, 9> shape{};
    if (link.partial && link.shaped)
      for (std::size_t m = 0; m < 9; ++m) shape[m] = (p_side ? link.shape_p : link.shape_q)[m];
    double integral = 0.0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const ElementNode& n = h.node(l[k]);
      const SimpsonPoints points = simpson_points(n.polygon());
      std::array<double, 9> f{};
      if (link.partial && link.shaped) {
        f = shape_below(h, r, l[k], shape);
      } else {
        f = point_factors(evaluator, n, source).factor;
        for (double& v : f) v *= link.fraction;
      }
      const std::array<double, 9> b = basis_integrals(points, n.area);
      for (int m = 0; m < basis_functions(points); ++m)
        integral += b[static_cast<std::size_t>(m)] * f[static_cast<std::size_t>(m)];
      std::array<float, 9>& to = out.points_[first + k];
      to.fill(0.0f);
      for (int m = 0; m < points.count; ++m)
        to[static_cast<std::size_t>(m)] = static_cast<float>(f[static_cast<std::size_t>(m)]);
      out.leaf_[first + k] = l[k];
    }
    if (integral > 0.0) return 1.0 / integral;
    const double exchange = h.node(r).area * f_rs;
    for (std::size_t k = 0; k < l.size(); ++k) {
      std::array<float, 9>& to = out.points_[first + k];
      const int count = h.node(l[k]).vertex_count == 4 ? 9 : 7;
      for (int m = 0; m < count; ++m) to[static_cast<std::size_t>(m)] = static_cast<float>(f_rs);
    }
    return exchange > 0.0 ? 1.0 / exchange : 0.0;
  };
  // One side: leaves below `r` against `s`, whose total exchange A_r F(r -> s) is `exchange`.
  // Writes the leaves' scaled factors to weight[first, ...).
  auto resolve = [&](NodeId r, NodeId s, double f_rs, double exchange, std::size_t first, std::uint8_t& flat) {
    const ElementNode& rn = h.node(r);
    if (rn.is_leaf()) {
      out.leaf_[first] = r;
      out.weight_[first] = f_rs;
      flat = 1;  // weight area / area = 1
      return;
    }
    const std::vector<NodeId>& l = leaves_of[static_cast<std::size_t>(r)];
    const std::span<const Vec3> source = h.node(s).polygon();
    double weighted = 0.0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const ElementNode& leaf = h.node(l[k]);
      const double f = evaluator.receiver_factor(leaf.polygon(), source, kLeafCentroidRatio);
      out.leaf_[first + k] = l[k];
      out.weight_[first + k] = f;
      weighted += leaf.area * f;
    }
    // Scaled to the link's exact exchange (visible fraction included); where the rule sees
    // nothing (the source grazes every leaf), HSA's uniform push and area-weighted mean.
    flat = !(exchange > 0.0) || !(weighted > 0.0);
    for (std::size_t k = 0; k < l.size(); ++k) {
      double& f = out.weight_[first + k];
      if (!(exchange > 0.0))
        f = 0.0;  // linked with a sampled visible fraction of 0
      else if (weighted > 0.0)
        f *= exchange / weighted;
      else
        f = f_rs;
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const Link& pair = pairs[i];
                        const Pair& e = out.pairs_[i];
                        const double exchange = exchange_of(h, pair);
                        if (fields) {
                          out.inverse_integral_[2 * i + 1] = resolve_fields(pair, true, e.p_first);
                          out.inverse_integral_[2 * i] = resolve_fields(pair, false, e.q_first);
                          continue;
                        }
                        resolve(pair.p, pair.q, pair.f_pq, exchange, e.p_first, uniform[2 * i]);
                        resolve(pair.q, pair.p, pair.f_qp, exchange, e.q_first, uniform[2 * i + 1]);
                      }
                    });
  // Grouped by leaf for the gather (a stable counting sort keeps entry order within a leaf).
  out.leaf_offsets_.assign(h.size() + 1, 0);
  for (const NodeId l : out.leaf_) ++out.leaf_offsets_[static_cast<std::size_t>(l) + 1];
  for (std::size_t i = 0; i < h.size(); ++i) out.leaf_offsets_[i + 1] += out.leaf_offsets_[i];
  (fields ? out.entry_.resize(total) : out.factor_.resize(total));
  out.other_side_.resize(total);
  std::vector<std::uint64_t> cursor(out.leaf_offsets_.begin(), out.leaf_offsets_.end() - 1);
  for (std::size_t k = 0; k < out.pairs_.size(); ++k) {
    const Pair& e = out.pairs_[k];
    for (std::size_t side = 0; side < 2; ++side) {
      const auto [first, end] = e.side(side);
      for (std::size_t i = first; i < end; ++i) {
        const std::uint64_t to = cursor[static_cast<std::size_t>(out.leaf_[i])]++;
        if (fields)
          out.entry_[to] = i;
        else
          out.factor_[to] = out.weight_[i];
        out.other_side_[to] = static_cast<std::uint32_t>(2 * k + side);  // p entries gather q's mean
      }
    }
  }
  if (fields) return;
  // The weights: each leaf's share A_leaf f / (A_p F(p -> q)) of its side's exchange, or its area
  // share where the side is uniform.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, pairs.size(), 64), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const Link& pair = pairs[i];
          const Pair& e = out.pairs_[i];
          const double exchange = exchange_of(h, pair);
          for (std::size_t side = 0; side < 2; ++side) {
            const auto [first, end] = e.side(side);
            const double side_area = h.node(side == 0 ? pair.p : pair.q).area;
            for (std::size_t k = first; k < end; ++k) {
              const double area = h.node(out.leaf_[k]).area;
              out.weight_[k] = uniform[2 * i + side] ? area / side_area : area * out.weight_[k] / exchange;
            }
          }
        }
      });
}

std::uint64_t LeafLinks::bytes() const {
  return pairs_.capacity() * sizeof(Pair) + leaf_.capacity() * sizeof(NodeId) + weight_.capacity() * sizeof(double) +
         leaf_offsets_.capacity() * sizeof(std::uint64_t) + factor_.capacity() * sizeof(double) +
         other_side_.capacity() * sizeof(std::uint32_t) + points_.capacity() * sizeof(points_[0]) +
         entry_.capacity() * sizeof(std::uint64_t) + inverse_integral_.capacity() * sizeof(double) +
         functions_.capacity();
}

void LeafLinks::gather_fields(NodeField& field) const {
  // What each side sends: its leaves' point factors against their moments, over their integral.
  auto sent = [&](std::size_t first, std::size_t n, double inverse_integral) {
    std::array<double, 3> b{};
    for (std::size_t k = first; k < first + n; ++k) {
      const std::size_t leaf = static_cast<std::size_t>(leaf_[k]);
      const PointValues& m = field.radiosity_moments[leaf];
      for (int j = 0; j < functions_[leaf]; ++j) {
        const double f = points_[k][static_cast<std::size_t>(j)];
        for (int c = 0; c < 3; ++c) b[static_cast<std::size_t>(c)] += f * m[static_cast<std::size_t>(j)][c];
      }
    }
    return Rgb(b[0] * inverse_integral, b[1] * inverse_integral, b[2] * inverse_integral);
  };
  std::vector<Rgb> means(2 * pairs_.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs_.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const Pair& e = pairs_[k];
                        means[2 * k] = sent(e.q_first, e.q_count, inverse_integral_[2 * k]);
                        means[2 * k + 1] = sent(e.p_first, e.p_count, inverse_integral_[2 * k + 1]);
                      }
                    });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nodes_, 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t n = range.begin(); n != range.end(); ++n) {
                        if (leaf_offsets_[n] == leaf_offsets_[n + 1]) continue;
                        PointValues sum;
                        sum.fill(Rgb::Zero());
                        for (std::uint64_t j = leaf_offsets_[n]; j < leaf_offsets_[n + 1]; ++j) {
                          const std::array<float, 9>& f = points_[entry_[j]];
                          const Rgb& b = means[other_side_[j]];
                          for (std::size_t k = 0; k < 9; ++k) sum[k] += static_cast<double>(f[k]) * b;
                        }
                        PointValues& h = field.irradiance[n];
                        for (std::size_t k = 0; k < 9; ++k) h[k] += sum[k];
                      }
                    });
}

void LeafLinks::gather(NodeField& field) const {
  if (fields_) {
    gather_fields(field);
    return;
  }
  auto mean = [&](std::size_t first, std::size_t n) {
    Rgb b = Rgb::Zero();
    for (std::size_t k = first; k < first + n; ++k)
      b += weight_[k] * field.radiosity[static_cast<std::size_t>(leaf_[k])];
    return b;
  };
  // Each side's mean once (index 2 k: pair k's q side, 2 k + 1: its p side), then each leaf adds
  // its terms in entry order: the same bits as a sequential loop over pairs, at any thread count.
  std::vector<Rgb> means(2 * pairs_.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs_.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const Pair& e = pairs_[k];
                        means[2 * k] = mean(e.q_first, e.q_count);
                        means[2 * k + 1] = mean(e.p_first, e.p_count);
                      }
                    });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nodes_, 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t n = range.begin(); n != range.end(); ++n) {
                        Rgb sum = Rgb::Zero();
                        for (std::uint64_t j = leaf_offsets_[n]; j < leaf_offsets_[n + 1]; ++j)
                          sum += factor_[j] * means[other_side_[j]];
                        add_constant(field.irradiance[n], sum);
                      }
                    });
}

}  // namespace hrad
