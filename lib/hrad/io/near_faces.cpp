#include "hrad/io/near_faces.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "hrad/core/scene_checks.h"
#include "hrad/geometry/convex_clip.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

namespace {

// Whether the convex polygon `outline` (counter-clockwise about `normal`) holds every point, to `tolerance`.
bool encloses(const std::vector<Vec3>& outline, const Vec3& normal, const std::vector<Vec3>& points, double tolerance) {
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Vec3 edge = outline[(i + 1) % outline.size()] - outline[i];
    const Vec3 inward = normal.cross(edge).normalized();
    for (const Vec3& p : points)
      if ((p - outline[i]).dot(inward) < -tolerance) return false;
  }
  return true;
}

// For each patch, the patches of other faces whose outline cuts it (the rule of cut_near_faces()).
std::vector<std::vector<int>> near_cutters(const Scene& scene, double gap, NearCuts& cuts) {
  std::vector<std::vector<int>> cutters(scene.patches.size());
  if (scene.patches.empty() || !(gap > 0.0)) return cutters;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm();
  // Bucketed by the normal's direction, either way (rounded to 1e-6), each with its offset along it.
  struct Member {
    double offset;
    int patch;
    bool forward;  // faces along the bucket's direction
  };
  std::map<std::tuple<long long, long long, long long>, std::vector<Member>> buckets;
  std::vector<double> diameter(scene.patches.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    diameter[i] = polygon_diameter(p.vertices);
    Vec3 d = p.normal;
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    const bool forward = d[axis] > 0.0;
    if (!forward) d = -d;
    const auto q = [](double x) { return static_cast<long long>(std::llround(x / 1e-6)); };
    buckets[{q(d.x()), q(d.y()), q(d.z())}].push_back({d.dot(p.vertices[0]), static_cast<int>(i), forward});
  }
  for (auto& [key, members] : buckets) {
    if (members.size() < 2) continue;
    std::sort(members.begin(), members.end(), [](const Member& a, const Member& b) {
      return std::pair{a.offset, a.patch} < std::pair{b.offset, b.patch};
    });
    double widest = 0.0;
    for (const Member& m : members) widest = std::max(widest, diameter[static_cast<std::size_t>(m.patch)]);
    const double window = gap * widest, floor = 1e-9 * size;
    for (std::size_t i = 0; i < members.size(); ++i) {
      // A behind facing forward, B in front facing back: they face each other across offset B - A.
      const Member& a = members[i];
      if (!a.forward) continue;
      for (std::size_t j = i + 1; j < members.size() && members[j].offset - a.offset <= window; ++j) {
        const Member& b = members[j];
        const double g = b.offset - a.offset;
        if (b.forward || !(g > floor)) continue;
        const Patch& pa = scene.patches[static_cast<std::size_t>(a.patch)];
        const Patch& pb = scene.patches[static_cast<std::size_t>(b.patch)];
        if (pa.face == pb.face || pa.normal.dot(pb.normal) > -1.0 + 1e-12) continue;
        const bool cut_a = g <= gap * diameter[static_cast<std::size_t>(b.patch)];
        const bool cut_b = g <= gap * diameter[static_cast<std::size_t>(a.patch)];
        if (!cut_a && !cut_b) continue;
        Patch shadow = pb;  // b projected onto a's plane
        for (Vec3& v : shadow.vertices) v -= (v - pa.vertices[0]).dot(pa.normal) * pa.normal;
        if (!patches_overlap(pa, shadow, pa.normal, 1e-7 * size)) continue;
        // A pair splits the patch cut unless the outline encloses it (a corridor's opposite walls).
        const bool splits_a = cut_a && !encloses(shadow.vertices, pb.normal, pa.vertices, 1e-7 * size);
        const bool splits_b = cut_b && !encloses(pa.vertices, pa.normal, shadow.vertices, 1e-7 * size);
        if (cuts.splitting_pairs == 0 && (splits_a || splits_b)) {
          cuts.first_behind = splits_a ? pa.face : pb.face;
          cuts.first_front = splits_a ? pb.face : pa.face;
          cuts.first_gap = g;
        }
        cuts.splitting_pairs += static_cast<std::size_t>(splits_a) + static_cast<std::size_t>(splits_b);
        if (cut_a) cutters[static_cast<std::size_t>(a.patch)].push_back(b.patch), ++cuts.pairs;
        if (cut_b) cutters[static_cast<std::size_t>(b.patch)].push_back(a.patch), ++cuts.pairs;
      }
    }
  }
  return cutters;
}

}  // namespace

NearCuts find_near_faces(const Scene& scene, double gap) {
  NearCuts cuts;
  near_cutters(scene, gap, cuts);
  return cuts;
}

NearCuts cut_near_faces(Scene& scene, double gap) {
  NearCuts cuts;
  const std::vector<std::vector<int>> cutters = near_cutters(scene, gap, cuts);
  if (cuts.pairs == 0) return cuts;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm();
  const std::size_t before = scene.patches.size();
  scene.patches = cut_patches(scene.patches, cutters, true, size);
  cuts.patches_added = scene.patches.size() > before ? scene.patches.size() - before : 0;
  relink_faces(scene);
  return cuts;
}

namespace {

// "FILE:LINE: KIND: N pairs of faces face each other from nearby (first: ...)", or "" when none split.
std::string near_pairs_line(const Scene& scene, const NearCuts& near, const char* kind) {
  if (near.splitting_pairs == 0) return {};
  const auto line = [&](int face) { return scene.faces[static_cast<std::size_t>(face)].line; };
  return fmt::format(
      "{}:{}: {}: {} pair{} of faces face each other from nearby (first: line {}, {:.3g} in front of "
      "line {})",
      scene.path, line(near.first_behind), kind, near.splitting_pairs, near.splitting_pairs == 1 ? "" : "s",
      line(near.first_front), near.first_gap, line(near.first_behind));
}

}  // namespace

std::string near_faces_warning(const Scene& uncut) {
  const std::string head = near_pairs_line(uncut, find_near_faces(uncut), "warning");
  if (head.empty()) return {};
  return head +
         ": the face behind is dark in the near face's shadow and lit around it, and its elements average the two "
         "(the near face gathers that mean); without --no-cut-near-faces, hrad solve and hrad sweep cut along the "
         "outline";
}

std::string near_faces_note(const Scene& uncut, const NearCuts& near, std::size_t patches_added) {
  const std::string head = near_pairs_line(uncut, near, "note");
  if (head.empty()) return {};
  return head + fmt::format(
                    ": hrad solve and hrad sweep cut the face behind along the near face's outline ({} patch{} more; "
                    "--no-cut-near-faces keeps the faces whole)",
                    patches_added, patches_added == 1 ? "" : "es");
}

}  // namespace hrad
