#include "hrad/solvers/hsa_links.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hrad {

HsaLinks::HsaLinks(const std::vector<Link>& links, const ElementHierarchy& h, const ClusterTree* tree,
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
  links_.resize(offsets_[n]);
  cluster_links_.resize(cluster_offsets_[n]);
  receiver_hidden_.resize(cluster_links_.size());
  source_hidden_.resize(cluster_links_.size());
  std::vector<std::uint64_t> cursor(offsets_.begin(), offsets_.end() - 1);
  std::vector<std::uint64_t> cluster_cursor(cluster_offsets_.begin(), cluster_offsets_.end() - 1);
  auto patches = [&](NodeRef r) { return is_cluster(r) ? tree->patches(cluster_index(r)).size() : std::size_t{0}; };
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
    // The direction as stored (in floats) is the one the projected areas are taken towards, so that
    // the shares of a link sum to what it carries.
    const Vec3 exact = (geometry.shape(l.q).centre - geometry.shape(l.p).centre).normalized();  // p towards q
    const std::array<float, 3> to_q = {static_cast<float>(exact.x()), static_cast<float>(exact.y()),
                                       static_cast<float>(exact.z())};
    const std::array<float, 3> to_p = {-to_q[0], -to_q[1], -to_q[2]};
    const Vec3 d(to_q[0], to_q[1], to_q[2]);
    auto directed = [&](NodeRef receiver, NodeRef source, double f, const std::array<float, 3>& to_source,
                        const Vec3& towards_source, const std::shared_ptr<const std::vector<int>>& receiver_hidden,
                        const std::shared_ptr<const std::vector<int>>& source_hidden) {
      ClusterLink c{static_cast<std::int32_t>(dense(source)), static_cast<float>(f), to_source, 0.0f};
      if (is_cluster(receiver)) {
        const double facing = geometry.projected_area(receiver, towards_source, receiver_hidden.get());
        c.factor = facing > 0.0 ? static_cast<float>(f * geometry.shape(receiver).area / facing) : 0.0f;
        cluster_receivers_ = true;
      }
      if (is_cluster(source)) {
        const double shown = geometry.projected_area(source, -towards_source, source_hidden.get());
        c.source_scale = shown > 0.0 ? static_cast<float>(1.0 / shown) : 0.0f;
      }
      cluster_terms_ += 1 + patches(receiver) + patches(source);
      return c;
    };
    if (l.f_pq > 0.0) {
      receiver_hidden_[cluster_cursor[dp]] = l.hidden_p;
      source_hidden_[cluster_cursor[dp]] = l.hidden_q;
      cluster_links_[cluster_cursor[dp]++] = directed(l.p, l.q, l.f_pq, to_q, d, l.hidden_p, l.hidden_q);
    }
    if (l.f_qp > 0.0) {
      receiver_hidden_[cluster_cursor[dq]] = l.hidden_q;
      source_hidden_[cluster_cursor[dq]] = l.hidden_p;
      cluster_links_[cluster_cursor[dq]++] = directed(l.q, l.p, l.f_qp, to_p, -d, l.hidden_q, l.hidden_p);
    }
  }
  for (const Link& l : links)
    for (const auto* hidden : {l.hidden_p.get(), l.hidden_q.get()})
      if (hidden != nullptr) hidden_bytes_ += hidden->capacity() * sizeof(int);
  if (cluster_receivers_) carried_.assign(cluster_links_.size(), Rgb::Zero());
}

std::uint64_t HsaLinks::bytes() const {
  return links_.capacity() * sizeof(DirectedLink) + cluster_links_.capacity() * sizeof(ClusterLink) +
         (offsets_.capacity() + cluster_offsets_.capacity()) * sizeof(std::uint64_t) +
         carried_.capacity() * sizeof(Rgb) +
         (receiver_hidden_.capacity() + source_hidden_.capacity()) * sizeof(std::shared_ptr<const std::vector<int>>) +
         hidden_bytes_;
}

Rgb HsaLinks::shown(const NodeField& field, std::uint64_t k) const {
  const ClusterLink& l = cluster_links_[k];
  const std::size_t source = static_cast<std::size_t>(l.source);
  if (source < elements_) return source_hidden_[k] ? Rgb::Zero() : field.radiosity[source];
  // A cluster shows towards the receiver (-u) the mean of its patches' radiosity weighted by their
  // projected areas that way.
  const std::vector<int>* hidden = source_hidden_[k].get();
  Rgb sum = Rgb::Zero();
  for (const int patch : tree_->patches(static_cast<int>(source - elements_))) {
    if (hidden != nullptr && std::binary_search(hidden->begin(), hidden->end(), patch)) continue;
    const Patch& p = scene_.patches[static_cast<std::size_t>(patch)];
    const double w = facing_cosine(p.normal, Vec3(-l.to_source[0], -l.to_source[1], -l.to_source[2]));
    if (w > 0.0) sum += (p.area * w) * field.radiosity[static_cast<std::size_t>(h_.root(patch))];
  }
  return static_cast<double>(l.source_scale) * sum;
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
          if (!receiver_hidden_[k]) sum += static_cast<double>(cluster_links_[k].factor) * shown(field, k);
        add_constant(h, sum);
        continue;
      }
      for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k)
        carried_[k] = static_cast<double>(cluster_links_[k].factor) * shown(field, k);
    }
  });
  if (!cluster_receivers_) return;
  // Each patch's shares of what its clusters received (Sillion 1995, oriented receivers with each
  // patch's exact projected area): it joins the irradiance gathered at the patch's root.
  tbb::parallel_for(tbb::blocked_range<int>(0, h_.patch_count(), 64), [&](const tbb::blocked_range<int>& range) {
    for (int p = range.begin(); p != range.end(); ++p) {
      const Vec3& n = scene_.patches[static_cast<std::size_t>(p)].normal;
      Rgb sum = Rgb::Zero();
      for (int c = tree_->parent_of_patch(p); c >= 0; c = tree_->cluster(c).parent) {
        const std::size_t i = elements_ + static_cast<std::size_t>(c);
        for (std::uint64_t k = cluster_offsets_[i]; k < cluster_offsets_[i + 1]; ++k) {
          const std::vector<int>* hidden = receiver_hidden_[k].get();
          if (hidden != nullptr && std::binary_search(hidden->begin(), hidden->end(), p)) continue;
          const std::array<float, 3>& u = cluster_links_[k].to_source;
          const double w = facing_cosine(n, Vec3(u[0], u[1], u[2]));
          if (w > 0.0) sum += w * carried_[k];
        }
      }
      add_constant(field.irradiance[static_cast<std::size_t>(h_.root(p))], sum);
    }
  });
}

}  // namespace hrad
