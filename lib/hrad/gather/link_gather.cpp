#include "hrad/gather/link_gather.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
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
  std::vector<std::size_t> path;
  std::vector<int> occluders;
  std::vector<Vec2> uv;
  // Per element, the last point (stamp) for which it was a link source on the path (`source`) or an
  // ancestor of one (`above`).
  std::vector<std::uint32_t> source, above;
  std::uint32_t stamp = 0;
};

namespace {

// A patch of a cluster end that sees nothing of the other end (Link::hidden_p).
bool listed(const ShadedPatches* list, int patch) { return !(visible_share(list, patch) > 0.0); }

bool is_blocking(PairClass c) { return c == PairClass::kFacingAway || c == PairClass::kFullyHidden; }

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
  auto walk = [&](auto&& self, NodeId id, bool partial) -> void {
    const ElementNode& node = h.node(id);
    if (!facing(node.polygon(), node.patch)) return;
    const Vec3& ny = scene_.patches[static_cast<std::size_t>(node.patch)].normal;
    if (partial && occlusion_) {
      const PairClass c = visibility_->classify_among(std::span<const Vec3>(&x, 1), p.patch, node.polygon(), node.patch,
                                                      nullptr, &s.occluders);
      ++w.classifications;
      if (is_blocking(c)) return;
      partial = c == PairClass::kPartial;
      if (partial && !node.is_leaf() && options_.open_partly_visible) {
        for (NodeId child = node.first_child; child < node.first_child + 4; ++child) self(self, child, true);
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
      for (NodeId child = node.first_child; child < node.first_child + 4; ++child) self(self, child, partial);
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
    // Partly visible from x (s.occluders: its classification's, the last one made).
    const int k = options_.visibility_samples;
    w.rays += static_cast<std::uint64_t>(k);
    sum += f * node.radiosity *
           detail::weighted_fraction(*visibility_, x, n, p.patch, node.polygon(), ny, node.patch, &s.occluders, k,
                                     detail::mix_seed(seed, static_cast<std::uint64_t>(id)), s.uv);
  };
  path(leaf_at(p.patch, x), &s.path);
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
        walk(walk, e.node, c == PairClass::kPartial);
        continue;
      }
      for (int q : solved_.tree->patches(cluster_index(e.node))) {
        if (q == p.patch || listed(e.source_hidden, q)) continue;
        ++w.patch_visits;
        mark(h.root(q));
        walk(walk, h.root(q), true);
      }
    }
  }
  if (!options_.gather_uncovered) return sum;
  // What no link on the path covers: pairs the refinement dropped (hidden by its rays, facing away,
  // coplanar), gathered with visibility decided from x (see the header).
  auto uncovered = [&](auto&& self, NodeId id) -> void {
    const std::size_t i = static_cast<std::size_t>(id);
    if (s.source[i] == stamp) return;
    if (s.above[i] != stamp) {
      ++w.uncovered;
      walk(walk, id, true);
      return;
    }
    const ElementNode& node = h.node(id);
    for (NodeId child = node.first_child; child < node.first_child + 4; ++child) self(self, child);
  };
  for (int q = 0; q < h.patch_count(); ++q) {
    if (q == p.patch || !facing(h.node(h.root(q)).polygon(), q)) continue;
    uncovered(uncovered, h.root(q));
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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      Scratch scratch;
                      GatherWork local;
                      std::size_t done = 0;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        if (points[i].patch < 0) continue;
                        out[i] = gather_point(points[i], scratch, local);
                        ++done;
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
