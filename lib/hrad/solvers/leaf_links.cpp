#include "hrad/solvers/hierarchical_leaf_factors.h"

#include <array>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/core/error.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/geometry/polygon.h"

namespace hrad::detail {
namespace {

// A_p F(p -> q) = A_q F(q -> p) (the analytic kernel is reciprocal to rounding).
double exchange_of(const ElementHierarchy& h, const LinkPair& pair) { return h.node(pair.p).area * pair.estimate.value; }

// Leaves this small against their distance to the link's other side take the one-point rule
// (receiver_factor_by_distance()).
constexpr double kLeafCentroidRatio = 0.1;

}  // namespace

LeafLinks leaf_links(const ElementHierarchy& h, std::span<const LinkPair> pairs) {
  LeafLinks out;
  out.pairs.reserve(pairs.size());
  std::vector<std::vector<NodeId>> leaves_of(h.size());  // memoised leaves_below of interior nodes
  auto count = [&](NodeId id) -> std::size_t {
    if (h.node(id).is_leaf()) return 1;
    std::vector<NodeId>& l = leaves_of[static_cast<std::size_t>(id)];
    if (l.empty()) l = h.leaves_below(id);
    return l.size();
  };
  std::size_t total = 0;
  for (const LinkPair& pair : pairs) {
    LeafLinks::Pair e;
    e.p_first = total;
    e.p_count = count(pair.p);
    e.q_first = total + e.p_count;
    e.q_count = count(pair.q);
    total += e.p_count + e.q_count;
    out.pairs.push_back(e);
  }
  if (2 * pairs.size() >= (std::size_t{1} << 32))
    throw Error(fmt::format("hierarchical: {} link pairs exceed the leaf gather's 32-bit side index", pairs.size()));
  // Each entry is written once below, so the arrays are left uninitialised (BigVector) and the
  // scaled factors wait in `weight` until grouped by leaf: 20 bytes per entry at the peak, not 32
  // (201 M entries at aeps = total/50000 on the Cornell box, where first touching memory is slow).
  out.leaf.resize(total);
  out.weight.resize(total);
  std::vector<std::uint8_t> uniform(2 * pairs.size(), 0);  // per side: HSA's uniform push and mean
  // One side: leaves below `r` against `s`, whose total exchange A_r F(r -> s) is `exchange`.
  // Writes the leaves' scaled factors to weight[first, ...).
  auto resolve = [&](NodeId r, NodeId s, double f_rs, double exchange, std::size_t first, std::uint8_t& flat) {
    const ElementNode& rn = h.node(r);
    if (rn.is_leaf()) {
      out.leaf[first] = r;
      out.weight[first] = f_rs;
      flat = 1;  // weight area / area = 1
      return;
    }
    const std::vector<NodeId>& l = leaves_of[static_cast<std::size_t>(r)];
    const std::span<const Vec3> source = h.node(s).polygon();
    double weighted = 0.0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const ElementNode& leaf = h.node(l[k]);
      const double f = receiver_factor_by_distance(leaf.polygon(), source, kLeafCentroidRatio);
      out.leaf[first + k] = l[k];
      out.weight[first + k] = f;
      weighted += leaf.area * f;
    }
    // Scaled to the link's exact exchange (visible fraction included); where the rule sees
    // nothing (the source grazes every leaf), HSA's uniform push and area-weighted mean.
    flat = !(exchange > 0.0) || !(weighted > 0.0);
    for (std::size_t k = 0; k < l.size(); ++k) {
      double& f = out.weight[first + k];
      if (!(exchange > 0.0)) f = 0.0;  // linked with a sampled visible fraction of 0
      else if (weighted > 0.0) f *= exchange / weighted;
      else f = f_rs;
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 8), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const LinkPair& pair = pairs[i];
      const LeafLinks::Pair& e = out.pairs[i];
      const double exchange = exchange_of(h, pair);
      resolve(pair.p, pair.q, pair.estimate.value, exchange, e.p_first, uniform[2 * i]);
      resolve(pair.q, pair.p, pair.estimate.reverse, exchange, e.q_first, uniform[2 * i + 1]);
    }
  });
  // Grouped by leaf for the gather (a stable counting sort keeps entry order within a leaf).
  out.leaf_offsets.assign(h.size() + 1, 0);
  for (const NodeId l : out.leaf) ++out.leaf_offsets[static_cast<std::size_t>(l) + 1];
  for (std::size_t i = 0; i < h.size(); ++i) out.leaf_offsets[i + 1] += out.leaf_offsets[i];
  out.factor.resize(total);
  out.other_side.resize(total);
  std::vector<std::uint64_t> cursor(out.leaf_offsets.begin(), out.leaf_offsets.end() - 1);
  for (std::size_t k = 0; k < out.pairs.size(); ++k) {
    const LeafLinks::Pair& e = out.pairs[k];
    for (std::size_t side = 0; side < 2; ++side) {
      const auto [first, end] = e.side(side);
      for (std::size_t i = first; i < end; ++i) {
        const std::uint64_t to = cursor[static_cast<std::size_t>(out.leaf[i])]++;
        out.factor[to] = out.weight[i];
        out.other_side[to] = static_cast<std::uint32_t>(2 * k + side);  // p entries gather q's mean
      }
    }
  }
  // The weights: each leaf's share A_leaf f / (A_p F(p -> q)) of its side's exchange, or its area
  // share where the side is uniform.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 64), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const LinkPair& pair = pairs[i];
      const LeafLinks::Pair& e = out.pairs[i];
      const double exchange = exchange_of(h, pair);
      for (std::size_t side = 0; side < 2; ++side) {
        const auto [first, end] = e.side(side);
        const double side_area = h.node(side == 0 ? pair.p : pair.q).area;
        for (std::size_t k = first; k < end; ++k) {
          const double area = h.node(out.leaf[k]).area;
          out.weight[k] = uniform[2 * i + side] ? area / side_area : area * out.weight[k] / exchange;
        }
      }
    }
  });
  return out;
}

void gather_leaf_links(ElementHierarchy& h, const LeafLinks& links) {
  auto mean = [&](std::size_t first, std::size_t n) {
    Rgb b = Rgb::Zero();
    for (std::size_t k = first; k < first + n; ++k) b += links.weight[k] * h.node(links.leaf[k]).radiosity;
    return b;
  };
  // Each side's mean once (index 2 k: pair k's q side, 2 k + 1: its p side), then each leaf adds
  // its terms in entry order: the same bits as a sequential loop over pairs, at any thread count.
  std::vector<Rgb> means(2 * links.pairs.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, links.pairs.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        const LeafLinks::Pair& e = links.pairs[k];
                        means[2 * k] = mean(e.q_first, e.q_count);
                        means[2 * k + 1] = mean(e.p_first, e.p_count);
                      }
                    });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, h.size(), 1024), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t n = range.begin(); n != range.end(); ++n) {
      Rgb sum = Rgb::Zero();
      for (std::uint64_t j = links.leaf_offsets[n]; j < links.leaf_offsets[n + 1]; ++j)
        sum += links.factor[j] * means[links.other_side[j]];
      h.node(static_cast<NodeId>(n)).gathered = sum;
    }
  });
}

}  // namespace hrad::detail
