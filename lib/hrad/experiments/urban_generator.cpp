#include "hrad/experiments/urban_generator.h"

#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/rng.h"

namespace hrad {
namespace {

constexpr double kBlock = 80.0, kLand = 60.0, kTile = 10.0;

struct Building {
  double x0, z0, x1, z1, h;
};

// Cuts the rectangle origin + [0,1] u + [0,1] v into nu x nv quads facing u x v.
void add_grid(GeneratedScene& g, const Vec3& origin, const Vec3& u, const Vec3& v, int nu, int nv, int material,
              int group) {
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const Vec3 a = origin + u * (double(i) / nu) + v * (double(j) / nv);
      const Vec3 du = u / nu, dv = v / nv;
      g.faces.push_back({{a, a + du, a + du + dv, a + dv}, material, group});
    }
}

int cuts(double length, double size) { return std::max(1, static_cast<int>(std::lround(length / size))); }

}  // namespace

GeneratedScene generate_urban(const UrbanGeneratorOptions& options) {
  if (options.facets < 200 || options.facets > 10000000)
    throw Error(fmt::format("--polygons: {} is not in [200, 10000000] for an urban scene", options.facets));
  detail::Rng rng(options.seed);
  // About 1300 facets a block at the default density; the facet size below makes up the rest.
  const int grid = std::max(1, static_cast<int>(std::ceil(std::sqrt(options.facets / 1300.0))));
  std::vector<Building> buildings;
  for (int bx = 0; bx < grid; ++bx)
    for (int bz = 0; bz < grid; ++bz)
      for (int k = 0; k < 4; ++k) {
        if (rng.uniform() < 0.1) continue;  // an empty lot
        const double cx = bx * kBlock + (k % 2 + 0.5) * kLand / 2, cz = bz * kBlock + (k / 2 + 0.5) * kLand / 2;
        const double wx = rng.uniform(12.0, 26.0), wz = rng.uniform(12.0, 26.0);
        // Buildings fill their quarter up to its edge half the time: neighbours then share a wall plane.
        const double hx = rng.uniform() < 0.5 ? kLand / 4 : wx / 2, hz = rng.uniform() < 0.5 ? kLand / 4 : wz / 2;
        buildings.push_back({cx - hx, cz - hz, cx + hx, cz + hz, rng.uniform(6.0, 45.0)});
      }
  const int ground_tiles = grid * grid * static_cast<int>(std::lround(kBlock / kTile * kBlock / kTile));
  double area = 0.0;
  for (const Building& b : buildings) area += 2 * (b.x1 - b.x0 + b.z1 - b.z0) * b.h + (b.x1 - b.x0) * (b.z1 - b.z0);
  const int wanted = std::max(5 * static_cast<int>(buildings.size()), options.facets - ground_tiles);
  const double size = std::sqrt(area / wanted);

  GeneratedScene g;
  g.materials = {{"ground", Rgb::Constant(0.1), Rgb::Zero()},
                 {"wall", Rgb::Constant(0.3), Rgb::Zero()},
                 {"roof", Rgb::Constant(0.2), Rgb::Zero()}};
  g.groups.push_back("ground");
  const int n_ground = static_cast<int>(std::lround(grid * kBlock / kTile));
  // Ground facing +y: u along z, v along x gives (z x x) = +y.
  add_grid(g, Vec3(0, 0, 0), Vec3(0, 0, grid * kBlock), Vec3(grid * kBlock, 0, 0), n_ground, n_ground, 0, 0);
  for (std::size_t k = 0; k < buildings.size(); ++k) {
    const Building& b = buildings[k];
    const int group = static_cast<int>(g.groups.size());
    g.groups.push_back(fmt::format("building{}", k));
    const double dx = b.x1 - b.x0, dz = b.z1 - b.z0;
    const Vec3 up(0, b.h, 0);
    // Walls facing out (u x v points away from the building).
    add_grid(g, Vec3(b.x1, 0, b.z0), Vec3(-dx, 0, 0), up, cuts(dx, size), cuts(b.h, size), 1, group);  // -z
    add_grid(g, Vec3(b.x0, 0, b.z1), Vec3(dx, 0, 0), up, cuts(dx, size), cuts(b.h, size), 1, group);   // +z
    add_grid(g, Vec3(b.x0, 0, b.z0), Vec3(0, 0, dz), up, cuts(dz, size), cuts(b.h, size), 1, group);   // -x
    add_grid(g, Vec3(b.x1, 0, b.z1), Vec3(0, 0, -dz), up, cuts(dz, size), cuts(b.h, size), 1, group);  // +x
    add_grid(g, Vec3(b.x0, b.h, b.z0), Vec3(0, 0, dz), Vec3(dx, 0, 0), cuts(dz, size), cuts(dx, size), 2,
             group);  // roof, +y
  }
  g.cells_x = g.cells_z = grid;
  g.room_size = Vec3(grid * kBlock, 45.0, grid * kBlock);
  return g;
}

}  // namespace hrad
