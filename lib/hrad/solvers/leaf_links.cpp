#include "hrad/solvers/leaf_links.h"

#include <array>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/core/error.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

// A_p F(p -> q) = A_q F(q -> p) (the links are reciprocal by construction).
double exchange_of(const ElementHierarchy& h, const Link& link) { return h.node(link.p).area * link.f_pq; }

// Leaves this small against their distance to the link's other side take the one-point rule
// (receiver_factor_by_distance()).
constexpr double kLeafCentroidRatio = 0.03;

}  // namespace

LeafLinks::LeafLinks(const ElementHierarchy& h, const FormFactorEvaluator& evaluator, std::span<const Link> pairs)
    : nodes_(h.size()) {
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
  out.weight_.resize(total);
  std::vector<std::uint8_t> uniform(2 * pairs.size(), 0);  // per side: HSA's uniform push and mean
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
                        resolve(pair.p, pair.q, pair.f_pq, exchange, e.p_first, uniform[2 * i]);
                        resolve(pair.q, pair.p, pair.f_qp, exchange, e.q_first, uniform[2 * i + 1]);
                      }
                    });
  // Grouped by leaf for the gather (a stable counting sort keeps entry order within a leaf).
  out.leaf_offsets_.assign(h.size() + 1, 0);
  for (const NodeId l : out.leaf_) ++out.leaf_offsets_[static_cast<std::size_t>(l) + 1];
  for (std::size_t i = 0; i < h.size(); ++i) out.leaf_offsets_[i + 1] += out.leaf_offsets_[i];
  out.factor_.resize(total);
  out.other_side_.resize(total);
  std::vector<std::uint64_t> cursor(out.leaf_offsets_.begin(), out.leaf_offsets_.end() - 1);
  for (std::size_t k = 0; k < out.pairs_.size(); ++k) {
    const Pair& e = out.pairs_[k];
    for (std::size_t side = 0; side < 2; ++side) {
      const auto [first, end] = e.side(side);
      for (std::size_t i = first; i < end; ++i) {
        const std::uint64_t to = cursor[static_cast<std::size_t>(out.leaf_[i])]++;
        out.factor_[to] = out.weight_[i];
        out.other_side_[to] = static_cast<std::uint32_t>(2 * k + side);  // p entries gather q's mean
      }
    }
  }
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
         other_side_.capacity() * sizeof(std::uint32_t);
}

void LeafLinks::gather(NodeField& field) const {
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
