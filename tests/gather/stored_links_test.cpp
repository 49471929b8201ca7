// A hierarchical solve's links through its solution file (gather/stored_links.h, io/solution_ply.h)
// and the gather of a solution read from a file (gather/solution_gather.h), as `hrad render
// --final-gather` and `hrad probe` run it: the links rebuilt exactly, the gather through them equal
// to the one in the solve's process, within sampling noise of the all-patches gather, exact where
// closed forms hold, and links that do not fit refused naming the file.
#include "hrad/gather/stored_links.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "../formfactor/howell.h"
#include "../support/temp_dir.h"
#include "gather_test_scenes.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/core/error.h"
#include "hrad/gather/gathered_image.h"
#include "hrad/gather/probes.h"
#include "hrad/gather/solution_gather.h"
#include "hrad/io/obj_reader.h"
#include "hrad/render/render.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

using test::make_box;
using test::material;

const Scene& cornell() {
  static const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return s;
}

using test::solve_keeping;

// The solution and its links written to `path` and read back.
struct ReadBack {
  Solution solution;
  std::optional<SolutionLinks> links;
};
ReadBack through_file(const std::string& path, const Solution& solution, const SolvedHierarchy* kept) {
  std::optional<SolutionLinks> stored;
  if (kept) stored = stored_links(*kept);
  write_solution_ply(path, solution, 1.0, stored ? &*stored : nullptr);
  ReadBack r;
  r.solution = read_solution_ply(path, &r.links);
  EXPECT_EQ(r.links.has_value(), kept != nullptr);
  if (stored && r.links) EXPECT_TRUE(*r.links == *stored);
  return r;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// The Cornell box's default solve (no clusters) and one with clusters, through the file: the same elements (corners,
// patches, tree), the same leaf radiosities, interior ones the area means the solver kept (to rounding), the same
// links; and so the gather through the restored links gives what the gather through the solve's own gives, to rounding.
TEST(StoredLinks, RoundTripThroughTheFileRebuildsWhatTheGatherReads) {
  test::TempDir dir;
  const std::vector<SurfaceSample> samples = patch_samples(cornell(), 16);
  std::vector<GatherPoint> points;
  for (const SurfaceSample& s : samples)
    points.push_back({s.position, cornell().patches[static_cast<std::size_t>(s.patch)].normal, s.patch});
  for (const Clustering clustering : {Clustering::kAuto, Clustering::kOn}) {
    SolveOptions o;
    o.clustering = clustering;
    Solution solution;
    const SolvedHierarchy kept = solve_keeping(cornell(), o, &solution);
    const ReadBack r = through_file(dir.path("s.ply"), solution, &kept);
    ASSERT_TRUE(r.links);
    const SolvedHierarchy restored = restored_links(cornell(), r.solution, *r.links, dir.path("s.ply"));
    const ElementHierarchy &a = *kept.hierarchy, &b = *restored.hierarchy;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      const ElementNode &x = a.node(static_cast<NodeId>(i)), &y = b.node(static_cast<NodeId>(i));
      ASSERT_EQ(x.vertex_count, y.vertex_count) << i;
      for (int k = 0; k < x.vertex_count; ++k) EXPECT_EQ(x.vertices[k], y.vertices[k]) << i;
      EXPECT_EQ(x.patch, y.patch);
      EXPECT_EQ(x.parent, y.parent);
      EXPECT_EQ(x.first_child, y.first_child);
      for (int c = 0; c < 3; ++c)
        if (x.is_leaf())
          EXPECT_EQ(x.radiosity[c], y.radiosity[c]) << i;
        else
          EXPECT_NEAR(x.radiosity[c], y.radiosity[c], 1e-12 * std::abs(x.radiosity[c])) << i;
    }
    ASSERT_EQ(kept.tree != nullptr, restored.tree != nullptr);
    if (clustering == Clustering::kOn) ASSERT_TRUE(kept.tree);
    if (kept.tree) EXPECT_EQ(kept.tree->size(), restored.tree->size());
    ASSERT_EQ(kept.links.size(), restored.links.size());
    for (std::size_t k = 0; k < kept.links.size(); ++k) {
      const Link &x = kept.links[k], &y = restored.links[k];
      EXPECT_EQ(x.p, y.p);
      EXPECT_EQ(x.q, y.q);
      EXPECT_EQ(x.partial, y.partial);
      for (int q = 0; q < static_cast<int>(cornell().patches.size()); ++q) {
        EXPECT_EQ(visible_share(x.hidden_p.get(), q) > 0.0, visible_share(y.hidden_p.get(), q) > 0.0);
        EXPECT_EQ(visible_share(x.hidden_q.get(), q) > 0.0, visible_share(y.hidden_q.get(), q) > 0.0);
      }
    }
    const std::vector<Rgb> before = LinkGather(cornell(), kept).gather(points);
    const std::vector<Rgb> after = LinkGather(cornell(), restored).gather(points);
    for (std::size_t i = 0; i < points.size(); ++i)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[i][c], before[i][c], 1e-12 * before[i].maxCoeff()) << i;
  }
}

