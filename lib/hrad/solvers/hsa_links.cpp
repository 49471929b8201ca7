#include "hrad/solvers/hsa_links.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hrad {
namespace {

// Links per chunk of the parallel build: a fixed size, so that the weights' order does not depend
// on the thread count.
constexpr std::size_t kBuildChunk = 2048;

}  // namespace

HsaLinks::HsaLinks(const LinkVector& links, const ElementHierarchy& h, const ClusterTree* tree,
                   const ClusterTransfer& geometry)
    : elements_(h.size()), scene_(geometry.scene()), tree_(tree), h_(h) {
  const std::size_t elements = h.size();
  const std::size_t n = elements + (tree != nullptr ? tree->size() : 0);
  auto dense = [&](NodeRef r) {
    return is_cluster(r) ? elements + static_cast<std::size_t>(cluster_index(r)) : static_cast<std::size_t>(r);
  };
  auto with_cluster = [](const Link& l) { return is_cluster(l.p) || is_cluster(l.q); };
  offsets_.assign(n + 1, 0);
  cluster_offsets_.assign(n + 1, 0);
  for (const Link& l : links) {
    auto& off = with_cluster(l) ? cluster_offsets_ : offsets_;
    if (l.f_pq > 0.0) ++off[dense(l.p) + 1];
    if (l.f_qp > 0.0) ++off[dense(l.q) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) {
    offsets_[i + 1] += offsets_[i];
    cluster_offsets_[i + 1] += cluster_offsets_[i];
  }
  // Each link's places, in link order within its receivers' ranges: slot[2 i] for p's direction,
  // slot[2 i + 1] for q's. 32 bits: four billion directed links would need 300 GB.
  if (std::max(offsets_[n], cluster_offsets_[n]) > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("hierarchical: more than 2^32 directed links of one kind");
  links_.resize(offsets_[n]);
  cluster_links_.resize(cluster_offsets_[n]);
  std::vector<std::uint32_t> slot(2 * links.size());
  {
    std::vector<std::uint64_t> cursor(offsets_.begin(), offsets_.end() - 1);
    std::vector<std::uint64_t> cluster_cursor(cluster_offsets_.begin(), cluster_offsets_.end() - 1);
    for (std::size_t i = 0; i < links.size(); ++i) {
      const Link& l = links[i];
      auto& at = with_cluster(l) ? cluster_cursor : cursor;
      if (l.f_pq > 0.0) slot[2 * i] = static_cast<std::uint32_t>(at[dense(l.p)]++);
      if (l.f_qp > 0.0) slot[2 * i + 1] = static_cast<std::uint32_t>(at[dense(l.q)]++);
    }
  }
  auto patches = [&](NodeRef r) { return is_cluster(r) ? tree->patches(cluster_index(r)).size() : std::size_t{0}; };
  if (tree != nullptr && tree->size() > 0) {
    position_.assign(scene_.patches.size(), 0);
    const std::span<const int> all = tree->patches(0);
    for (std::size_t k = 0; k < all.size(); ++k) position_[static_cast<std::size_t>(all[k])] = static_cast<int>(k);
  }
  // The links in chunks of a fixed size, in parallel. A chunk's cluster-end weights go to a buffer
  // of its own, placed after the earlier chunks' when all are done: weights_ is in link order at
  // any thread count.
  struct Chunk {
    std::vector<float> weights;
    std::uint64_t terms = 0;
    bool cluster_receivers = false;
  };
  const std::size_t chunks = (links.size() + kBuildChunk - 1) / kBuildChunk;
  std::vector<Chunk> chunk(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    Chunk& out = chunk[k];
    for (std::size_t i = k * kBuildChunk, end = std::min(links.size(), i + kBuildChunk); i < end; ++i) {
      const Link& l = links[i];
      if (!with_cluster(l)) {
        auto directed = [&](std::size_t source, const std::array<float, 9>& shape, const std::array<float, 9>& weight,
                            double f) {
          DirectedLink d{static_cast<std::int32_t>(source), shape, weight};
          if (!l.shaped) {
            // A flat field on both sides: the source's radiosity integral (the moments' sum over its
            // basis, whose functions sum to 1) over its area.
            d.factor.fill(static_cast<float>(f));
            const ElementNode& s = h_.node(static_cast<NodeId>(source));
            d.weight.fill(0.0f);
            for (int j = 0; j < (s.vertex_count == 4 ? 9 : 6); ++j) d.weight[j] = static_cast<float>(1.0 / s.area);
          }
          return d;
        };
        if (l.f_pq > 0.0) links_[slot[2 * i]] = directed(dense(l.q), l.shape_p, l.source_q, l.f_pq);
        if (l.f_qp > 0.0) links_[slot[2 * i + 1]] = directed(dense(l.p), l.shape_q, l.source_p, l.f_qp);
        continue;
      }
      // Each cluster end's two weights, once for both directions (hsa_links.h ClusterLink), at
      // offsets within the chunk's buffer.
      struct EndWeights {
        std::uint64_t gets = 0, sends = 0;
        double w_gets = 0.0;
      };
      auto end_weights = [&](NodeRef end, NodeRef other, const ShadedPatches* shaded) {
        EndWeights e;
        if (!is_cluster(end)) return e;
        e.sends = out.weights.size();
        const double w_sends = geometry.link_weights(end, other, shaded, &out.weights, LinkWeights::kSends);
        if (w_sends > 0.0) {
          e.gets = e.sends, e.w_gets = w_sends;
          return e;
        }
        // No ray of the end's own reached the other end: by the patches' facing weights.
        e.gets = out.weights.size();
        e.w_gets = geometry.link_weights(end, other, shaded, &out.weights, LinkWeights::kGets);
        return e;
      };
      const EndWeights end_p = end_weights(l.p, l.q, l.hidden_p.get());
      const EndWeights end_q = end_weights(l.q, l.p, l.hidden_q.get());
      auto directed = [&](NodeRef receiver, NodeRef source, double f, const EndWeights& r, const EndWeights& s) {
        const double area = geometry.shape(receiver).area;
        const double sent = is_cluster(source) ? 1.0 : f * area;  // per unit of shown()
        ClusterLink c{static_cast<std::int32_t>(dense(source)), static_cast<float>(sent / area), r.gets, s.sends};
        if (is_cluster(receiver)) {
          c.factor = r.w_gets > 0.0 ? static_cast<float>(sent / r.w_gets) : 0.0f;
          out.cluster_receivers = true;
        }
        out.terms += 1 + patches(receiver) + patches(source);
        return c;
      };
      if (l.f_pq > 0.0) cluster_links_[slot[2 * i]] = directed(l.p, l.q, l.f_pq, end_p, end_q);
      if (l.f_qp > 0.0) cluster_links_[slot[2 * i + 1]] = directed(l.q, l.p, l.f_qp, end_q, end_p);
    }
  });
  std::vector<std::uint64_t> base(chunks + 1, 0);
  for (std::size_t k = 0; k < chunks; ++k) {
    base[k + 1] = base[k] + chunk[k].weights.size();
    cluster_terms_ += chunk[k].terms;
    cluster_receivers_ = cluster_receivers_ || chunk[k].cluster_receivers;
  }
  weights_.resize(base[chunks]);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    std::copy(chunk[k].weights.begin(), chunk[k].weights.end(),
              weights_.begin() + static_cast<std::ptrdiff_t>(base[k]));
    std::vector<float>().swap(chunk[k].weights);
    for (std::size_t i = k * kBuildChunk, end = std::min(links.size(), i + kBuildChunk); i < end; ++i) {
      const Link& l = links[i];
      if (!with_cluster(l)) continue;
      auto place = [&](ClusterLink& c, NodeRef receiver, NodeRef source) {
        if (is_cluster(receiver)) c.receiver_q += base[k];
        if (is_cluster(source)) c.source_q += base[k];
      };
      if (l.f_pq > 0.0) place(cluster_links_[slot[2 * i]], l.p, l.q);
      if (l.f_qp > 0.0) place(cluster_links_[slot[2 * i + 1]], l.q, l.p);
    }
  });
  if (cluster_receivers_) carried_.assign(cluster_links_.size(), Rgb::Zero());
}

