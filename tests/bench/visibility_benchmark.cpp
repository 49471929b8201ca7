// Visibility benchmarks: segment queries per second against scene size, pair classification in
// the Cornell box (share of pairs settled without rays), sampled pair estimates, and the exact
// from-point region.
//
//   build/bin/visibility_benchmark --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <random>

#include <Eigen/Geometry>

#include "hrad/geometry/polygon.h"
#include "hrad/io/obj_reader.h"
#include "hrad/visibility/visibility.h"
#include "hrad/visibility/visible_region.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

int add_patch(Scene& s, std::vector<Vec3> v) {
  Patch p;
  p.vertices = std::move(v);
  const Vec3 n = newell_normal(p.vertices);
  p.normal = n.normalized();
  p.area = 0.5 * n.norm();
  p.material = 0;
  s.patches.push_back(std::move(p));
  return static_cast<int>(s.patches.size()) - 1;
}

/// A closed unit room (12 triangles, fronts inside) filled with `clutter` random triangles whose
/// size shrinks like clutter^(-1/2), so that the total occluder area and the share of blocked
/// rays stay about the same at every scene size.
Scene cluttered_room(int clutter, std::uint64_t seed) {
  Scene s;
  s.materials.push_back(Material{"grey", Rgb::Constant(0.5), Rgb::Zero()});
  const Vec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  for (const auto& q : quads) {
    add_patch(s, {c[q[0]], c[q[1]], c[q[2]]});
    add_patch(s, {c[q[0]], c[q[2]], c[q[3]]});
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 0.95), d(-1, 1);
  const double size = 0.9 / std::sqrt(double(clutter));
  for (int i = 0; i < clutter; ++i) {
    const Vec3 p(u(rng), u(rng), u(rng));
    add_patch(s, {p, p + size * Vec3(d(rng), d(rng), d(rng)), p + size * Vec3(d(rng), d(rng), d(rng))});
  }
  return s;
}

/// A closed unit room (12 triangles) furnished with closed boxes (12 triangles each, random
/// sizes and orientations, at most `triangles` in all); the boxes shrink like count^(-1/2) so that
/// the share of blocked rays stays about the same at every scene size. A furnished room is the
/// usual radiosity scene: rays end on the first object they meet.
Scene furnished_room(int triangles, std::uint64_t seed) {
  Scene s = cluttered_room(0, seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 0.9), d(-1, 1), e(0.5, 1.0);
  const int boxes = (triangles - 12) / 12;
  const double size = 0.5 / std::sqrt(double(boxes));
  for (int i = 0; i < boxes; ++i) {
    const Vec3 c(u(rng), u(rng), u(rng));
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(Eigen::Vector4d(d(rng), d(rng), d(rng), d(rng)).normalized()).toRotationMatrix();
    const Vec3 h = size * Vec3(e(rng), e(rng), e(rng));
    Vec3 v[8];
    for (int k = 0; k < 8; ++k)
      v[k] = c + r * Vec3((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z());
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      add_patch(s, {v[q[0]], v[q[1]], v[q[2]]});
      add_patch(s, {v[q[0]], v[q[2]], v[q[3]]});
    }
  }
  return s;
}

struct Query {
  Vec3 a, b;
  int pa, pb;
};

/// Segments between uniform points of two random walls of the room (patches 0..11).
std::vector<Query> wall_queries(const Scene& s, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<int> wall(0, 11);
  std::vector<Query> q;
  auto point = [&](int p) {
    const auto& v = s.patches[p].vertices;
    double s1 = u(rng), s2 = u(rng);
    if (s1 + s2 > 1) {
      s1 = 1 - s1;
      s2 = 1 - s2;
    }
    return Vec3(v[0] + s1 * (v[1] - v[0]) + s2 * (v[2] - v[0]));
  };
  while (static_cast<int>(q.size()) < count) {
    const int pa = wall(rng), pb = wall(rng);
    if (pa / 2 == pb / 2) continue;  // same wall
    q.push_back({point(pa), point(pb), pa, pb});
  }
  return q;
}