// Relative L2 distance between two images' pixels (all channels).
double image_l2(const HdrImage& a, const HdrImage& b) {
  double d = 0.0, s = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    d += (a.pixels[i] - b.pixels[i]).square().sum();
    s += b.pixels[i].square().sum();
  }
  return std::sqrt(d / s);
}

// The default Cornell-box solve read from its file, gathered as `hrad render --final-gather` and
// `hrad probe` do (their options), through the links and over all patches. Both estimate the same
// sum with their own visibility samples, so they differ by sampling noise: at most the two gathers'
// own differences between two seeds added (two unbiased estimates with noise s1, s2 differ by about
// sqrt(s1^2 + s2^2), one seed change by sqrt(2) s). A source missed or counted twice, or a
// visibility class trusted where it does not hold, of that size fails.
TEST(StoredLinks, RenderAndProbesThroughTheFileAgreeWithTheAllPatchesGather) {
  test::TempDir dir;
  Solution solution;
  const SolvedHierarchy kept = solve_keeping(cornell(), SolveOptions{}, &solution);
  const ReadBack r = through_file(dir.path("s.ply"), solution, &kept);
  const auto gather = [&](GatherSources sources, LeafGatherOptions all, std::uint64_t seed) {
    all.seed = seed;
    return std::make_unique<SolutionGather>(cornell(), r.solution, r.links, dir.path("s.ply"), sources, all);
  };
  // The image: hrad render's options (32 rays a point shared by its partly visible sources).
  LeafGatherOptions image_all;
  image_all.partial = PartialSampling::shared;
  image_all.visibility_samples = 32;
  image_all.classify_points = false;
  RenderOptions ro;
  ro.camera = default_camera(r.solution, 40, 40);
  ro.samples_per_pixel = 2;
  HdrImage images[2][2];  // [through links][seed - 1]
  for (int links = 0; links < 2; ++links)
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const auto g = gather(links ? GatherSources::automatic : GatherSources::all, image_all, seed);
      EXPECT_EQ(g->through_links(), links == 1);
      images[links][seed - 1] = render_gathered(r.solution, g->gather(), ro).radiosity;
    }
  const double image_noise = image_l2(images[0][1], images[0][0]) + image_l2(images[1][1], images[1][0]);
  std::printf("image: links vs all patches %.4g (seed to seed: all %.4g, links %.4g)\n",
              image_l2(images[1][0], images[0][0]), image_l2(images[0][1], images[0][0]),
              image_l2(images[1][1], images[1][0]));
  EXPECT_GT(image_noise, 0.0);
  EXPECT_LE(image_l2(images[1][0], images[0][0]), image_noise);

  // The probes: hrad probe's options (64 points on each partly visible source, classified from the
  // point), at the error samples, the reflected light compared.
  const std::vector<SurfaceSample> samples = patch_samples(cornell(), 16);
  std::vector<ProbePoint> probes;
  for (const SurfaceSample& s : samples)
    probes.push_back({s.position, cornell().patches[static_cast<std::size_t>(s.patch)].normal});
  LeafGatherOptions probe_all;
  probe_all.tolerance = 1e-3;
  std::vector<Rgb> values[2][2];
  for (int links = 0; links < 2; ++links)
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
      const auto g = gather(links ? GatherSources::links : GatherSources::all, probe_all, seed);
      for (const ProbeValue& v : gather_probes(g->gather(), probes)) {
        EXPECT_GE(v.patch, 0);
        values[links][seed - 1].push_back(v.radiosity - cornell().material_of(cornell().patches[v.patch]).emission);
      }
    }
  const auto l2 = [&](const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    return compare_at_samples(cornell(), samples, a, b).relative_l2;
  };
  const double probe_noise = l2(values[0][1], values[0][0]) + l2(values[1][1], values[1][0]);
  std::printf("probes: links vs all patches %.4g (seed to seed: all %.4g, links %.4g)\n",
              l2(values[1][0], values[0][0]), l2(values[0][1], values[0][0]), l2(values[1][1], values[1][0]));
  EXPECT_GT(probe_noise, 0.0);
  EXPECT_LE(l2(values[1][0], values[0][0]), probe_noise);
}

