#include "hrad/solvers/send_closure.h"

#include <array>
#include <cmath>
#include <cstddef>

namespace hrad {

std::vector<SendClosure> send_closures(const ElementHierarchy& h, const HsaLinks& links, const PushPull& push_pull,
                                       double aeps, bool linear, bool under_clusters, bool closed_scene,
                                       std::size_t* unclosed) {
  const std::size_t n = h.size();
  // The element that cannot split above each node (kNoNode where none is above or the node's own
  // area still allows a split): children have larger ids than their parent.
  std::vector<NodeId> block(n, kNoNode);
  bool below = false;
  for (std::size_t i = 0; i < n; ++i) {
    const ElementNode& e = h.node(static_cast<NodeId>(i));
    if (e.parent == kNoNode) continue;
    const std::size_t parent = static_cast<std::size_t>(e.parent);
    if (block[parent] != kNoNode) {
      block[i] = block[parent];
    } else if (h.node(e.parent).area * 0.25 < aeps) {
      block[i] = e.parent;
    }
    below = below || block[i] != kNoNode;
  }
  // The leaves of a split patch under cluster links (below).
  bool split_patches = false;
  if (under_clusters)
    for (int p = 0; p < h.patch_count() && !split_patches; ++p) split_patches = !h.node(h.root(p)).is_leaf();
  if (!below && !linear && !split_patches && !closed_scene) return {};

  std::vector<std::array<double, 9>> d = links.send_coefficients([&](NodeId r, const std::array<float, 9>& factor) {
    const std::array<double, 9>& w = push_pull.mean_weights(r);
    double mean = 0.0;
    for (int k = 0; k < 9; ++k) mean += w[static_cast<std::size_t>(k)] * static_cast<double>(factor[k]);
    return h.node(r).area * mean;
  });
  // Down the tree by the push's restriction (the adjoint of the moments' pull): d[i] becomes what
  // the links at i and above it take from i's moments. Per leaf, what a unit radiosity sends per
  // unit area: sum_i d_i integral(phi_i) / A.
  std::vector<double> sigma(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const ElementNode& e = h.node(static_cast<NodeId>(i));
    if (e.is_leaf()) {
      const std::array<double, 9>& integral = push_pull.basis_integrals_of(static_cast<NodeId>(i));
      const int functions = e.vertex_count == 4 ? 9 : 6;
      for (int k = 0; k < functions; ++k)
        sigma[i] += d[i][static_cast<std::size_t>(k)] * integral[static_cast<std::size_t>(k)] / e.area;
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const std::array<double, 9> part = restrict_to_child(d[i], e.vertex_count, e.split, k);
      std::array<double, 9>& child = d[static_cast<std::size_t>(e.first_child + k)];
      for (int j = 0; j < 9; ++j) child[static_cast<std::size_t>(j)] += part[static_cast<std::size_t>(j)];
    }
  }
  // What the links with a cluster end take from a uniform radiosity, per unit area, down the tree.
  std::vector<double> clustered = links.cluster_sends();
  for (std::size_t i = 0; i < n; ++i) {
    const ElementNode& e = h.node(static_cast<NodeId>(i));
    if (e.parent != kNoNode) clustered[i] += clustered[static_cast<std::size_t>(e.parent)];
  }
  // Each block's area mean of sigma over its leaves, and of the whole closure.
  std::vector<double> sum(n, 0.0), area(n, 0.0), whole(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const ElementNode& e = h.node(static_cast<NodeId>(i));
    if (!e.is_leaf() || block[i] == kNoNode) continue;
    sum[static_cast<std::size_t>(block[i])] += e.area * sigma[i];
    whole[static_cast<std::size_t>(block[i])] += e.area * (sigma[i] + clustered[i]);
    area[static_cast<std::size_t>(block[i])] += e.area;
  }
  // Per patch, over the closed leaves of a split patch outside any block that cluster links reach:
  // their whole closure and their area.
  std::vector<double> patch_whole(static_cast<std::size_t>(h.patch_count()), 0.0),
      patch_area(static_cast<std::size_t>(h.patch_count()), 0.0);
  if (split_patches)
    for (std::size_t i = 0; i < n; ++i) {
      const ElementNode& e = h.node(static_cast<NodeId>(i));
      if (!e.is_leaf() || block[i] != kNoNode || e.parent == kNoNode || !(clustered[i] > 0.0) ||
          sigma[i] + clustered[i] < kClosedBlock)
        continue;
      patch_whole[static_cast<std::size_t>(e.patch)] += e.area * (sigma[i] + clustered[i]);
      patch_area[static_cast<std::size_t>(e.patch)] += e.area;
    }
  std::vector<SendClosure> closure(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ElementNode& leaf = h.node(static_cast<NodeId>(i));
    if (!leaf.is_leaf()) continue;
    const std::size_t b = static_cast<std::size_t>(block[i]);
    const std::size_t patch = static_cast<std::size_t>(leaf.patch);
    if (closed_scene && sigma[i] > 0.0 && 1.0 - clustered[i] > 0.0 &&
        std::abs((1.0 - clustered[i]) / sigma[i] - 1.0) <= kLargestClosureMove) {
      // The scene keeps its light: every leaf's closure is 1 (closed_scene.h).
      closure[i] = {d[i], sigma[i], 1.0 - clustered[i]};
      continue;
    }
    if (closed_scene && unclosed != nullptr) ++*unclosed;
    if (split_patches && block[i] == kNoNode && leaf.parent != kNoNode && clustered[i] > 0.0 &&
        sigma[i] + clustered[i] >= kClosedBlock) {
      // Each leaf sends, through the element links, what brings its whole closure to the mean of
      // its patch's closed leaves (send_closure.h).
      const double target = patch_whole[patch] / patch_area[patch] - clustered[i];
      if (sigma[i] > 0.0 && target > 0.0 && std::abs(target / sigma[i] - 1.0) <= kLargestClosureMove)
        closure[i] = {d[i], sigma[i], target};
    } else if (block[i] != kNoNode && whole[b] >= kClosedBlock * area[b]) {
      closure[i] = {d[i], sigma[i], sum[b] / area[b]};
    } else if (linear && sigma[i] + clustered[i] >= kClosedBlock) {
      // A linear leaf sends its power times what a uniform radiosity on it sends: its slope only
      // shares that among the links.
      closure[i] = {d[i], sigma[i], sigma[i]};
    }
  }
  return closure;
}

}  // namespace hrad
