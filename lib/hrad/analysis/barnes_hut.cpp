#include "hrad/analysis/barnes_hut.h"

#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include "hrad/core/stopwatch.h"

namespace hrad {
namespace {

struct Cell {
  Vec3 centre = Vec3::Zero();  ///< of the cube
  double half = 0.0;           ///< half the side
  Vec3 mass_centre = Vec3::Zero();
  double mass = 0.0;
  std::array<int, 8> child{-1, -1, -1, -1, -1, -1, -1, -1};
  std::vector<int> bodies;  ///< leaves only
  bool leaf() const {
    return child[0] < 0 && child[1] < 0 && child[2] < 0 && child[3] < 0 && child[4] < 0 && child[5] < 0 &&
           child[6] < 0 && child[7] < 0;
  }
};

constexpr int kMaxDepth = 40;

class Octree {
 public:
  explicit Octree(const std::vector<Body>& bodies) : bodies_(bodies) {
    Vec3 lo = bodies.empty() ? Vec3::Zero() : bodies[0].position, hi = lo;
    for (const Body& b : bodies) {
      lo = lo.cwiseMin(b.position);
      hi = hi.cwiseMax(b.position);
    }
    Cell root;
    root.centre = 0.5 * (lo + hi);
    root.half = std::max(0.5 * (hi - lo).maxCoeff(), 1e-300) * (1.0 + 1e-12);
    cells_.push_back(root);
    std::vector<int> all(bodies.size());
    std::iota(all.begin(), all.end(), 0);
    build(0, std::move(all), 0);
  }
  const std::vector<Cell>& cells() const { return cells_; }

 private:
  void build(int c, std::vector<int> ids, int depth) {
    double m = 0.0;
    Vec3 mx = Vec3::Zero();
    for (int i : ids) {
      m += bodies_[i].mass;
      mx += bodies_[i].mass * bodies_[i].position;
    }
    cells_[c].mass = m;
    cells_[c].mass_centre = m > 0.0 ? Vec3(mx / m) : cells_[c].centre;
    if (ids.size() <= 1 || depth >= kMaxDepth) {
      cells_[c].bodies = std::move(ids);
      return;
    }
    std::array<std::vector<int>, 8> part;
    const Vec3 centre = cells_[c].centre;
    for (int i : ids) {
      const Vec3& p = bodies_[i].position;
      part[(p.x() >= centre.x()) | ((p.y() >= centre.y()) << 1) | ((p.z() >= centre.z()) << 2)].push_back(i);
    }
    for (int k = 0; k < 8; ++k) {
      if (part[k].empty()) continue;
      Cell child;
      child.half = 0.5 * cells_[c].half;
      child.centre = centre + child.half * Vec3((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
      const int id = static_cast<int>(cells_.size());
      cells_.push_back(child);  // may reallocate: index, never hold references across this
      cells_[c].child[k] = id;
      build(id, std::move(part[k]), depth + 1);
    }
  }

  const std::vector<Body>& bodies_;
  std::vector<Cell> cells_;
};

Vec3 pull(const Vec3& from, const Vec3& to, double mass, double eps2) {
  const Vec3 d = to - from;
  const double r2 = d.squaredNorm() + eps2;
  return mass / (r2 * std::sqrt(r2)) * d;
}

}  // namespace

double BarnesHutResult::mean_interactions() const {
  if (interactions.empty()) return 0.0;
  return static_cast<double>(std::accumulate(interactions.begin(), interactions.end(), std::size_t{0})) /
         interactions.size();
}

std::vector<Body> random_bodies(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Body> out(n);
  for (Body& b : out) {
    b.position = Vec3(u(rng), u(rng), u(rng));
    b.mass = 0.5 + u(rng);
  }
  return out;
}

BarnesHutResult barnes_hut(const std::vector<Body>& bodies, const BarnesHutOptions& options) {
  const Octree tree(bodies);
  const std::vector<Cell>& cells = tree.cells();
  const double eps2 = options.softening * options.softening;
  BarnesHutResult r;
  r.cells = cells.size();
  r.acceleration.assign(bodies.size(), Vec3::Zero());
  r.interactions.assign(bodies.size(), 0);
  std::vector<int> stack;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Vec3& x = bodies[i].position;
    Vec3 acc = Vec3::Zero();
    std::size_t count = 0;
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Cell& c = cells[stack.back()];
      stack.pop_back();
      if (c.leaf()) {
        for (int j : c.bodies) {
          if (static_cast<std::size_t>(j) == i) continue;
          acc += pull(x, bodies[j].position, bodies[j].mass, eps2);
          ++count;
        }
        continue;
      }
      const bool contains = ((x - c.centre).cwiseAbs().array() <= c.half).all();
      const double d = (c.mass_centre - x).norm();
      if (!contains && 2.0 * c.half < options.theta * d) {  // s / d < theta
        acc += pull(x, c.mass_centre, c.mass, eps2);
        ++count;
        continue;
      }
      for (int k : c.child)
        if (k >= 0) stack.push_back(k);
    }
    r.acceleration[i] = acc;
    r.interactions[i] = count;
  }
  return r;
}

std::vector<Vec3> direct_accelerations(const std::vector<Body>& bodies, double softening) {
  const double eps2 = softening * softening;
  std::vector<Vec3> acc(bodies.size(), Vec3::Zero());
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (std::size_t j = 0; j < bodies.size(); ++j)
      if (i != j) acc[i] += pull(bodies[i].position, bodies[j].position, bodies[j].mass, eps2);
  return acc;
}

double relative_rms_error(const std::vector<Vec3>& approx, const std::vector<Vec3>& reference) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    num += (approx[i] - reference[i]).squaredNorm();
    den += reference[i].squaredNorm();
  }
  return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

std::vector<BarnesHutSample> barnes_hut_sweep(const std::vector<int>& ns, const std::vector<double>& thetas,
                                              unsigned seed, int direct_limit) {
  std::vector<BarnesHutSample> out;
  for (int n : ns) {
    const std::vector<Body> bodies = random_bodies(n, seed);
    const BarnesHutOptions defaults;
    std::vector<Vec3> reference;
    if (n <= direct_limit) reference = direct_accelerations(bodies, defaults.softening);
    for (double theta : thetas) {
      BarnesHutOptions options;
      options.theta = theta;
      const Stopwatch watch;
      const BarnesHutResult r = barnes_hut(bodies, options);
      BarnesHutSample s;
      s.seconds = watch.seconds();
      s.n = n;
      s.theta = theta;
      s.mean_interactions = r.mean_interactions();
      for (std::size_t c : r.interactions) s.max_interactions = std::max(s.max_interactions, c);
      s.naive_interactions = n - 1;
      if (!reference.empty()) s.relative_force_error = relative_rms_error(r.acceleration, reference);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace hrad
