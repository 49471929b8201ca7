#include "hrad/gather/link_gather.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "hrad/core/error.h"
#include "hrad/core/rng.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/gather/from_point.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

/// One directed link at its receiver: the source node and the pair's visibility.
struct LinkGather::Source {
  NodeRef node = kNoNode;
  bool partial = false;
  const ShadedPatches* receiver_hidden =
      nullptr;                                   ///< patches of a cluster receiver that see part or none of the source
  const ShadedPatches* source_hidden = nullptr;  ///< patches of a cluster source that see part or none of the receiver
};

struct LinkGather::Scratch {
  // The leaf whose points are being gathered, and per element the class of the pair (leaf, element)
  // with its occluders, valid where `classified` equals `group` (the leaf's turn).
  NodeId leaf = kNoNode;
  std::uint32_t group = 0;
  // Whether the leaf's points classify partly visible sources from the leaf first (see the header).
  bool from_leaf = true;
  // Per element, its occluders as seen from the point being gathered (valid during its walk).
  std::vector<std::vector<int>> point_occluders;
  std::vector<std::uint32_t> classified;
  std::vector<PairClass> leaf_class;
  std::vector<std::vector<int>> leaf_occluders;
  // Per source patch, the pair (the leaf's patch, that patch) looked up in patch_pairs_, valid where
  // `patch_found` equals `patch_group` (the leaf's patch's turn).
  std::uint32_t patch_group = 0;
  std::vector<std::uint32_t> patch_found;
  std::vector<const PatchPair*> patch_pair;
  std::vector<std::size_t> path;
  std::vector<int> occluders;
  std::vector<Vec2> uv;
  // A point's partly visible sources when their rays are shared (PartialSampling::shared).
  struct Partial {
    NodeId node = kNoNode;
    double factor = 0.0;
    std::size_t first_occluder = 0, occluder_count = 0;
  };
  std::vector<Partial> partial;
  std::vector<int> partial_occluders;
  std::vector<double> importance;
  std::vector<int> counts;
  // Per element, the last point (stamp) for which it was a link source on the path (`source`) or an
  // ancestor of one (`above`).
  std::vector<std::uint32_t> source, above;
  std::uint32_t stamp = 0;
};

namespace {

// A patch of a cluster end that sees nothing of the other end (Link::hidden_p).
bool listed(const ShadedPatches* list, int patch) { return !(visible_share(list, patch) > 0.0); }

// How far x lies inside the convex polygon (normal n, counter-clockwise seen from its front): the
// smallest signed distance to its edges' lines, positive inside.
double inside_depth(std::span<const Vec3> polygon, const Vec3& n, const Vec3& x) {
  double depth = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3 e = polygon[(i + 1) % polygon.size()] - a;
    depth = std::min(depth, n.dot(e.cross(x - a)) / e.norm());
  }
  return depth;
}

}  // namespace