// Closed forms through the file, with hrad probe's options:
//  * a closed room whose every leaf holds B = E / (1 - rho) (the solve's field replaced by it
//    before writing): a probe on a wall gets B back, one in space (no leaf: the all-patches gather)
//    H = B, to 1e-9;
//  * a point on the floor under a square emitter (which reflects nothing, so B = E on each of its
//    elements) gathers E times Howell's factor (B-3 summed over the four rectangles at its foot).
TEST(StoredLinks, ProbesThroughTheFileMeetClosedForms) {
  test::TempDir dir;
  LeafGatherOptions all_options;
  all_options.tolerance = 1e-3;
  {
    const double rho = 0.6, e = 1.5, b = e / (1 - rho);
    const Scene box = make_box(3, 2.5, 4, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0}, true);
    SolveOptions o;
    o.feps = 0.003;
    Solution solution;
    const SolvedHierarchy kept = solve_keeping(box, o, &solution);
    for (Rgb& f : solution.face_radiosity) f = Rgb::Constant(b);
    const ReadBack r = through_file(dir.path("room.ply"), solution, &kept);
    const SolutionGather g(box, r.solution, r.links, dir.path("room.ply"), GatherSources::automatic, all_options);
    ASSERT_TRUE(g.through_links());
    std::vector<ProbePoint> probes;
    for (const Patch& p : box.patches) probes.push_back({0.3 * p.vertices[0] + 0.7 * p.vertices[2], p.normal});
    probes.push_back({Vec3(1.2, 1.1, 2.9), Vec3(0.3, -0.8, 0.5).normalized()});
    const std::vector<ProbeValue> v = gather_probes(g.gather(), probes);
    for (std::size_t i = 0; i + 1 < probes.size(); ++i) {
      ASSERT_GE(v[i].patch, 0) << i;
      EXPECT_LT(test::relative_error(v[i].radiosity[1], b), 1e-9) << i;
    }
    EXPECT_EQ(v.back().patch, -1);
    EXPECT_LT(test::relative_error(v.back().irradiance[0], b), 1e-9);
    EXPECT_GT(g.gather().work().points, 0u);
  }
  {
    const test::SolvedSquareEmitter solved = test::solved_square_emitter();
    const double a = solved.a, c = solved.c, e = solved.e;
    const Scene& s = solved.scene;
    const ReadBack r = through_file(dir.path("square.ply"), solved.solution, &solved.kept);
    const SolutionGather g(s, r.solution, r.links, dir.path("square.ply"), GatherSources::links, all_options);
    std::vector<ProbePoint> probes;
    std::vector<double> factors;
    for (const auto& [u, v] : {std::pair{1.0, 1.0}, std::pair{0.3, 1.7}, std::pair{1.9, 0.05}, std::pair{-2.0, 4.0}}) {
      probes.push_back({Vec3(u, 0, v), Vec3::UnitY()});
      factors.push_back(test::howell_b3(u, v, c) + test::howell_b3(a - u, v, c) + test::howell_b3(u, a - v, c) +
                        test::howell_b3(a - u, a - v, c));
    }
    const std::vector<ProbeValue> v = gather_probes(g.gather(), probes);
    for (std::size_t i = 0; i < probes.size(); ++i) {
      EXPECT_EQ(v[i].patch, 0) << i;
      EXPECT_LT(test::relative_error(v[i].irradiance[1], 2 * e * factors[i]), 1e-9) << i;
    }
  }
}

