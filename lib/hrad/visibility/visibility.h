// Visibility between points and polygons of a scene, decided with exact predicates.
// The one visibility oracle every solver asks; CGAL stays inside the implementation.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"
#include "hrad/core/work_counter.h"

namespace hrad {

/// How a pair of polygons sees each other, decided before any ray is cast.
enum class PairClass { kFacingAway, kFullyVisible, kFullyHidden, kPartial };

/// Whether no light passes between the pair: facing away or fully hidden.
inline bool is_blocking(PairClass c) { return c == PairClass::kFacingAway || c == PairClass::kFullyHidden; }

/// Whether light passes between a point of one patch and a point of another (Visibility::sight()).
enum class Sight {
  kFacingAway,  ///< a point is off its patch, or not strictly in front of the other's patch there
  kBlocked,     ///< facing, and the open segment between them meets another patch
  kVisible,     ///< facing, and nothing between them
};

/// What a ray first meets (Visibility::first_hit()).
struct RayHit {
  int patch = -1;      ///< -1: nothing (the ray leaves the scene)
  bool front = false;  ///< it meets `patch` from the side its normal faces
};

/// Fraction of the pair that is mutually visible, with an error estimate.
struct VisibilityEstimate {
  double fraction = 1.0;  ///< in [0, 1]
  double error = 0.0;     ///< estimate of |fraction - true fraction| (0 when classified exactly)
  PairClass pair_class = PairClass::kFullyVisible;
};

/// Counters for solver reports, safe to add to from many threads (work_counter.h).
struct VisibilityCounters {
  WorkCounter segment_queries;
  WorkCounter pairs_facing_away;
  WorkCounter pairs_visible;
  WorkCounter pairs_hidden;
  WorkCounter pairs_partial;
  WorkCounter pair_queries;   ///< classify() calls, including those inside estimate()
  WorkCounter point_queries;  ///< estimate_from_point() calls

  void reset() {
    for (WorkCounter* c : {&segment_queries, &pairs_facing_away, &pairs_visible, &pairs_hidden, &pairs_partial,
                           &pair_queries, &point_queries})
      c->reset();
  }
};

/// Visibility oracle over the patches of one scene. Elements are sub-polygons of patches: every
/// query names the patch each polygon or point lies on, so that the endpoints' own patches never
/// block (see the implementation file for the exact touching rules).
class Visibility {
 public:
  virtual ~Visibility() = default;

  /// True iff the open segment a-b meets a patch other than `patch_a` and `patch_b`. An end that
  /// names its patch (>= 0) lies on it, to the rounding of its doubles: it stands for the point of
  /// the patch's surface with the same coordinates across the patch's dominant normal axis (exactly
  /// the double point when that lies on the surface), and the segment is decided between those
  /// points exactly. So a zero-thickness wall's back-to-back twin, or a closed surface around the
  /// patch, never blocks or lets through a segment by which side of the plane a rounded sample
  /// point fell on. An end with patch -1 is the double point itself.
  virtual bool segment_blocked(const Vec3& a, int patch_a, const Vec3& b, int patch_b) const = 0;

  /// Light transport between the point `a` of patch `patch_a` and the point `b` of patch `patch_b`
  /// (both >= 0; the points stand for points of their patches as in segment_blocked()), decided
  /// exactly: kFacingAway unless both points lie on their patches and each lies strictly in
  /// front of the other's patch there (positive cosines at both ends); then kBlocked or
  /// kVisible as segment_blocked() says. What sampled form factors count: with exact facing as
  /// well as exact occlusion, no pair of points can carry light through a closed surface, however
  /// the points' doubles were rounded. Counted as a segment query.
  virtual Sight sight(const Vec3& a, int patch_a, const Vec3& b, int patch_b) const = 0;
  /// sight() where only the patches `occluders` can block (as segment_blocked_among()).
  virtual Sight sight_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                            std::span<const int> occluders) const = 0;

  /// Classifies a pair by shaft culling (Haines & Wallace 1994) with exact predicates.
  virtual PairClass classify(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b) const = 0;