void segment_queries(benchmark::State& state, bool cgal_tree, bool furnished) {
  const int triangles = static_cast<int>(state.range(0));
  const Scene s = furnished ? furnished_room(triangles, 1) : cluttered_room(triangles - 12, 1);
  VisibilityOptions options;
  options.cgal_tree_for_segments = cgal_tree;
  const auto v = make_visibility(s, options);
  const auto q = wall_queries(s, 1 << 14, 2);
  std::size_t i = 0, blocked = 0, done = 0;
  for (auto _ : state) {
    const Query& x = q[i++ & (q.size() - 1)];
    const bool b = v->segment_blocked(x.a, x.pa, x.b, x.pb);
    blocked += b;
    ++done;
    benchmark::DoNotOptimize(b);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(done));
  state.counters["triangles"] = double(s.patches.size());
  state.counters["blocked_share"] = double(blocked) / double(done);
}

// Segments between points of two different walls of a unit room holding `triangles` in all:
// furnished with closed boxes, or filled with a uniform soup of small triangles (the hard case:
// few rays end early, and a ray crosses O(n^(1/3)) boxes of the hierarchy).
void BM_SegmentQueriesFurnished(benchmark::State& state) { segment_queries(state, false, true); }
BENCHMARK(BM_SegmentQueriesFurnished)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kNanosecond);
void BM_SegmentQueriesSoup(benchmark::State& state) { segment_queries(state, false, false); }
BENCHMARK(BM_SegmentQueriesSoup)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kNanosecond);

// The same queries through CGAL's AABB_tree (same exact predicates, same answers).
void BM_SegmentQueriesFurnishedCgalTree(benchmark::State& state) { segment_queries(state, true, true); }
BENCHMARK(BM_SegmentQueriesFurnishedCgalTree)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kNanosecond);
void BM_SegmentQueriesSoupCgalTree(benchmark::State& state) { segment_queries(state, true, false); }
BENCHMARK(BM_SegmentQueriesSoupCgalTree)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kNanosecond);

void BM_BuildTree(benchmark::State& state) {
  const Scene s = cluttered_room(static_cast<int>(state.range(0)) - 12, 1);
  for (auto _ : state) benchmark::DoNotOptimize(make_visibility(s));
  state.counters["triangles"] = double(state.range(0));
}
BENCHMARK(BM_BuildTree)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

/// Every patch of the scene split into k x k elements (quads bilinearly, triangles by a
/// barycentric grid), each with the patch it lies on.
std::vector<std::pair<std::vector<Vec3>, int>> elements(const Scene& s, int k) {
  std::vector<std::pair<std::vector<Vec3>, int>> out;
  for (int p = 0; p < static_cast<int>(s.patches.size()); ++p) {
    const auto& v = s.patches[p].vertices;
    if (v.size() == 4) {
      auto at = [&](int i, int j) {
        const double a = double(i) / k, b = double(j) / k;
        return Vec3((1 - a) * (1 - b) * v[0] + a * (1 - b) * v[1] + a * b * v[2] + (1 - a) * b * v[3]);
      };
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) out.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, p});
    } else if (v.size() == 3) {
      auto at = [&](int i, int j) {
        return Vec3(v[0] + (double(i) / k) * (v[1] - v[0]) + (double(j) / k) * (v[2] - v[0]));
      };
      for (int i = 0; i < k; ++i)
        for (int j = 0; i + j < k; ++j) {
          out.push_back({{at(i, j), at(i + 1, j), at(i, j + 1)}, p});
          if (i + j + 1 < k) out.push_back({{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}, p});
        }
    }
  }
  return out;
}

const std::string kCornell = test::source_dir() + "/notebooks_data/scenes/cornell_box.obj";

