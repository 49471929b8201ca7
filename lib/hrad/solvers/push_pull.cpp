#include "hrad/solvers/push_pull.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hrad/formfactor/simpson_rule.h"

namespace hrad {
namespace {

// Lagrange basis of the nodes 0, 1/2, 1 (node index 0, 1, 2).
double lagrange(int node, double t) {
  switch (node) {
    case 0:
      return 2.0 * (t - 0.5) * (t - 1.0);
    case 1:
      return -4.0 * t * (t - 1.0);
    default:
      return 2.0 * t * (t - 0.5);
  }
}

// Restriction of a field to child k: child point j's value is sum_i R[k][j][i] parent_value[i],
// the parent's polynomial at the child's point.
using Restriction = std::array<std::array<std::array<double, 9>, 9>, 4>;

// Quads: biquadratic on the bilinear map, points in simpson_points() order at (u, v) = kQuadUv.
// Child k of ElementHierarchy::split() spans the rectangle quad_child_uv(kind, k) of the parent's
// (u, v), and its own bilinear map is the parent's there.
constexpr const auto& kQuadUv = kSimpsonQuadUv;

Restriction quad_restriction(SplitKind kind) {
  Restriction r{};
  for (int k = 0; k < 4; ++k) {
    const std::array<std::array<double, 2>, 4> corner = quad_child_uv(kind, k);
    for (int j = 0; j < 9; ++j) {
      const double a = kQuadUv[j][0], b = kQuadUv[j][1];
      const double w[4] = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
      double u = 0.0, v = 0.0;
      for (int m = 0; m < 4; ++m) u += w[m] * corner[m][0], v += w[m] * corner[m][1];
      for (int i = 0; i < 9; ++i)
        r[k][j][i] =
            lagrange(static_cast<int>(2 * kQuadUv[i][0]), u) * lagrange(static_cast<int>(2 * kQuadUv[i][1]), v);
    }
  }
  return r;
}

// Triangles: the quadratic through the values at the vertices (0, 1, 2) and edge midpoints (3: edge
// 01, 4: edge 12, 5: edge 20), in barycentric coordinates; point 6 (the centroid) takes the
// quadratic's value. Children of split(): {v0, m01, m20}, {v1, m12, m01}, {v2, m20, m12}, {m01, m12, m20}.
Restriction triangle_restriction() {
  using Bary = std::array<double, 3>;
  const auto& point = kSimpsonTriangleBary;
  const int corner[4][3] = {{0, 3, 5}, {1, 4, 3}, {2, 5, 4}, {3, 4, 5}};
  auto basis = [](int i, const Bary& l) { return i < 3 ? l[i] * (2.0 * l[i] - 1.0) : 4.0 * l[i - 3] * l[(i - 2) % 3]; };
  Restriction r{};
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 7; ++j) {
      Bary at{0, 0, 0};
      for (int m = 0; m < 3; ++m)
        for (int d = 0; d < 3; ++d) at[d] += point[j][m] * point[corner[k][m]][d];
      for (int i = 0; i < 6; ++i) r[k][j][i] = basis(i, at);
    }
  return r;
}

const Restriction& restriction(int vertex_count, SplitKind kind) {
  static const Restriction quadrants = quad_restriction(SplitKind::kQuadrants);
  static const Restriction strips_u = quad_restriction(SplitKind::kStripsU);
  static const Restriction strips_v = quad_restriction(SplitKind::kStripsV);
  static const Restriction triangle = triangle_restriction();
  if (vertex_count != 4) return triangle;
  return kind == SplitKind::kStripsU ? strips_u : kind == SplitKind::kStripsV ? strips_v : quadrants;
}

}  // namespace