  /// classify() with candidate occluder lists (Haines & Wallace 1994, sec. 5; Teller & Hanrahan
  /// 1993 pass such lists down a hierarchy). Only the patches in `candidates` (sorted; every patch
  /// when null) can occlude, and `occluders` (when not null) receives, sorted, the patches whose
  /// triangles may meet the pair's shaft. The shaft of a sub-pair (a point or sub-polygon of `a`
  /// with a sub-polygon of `b`) lies in the pair's shaft, so the pair's occluders are complete
  /// candidates for every sub-pair: the answer is the one a search of the whole scene gives, at a
  /// cost that falls with the list instead of the scene. `a` may be a single point.
  virtual PairClass classify_among(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                                   const std::vector<int>* candidates, std::vector<int>* occluders) const = 0;

  /// segment_blocked() where only the patches `occluders` can block (e.g. a pair's occluders from
  /// classify_among(), for a segment between points of the pair). Counted as a segment query.
  virtual bool segment_blocked_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                                     std::span<const int> occluders) const = 0;

  /// Classifies the pair and, only when partial, samples `samples` stratified point pairs
  /// (deterministic in `seed`) to estimate the visible fraction. Only mutually facing sample
  /// pairs (each point strictly in front of the other polygon's plane, the pairs the form factor
  /// weighs) count; the fraction is visible / facing and the error the Wilson half-width.
  virtual VisibilityEstimate estimate(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                                      int samples, std::uint64_t seed) const = 0;

  /// True when some patch can block some pair of other patches (an empty convex room: false).
  virtual bool scene_has_occlusion() const = 0;

  /// Fraction of the polygon `b` (on patch `patch_b`) visible from the point `x` (on patch
  /// `patch_x`, or -1 for a point on no patch), by area: 0 when `b` faces away from x, otherwise
  /// `samples` stratified points of `b` (deterministic in `seed`) unless the pair is classified
  /// exactly first. The default samples with segment_blocked().
  virtual VisibilityEstimate estimate_from_point(const Vec3& x, int patch_x, std::span<const Vec3> b, int patch_b,
                                                 int samples, std::uint64_t seed) const;

  /// The first patch other than `patch` that the ray from `x` along `direction` (unit, not
  /// parallel to nothing in particular) meets, and from which side; nothing (-1) when it leaves
  /// the scene. Decided in double precision (Moller & Trumbore 1997) with triangles' edges taken
  /// as closed, for statistics over many rays (closed_scene.h), not for the exact sight of a pair.
  /// Meetings within 1e-12 of the scene's extent of `x` are ignored (a zero-thickness wall's
  /// back-to-back twin of `patch`); of patches met at one distance (a zero-thickness wall seen
  /// from either side) the one met from its front counts. Counted as a segment query.
  virtual RayHit first_hit(const Vec3& x, int patch, const Vec3& direction) const = 0;

  VisibilityCounters& counters() const { return counters_; }

 private:
  mutable VisibilityCounters counters_;
};

/// The CGAL implementation: AABB tree of the scene's triangles, exact predicates.
std::unique_ptr<Visibility> make_visibility(const Scene& scene);

struct VisibilityOptions {
  /// Segment queries walk CGAL's AABB_tree instead of hrad's compact SAH hierarchy
  /// (segment_bvh.h). Both cull conservatively and decide with the same exact predicates, so the
  /// answers are identical; the compact one is faster (visibility_benchmark). Shaft queries
  /// always use CGAL's tree.
  bool cgal_tree_for_segments = false;
  /// On: occluders that touch a pair's shaft without the plane tests settling them are decided by
  /// exact rational clipping, so such pairs can be fully visible rather than partial. Off (the
  /// default): they count as partial and sampling decides. In the Cornell box the exact step
  /// settles ~1.5% more pairs at ~10x the classification cost (visibility_benchmark).
  bool exact_shaft_contacts = false;
};
std::unique_ptr<Visibility> make_visibility(const Scene& scene, const VisibilityOptions& options);

}  // namespace hrad