LinkGather::LinkGather(const Scene& scene, const SolvedHierarchy& solved, const LinkGatherOptions& options,
                       const FinalGather* in_space)
    : scene_(scene), solved_(solved), options_(options), in_space_(in_space) {
  if (!solved.hierarchy) throw Error("--gather-sources links: the solve kept no hierarchy");
  if (options.visibility_samples < 1 || options.visibility_samples > 1 << 20)
    throw Error(fmt::format("--visibility-samples: {} is not in [1, 1048576]", options.visibility_samples));
  visibility_ = make_visibility(scene);
  occlusion_ = visibility_->scene_has_occlusion();
  if (!(options.tolerance >= 0.0))
    throw Error(fmt::format("--gather-tolerance: {} is not a number >= 0", options.tolerance));
  const ElementHierarchy& h = *solved.hierarchy;
  const std::size_t elements = h.size();
  // D_N of every interior element, from the leaves below it; the mean radiosity from the roots.
  deviation_.assign(elements, 0.0);
  leaf_count_.assign(elements, 1);
  for (std::size_t i = 0; i < elements; ++i) {
    const ElementNode& node = h.node(static_cast<NodeId>(i));
    if (node.is_leaf()) continue;
    Rgb sum = Rgb::Zero();
    const std::vector<NodeId> leaves = h.leaves_below(static_cast<NodeId>(i));
    leaf_count_[i] = static_cast<std::uint32_t>(leaves.size());
    for (const NodeId leaf : leaves) sum += h.node(leaf).area * (h.node(leaf).radiosity - node.radiosity).abs();
    deviation_[i] = (sum / node.area).maxCoeff();
  }
  Rgb weighted = Rgb::Zero();
  double area = 0.0;
  for (int p = 0; p < h.patch_count(); ++p) {
    weighted += h.node(h.root(p)).area * h.node(h.root(p)).radiosity;
    area += h.node(h.root(p)).area;
  }
  mean_radiosity_ = area > 0.0 ? (weighted / area).maxCoeff() : 0.0;
  const std::size_t n = elements + (solved.tree ? solved.tree->size() : 0);
  auto dense = [&](NodeRef r) {
    return is_cluster(r) ? elements + static_cast<std::size_t>(cluster_index(r)) : static_cast<std::size_t>(r);
  };
  // Both directions of every link, grouped by receiver (a self-link once).
  offsets_.assign(n + 1, 0);
  for (const Link& l : solved.links) {
    ++offsets_[dense(l.p) + 1];
    if (l.q != l.p) ++offsets_[dense(l.q) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) offsets_[i + 1] += offsets_[i];
  sources_.resize(offsets_[n]);
  pair_class_ = std::make_unique<std::atomic<std::uint8_t>[]>(sources_.size());
  for (std::size_t k = 0; k < sources_.size(); ++k) pair_class_[k].store(kUnclassified, std::memory_order_relaxed);
  std::vector<std::uint64_t> cursor(offsets_.begin(), offsets_.end() - 1);
  for (const Link& l : solved.links) {
    sources_[cursor[dense(l.p)]++] = {l.q, l.partial, l.hidden_p.get(), l.hidden_q.get()};
    if (l.q != l.p) sources_[cursor[dense(l.q)]++] = {l.p, l.partial, l.hidden_q.get(), l.hidden_p.get()};
  }
}

LinkGather::~LinkGather() = default;

NodeId LinkGather::leaf_at(int patch, const Vec3& x) const {
  const ElementHierarchy& h = *solved_.hierarchy;
  const Vec3& n = scene_.patches[static_cast<std::size_t>(patch)].normal;
  NodeId id = h.root(patch);
  while (!h.node(id).is_leaf()) {
    // The child holding x; on a shared edge (or off all by rounding) the one it lies deepest in.
    NodeId best = kNoNode;
    double best_depth = -std::numeric_limits<double>::infinity();
    for (NodeId c = h.node(id).first_child; c < h.node(id).first_child + 4; ++c) {
      const double d = inside_depth(h.node(c).polygon(), n, x);
      if (d > best_depth) {
        best_depth = d;
        best = c;
      }
    }
    id = best;
  }
  return id;
}

void LinkGather::path(NodeId leaf, std::vector<std::size_t>* out) const {
  const ElementHierarchy& h = *solved_.hierarchy;
  out->clear();
  for (NodeId id = leaf; id != kNoNode; id = h.node(id).parent) out->push_back(static_cast<std::size_t>(id));
  if (!solved_.tree) return;
  for (int c = solved_.tree->parent_of_patch(h.node(leaf).patch); c >= 0; c = solved_.tree->cluster(c).parent)
    out->push_back(h.size() + static_cast<std::size_t>(c));
}

std::size_t LinkGather::links_on_path(NodeId leaf) const {
  std::vector<std::size_t> p;
  path(leaf, &p);
  std::size_t count = 0;
  for (std::size_t r : p) count += offsets_[r + 1] - offsets_[r];
  return count;
}

std::size_t LinkGather::sources_on_path(NodeId leaf) const {
  std::vector<std::size_t> p;
  path(leaf, &p);
  std::size_t count = 0;
  for (std::size_t r : p)
    for (std::uint64_t k = offsets_[r]; k < offsets_[r + 1]; ++k) {
      const NodeRef node = sources_[k].node;
      count += is_cluster(node) ? solved_.tree->patches(cluster_index(node)).size() : 1;
    }
  return count;
}

PairClass LinkGather::pair_class(std::size_t receiver, std::uint64_t k, GatherWork& w) const {
  const Source& e = sources_[k];
  if (!occlusion_) return PairClass::kFullyVisible;
  if (e.partial || receiver >= solved_.hierarchy->size()) return PairClass::kPartial;
  std::atomic<std::uint8_t>& known = pair_class_[k];
  std::uint8_t c = known.load(std::memory_order_relaxed);
  if (c == kUnclassified) {
    // Deterministic, so two threads that classify the same link at once find the same class; only
    // the one that stores it counts the classification, so the work counted does not depend on
    // the threads' timing.
    const ElementHierarchy& h = *solved_.hierarchy;
    const ElementNode& a = h.node(static_cast<NodeId>(receiver));
    const ElementNode& b = h.node(e.node);
    c = static_cast<std::uint8_t>(
        visibility_->classify_among(a.polygon(), a.patch, b.polygon(), b.patch, nullptr, nullptr));
    std::uint8_t expected = kUnclassified;
    if (known.compare_exchange_strong(expected, c, std::memory_order_relaxed)) ++w.classifications;
  }
  return static_cast<PairClass>(c);
}

const LinkGather::PatchPair& LinkGather::patch_pair(int p, int q, GatherWork& w) const {
  const std::uint64_t key = static_cast<std::uint64_t>(p) << 32 | static_cast<std::uint32_t>(q);
  const auto found = patch_pairs_.find(key);
  if (found != patch_pairs_.end()) return found->second;
  // Deterministic, so two threads that classify the same pair at once find the same class; only
  // the one that inserts it counts the classification.
  const ElementHierarchy& h = *solved_.hierarchy;
  PatchPair pair;
  pair.cls = visibility_->classify_among(h.node(h.root(p)).polygon(), p, h.node(h.root(q)).polygon(), q, nullptr,
                                         &pair.occluders);
  const auto [at, inserted] = patch_pairs_.insert({key, std::move(pair)});
  if (inserted) ++w.classifications;
  return at->second;
}

const LinkGather::PatchPair& LinkGather::patch_pair_of(int q, Scratch& s, GatherWork& w) const {
  const std::size_t i = static_cast<std::size_t>(q);
  if (s.patch_found[i] != s.patch_group) {
    s.patch_pair[i] = &patch_pair(solved_.hierarchy->node(s.leaf).patch, q, w);
    s.patch_found[i] = s.patch_group;
  }
  return *s.patch_pair[i];
}

PairClass LinkGather::leaf_class(NodeId id, const std::vector<int>* candidates, Scratch& s, GatherWork& w) const {
  const std::size_t i = static_cast<std::size_t>(id);
  if (s.classified[i] != s.group) {
    const ElementHierarchy& h = *solved_.hierarchy;
    const ElementNode& a = h.node(s.leaf);
    const ElementNode& b = h.node(id);
    if (!candidates) {
      const PatchPair& pair = patch_pair_of(b.patch, s, w);
      candidates = &pair.occluders;
      if (is_blocking(pair.cls)) {  // so is every pair of their elements
        s.leaf_class[i] = pair.cls;
        s.classified[i] = s.group;
        return s.leaf_class[i];
      }
    }
    s.leaf_class[i] =
        visibility_->classify_among(a.polygon(), a.patch, b.polygon(), b.patch, candidates, &s.leaf_occluders[i]);
    s.classified[i] = s.group;
    ++w.classifications;
  }
  return s.leaf_class[i];
}

Rgb LinkGather::gather_point(const GatherPoint& p, Scratch& s, GatherWork& w) const {
  const ElementHierarchy& h = *solved_.hierarchy;
  const Vec3& x = p.position;
  const Vec3& n = p.normal;
  const std::uint64_t seed = detail::point_seed(p, options_.seed);
  ++w.points;
  Rgb sum = Rgb::Zero();
  // Is x in front of the source's plane (by more than rounding: a point in that plane sees it
  // edge-on) and does `polygon` reach above x's tangent plane? Otherwise it has no factor.
  auto facing = [&](std::span<const Vec3> polygon, int q) {
    const Patch& source = scene_.patches[static_cast<std::size_t>(q)];
    if (!(source.normal.dot(x - polygon[0]) > 1e-9 * polygon_diameter(polygon))) return false;
    bool above = false;
    for (const Vec3& v : polygon) above |= n.dot(v - x) > 0.0;
    return above;
  };
  // A source element: classified from x where its link is partial (hidden: nothing; fully visible:
  // no rays below it; still partial and split: opened, unless the options say otherwise); gathered
  // whole when its Barnes-Hut bound allows (see the header), else its children.
  const double tolerance = options_.tolerance * mean_radiosity_;
  auto walk = [&](auto&& self, NodeId id, bool partial, const std::vector<int>* candidates) -> void {
    const ElementNode& node = h.node(id);
    if (!facing(node.polygon(), node.patch)) return;
    const Vec3& ny = scene_.patches[static_cast<std::size_t>(node.patch)].normal;
    const std::vector<int>* occluders = nullptr;
    const std::vector<int>* below = nullptr;
    if (partial && occlusion_) {
      // From x's leaf first when it classifies for several points (a leaf that sees all or none of
      // the node decides every point on it), then from x where the leaf sees part of it; or from x
      // straight away, among the enclosing node's occluders (the patch pair's at the top).
      PairClass c = PairClass::kPartial;
      std::vector<int>& from_point = s.point_occluders[static_cast<std::size_t>(id)];
      if (s.from_leaf) {
        c = leaf_class(id, candidates, s, w);
        occluders = &s.leaf_occluders[static_cast<std::size_t>(id)];
      } else if (!candidates) {
        const PatchPair& pair = patch_pair_of(node.patch, s, w);
        c = pair.cls;
        occluders = &pair.occluders;
      } else {
        occluders = candidates;
      }
      if (c == PairClass::kPartial && (options_.classify_points || !s.from_leaf)) {
        c = visibility_->classify_among(std::span<const Vec3>(&x, 1), p.patch, node.polygon(), node.patch, occluders,
                                        &from_point);
        ++w.classifications;
        if (c == PairClass::kPartial) occluders = &from_point;
      }
      if (is_blocking(c)) return;
      partial = c == PairClass::kPartial;
      // The children's candidates: complete for the shaft they are classified in first.
      below = s.from_leaf ? &s.leaf_occluders[static_cast<std::size_t>(id)] : occluders;
      if (partial && !node.is_leaf() && options_.open_partly_visible) {
        for (NodeId child = node.first_child; child < node.first_child + 4; ++child) self(self, child, true, below);
        return;
      }
    }
    double f = -1.0;
    bool whole = node.is_leaf() || deviation_[static_cast<std::size_t>(id)] == 0.0 || std::isinf(tolerance);
    if (!whole) {
      const double deviation = deviation_[static_cast<std::size_t>(id)];
      auto [k_min, k_max] = detail::kernel_bounds(x, n, node.polygon(), ny.dot(x - node.vertices[0]));
      if (partial) k_min = 0.0;
      // The factor is at most A k_max / pi: where even that fails the test, skip evaluating it.
      if ((k_max - k_min) * deviation <= tolerance * k_max) {
        f = point_to_polygon(x, n, node.polygon(), kLambertSumOnly);
        ++w.node_visits;
        whole = node.area / std::numbers::pi * (k_max - k_min) * deviation <= tolerance * f;
      }
    }
    if (!whole) {
      for (NodeId child = node.first_child; child < node.first_child + 4; ++child)
        self(self, child, partial, partial && occlusion_ ? below : nullptr);
      return;
    }
    if (f < 0.0) {
      f = point_to_polygon(x, n, node.polygon(), kLambertSumOnly);
      ++w.node_visits;
    }
    if (!(f > 0.0)) return;
    ++w.nodes_gathered;
    w.leaves_covered += leaf_count_[static_cast<std::size_t>(id)];
    if (!partial) {
      sum += f * node.radiosity;
      return;
    }
    // Partly visible from x's leaf (and from x when classified): only `occluders` can block.
    if (options_.partial == PartialSampling::shared) {
      const double importance = f * node.radiosity.sum();
      if (!(importance > 0.0)) return;
      s.partial.push_back({id, f, s.partial_occluders.size(), occluders ? occluders->size() : 0});
      if (occluders) s.partial_occluders.insert(s.partial_occluders.end(), occluders->begin(), occluders->end());
      s.importance.push_back(importance);
      return;
    }
    const int k = options_.visibility_samples;
    w.rays += static_cast<std::uint64_t>(k);
    sum += f * node.radiosity *
           detail::weighted_fraction(*visibility_, x, n, p.patch, node.polygon(), ny, node.patch, occluders, k,
                                     detail::mix_seed(seed, static_cast<std::uint64_t>(id)), s.uv);
  };
  s.partial.clear();
  s.partial_occluders.clear();
  s.importance.clear();
  path(s.leaf, &s.path);
  if (options_.gather_uncovered && s.source.size() != h.size()) {
    s.source.assign(h.size(), 0);
    s.above.assign(h.size(), 0);
    s.stamp = 0;
  }
  const std::uint32_t stamp = ++s.stamp;
  auto mark = [&](NodeId id) {
    if (!options_.gather_uncovered) return;
    s.source[static_cast<std::size_t>(id)] = stamp;
    for (NodeId a = h.node(id).parent; a != kNoNode && s.above[static_cast<std::size_t>(a)] != stamp;
         a = h.node(a).parent)
      s.above[static_cast<std::size_t>(a)] = stamp;
  };
  for (std::size_t r : s.path) {
    for (std::uint64_t k = offsets_[r]; k < offsets_[r + 1]; ++k) {
      const Source& e = sources_[k];
      if (listed(e.receiver_hidden, p.patch)) continue;
      if (!is_cluster(e.node)) {
        if (h.node(e.node).patch == p.patch) continue;  // a planar patch does not see itself
        ++w.patch_visits;
        mark(e.node);
        const PairClass c = pair_class(r, k, w);
        if (is_blocking(c)) continue;
        walk(walk, e.node, c == PairClass::kPartial, nullptr);
        continue;
      }
      for (int q : solved_.tree->patches(cluster_index(e.node))) {
        if (q == p.patch || listed(e.source_hidden, q)) continue;
        ++w.patch_visits;
        mark(h.root(q));
        walk(walk, h.root(q), true, nullptr);
      }
    }
  }
  // What no link on the path covers: pairs the refinement dropped (hidden by its rays, facing away,
  // coplanar), gathered with visibility decided from x (see the header).
  auto uncovered = [&](auto&& self, NodeId id) -> void {
    const std::size_t i = static_cast<std::size_t>(id);
    if (s.source[i] == stamp) return;
    if (s.above[i] != stamp) {
      ++w.uncovered;
      walk(walk, id, true, nullptr);
      return;
    }
    const ElementNode& node = h.node(id);
    for (NodeId child = node.first_child; child < node.first_child + 4; ++child) self(self, child);
  };
  if (options_.gather_uncovered)
    for (int q = 0; q < h.patch_count(); ++q) {
      if (q == p.patch || !facing(h.node(h.root(q)).polygon(), q)) continue;
      uncovered(uncovered, h.root(q));
    }
  if (s.partial.empty()) return sum;
  // Shared rays: systematic sampling over the partly visible sources' unoccluded contributions C_i
  // (C their sum); source i with m_i of the m rays adds C / m * m_i * its visible fraction, an
  // estimate of C_i V_i (as leaf_gather.h).
  const double per_ray =
      detail::systematic_counts(s.importance, options_.visibility_samples, detail::mix_seed(seed, 0xfeed), &s.counts);
  for (std::size_t i = 0; i < s.partial.size(); ++i) {
    if (s.counts[i] <= 0) continue;
    const Scratch::Partial& e = s.partial[i];
    const ElementNode& node = h.node(e.node);
    const Vec3& ny = scene_.patches[static_cast<std::size_t>(node.patch)].normal;
    s.occluders.assign(s.partial_occluders.begin() + static_cast<std::ptrdiff_t>(e.first_occluder),
                       s.partial_occluders.begin() + static_cast<std::ptrdiff_t>(e.first_occluder + e.occluder_count));
    w.rays += static_cast<std::uint64_t>(s.counts[i]);
    const double fraction = detail::weighted_fraction(*visibility_, x, n, p.patch, node.polygon(), ny, node.patch,
                                                      occlusion_ ? &s.occluders : nullptr, s.counts[i],
                                                      detail::mix_seed(seed, static_cast<std::uint64_t>(e.node)), s.uv);
    sum += per_ray * s.counts[i] * fraction * (node.radiosity / node.radiosity.sum());
  }
  return sum;
}

std::vector<Rgb> LinkGather::gather(std::span<const GatherPoint> points, ProgressReporter* progress) const {
  std::vector<Rgb> out(points.size(), Rgb::Zero());
  // Points in space go to the all-patches gather in one batch.
  std::vector<GatherPoint> in_space;
  std::vector<std::size_t> in_space_at;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].patch < 0) {
      in_space.push_back(points[i]);
      in_space_at.push_back(i);
    }
  if (!in_space.empty()) {
    if (!in_space_) throw Error("--gather-sources links: a point lies on no patch and there is no all-patches gather");
    const std::vector<Rgb> h = in_space_->gather(in_space, progress);
    for (std::size_t i = 0; i < in_space.size(); ++i) out[in_space_at[i]] = h[i];
  }
  // The points on patches, grouped by leaf: a leaf's points share its classifications.
  const ElementHierarchy& h = *solved_.hierarchy;
  std::vector<std::pair<NodeId, std::size_t>> order;
  order.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].patch >= 0) order.emplace_back(kNoNode, i);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t j = r.begin(); j != r.end(); ++j) {
                        const GatherPoint& p = points[order[j].second];
                        order[j].first = leaf_at(p.patch, p.position);
                      }
                    });
  // By patch, then leaf: a thread's consecutive leaves share their patch's pairs.
  std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    const int pa = h.node(a.first).patch, pb = h.node(b.first).patch;
    return pa != pb ? pa < pb : a < b;
  });
  std::vector<std::size_t> groups;  // where each leaf's points start in `order`
  for (std::size_t j = 0; j < order.size(); ++j)
    if (j == 0 || order[j].first != order[j - 1].first) groups.push_back(j);
  groups.push_back(order.size());
  tbb::enumerable_thread_specific<Scratch> scratches([&] {
    Scratch s;
    s.classified.assign(h.size(), 0);
    s.leaf_class.assign(h.size(), PairClass::kPartial);
    s.leaf_occluders.resize(h.size());
    s.point_occluders.resize(h.size());
    s.patch_found.assign(static_cast<std::size_t>(h.patch_count()), 0);
    s.patch_pair.assign(static_cast<std::size_t>(h.patch_count()), nullptr);
    s.leaf = kNoNode;
    return s;
  });
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, groups.size() - 1, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        Scratch& scratch = scratches.local();
        GatherWork local;
        std::size_t done = 0;
        for (std::size_t g = r.begin(); g != r.end(); ++g) {
          const NodeId leaf = order[groups[g]].first;
          if (scratch.leaf == kNoNode || h.node(leaf).patch != h.node(scratch.leaf).patch) ++scratch.patch_group;
          scratch.leaf = leaf;
          ++scratch.group;
          scratch.from_leaf =
              !options_.classify_points || options_.partial != PartialSampling::per_node ||
              groups[g + 1] - groups[g] >= static_cast<std::size_t>(std::max(1, options_.leaf_first_points));
          for (std::size_t j = groups[g]; j != groups[g + 1]; ++j) {
            out[order[j].second] = gather_point(points[order[j].second], scratch, local);
            ++done;
          }
        }
        {
          const std::lock_guard<std::mutex> lock(work_mutex_);
          work_ += local;
        }
        if (progress) progress->advance(done);
      });
  return out;
}

GatherWork LinkGather::work() const {
  GatherWork w;
  {
    const std::lock_guard<std::mutex> lock(work_mutex_);
    w = work_;
  }
  if (in_space_) w += in_space_->work();
  return w;
}

}  // namespace hrad