std::uint64_t HsaLinks::bytes() const {
  return links_.capacity() * sizeof(DirectedLink) + cluster_links_.capacity() * sizeof(ClusterLink) +
         (offsets_.capacity() + cluster_offsets_.capacity()) * sizeof(std::uint64_t) +
         carried_.capacity() * sizeof(Rgb) + weights_.capacity() * sizeof(float) + position_.capacity() * sizeof(int);
}

std::vector<double> HsaLinks::cluster_sends() const {
  std::vector<double> out(elements_, 0.0);
  const std::size_t n = cluster_offsets_.size() - 1;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
      const ClusterLink& l = cluster_links_[k];
      const std::size_t source = static_cast<std::size_t>(l.source);
      // What the receiver gets per unit of shown(): A_R times the factor for an element receiver;
      // for a cluster receiver the factor times W = sum_j A_j q_j, shared among its patches.
      double delivered = 0.0;
      if (i < elements_) {
        delivered = h_.node(static_cast<NodeId>(i)).area * static_cast<double>(l.factor);
      } else {
        const float* g = weights_.data() + l.receiver_q;
        double w = 0.0;
        for (const int patch : tree_->patches(static_cast<int>(i - elements_)))
          w += scene_.patches[static_cast<std::size_t>(patch)].area * static_cast<double>(*g++);
        delivered = static_cast<double>(l.factor) * w;
      }
      if (source < elements_) {
        // shown() = B of the element; per unit of its area.
        out[source] += delivered / h_.node(static_cast<NodeId>(source)).area;
        continue;
      }
      const float* q = weights_.data() + l.source_q;
      for (const int patch : tree_->patches(static_cast<int>(source - elements_))) {
        const double w = static_cast<double>(*q++);
        if (w > 0.0) out[static_cast<std::size_t>(h_.root(patch))] += delivered * w;
      }
    }
  return out;
}