// All ordered element pairs of the Cornell box at k x k elements per patch: the share of pairs the
// classification settles without rays (facing away, fully visible, fully hidden).
void classify_cornell(benchmark::State& state, bool exact_contacts) {
  const Scene s = read_obj_scene(kCornell);
  VisibilityOptions options;
  options.exact_shaft_contacts = exact_contacts;
  const auto v = make_visibility(s, options);
  const auto el = elements(s, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    v->counters().reset();
    for (const auto& [a, pa] : el)
      for (const auto& [b, pb] : el)
        if (pa != pb) benchmark::DoNotOptimize(v->classify(a, pa, b, pb));
  }
  const auto& c = v->counters();
  const double pairs = double(c.pair_queries.load());
  const double facing = pairs - double(c.pairs_facing_away.load());
  state.SetItemsProcessed(static_cast<std::int64_t>(pairs) * state.iterations());
  state.counters["elements"] = double(el.size());
  state.counters["pairs"] = pairs;
  state.counters["settled_share"] = 1.0 - double(c.pairs_partial.load()) / pairs;
  state.counters["facing_away"] = double(c.pairs_facing_away.load()) / pairs;
  state.counters["visible"] = double(c.pairs_visible.load()) / pairs;
  state.counters["hidden"] = double(c.pairs_hidden.load()) / pairs;
  state.counters["partial"] = double(c.pairs_partial.load()) / pairs;
  state.counters["settled_of_facing"] = 1.0 - double(c.pairs_partial.load()) / facing;
}
void BM_ClassifyCornell(benchmark::State& state) { classify_cornell(state, true); }
BENCHMARK(BM_ClassifyCornell)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);
// Without the exact settling of occluders that only touch the shaft.
void BM_ClassifyCornellNoContacts(benchmark::State& state) { classify_cornell(state, false); }
BENCHMARK(BM_ClassifyCornellNoContacts)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

// Sampled estimates of the Cornell box's partial pairs (the rays a solver pays for).
void BM_EstimatePartialCornell(benchmark::State& state) {
  const Scene s = read_obj_scene(kCornell);
  const auto v = make_visibility(s);
  const auto el = elements(s, 2);
  std::vector<std::pair<int, int>> partial;
  for (int i = 0; i < static_cast<int>(el.size()); ++i)
    for (int j = 0; j < static_cast<int>(el.size()); ++j)
      if (el[i].second != el[j].second &&
          v->classify(el[i].first, el[i].second, el[j].first, el[j].second) == PairClass::kPartial)
        partial.push_back({i, j});
  const int samples = static_cast<int>(state.range(0));
  v->counters().reset();
  std::size_t k = 0;
  for (auto _ : state) {
    const auto [i, j] = partial[k++ % partial.size()];
    benchmark::DoNotOptimize(v->estimate(el[i].first, el[i].second, el[j].first, el[j].second, samples, k));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rays_per_s"] =
      benchmark::Counter(double(v->counters().segment_queries.load()), benchmark::Counter::kIsRate);
  state.counters["partial_pairs"] = double(partial.size());
}
BENCHMARK(BM_EstimatePartialCornell)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

// The exact from-point region: a Cornell box floor element seen from a point under the ceiling.
void BM_VisibleRegionCornell(benchmark::State& state) {
  const Scene s = read_obj_scene(kCornell);
  int floor = 0;
  for (int p = 0; p < static_cast<int>(s.patches.size()); ++p)
    if (s.patches[p].group == "floor") floor = p;
  const Vec3 eye(278.0, 540.0, 279.6);
  double fraction = 0.0;
  for (auto _ : state) {
    const VisibleRegion r = visible_region(s, eye, -1, s.patches[floor].vertices, floor);
    fraction = r.area_fraction;
    benchmark::DoNotOptimize(r);
  }
  state.counters["visible_fraction"] = fraction;
}
BENCHMARK(BM_VisibleRegionCornell)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