std::array<double, 9> restrict_to_child(const std::array<double, 9>& parent, int vertex_count, SplitKind kind,
                                        int child) {
  const Restriction& r = restriction(vertex_count, kind);
  const int inputs = vertex_count == 4 ? 9 : 6, outputs = vertex_count == 4 ? 9 : 7;
  std::array<double, 9> out{};
  for (int j = 0; j < outputs; ++j)
    for (int m = 0; m < inputs; ++m)
      out[static_cast<std::size_t>(j)] +=
          r[static_cast<std::size_t>(child)][static_cast<std::size_t>(j)][static_cast<std::size_t>(m)] *
          parent[static_cast<std::size_t>(m)];
  return out;
}

PushPull::PushPull(const Scene& scene, const ElementHierarchy& hierarchy, const ClusterTree* tree, int channels,
                   Basis basis)
    : scene_(scene),
      h_(hierarchy),
      tree_(tree),
      channels_(channels),
      basis_(basis),
      mean_weights_(hierarchy.size()),
      basis_integrals_(hierarchy.size()) {
  if (basis_ == Basis::kLinear) {
    point_weights_.resize(h_.size());
    projections_.resize(h_.size());
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, h_.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const SimpsonPoints s = simpson_points(h_.node(static_cast<NodeId>(i)).polygon());
                        double total = 0.0;
                        for (int k = 0; k < s.count; ++k) total += s.weight[k];
                        std::array<double, 9>& w = mean_weights_[i];
                        w.fill(0.0);
                        for (int k = 0; k < s.count; ++k) w[k] = total > 0.0 ? s.weight[k] / total : 0.0;
                        basis_integrals_[i] = basis_integrals(s, total);
                        if (basis_ == Basis::kLinear && h_.node(static_cast<NodeId>(i)).is_leaf()) {
                          point_weights_[i] = s.weight;
                          projections_[i] = linear_projection(s);
                        }
                      }
                    });
}

NodeField PushPull::make_field() const {
  NodeField field;
  field.resize(h_.size(), tree_ != nullptr ? tree_->size() : 0);
  for (std::size_t i = 0; i < h_.size(); ++i) {
    field.radiosity[i] = h_.node(static_cast<NodeId>(i)).radiosity;
    if (basis_ == Basis::kLinear) field.point_radiosity[i].fill(field.radiosity[i]);
  }
  pull(field);
  return field;
}

void limit_positivity(PointValues& b, const std::array<double, 9>& mean_weights, int vertex_count, int channels) {
  const int points = vertex_count == 4 ? 9 : 7;
  Rgb mean = Rgb::Zero();
  for (int k = 0; k < points; ++k) mean += mean_weights[static_cast<std::size_t>(k)] * b[static_cast<std::size_t>(k)];
  for (int c = 0; c < channels; ++c) {
    // A linear (bilinear) field is smallest at a corner, the first points.
    double lowest = b[0][c];
    for (int k = 1; k < linear_corners(vertex_count); ++k) lowest = std::min(lowest, b[static_cast<std::size_t>(k)][c]);
    if (lowest >= 0.0) continue;
    // Scaled about the mean by theta, the lowest corner lands on 0 (up to rounding, clamped away).
    const double theta = mean[c] > 0.0 ? mean[c] / (mean[c] - lowest) : 0.0;
    for (int k = 0; k < points; ++k) {
      double& v = b[static_cast<std::size_t>(k)][c];
      v = mean[c] > 0.0 ? std::max(0.0, mean[c] + theta * (v - mean[c])) : mean[c];
    }
  }
}

