#include "hrad/gather/stored_links.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/face_geometry.h"

namespace hrad {
namespace {

// The patches of a cluster end that see nothing of the other end (what LinkGather reads of a
// link's shaded list: visible_share() == 0).
std::vector<std::int32_t> hidden_patches(const ShadedPatches* shaded) {
  std::vector<std::int32_t> out;
  if (shaded == nullptr) return out;
  for (const ShadedPatch& s : *shaded)
    if (!(s.visible > 0.0f)) out.push_back(s.patch);
  std::sort(out.begin(), out.end());
  return out;
}

std::shared_ptr<const ShadedPatches> hidden_list(const std::vector<std::int32_t>& patches) {
  if (patches.empty()) return nullptr;
  auto out = std::make_shared<ShadedPatches>();
  for (std::int32_t p : patches) out->push_back({p, 0.0f});
  return out;
}

}  // namespace

SolutionLinks stored_links(const SolvedHierarchy& solved) {
  if (!solved.hierarchy) throw Error("stored links: the solve kept no hierarchy");
  const ElementHierarchy& h = *solved.hierarchy;
  SolutionLinks out;
  out.first_child.reserve(h.size());
  for (const ElementNode& n : h.nodes()) out.first_child.push_back(n.first_child);
  if (solved.tree)
    for (const Cluster& c : solved.tree->clusters()) out.cluster_parent.push_back(c.parent);
  out.links.reserve(solved.links.size());
  for (const Link& l : solved.links)
    out.links.push_back({l.p, l.q, l.partial, hidden_patches(l.hidden_p.get()), hidden_patches(l.hidden_q.get())});
  return out;
}

SolvedHierarchy restored_links(const Scene& scene, const Solution& solution, const SolutionLinks& links,
                               const std::string& path) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: {}", path, what)); };
  const std::size_t patches = scene.patches.size();
  if (links.first_child.size() < patches)
    fail(fmt::format("element node: {} nodes, fewer than the scene's {} patches", links.first_child.size(), patches));
  SolvedHierarchy out;
  out.hierarchy = std::make_unique<ElementHierarchy>(scene);
  ElementHierarchy& h = *out.hierarchy;
  // The splits in the order they were made: children are appended in blocks of 4.
  std::vector<std::pair<std::int32_t, std::int32_t>> splits;  // (first child, node)
  for (std::size_t i = 0; i < links.first_child.size(); ++i)
    if (links.first_child[i] >= 0) splits.emplace_back(links.first_child[i], static_cast<std::int32_t>(i));
  std::sort(splits.begin(), splits.end());
  for (const auto& [first, id] : splits) {
    if (static_cast<std::size_t>(id) >= h.size())
      fail(fmt::format("element node {}: split before the node exists (first_child {})", id, first));
    const NodeId made = h.split(id);
    if (made != first)
      fail(fmt::format("element node {}: first_child {}, but splitting the nodes in that order gives {}", id, first,
                       made));
  }
  if (h.size() != links.first_child.size())
    fail(fmt::format("element node: {} nodes, but their splits make {}", links.first_child.size(), h.size()));
  // The leaves are the faces, in order: the same patch and the same area (the face's loop adds only
  // T-vertices on the leaf's edges).
  const std::vector<NodeId> leaves = h.all_leaves();
  if (leaves.size() != solution.faces.size())
    fail(fmt::format("element node: the hierarchy has {} leaves but the solution {} faces", leaves.size(),
                     solution.faces.size()));
  // The face's loop holds its leaf's corners (to the weld, at most 1e-9 of the scene's diagonal): a
  // file whose hierarchy cut a node another way (quadrants against strips, element_hierarchy.h
  // SplitKind) can have leaves of the same patches and areas.
  const auto [lo, hi] = scene.bounds();
  const double weld = patches > 0 ? 1e-8 * (hi - lo).norm() : 0.0;
  for (std::size_t f = 0; f < leaves.size(); ++f) {
    ElementNode& leaf = h.node(leaves[f]);
    const double tol = std::max(1e-3 * std::sqrt(leaf.area), weld);
    for (const Vec3& c : leaf.polygon())
      if (std::none_of(solution.faces[f].begin(), solution.faces[f].end(),
                       [&](int v) { return (solution.vertices[static_cast<std::size_t>(v)] - c).norm() <= tol; }))
        fail(
            fmt::format("element node {}: its corner ({:.9g}, {:.9g}, {:.9g}) is not a vertex of face {}: the file's "
                        "elements were cut another way",
                        leaves[f], c.x(), c.y(), c.z(), f));
    const double area = face_area(solution, f);
    if (leaf.patch != solution.face_patch[f] || !(std::abs(area - leaf.area) <= 1e-9 * leaf.area))
      fail(
          fmt::format("element node {}: a leaf of patch {} and area {:.17g}, but face {} lies on patch {} with area "
                      "{:.17g}",
                      leaves[f], leaf.patch, leaf.area, f, solution.face_patch[f], area));
    leaf.radiosity = solution.face_radiosity[f];
  }
  h.pull_radiosity();
  if (!links.cluster_parent.empty()) {
    out.tree = std::make_unique<ClusterTree>(scene);
    if (out.tree->size() != links.cluster_parent.size())
      fail(fmt::format("element cluster: {} clusters, but the scene's cluster tree has {}", links.cluster_parent.size(),
                       out.tree->size()));
    for (std::size_t c = 0; c < links.cluster_parent.size(); ++c)
      if (out.tree->cluster(static_cast<int>(c)).parent != links.cluster_parent[c])
        fail(fmt::format("element cluster {}: parent {}, but the scene's cluster tree has {}", c,
                         links.cluster_parent[c], out.tree->cluster(static_cast<int>(c)).parent));
  }
  out.links.reserve(links.links.size());
  for (std::size_t k = 0; k < links.links.size(); ++k) {
    const SolutionLinks::Link& l = links.links[k];
    for (const NodeRef end : {l.p, l.q})
      if (is_cluster(end) ? cluster_index(end) >= static_cast<int>(links.cluster_parent.size())
                          : end < 0 || static_cast<std::size_t>(end) >= h.size())
        fail(fmt::format("element link {}: end {} is neither a node nor a cluster", k, end));
    for (const std::vector<std::int32_t>* list : {&l.hidden_p, &l.hidden_q})
      for (std::int32_t p : *list)
        if (p < 0 || static_cast<std::size_t>(p) >= patches)
          fail(fmt::format("element link {}: lists patch {}, but the scene has {} patches", k, p, patches));
    Link link;
    link.p = l.p;
    link.q = l.q;
    link.partial = l.partial;
    link.hidden_p = hidden_list(l.hidden_p);
    link.hidden_q = hidden_list(l.hidden_q);
    out.links.push_back(std::move(link));
  }
  return out;
}

}  // namespace hrad
