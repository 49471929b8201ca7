#include "hrad/visibility/segment_bvh.h"

#include <numeric>

namespace hrad::detail {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kLeafSize = 4;
constexpr std::uint32_t kMaxDepth = 48;  // bounds the traversal stack (SegmentBvh::kStack)

float round_down(double x) {
  float f = static_cast<float>(x);
  return double(f) > x ? std::nextafter(f, -INFINITY) : f;
}
float round_up(double x) {
  float f = static_cast<float>(x);
  return double(f) < x ? std::nextafter(f, INFINITY) : f;
}

/// The binary tree as built, one box per node; converted to the two-boxes-per-node layout.
struct BuildNode {
  Box3 box;
  std::uint32_t first = 0;  ///< leaf: first primitive position; inner: left child (right = first + 1)
  std::uint32_t count = 0;  ///< primitives in a leaf, 0 for an inner node
};

void store(const Box3& b, float* lo, float* hi) {
  for (int k = 0; k < 3; ++k) lo[k] = round_down(b.lo[k]), hi[k] = round_up(b.hi[k]);
}

}  // namespace

SegmentBvh::SegmentBvh(const std::vector<Box3>& boxes) {
  std::vector<BuildNode> build;
  const auto count = static_cast<std::uint32_t>(boxes.size());
  if (count == 0) return;
  order_.resize(count);
  std::iota(order_.begin(), order_.end(), 0u);
  std::vector<std::array<double, 3>> centre(count);
  for (std::uint32_t i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) centre[i][k] = 0.5 * (boxes[i].lo[k] + boxes[i].hi[k]);
  build.reserve(2 * count);
  build.emplace_back();
  struct Task {
    std::uint32_t node, begin, end, depth;
  };
  std::vector<Task> tasks{{0, 0, count, 0}};
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    Box3 bounds, centres;
    for (std::uint32_t i = t.begin; i < t.end; ++i) {
      bounds.extend(boxes[order_[i]]);
      Box3 c;
      c.lo = c.hi = centre[order_[i]];
      centres.extend(c);
    }
    build[t.node].box = bounds;
    const std::uint32_t n = t.end - t.begin;
    auto make_leaf = [&] {
      build[t.node].first = t.begin;
      build[t.node].count = n;
    };
    if (n <= kLeafSize || t.depth >= kMaxDepth) {
      make_leaf();
      continue;
    }
    // Binned SAH over the centroids: cost of a split = sum over sides of half-area * count.
    int best_axis = -1, best_split = 0;
    double best_cost = INFINITY;
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = centres.lo[axis], extent = centres.hi[axis] - lo;
      if (!(extent > 0.0)) continue;
      Box3 bin_box[kBins];
      std::uint32_t bin_count[kBins] = {};
      for (std::uint32_t i = t.begin; i < t.end; ++i) {
        const int b = std::min(kBins - 1, static_cast<int>(kBins * ((centre[order_[i]][axis] - lo) / extent)));
        bin_box[b].extend(boxes[order_[i]]);
        ++bin_count[b];
      }
      double right_area[kBins];
      std::uint32_t right_count[kBins];
      Box3 acc;
      std::uint32_t c = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bin_box[b]);
        c += bin_count[b];
        right_area[b] = c ? acc.half_area() : 0.0;
        right_count[b] = c;
      }
      acc = Box3();
      c = 0;
      for (int b = 0; b + 1 < kBins; ++b) {
        acc.extend(bin_box[b]);
        c += bin_count[b];
        if (c == 0 || right_count[b + 1] == 0) continue;
        const double cost = acc.half_area() * c + right_area[b + 1] * right_count[b + 1];
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_split = b + 1;
      }
    }
    std::uint32_t mid = t.begin;
    if (best_axis >= 0) {
      const double lo = centres.lo[best_axis], extent = centres.hi[best_axis] - lo;
      // A leaf costs one exact test per primitive; a split costs about one box test more.
      if (n <= 2 * kLeafSize && best_cost >= (n - 1.0) * bounds.half_area()) {
        make_leaf();
        continue;
      }
      const auto split = std::partition(order_.begin() + t.begin, order_.begin() + t.end, [&](std::uint32_t i) {
        return std::min(kBins - 1, static_cast<int>(kBins * ((centre[i][best_axis] - lo) / extent))) < best_split;
      });
      mid = static_cast<std::uint32_t>(split - order_.begin());
    }
    if (mid == t.begin || mid == t.end) {  // all centroids alike: halve the list
      mid = t.begin + n / 2;
    }
    const auto left = static_cast<std::uint32_t>(build.size());
    build.emplace_back();
    build.emplace_back();
    build[t.node].first = left;
    build[t.node].count = 0;
    tasks.push_back({left + 1, mid, t.end, t.depth + 1});
    tasks.push_back({left, t.begin, mid, t.depth + 1});
  }
  // Collapse to four-wide nodes: a node's children are its binary children, with inner ones
  // opened (largest box first) until there are four.
  store(build[0].box, root_lo_, root_hi_);
  if (build[0].count == 0) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> todo{{0, 0}};  // (build node, node)
    nodes_.emplace_back();
    while (!todo.empty()) {
      const auto [b, slot] = todo.back();
      todo.pop_back();
      std::vector<std::uint32_t> kids{build[b].first, build[b].first + 1};
      while (kids.size() < 4) {
        int open = -1;
        double area = -1.0;
        for (std::size_t i = 0; i < kids.size(); ++i)
          if (build[kids[i]].count == 0 && build[kids[i]].box.half_area() > area)
            area = build[kids[i]].box.half_area(), open = static_cast<int>(i);
        if (open < 0) break;
        const std::uint32_t inner = kids[open];
        kids[open] = build[inner].first;
        kids.push_back(build[inner].first + 1);
      }
      for (std::size_t c = 0; c < kids.size(); ++c) {
        const BuildNode& child = build[kids[c]];
        float lo[3], hi[3];
        store(child.box, lo, hi);
        std::uint32_t next = 0;
        if (child.count == 0) {
          next = static_cast<std::uint32_t>(nodes_.size());
          nodes_.emplace_back();
          todo.push_back({kids[c], next});
        }
        Node& out = nodes_[slot];
        for (int k = 0; k < 3; ++k) out.lo[k][c] = lo[k], out.hi[k][c] = hi[k];
        out.count[c] = child.count;
        out.child[c] = child.count > 0 ? child.first : next;
        out.valid |= 1 << c;
      }
      for (std::size_t c = kids.size(); c < 4; ++c) {  // unused slots: empty boxes, never valid
        Node& out = nodes_[slot];
        for (int k = 0; k < 3; ++k) out.lo[k][c] = 1.0f, out.hi[k][c] = 0.0f;
        out.count[c] = 0;
        out.child[c] = 0;
      }
    }
  }
  leaf_lo_.resize(count);
  leaf_hi_.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) leaf_lo_[i] = boxes[order_[i]].lo, leaf_hi_[i] = boxes[order_[i]].hi;
}

}  // namespace hrad::detail
