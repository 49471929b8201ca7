#include "hrad/io/flush_faces.h"

#include <map>
#include <string>
#include <utility>

#include "hrad/core/scene_checks.h"
#include "hrad/geometry/convex_clip.h"

namespace hrad {

FlushCuts cut_flush_faces(Scene& scene) {
  FlushCuts cuts;
  const std::vector<std::pair<int, int>> pairs = flush_pairs(scene);
  if (pairs.empty()) return cuts;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm();
  // Which lies on top (flush_faces.h): the smaller object, then the smaller face, then the later face.
  std::map<std::string, double> object_area;
  for (const Patch& p : scene.patches) object_area[p.group] += p.area;
  const auto on_top = [&](int fa, int fb) {
    const InputFace& a = scene.faces[static_cast<std::size_t>(fa)];
    const InputFace& b = scene.faces[static_cast<std::size_t>(fb)];
    const double ga = object_area[a.group], gb = object_area[b.group];
    if (ga != gb) return ga < gb;
    if (a.area != b.area) return a.area < b.area;
    return fa > fb;
  };
  std::vector<std::vector<int>> covers(scene.patches.size());  // per patch beneath: the patches on it
  for (const auto& [i, j] : pairs) {
    const int fi = scene.patches[static_cast<std::size_t>(i)].face,
              fj = scene.patches[static_cast<std::size_t>(j)].face;
    const auto [top, beneath] = on_top(fi, fj) ? std::pair{i, j} : std::pair{j, i};
    covers[static_cast<std::size_t>(beneath)].push_back(top);
    if (cuts.pairs++ == 0) {
      cuts.first_top = scene.patches[static_cast<std::size_t>(top)].face;
      cuts.first_beneath = scene.patches[static_cast<std::size_t>(beneath)].face;
    }
  }
  // The patches beneath may come before or after the patches on top of them: all are cut from the
  // patches as given.
  scene.patches = cut_patches(scene.patches, covers, false, size, &cuts.covered_area);
  std::vector<char> had(scene.faces.size(), 0);
  for (std::size_t f = 0; f < scene.faces.size(); ++f) had[f] = !scene.faces[f].patches.empty();
  relink_faces(scene);
  for (std::size_t f = 0; f < scene.faces.size(); ++f)
    if (had[f] && scene.faces[f].patches.empty()) ++cuts.hidden_faces;
  return cuts;
}

}  // namespace hrad