// Links that do not fit the scene or the solution they were read with are one-line errors naming
// the file and the element (and record); asking for links a file does not have names the option.
TEST(StoredLinks, LinksThatDoNotFitAreErrorsNamingTheFile) {
  test::TempDir dir;
  Solution solution;
  const SolvedHierarchy kept = solve_keeping(cornell(), SolveOptions{}, &solution);
  const SolutionLinks good = stored_links(kept);
  const std::string path = dir.path("s.ply");
  auto restore = [&](const Solution& s, const SolutionLinks& l, const Scene& scene = cornell()) {
    return error_of([&] { (void)restored_links(scene, s, l, path); });
  };
  auto expect = [&](const std::string& message, const std::string& what) {
    EXPECT_EQ(message.rfind(path + ": " + what, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  // A finer solve's faces: the leaves are not the faces.
  {
    SolveOptions o;
    o.aeps = cornell().total_area() / 4000;
    Solution finer;
    solve(cornell(), o, &finer);
    expect(restore(finer, good), "element node: the hierarchy has");
  }
  // A leaf given the children of a split node: two splits make one block.
  {
    SolutionLinks l = good;
    std::size_t split = 0, leaf = 0;
    while (l.first_child[split] < 0) ++split;
    while (l.first_child[leaf] >= 0) ++leaf;
    l.first_child[leaf] = l.first_child[split];
    expect(restore(solution, l), "element node ");
  }
  // A face whose loop misses its leaf's corner (elements cut another way): one corner of face 5
  // moved a quarter of the way along its edge.
  {
    Solution s = solution;
    const std::vector<int>& loop = s.faces[5];
    const Vec3 along = s.vertices[static_cast<std::size_t>(loop[1])] - s.vertices[static_cast<std::size_t>(loop[0])];
    s.vertices[static_cast<std::size_t>(loop[0])] += 0.25 * along;
    const std::string e = restore(s, good);
    expect(e, "element node ");
    EXPECT_NE(e.find("is not a vertex of face"), std::string::npos) << e;
  }
  // A face on another patch than its leaf.
  {
    Solution s = solution;
    s.face_patch[5] = (s.face_patch[5] + 1) % static_cast<int>(cornell().patches.size());
    expect(restore(s, good), "element node ");
  }
  // A listed patch the scene does not have; a cluster tree the scene does not make.
  {
    SolutionLinks l = good;
    l.links[3].hidden_q = {static_cast<std::int32_t>(cornell().patches.size())};
    expect(restore(solution, l), "element link 3: lists patch");
    l = good;
    l.cluster_parent = {-1, 0};
    expect(restore(solution, l), "element cluster: 2 clusters");
  }
  // --gather-sources links on a file without links (a full-matrix solve's).
  {
    SolveOptions o;
    o.method = Method::kFull;
    Solution full;
    solve(cornell(), o, &full);
    const ReadBack r = through_file(dir.path("full.ply"), full, nullptr);
    const std::string e = error_of(
        [&] { SolutionGather(cornell(), r.solution, r.links, dir.path("full.ply"), GatherSources::links, {}); });
    EXPECT_EQ(e.rfind("--gather-sources links: " + dir.path("full.ply"), 0), 0u) << e;
    const SolutionGather all(cornell(), r.solution, r.links, dir.path("full.ply"), GatherSources::automatic, {});
    EXPECT_FALSE(all.through_links());
  }
}

}  // namespace
}  // namespace hrad