Rgb PushPull::push_pull_element(NodeField& field, NodeId id, const PointValues& down, LeafChange* change) const {
  const ElementNode& n = h_.node(id);
  const std::size_t i = static_cast<std::size_t>(id);
  PointValues total = field.irradiance[i];
  for (int k = 0; k < 9; ++k) total[k] += down[k];
  if (n.is_leaf() && basis_ == Basis::kLinear) {
    // The L2 projection of E + rho H onto the leaf's linear space (linear_basis.h).
    PointValues b;
    b.fill(Rgb::Zero());
    const int points = n.vertex_count == 4 ? 9 : 7;
    for (int k = 0; k < points; ++k) b[k] = n.emission + n.reflectance * total[k];
    b = project_linear(projections_[i], n.vertex_count, b);
    limit_positivity(b, mean_weights_[i], n.vertex_count, channels_);
    Rgb mean = Rgb::Zero();
    for (int k = 0; k < points; ++k) {
      mean += mean_weights_[i][k] * b[k];
      double moved = 0.0, reflected = 0.0;
      for (int c = 0; c < channels_; ++c) {
        moved = std::max(moved, std::abs(b[k][c] - field.point_radiosity[i][k][c]));
        reflected = std::max(reflected, std::abs(b[k][c] - n.emission[c]));
      }
      change->add_leaf(n.area * mean_weights_[i][k], moved, reflected);
    }
    Rgb h = Rgb::Zero();
    for (int k = 0; k < points; ++k) h += mean_weights_[i][k] * total[k];
    field.leaf_irradiance[i] = h;  // the projection keeps the mean: mean B = E + rho h
    field.point_radiosity[i] = b;
    field.radiosity[i] = mean;
    leaf_moments(field, id);
    return mean;
  }
  if (n.is_leaf()) {
    Rgb mean = Rgb::Zero();
    for (int k = 0; k < 9; ++k) mean += mean_weights_[i][k] * total[k];
    const Rgb b = n.emission + n.reflectance * mean;
    field.leaf_irradiance[i] = mean;
    for (int k = 0; k < 9; ++k) field.point_radiosity[i][k] = n.emission + n.reflectance * total[k];
    double moved = 0.0, reflected = 0.0;
    for (int c = 0; c < channels_; ++c) {
      moved = std::max(moved, std::abs(b[c] - field.radiosity[i][c]));
      reflected = std::max(reflected, std::abs(b[c] - n.emission[c]));
    }
    change->add_leaf(n.area, moved, reflected);
    field.radiosity[i] = b;
    leaf_moments(field, id);
    return b;
  }
  const Restriction& r = restriction(n.vertex_count, n.split);
  const int inputs = n.vertex_count == 4 ? 9 : 6, outputs = n.vertex_count == 4 ? 9 : 7;
  Rgb sum = Rgb::Zero();
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    PointValues child;
    child.fill(Rgb::Zero());
    for (int j = 0; j < outputs; ++j)
      for (int m = 0; m < inputs; ++m) child[j] += r[k][j][m] * total[m];
    const NodeId c = n.first_child + k;
    const double a = h_.node(c).area;
    sum += a * push_pull_element(field, c, child, change);
    area += a;
  }
  field.radiosity[i] = sum / area;
  pull_moments(field, id);
  return field.radiosity[i];
}

void PushPull::leaf_moments(NodeField& field, NodeId id) const {
  const std::size_t i = static_cast<std::size_t>(id);
  PointValues& m = field.radiosity_moments[i];
  if (basis_ == Basis::kLinear) {
    const int points = h_.node(id).vertex_count == 4 ? 9 : 7;
    m = point_field_moments(point_weights_[i], points, field.point_radiosity[i]);
  } else {
    for (int k = 0; k < 9; ++k) m[k] = basis_integrals_[i][k] * field.radiosity[i];
  }
  if (send_closure_.empty() || !(send_closure_[i].sigma > 0.0)) return;
  // Sent: sum_k d_k m_k; wanted: `closed` times the power, sum_k m_k (the basis sums to 1). The
  // difference goes along a uniform field's moments, which send sigma A per unit radiosity.
  const SendClosure& c = send_closure_[i];
  Rgb sent = Rgb::Zero(), power = Rgb::Zero();
  for (int k = 0; k < 9; ++k) {
    sent += c.coefficients[k] * m[k];
    power += m[k];
  }
  const Rgb move = (c.closed * power - sent) / (c.sigma * h_.node(id).area);
  for (int k = 0; k < 9; ++k) m[k] += basis_integrals_[i][k] * move;
}

