// A compact bounding-volume hierarchy for any-hit segment queries: binned surface-area-heuristic
// build (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"), collapsed to
// four children per node whose float boxes are tested together with SSE (Dammertz et al. 2008,
// "Shallow bounding volume hierarchies for fast SIMD ray tracing"), iterative traversal. It only culls: the caller's
// exact test decides every primitive, and every culling test is conservative (it can visit a box the segment misses,
// never skip one it meets). No CGAL here.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <immintrin.h>

namespace hrad::detail {

struct Box3 {
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY};
  std::array<double, 3> hi{-INFINITY, -INFINITY, -INFINITY};
  void extend(const Box3& b) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], b.lo[k]), hi[k] = std::max(hi[k], b.hi[k]);
  }
  double half_area() const {
    const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
  }
};

/// Slab test of the segment a-b against boxes padded by 2^-40 of the largest coordinate magnitude
/// in play, far above the test's rounding error, so it never rejects a box the segment meets.
/// Branch-free: an axis along which the segment is flat gets an infinite inverse, so its slab
/// gives (-inf, inf) when the segment lies inside it and an empty range otherwise; the NaN of
/// 0 * inf (an endpoint exactly on a padded face, a measure-zero case) is ignored by the
/// min/max below, which only makes the test more permissive.
class SegmentCull {
 public:
  SegmentCull(const std::array<double, 3>& a, const std::array<double, 3>& b, double scene_magnitude) {
    double m = scene_magnitude;
    for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(a[k]), std::abs(b[k])});
    const double pad = std::ldexp(m, -40) + std::numeric_limits<double>::min();
    // The four-wide float test pads by 2^-16 m, far above float rounding (2^-24 relative).
    const double pad4 = std::ldexp(m, -16) + std::numeric_limits<float>::min();
    for (int k = 0; k < 3; ++k) {
      const double d = b[k] - a[k];
      inverse_[k] = 1.0 / d;  // +-inf when d == 0
      near_is_lo_[k] = inverse_[k] >= 0;
      // (box - pad - a) * inverse, with the sign of inverse choosing which face is near.
      near_offset_[k] = near_is_lo_[k] ? -pad - a[k] : pad - a[k];
      far_offset_[k] = near_is_lo_[k] ? pad - a[k] : -pad - a[k];
      inverse4_[k] = _mm_set1_ps(static_cast<float>(inverse_[k]));
      near_offset4_[k] = _mm_set1_ps(static_cast<float>(near_is_lo_[k] ? -pad4 - a[k] : pad4 - a[k]));
      far_offset4_[k] = _mm_set1_ps(static_cast<float>(near_is_lo_[k] ? pad4 - a[k] : -pad4 - a[k]));
    }
  }
  template <class T>
  bool may_meet(const T* lo, const T* hi) const {
    double t0 = -0x1.0p-30, t1 = 1.0 + 0x1.0p-30;
    for (int k = 0; k < 3; ++k) {
      const double near = near_is_lo_[k] ? double(lo[k]) : double(hi[k]);
      const double far = near_is_lo_[k] ? double(hi[k]) : double(lo[k]);
      const double tn = (near + near_offset_[k]) * inverse_[k];
      const double tf = (far + far_offset_[k]) * inverse_[k];
      t0 = tn > t0 ? tn : t0;  // NaN compares false: ignored
      t1 = tf < t1 ? tf : t1;
    }
    return t0 <= t1;
  }
  /// The same test on four float boxes at once (lo[axis][box], hi[axis][box]); bit i of the
  /// result is set when box i may meet the segment. _mm_max_ps/_mm_min_ps return their second
  /// operand when the first is NaN, so a NaN slab is ignored here too.
  int may_meet4(const float (*lo)[4], const float (*hi)[4]) const {
    __m128 t0 = _mm_set1_ps(-0x1.0p-20f), t1 = _mm_set1_ps(1.0f + 0x1.0p-20f);
    for (int k = 0; k < 3; ++k) {
      const __m128 near = _mm_load_ps(near_is_lo_[k] ? lo[k] : hi[k]);
      const __m128 far = _mm_load_ps(near_is_lo_[k] ? hi[k] : lo[k]);
      t0 = _mm_max_ps(_mm_mul_ps(_mm_add_ps(near, near_offset4_[k]), inverse4_[k]), t0);
      t1 = _mm_min_ps(_mm_mul_ps(_mm_add_ps(far, far_offset4_[k]), inverse4_[k]), t1);
    }
    return _mm_movemask_ps(_mm_cmple_ps(t0, t1));
  }

 private:
  double inverse_[3], near_offset_[3], far_offset_[3];
  __m128 inverse4_[3], near_offset4_[3], far_offset4_[3];
  bool near_is_lo_[3];
};

class SegmentBvh {
 public:
  SegmentBvh() = default;
  /// Builds over the primitives' boxes; order() then lists primitive indices leaf by leaf.
  explicit SegmentBvh(const std::vector<Box3>& boxes);

  /// Primitive indices in leaf order (callers store their primitives in this order).
  const std::vector<std::uint32_t>& order() const { return order_; }

  /// Calls test(i) for the primitives (positions in order()) whose padded box the segment may
  /// meet, until one returns true; returns whether one did.
  template <class Test>
  bool any_hit(const SegmentCull& cull, Test&& test) const {
    if (order_.empty() || !cull.may_meet(root_lo_, root_hi_)) return false;
    auto leaf = [&](std::uint32_t first, std::uint32_t count) {
      for (std::uint32_t i = first; i < first + count; ++i)
        if (cull.may_meet(leaf_lo_[i].data(), leaf_hi_[i].data()) && test(i)) return true;
      return false;
    };
    if (nodes_.empty()) return leaf(0, static_cast<std::uint32_t>(order_.size()));
    std::uint32_t stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      int mask = cull.may_meet4(n.lo, n.hi) & n.valid;
      while (mask != 0) {
        const int c = __builtin_ctz(static_cast<unsigned>(mask));
        mask &= mask - 1;
        if (n.count[c] > 0) {
          if (leaf(n.child[c], n.count[c])) return true;
        } else {
          stack[top++] = n.child[c];
        }
      }
    }
    return false;
  }

  static constexpr int kStack = 3 * 48 + 4;  ///< depth <= 48 binary levels, <= 3 pushes per level

 private:
  /// An inner node with up to four children's boxes: a child is a leaf range
  /// [child, child + count) of order() when count > 0, else the index of an inner node.
  struct alignas(64) Node {
    float lo[3][4], hi[3][4];  ///< [axis][child], rounded outward from the double boxes
    std::uint32_t child[4];
    std::uint32_t count[4];
    int valid = 0;  ///< bit i set when child i exists
  };
  std::vector<Node> nodes_;
  float root_lo_[3], root_hi_[3];
  std::vector<std::uint32_t> order_;
  std::vector<std::array<double, 3>> leaf_lo_, leaf_hi_;  ///< primitive boxes in leaf order
};

}  // namespace hrad::detail
