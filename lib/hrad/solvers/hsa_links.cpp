#include "hrad/solvers/hsa_links.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>


namespace hrad {

HsaLinks::HsaLinks(const std::vector<Link>& links, const ElementHierarchy& h, const ClusterTree* tree,
                   const ClusterTransfer& geometry)
    : elements_(h.size()), tree_(tree), h_(h) {
  const std::size_t elements = h.size();
  const std::size_t n = elements + (tree != nullptr ? tree->size() : 0);
  auto dense = [&](NodeRef r) { return is_cluster(r) ? elements + static_cast<std::size_t>(cluster_index(r)) : static_cast<std::size_t>(r); };
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
  links_.resize(offsets_[n]);
  cluster_links_.resize(cluster_offsets_[n]);
  std::vector<std::uint64_t> cursor(offsets_.begin(), offsets_.end() - 1);
  std::vector<std::uint64_t> cluster_cursor(cluster_offsets_.begin(), cluster_offsets_.end() - 1);
  for (const Link& l : links) {
    const std::size_t dp = dense(l.p), dq = dense(l.q);
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
          for (int k = 0; k < (s.vertex_count == 4 ? 9 : 6); ++k) d.weight[k] = static_cast<float>(1.0 / s.area);
        }
        return d;
      };
      if (l.f_pq > 0.0) links_[cursor[dp]++] = directed(dq, l.shape_p, l.source_q, l.f_pq);
      if (l.f_qp > 0.0) links_[cursor[dq]++] = directed(dp, l.shape_q, l.source_p, l.f_qp);
      continue;
    }
    const Vec3 d = (geometry.shape(l.q).centre - geometry.shape(l.p).centre).normalized();  // p towards q
    const std::array<float, 3> to_q = {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())};
    const std::array<float, 3> to_p = {-to_q[0], -to_q[1], -to_q[2]};
    if (l.f_pq > 0.0) cluster_links_[cluster_cursor[dp]++] = {static_cast<std::int32_t>(dq), static_cast<float>(l.f_pq), to_q};
    if (l.f_qp > 0.0) cluster_links_[cluster_cursor[dq]++] = {static_cast<std::int32_t>(dp), static_cast<float>(l.f_qp), to_p};
  }
}

std::uint64_t HsaLinks::bytes() const {
  return links_.capacity() * sizeof(DirectedLink) + cluster_links_.capacity() * sizeof(ClusterLink) +
         (offsets_.capacity() + cluster_offsets_.capacity()) * sizeof(std::uint64_t);
}

Rgb HsaLinks::shown(const NodeField& field, std::size_t source, const std::array<float, 3>& towards) const {
  if (source < elements_) return field.radiosity[source];
  // A cluster shows towards u the mean of its surfaces' radiosity weighted by their projected area
  // towards u, from the per-axis means (Sillion 1995).
  const std::size_t c = source - elements_;
  const Cluster& k = tree_->cluster(static_cast<int>(c));
  Rgb sum = Rgb::Zero();
  double weight = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double ua = towards[a];
    const double w = ua > 0.0 ? ua * k.axis_plus[a] : -ua * k.axis_minus[a];
    sum += w * field.shown[c][ua > 0.0 ? a : 3 + a];
    weight += w;
  }
  return weight > 0.0 ? Rgb(sum / weight) : field.radiosity[source];
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
        for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
          const ClusterLink& l = cluster_links_[k];
          const std::array<float, 3> back = {-l.to_source[0], -l.to_source[1], -l.to_source[2]};
          sum += static_cast<double>(l.factor) * shown(field, static_cast<std::size_t>(l.source), back);
        }
        add_constant(h, sum);
        continue;
      }
      // A cluster receives the link's power A_R F B_S, spread over its surfaces by their projected
      // area towards the source, per signed axis, so that what its surfaces get sums to that power
      // (Sillion 1995, oriented receivers; exact for axis-aligned surfaces in the far field).
      const std::size_t c = i - elements_;
      const Cluster& kc = tree_->cluster(static_cast<int>(c));
      AxisBins& bins = field.received[c];
      for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
        const ClusterLink& l = cluster_links_[k];
        const std::array<float, 3> back = {-l.to_source[0], -l.to_source[1], -l.to_source[2]};
        double facing = 0.0;
        for (int a = 0; a < 3; ++a)
          facing += l.to_source[a] > 0.0f ? l.to_source[a] * kc.axis_plus[a] : -l.to_source[a] * kc.axis_minus[a];
        if (!(facing > 0.0)) continue;
        const Rgb power = (static_cast<double>(l.factor) * kc.area / facing) * shown(field, static_cast<std::size_t>(l.source), back);
        for (int a = 0; a < 3; ++a) {
          const double da = l.to_source[a];
          if (da > 0.0) bins[a] += da * power;
          else if (da < 0.0) bins[3 + a] += -da * power;
        }
      }
    }
  });
}

}  // namespace hrad
