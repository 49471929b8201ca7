// Brightness of umbras: on the bundled Cornell box, the leaves that see none of the light (every
// point of the leaf hidden from every emitter, decided by the final gather's own visibility) are lit
// only by interreflection, through links that may be coarse and partly visible. A link gives its
// receiver the visibility averaged over the receiver (or, with the HSA push, a quadratic field
// through the receiver's points), so leaves in an umbra can gather light that their own points do
// not see. This measures it: each umbra leaf's radiosity against the final gather of the same
// solution at points across the leaf (gather/leaf_gather.h, leaf by leaf, exact factors, visibility
// from each point), area-weighted per surface group:
//   bias(group) = sum_L A_L (B_L - Bg_L) / sum_L A_L Bg_L,   Bg_L the leaf's mean gathered radiosity.
// Counters: bias in percent per group (floor, red wall, blocks, ceiling), the largest single leaf's,
// and the elements. Arguments: aeps as total area / arg, and the push (0 = hsa, 1 = leaf).
//   build/bin/umbra_benchmark --benchmark_counters_tabular=true
// (aeps total/12000 gives about 6k elements and takes a few minutes a run.)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>

#include "hrad/gather/leaf_gather.h"
#include "hrad/io/obj_reader.h"
#include "hrad/solvers/solve.h"

namespace hrad {
namespace {

const Scene& cornell() {
  static const Scene s = read_obj_scene(std::string(HRAD_SOURCE_DIR) + "/notebooks_data/scenes/cornell_box.obj");
  return s;
}

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

void BM_UmbraBias(benchmark::State& state) {
  const Scene& scene = cornell();
  SolveOptions options;
  options.aeps = scene.total_area() / static_cast<double>(state.range(0));
  options.push = state.range(1) == 0 ? Push::kHsa : Push::kLeaf;
  for (auto _ : state) {
    Solution s;
    solve(scene, options, &s);
    const LeafPoints lp = leaf_points(scene, s);
    // Umbra leaves: no point gathers any emission (the solution with B = E on emitters, 0 elsewhere).
    Solution emission = s;
    emission.face_field.clear();
    for (std::size_t f = 0; f < s.faces.size(); ++f)
      emission.face_radiosity[f] =
          scene.materials[static_cast<std::size_t>(scene.patches[static_cast<std::size_t>(s.face_patch[f])].material)]
              .emission;
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
      const Material& m =
          scene.materials[static_cast<std::size_t>(scene.patches[static_cast<std::size_t>(s.face_patch[f])].material)];
      area[f] += lp.weight[i];
      gathered[f] += lp.weight[i] * (m.emission + m.reflectance * h[k]).sum();
    }
    struct Group {
      double bias = 0.0, base = 0.0, worst = 0.0;
    };
    std::map<std::string, Group> groups;
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      if (lit[f] || !(area[f] > 0.0)) continue;
      const Patch& patch = scene.patches[static_cast<std::size_t>(s.face_patch[f])];
      if (scene.materials[static_cast<std::size_t>(patch.material)].is_emitter()) continue;
      const double g = gathered[f] / area[f], b = s.face_radiosity[f].sum();
      Group& group = groups[patch.group];
      group.bias += area[f] * (b - g);
      group.base += area[f] * g;
      group.worst = std::max(group.worst, (b - g) / g);
    }
    for (const auto& [name, g] : groups) {
      state.counters[name + "%"] = 100.0 * g.bias / g.base;
      state.counters[name + " leaf max%"] = 100.0 * g.worst;
    }
    state.counters["elements"] = static_cast<double>(s.faces.size());
  }
}
BENCHMARK(BM_UmbraBias)
    ->ArgsProduct({{4000, 12000}, {0, 1}})
    ->ArgNames({"total/aeps", "leaf_push"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
