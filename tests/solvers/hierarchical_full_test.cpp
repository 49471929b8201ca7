// Hierarchical radiosity against the full matrix (same kernels, but a dense n x n system solved by
// LU): with feps -> 0 every pair is refined to the full matrix's elements, so HR approaches it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "hrad/geometry/polygon.h"
#include "hrad/io/obj_reader.h"
#include "hrad/solvers/hierarchical.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

std::string scene_path(const std::string& name) { return test::source_dir() + "/notebooks_data/scenes/" + name; }

std::vector<Vec3> face_polygon(const Solution& s, std::size_t f) {
  std::vector<Vec3> poly;
  for (int v : s.faces[f]) poly.push_back(s.vertices[static_cast<std::size_t>(v)]);
  return poly;
}

bool contains(std::span<const Vec3> poly, const Vec3& x) {
  const Vec3 n = newell_normal(poly);
  const double scale = n.norm();
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec3& a = poly[k];
    const Vec3& b = poly[(k + 1) % poly.size()];
    if ((b - a).cross(x - a).dot(n) < -1e-9 * scale) return false;
  }
  return true;
}

// Area-weighted mean of |B_hr - B_ref| over the reference's leaves (each compared with the HR leaf
// containing its centroid), divided by the area-weighted mean of B_ref; all channels.
double relative_l1_difference(const Solution& hr, const Solution& ref) {
  double diff = 0.0, norm = 0.0;
  for (std::size_t f = 0; f < ref.faces.size(); ++f) {
    const std::vector<Vec3> poly = face_polygon(ref, f);
    const Vec3 c = polygon_centroid(poly);
    const double area = polygon_area(poly);
    std::size_t found = hr.faces.size();
    for (std::size_t g = 0; g < hr.faces.size() && found == hr.faces.size(); ++g) {
      if (hr.face_patch[g] == ref.face_patch[f] && contains(face_polygon(hr, g), c)) found = g;
    }
    EXPECT_LT(found, hr.faces.size()) << "no HR leaf contains reference leaf " << f;
    if (found == hr.faces.size()) continue;
    diff += area * (hr.face_radiosity[found] - ref.face_radiosity[f]).abs().sum();
    norm += area * ref.face_radiosity[f].abs().sum();
  }
  return diff / norm;
}

TEST(HierarchicalVersusFull, ApproachesTheFullMatrixAsFepsShrinks) {
  // With feps -> 0 every pair is refined down to the elements the full matrix uses at
  // max_area = aeps (both split 1-to-4 the same way), so the two answers must meet.
  const Scene s = read_obj_scene(scene_path("two_surfaces_edge.obj"));
  const double aeps = 16.0 / 256.0;
  SolveOptions full;
  full.method = Method::kFull;
  full.max_area = aeps;
  Solution reference;
  const SolveSummary ref_sum = solve(s, full, &reference);
  ASSERT_EQ(reference.faces.size(), 512u);
  (void)ref_sum;

  std::vector<double> differences;
  std::vector<std::size_t> links;
  for (const double feps : {0.1, 0.03, 0.01, 0.001}) {
    SolveOptions o;
    o.feps = feps;
    o.aeps = aeps;
    Solution sol;
    const SolveSummary sum = solve_hierarchical(s, o, &sol);
    ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
    differences.push_back(relative_l1_difference(sol, reference));
    links.push_back(sum.links);
  }
  for (std::size_t k = 1; k < differences.size(); ++k) {
    EXPECT_LE(differences[k], differences[k - 1] * 1.05) << "feps step " << k;
    EXPECT_GT(links[k], links[k - 1]);
  }
  EXPECT_LT(differences.back(), 0.25 * differences.front());
  EXPECT_LT(differences.back(), 0.005);
}

}  // namespace
}  // namespace hrad