void PushPull::pull_moments(NodeField& field, NodeId id) const {
  // The parent's basis function i restricted to child k is sum_j R[k][j][i] times the child's
  // function j, so its moment is sum_k sum_j R[k][j][i] m_child_k[j].
  const ElementNode& n = h_.node(id);
  const Restriction& r = restriction(n.vertex_count, n.split);
  const int functions = n.vertex_count == 4 ? 9 : 6;
  PointValues& m = field.radiosity_moments[static_cast<std::size_t>(id)];
  m.fill(Rgb::Zero());
  for (int k = 0; k < 4; ++k) {
    const PointValues& c = field.radiosity_moments[static_cast<std::size_t>(n.first_child + k)];
    for (int j = 0; j < functions; ++j)
      for (int f = 0; f < functions; ++f) m[f] += r[k][j][f] * c[j];
  }
}

LeafChange PushPull::push_pull(NodeField& field) const {
  std::vector<LeafChange> per_patch(static_cast<std::size_t>(h_.patch_count()));
  tbb::parallel_for(tbb::blocked_range<int>(0, h_.patch_count(), 8), [&](const tbb::blocked_range<int>& range) {
    for (int p = range.begin(); p != range.end(); ++p) {
      PointValues down;
      down.fill(Rgb::Zero());
      push_pull_element(field, h_.root(p), down, &per_patch[static_cast<std::size_t>(p)]);
    }
  });
  pull_clusters(field);
  LeafChange all;
  for (const LeafChange& c : per_patch) all.add(c);
  return all;
}

Rgb PushPull::pull_element(NodeField& field, NodeId id) const {
  const ElementNode& n = h_.node(id);
  const std::size_t i = static_cast<std::size_t>(id);
  if (n.is_leaf()) {
    leaf_moments(field, id);
    return field.radiosity[i];
  }
  Rgb sum = Rgb::Zero();
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double a = h_.node(n.first_child + k).area;
    sum += a * pull_element(field, n.first_child + k);
    area += a;
  }
  field.radiosity[i] = sum / area;
  pull_moments(field, id);
  return field.radiosity[i];
}

void PushPull::pull(NodeField& field) const {
  tbb::parallel_for(tbb::blocked_range<int>(0, h_.patch_count(), 8), [&](const tbb::blocked_range<int>& range) {
    for (int p = range.begin(); p != range.end(); ++p) pull_element(field, h_.root(p));
  });
  pull_clusters(field);
}

void PushPull::pull_clusters(NodeField& field) const {
  if (tree_ == nullptr) return;
  const std::size_t base = field.elements;
  // Children have larger indices than their parent: a reverse sweep is bottom-up.
  for (std::size_t c = tree_->size(); c-- > 0;) {
    const Cluster& k = tree_->cluster(static_cast<int>(c));
    Rgb sum = Rgb::Zero();
    for (const NodeRef child : k.children) {
      if (is_cluster(child)) {
        sum += tree_->cluster(cluster_index(child)).area *
               field.radiosity[base + static_cast<std::size_t>(cluster_index(child))];
      } else {
        sum += h_.node(child).area * field.radiosity[static_cast<std::size_t>(child)];
      }
    }
    field.radiosity[base + c] = sum / k.area;
  }
}

void PushPull::store(const NodeField& field, ElementHierarchy& h, std::vector<Rgb>* cluster_radiosity) const {
  for (std::size_t i = 0; i < h.size(); ++i) {
    ElementNode& n = h.node(static_cast<NodeId>(i));
    n.radiosity = field.radiosity[i];
    n.gathered = field.leaf_irradiance[i];
  }
  if (cluster_radiosity != nullptr) {
    cluster_radiosity->assign(field.radiosity.begin() + static_cast<std::ptrdiff_t>(field.elements),
                              field.radiosity.end());
  }
}

}  // namespace hrad
