#include "support/umbra_bias.h"

#include <algorithm>
#include <vector>

#include "hrad/gather/leaf_gather.h"

namespace hrad::test {
namespace {

// Points across each leaf: the leaf fanned into triangles, each with the degree-3 rule of Strang &
// Fix (centroid weight -27/48, three points weight 25/48), weights in area.
struct LeafPoints {
  std::vector<GatherPoint> points;
  std::vector<double> weight;
  std::vector<std::size_t> leaf;
};

LeafPoints leaf_points(const Scene& scene, const Solution& s) {
  static constexpr double kBary[4][3] = {
      {1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.6, 0.2, 0.2}, {0.2, 0.6, 0.2}, {0.2, 0.2, 0.6}};
  static constexpr double kWeight[4] = {-27.0 / 48, 25.0 / 48, 25.0 / 48, 25.0 / 48};
  LeafPoints out;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const std::vector<int>& face = s.faces[f];
    const int patch = s.face_patch[f];
    const Vec3& a = s.vertices[static_cast<std::size_t>(face[0])];
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3& b = s.vertices[static_cast<std::size_t>(face[k])];
      const Vec3& c = s.vertices[static_cast<std::size_t>(face[k + 1])];
      const double area = 0.5 * (b - a).cross(c - a).norm();
      for (int i = 0; i < 4; ++i) {
        out.points.push_back({kBary[i][0] * a + kBary[i][1] * b + kBary[i][2] * c,
                              scene.patches[static_cast<std::size_t>(patch)].normal, patch});
        out.weight.push_back(area * kWeight[i]);
        out.leaf.push_back(f);
      }
    }
  }
  return out;
}

}  // namespace

std::map<std::string, UmbraBias> umbra_bias(const Scene& scene, const Solution& s) {
  const LeafPoints lp = leaf_points(scene, s);
  auto material = [&](std::size_t face) -> const Material& {
    return scene.material_of(scene.patches[static_cast<std::size_t>(s.face_patch[face])]);
  };
  // Umbra leaves: no point gathers any emission (the solution with B = E on emitters, 0 elsewhere).
  Solution emission = s;
  emission.face_field.clear();
  for (std::size_t f = 0; f < s.faces.size(); ++f) emission.face_radiosity[f] = material(f).emission;
  LeafGatherOptions gather;
  gather.tolerance = 1e-9;  // groups the dark patches whole; every lit leaf on its own
  gather.visibility_samples = 16;
  const std::vector<Rgb> direct = LeafGather(scene, emission, gather).gather(lp.points);
  std::vector<char> lit(s.faces.size(), 0);
  for (std::size_t i = 0; i < lp.points.size(); ++i)
    if (direct[i].maxCoeff() > 0.0) lit[lp.leaf[i]] = 1;
  std::vector<GatherPoint> dark;
  std::vector<std::size_t> dark_index;
  for (std::size_t i = 0; i < lp.points.size(); ++i)
    if (!lit[lp.leaf[i]]) dark.push_back(lp.points[i]), dark_index.push_back(i);
  gather.tolerance = 0.0;  // leaf by leaf: the sweep's reference gather
  gather.visibility_samples = 64;
  const std::vector<Rgb> h = LeafGather(scene, s, gather).gather(dark);
  std::vector<double> area(s.faces.size(), 0.0), gathered(s.faces.size(), 0.0);
  for (std::size_t k = 0; k < dark.size(); ++k) {
    const std::size_t i = dark_index[k], f = lp.leaf[i];
    const Material& m = material(f);
    area[f] += lp.weight[i];
    gathered[f] += lp.weight[i] * (m.emission + m.reflectance * h[k]).sum();
  }
  std::map<std::string, UmbraBias> groups;
  std::map<std::string, double> base;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (lit[f] || !(area[f] > 0.0) || material(f).is_emitter()) continue;
    const std::string& name = scene.patches[static_cast<std::size_t>(s.face_patch[f])].group;
    const double g = gathered[f] / area[f], b = s.face_radiosity[f].sum();
    UmbraBias& group = groups[name];
    group.bias += area[f] * (b - g);
    base[name] += area[f] * g;
    group.worst = std::max(group.worst, (b - g) / g);
    ++group.leaves;
  }
  for (auto& [name, g] : groups) g.bias /= base[name];
  return groups;
}

}  // namespace hrad::test
