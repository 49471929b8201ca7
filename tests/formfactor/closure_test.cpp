// Closure: in a closed box whose faces are tessellated with different grids (T-junctions where they
// meet), the factors from each element to all elements of the other faces sum to 1.
#include <gtest/gtest.h>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "test_geometry.h"

namespace hrad::test {
namespace {

struct Element {
  Polygon polygon;
  int face;
};

// Splits the rectangle origin + [0,1] u + [0,1] v (normal u x v) into n x m elements.
void tessellate(const Vec3& origin, const Vec3& u, const Vec3& v, int n, int m, int face, std::vector<Element>& out) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      out.push_back({rectangle(origin + (double(i) / n) * u + (double(j) / m) * v, u / n, v / m), face});
}

std::vector<Element> box(const Vec3& size) {
  const Vec3 x(size.x(), 0, 0), y(0, size.y(), 0), z(0, 0, size.z());
  std::vector<Element> e;
  tessellate(Vec3::Zero(), x, y, 3, 2, 0, e);  // floor, +z
  tessellate(z, y, x, 2, 5, 1, e);             // ceiling, -z
  tessellate(Vec3::Zero(), z, x, 1, 3, 2, e);  // y = 0, +y
  tessellate(y, x, z, 4, 1, 3, e);             // y = Ly, -y
  tessellate(Vec3::Zero(), y, z, 2, 2, 4, e);  // x = 0, +x
  tessellate(x, z, y, 3, 3, 5, e);             // x = Lx, -x
  return e;
}

void expect_closure(const std::vector<Element>& elements, const std::string& what) {
  std::vector<double> rows(elements.size(), 0.0);
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (std::size_t j = i + 1; j < elements.size(); ++j) {
      const PairFormFactor f = polygon_to_polygon(elements[i].polygon, elements[j].polygon);
      if (elements[i].face == elements[j].face) {
        EXPECT_EQ(f.from_to, 0.0);  // coplanar
        continue;
      }
      rows[i] += f.from_to;
      rows[j] += f.to_from;
    }
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_NEAR(rows[i], 1.0, 1e-12) << what << " element " << i;
}

TEST(FormFactorClosure, TessellatedBoxesSumToOne) {
  expect_closure(box(Vec3(1, 1, 1)), "cube");
  expect_closure(box(Vec3(2.0, 0.7, 1.3)), "box");
  expect_closure(box(Vec3(10.0, 0.3, 4.0)), "flat box");
}

TEST(FormFactorClosure, MovedAndRescaledBoxSumsToOne) {
  std::mt19937_64 rng(5);
  for (double s : {1e-6, 1e6}) {
    std::vector<Element> e = box(Vec3(1.5, 1.0, 0.8));
    const Eigen::Matrix3d r = random_rotation(rng);
    for (Element& el : e) el.polygon = moved(el.polygon, r, Vec3(3.0, -2.0, 1.0) * s, s);
    expect_closure(e, "moved, scale " + std::to_string(s));
  }
}

}  // namespace
}  // namespace hrad::test