Rgb HsaLinks::shown(const NodeField& field, std::uint64_t k) const {
  const ClusterLink& l = cluster_links_[k];
  const std::size_t source = static_cast<std::size_t>(l.source);
  if (source < elements_) return field.radiosity[source];
  // A cluster sends sum_j A_j q_j B_j: each patch by its own factor to the receiver.
  const float* q = weights_.data() + l.source_q;
  Rgb sum = Rgb::Zero();
  for (const int patch : tree_->patches(static_cast<int>(source - elements_))) {
    const double w = static_cast<double>(*q++);
    if (w > 0.0)
      sum += (scene_.patches[static_cast<std::size_t>(patch)].area * w) *
             field.radiosity[static_cast<std::size_t>(h_.root(patch))];
  }
  return sum;
}

void HsaLinks::gather(NodeField& field) const {
  const std::size_t n = offsets_.size() - 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      if (i < elements_) {
        PointValues& h = field.irradiance[i];
        for (std::uint64_t k = offsets_[i]; k < offsets_[i + 1]; ++k) {
          const DirectedLink& l = links_[k];
          const PointValues& source = field.radiosity_moments[static_cast<std::size_t>(l.source)];
          Rgb b = Rgb::Zero();
          for (int j = 0; j < 9; ++j) b += static_cast<double>(l.weight[j]) * source[j];
          for (int j = 0; j < 9; ++j) h[j] += static_cast<double>(l.factor[j]) * b;
        }
        // An element receives what each source shows towards it.
        Rgb sum = Rgb::Zero();
        for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k)
          sum += static_cast<double>(cluster_links_[k].factor) * shown(field, k);
        add_constant(h, sum);
        continue;
      }
      for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k)
        carried_[k] = static_cast<double>(cluster_links_[k].factor) * shown(field, k);
    }
  });
  if (!cluster_receivers_) return;
  // Each patch's shares of what its clusters received (its weight per unit area, q_j): it joins
  // the irradiance gathered at the patch's root.
  tbb::parallel_for(tbb::blocked_range<int>(0, h_.patch_count(), 64), [&](const tbb::blocked_range<int>& range) {
    for (int p = range.begin(); p != range.end(); ++p) {
      Rgb sum = Rgb::Zero();
      for (int c = tree_->parent_of_patch(p); c >= 0; c = tree_->cluster(c).parent) {
        const std::size_t i = elements_ + static_cast<std::size_t>(c);
        const std::uint64_t index =
            static_cast<std::uint64_t>(position_[static_cast<std::size_t>(p)] - tree_->cluster(c).begin);
        for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
          const double w = static_cast<double>(weights_[cluster_links_[k].receiver_q + index]);
          if (w > 0.0) sum += w * carried_[k];
        }
      }
      add_constant(field.irradiance[static_cast<std::size_t>(h_.root(p))], sum);
    }
  });
}

}  // namespace hrad
