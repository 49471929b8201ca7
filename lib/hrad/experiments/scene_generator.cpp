#include "hrad/experiments/scene_generator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <ostream>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/rng.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/atomic_file.h"

namespace hrad {
namespace {

constexpr double kCell = 2.5;         // floor cell, metres
constexpr double kHeight = 3.0;       // room height
constexpr double kFloorGap = 0.01;    // furniture floats 1 cm above the floor (closed boxes)
constexpr double kGroupRadius = 1.1;  // a group's footprint stays in this circle about its cell's centre

enum MaterialId { kWall, kFloor, kCeiling, kLight, kWood, kMetal, kFabric, kCardboard, kScreen };

std::vector<Material> generated_materials() {
  auto m = [](const char* name, Rgb rho, Rgb e = Rgb::Zero()) { return Material{name, rho, e}; };
  return {m("wall", Rgb(0.70, 0.70, 0.68)),    m("floor", Rgb(0.35, 0.30, 0.25)),
          m("ceiling", Rgb(0.80, 0.80, 0.80)), m("light", Rgb(0.80, 0.80, 0.80), Rgb(10.0, 10.0, 9.0)),
          m("wood", Rgb(0.55, 0.40, 0.25)),    m("metal", Rgb(0.50, 0.50, 0.55)),
          m("fabric", Rgb(0.20, 0.30, 0.60)),  m("cardboard", Rgb(0.60, 0.50, 0.35)),
          m("screen", Rgb(0.05, 0.05, 0.05))};
}

using detail::Rng;  // core/rng.h: the same stream on every platform, so a seed gives the same scene

struct Box {
  double x0, x1, y0, y1, z0, z1;  // in the group's frame (x, z about the cell centre)
  int material;
};

class Builder {
 public:
  explicit Builder(GeneratedScene& s) : s_(s) {}

  int group(std::string name) {
    s_.groups.push_back(std::move(name));
    return static_cast<int>(s_.groups.size()) - 1;
  }

  // A quad whose front faces `towards`.
  void quad(std::vector<Vec3> v, const Vec3& towards, int material, int group) {
    if (newell_normal(v).dot(towards) < 0.0) std::reverse(v.begin(), v.end());
    s_.faces.push_back({std::move(v), material, group});
  }

  // The 6 outward faces of `b`, turned by `angle` about the vertical through (cx, 0, cz).
  void box(const Box& b, double cx, double cz, double angle, int group) {
    const double c = std::cos(angle), s = std::sin(angle);
    auto at = [&](double x, double y, double z) { return Vec3(cx + c * x - s * z, y, cz + s * x + c * z); };
    const Vec3 centre = at(0.5 * (b.x0 + b.x1), 0.5 * (b.y0 + b.y1), 0.5 * (b.z0 + b.z1));
    const std::array<Vec3, 8> p = {at(b.x0, b.y0, b.z0), at(b.x1, b.y0, b.z0), at(b.x1, b.y0, b.z1),
                                   at(b.x0, b.y0, b.z1), at(b.x0, b.y1, b.z0), at(b.x1, b.y1, b.z0),
                                   at(b.x1, b.y1, b.z1), at(b.x0, b.y1, b.z1)};
    const std::array<std::array<int, 4>, 6> faces = {
        {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}}};
    for (const auto& f : faces) {
      std::vector<Vec3> v = {p[f[0]], p[f[1]], p[f[2]], p[f[3]]};
      const Vec3 mid = 0.25 * (v[0] + v[1] + v[2] + v[3]);
      quad(std::move(v), mid - centre, b.material, group);
    }
  }

 private:
  GeneratedScene& s_;
};

// Furniture groups in their own frame, every part 5 mm or more from the others, inside kGroupRadius.
std::vector<Box> table(bool monitor, double dz) {
  std::vector<Box> parts = {{-0.6, 0.6, 0.70, 0.74, -0.4 + dz, 0.4 + dz, kWood}};
  for (const double x : {-0.57, 0.52})
    for (const double z : {-0.37, 0.32})
      parts.push_back({x, x + 0.05, kFloorGap, 0.695, z + dz, z + 0.05 + dz, kMetal});
  if (monitor) parts.push_back({-0.25, 0.25, 0.745, 1.05, -0.05 + dz, 0.05 + dz, kScreen});
  return parts;
}

std::vector<Box> chair(double dz) {
  std::vector<Box> parts = {{-0.22, 0.22, 0.43, 0.47, -0.22 + dz, 0.22 + dz, kFabric},
                            {-0.22, 0.22, 0.475, 0.9, 0.18 + dz, 0.22 + dz, kFabric}};
  for (const double x : {-0.2, 0.16})
    for (const double z : {-0.2, 0.16}) parts.push_back({x, x + 0.04, kFloorGap, 0.425, z + dz, z + 0.04 + dz, kMetal});
  return parts;
}

std::vector<Box> cabinet(Rng& rng) {
  const double w = rng.uniform(0.4, 1.0), d = rng.uniform(0.4, 0.6), h = rng.uniform(0.6, 2.0);
  return {{-w / 2, w / 2, kFloorGap, h, -d / 2, d / 2, kWood}};
}

std::vector<Box> stack(Rng& rng, int count) {
  std::vector<Box> parts;
  double y = kFloorGap, half = rng.uniform(0.3, 0.45);
  for (int k = 0; k < count; ++k) {
    const double h = rng.uniform(0.2, 0.4);
    parts.push_back({-half, half, y, y + h, -half * 0.8, half * 0.8, kCardboard});
    y += h + 0.005;
    half *= rng.uniform(0.75, 0.95);
  }
  return parts;
}

// A group chosen at random among those that fit in `budget` polygons; empty when none does.
std::pair<std::string, std::vector<Box>> furniture(Rng& rng, int budget) {
  const int pick = static_cast<int>(rng.below(100));
  if (pick < 35 && budget >= 72) {
    const bool monitor = rng.below(2) == 0;
    std::vector<Box> parts = table(monitor, -0.25);
    for (const Box& b : chair(0.55)) parts.push_back(b);
    return {"desk", parts};
  }
  if (pick < 50 && budget >= 36) return {"table", table(true, 0.0)};
  if (pick < 75 && budget >= 6 && budget < 30) return {"boxes", stack(rng, std::min(5, budget / 6))};
  if (pick < 75 && budget >= 6) return {"cabinet", cabinet(rng)};
  if (budget >= 6) return {"boxes", stack(rng, std::min(budget / 6, 2 + static_cast<int>(rng.below(4))))};
  return {};
}

// A square grid of square pillars in a closed hall: the floor and ceiling are tiled in t x t tiles,
// one tile of every pillar_pitch x pillar_pitch block is a pillar (no floor or ceiling tile there,
// 4 walls tiled in storeys of t), lights on a checkerboard of the remaining ceiling tiles.
GeneratedScene pillar_hall(int n) {
  constexpr double t = 1.0, height = 4.0;
  constexpr int pitch = 3, storeys = 4;  // one pillar per 3 x 3 tiles; 4 x 4 = 16 pillar faces
  GeneratedScene s;
  s.materials = generated_materials();
  Builder b(s);
  // Per block of pitch^2 tiles: 2 (pitch^2 - 1) floor and ceiling tiles and 4 storeys of pillar faces.
  const double per_block = 2.0 * (pitch * pitch - 1) + 4.0 * storeys;
  const int blocks = std::max(1, static_cast<int>(std::sqrt(n / per_block)));
  const int tiles = blocks * pitch;
  s.cells_x = s.cells_z = tiles;
  const double size = tiles * t;
  s.room_size = Vec3(size, height, size);
  const int floor_group = b.group("floor"), ceiling_group = b.group("ceiling"), wall_group = b.group("walls"),
            light_group = b.group("lights"), pillar_group = b.group("pillars");
  auto pillar_tile = [&](int i, int k) { return i % pitch == 1 && k % pitch == 1; };
  for (int i = 0; i < tiles; ++i)
    for (int k = 0; k < tiles; ++k) {
      const double x0 = i * t, x1 = x0 + t, z0 = k * t, z1 = z0 + t;
      if (pillar_tile(i, k)) {
        // The pillar's four faces, outwards, from floor to ceiling in storeys.
        for (int y = 0; y < storeys; ++y) {
          const double y0 = y * height / storeys, y1 = (y + 1) * height / storeys;
          b.quad({{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}}, -Vec3::UnitZ(), kWall, pillar_group);
          b.quad({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, Vec3::UnitZ(), kWall, pillar_group);
          b.quad({{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}, -Vec3::UnitX(), kWall, pillar_group);
          b.quad({{x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}}, Vec3::UnitX(), kWall, pillar_group);
        }
        continue;
      }
      b.quad({{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}, Vec3::UnitY(), kFloor, floor_group);
      const bool light = (i % pitch == 0) && (k % pitch == 0) && ((i / pitch + k / pitch) % 2 == 0);
      b.quad({{x0, height, z0}, {x1, height, z0}, {x1, height, z1}, {x0, height, z1}}, -Vec3::UnitY(),
             light ? kLight : kCeiling, light ? light_group : ceiling_group);
    }
  // The hall's walls, one tile wide and a storey high.
  for (int y = 0; y < storeys; ++y) {
    const double y0 = y * height / storeys, y1 = (y + 1) * height / storeys;
    for (int i = 0; i < tiles; ++i) {
      const double a0 = i * t, a1 = a0 + t;
      b.quad({{a0, y0, 0}, {a1, y0, 0}, {a1, y1, 0}, {a0, y1, 0}}, Vec3::UnitZ(), kWall, wall_group);
      b.quad({{a0, y0, size}, {a1, y0, size}, {a1, y1, size}, {a0, y1, size}}, -Vec3::UnitZ(), kWall, wall_group);
      b.quad({{0, y0, a0}, {0, y0, a1}, {0, y1, a1}, {0, y1, a0}}, Vec3::UnitX(), kWall, wall_group);
      b.quad({{size, y0, a0}, {size, y0, a1}, {size, y1, a1}, {size, y1, a0}}, -Vec3::UnitX(), kWall, wall_group);
    }
  }
  return s;
}

// A warehouse: a closed hall 6 m high whose floor, ceiling and walls are tiled in 2 m tiles, with
// rows of shelving racks along x separated by 3 m aisles. A rack unit is two uprights and four
// shelves, each a closed box (the office's rule: 1 cm above the floor, >= 5 mm between parts), so the
// scene stays closed; lights on every other ceiling tile in both directions. Every row holds the same
// number of units: a whole grid, the one whose polygon count is nearest n.
GeneratedScene warehouse(int n) {
  constexpr double tile = 2.0, height = 6.0, storey = 2.0, aisle = 3.0, depth = 1.0, rack_height = 4.5;
  constexpr double upright = 0.05, board = 0.04, gap = 0.005, unit = 2.4, margin = 2.0;
  constexpr int storeys = 3, faces_per_unit = 36;  // 6 boxes
  const double row_pitch = depth + aisle;
  auto tiles_along = [&](double length) { return static_cast<int>(std::ceil(length / tile - 1e-9)); };
  // Units per row about 5/3 of the rows, so that the hall is about square.
  auto units_per_row = [](int rows) { return std::max(1, static_cast<int>(std::lround(rows * 5.0 / 3.0))); };
  auto hall = [&](int rows) {
    return Vec3(tiles_along(2.0 * margin + units_per_row(rows) * (unit + gap)) * tile, height,
                tiles_along(2.0 * margin + rows * row_pitch - aisle) * tile);
  };
  auto count = [&](int rows) {
    const Vec3 size = hall(rows);
    const int tx = tiles_along(size.x()), tz = tiles_along(size.z());
    return faces_per_unit * rows * units_per_row(rows) + 2 * tx * tz + 2 * storeys * (tx + tz);
  };
  int rows = 1;
  while (std::abs(count(rows + 1) - n) < std::abs(count(rows) - n)) ++rows;
  GeneratedScene s;
  s.materials = generated_materials();
  Builder b(s);
  const Vec3 size = hall(rows);
  const int tx = tiles_along(size.x()), tz = tiles_along(size.z());
  s.cells_x = tx;
  s.cells_z = tz;
  s.room_size = size;
  const int floor_group = b.group("floor"), ceiling_group = b.group("ceiling"), wall_group = b.group("walls"),
            light_group = b.group("lights");
  for (int i = 0; i < tx; ++i)
    for (int k = 0; k < tz; ++k) {
      const double x0 = i * tile, x1 = x0 + tile, z0 = k * tile, z1 = z0 + tile;
      b.quad({{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}, Vec3::UnitY(), kFloor, floor_group);
      const bool light = i % 2 == 0 && k % 2 == 0;
      b.quad({{x0, height, z0}, {x1, height, z0}, {x1, height, z1}, {x0, height, z1}}, -Vec3::UnitY(),
             light ? kLight : kCeiling, light ? light_group : ceiling_group);
    }
  for (int y = 0; y < storeys; ++y) {
    const double y0 = y * storey, y1 = y0 + storey;
    for (int i = 0; i < tx; ++i) {
      const double a0 = i * tile, a1 = a0 + tile;
      b.quad({{a0, y0, 0}, {a1, y0, 0}, {a1, y1, 0}, {a0, y1, 0}}, Vec3::UnitZ(), kWall, wall_group);
      b.quad({{a0, y0, size.z()}, {a1, y0, size.z()}, {a1, y1, size.z()}, {a0, y1, size.z()}}, -Vec3::UnitZ(), kWall,
             wall_group);
    }
    for (int k = 0; k < tz; ++k) {
      const double a0 = k * tile, a1 = a0 + tile;
      b.quad({{0, y0, a0}, {0, y0, a1}, {0, y1, a1}, {0, y1, a0}}, Vec3::UnitX(), kWall, wall_group);
      b.quad({{size.x(), y0, a0}, {size.x(), y0, a1}, {size.x(), y1, a1}, {size.x(), y1, a0}}, -Vec3::UnitX(), kWall,
             wall_group);
    }
  }
  // A unit in its own frame (x along the row from its start, z across from the row's front).
  std::vector<Box> parts = {{0.0, upright, kFloorGap, rack_height, 0.0, depth, kMetal},
                            {unit - upright, unit, kFloorGap, rack_height, 0.0, depth, kMetal}};
  for (const double y : {0.15, 1.25, 2.35, 3.45})
    parts.push_back({upright + gap, unit - upright - gap, y, y + board, 0.0, depth, kWood});
  const double x_start = 0.5 * (size.x() - units_per_row(rows) * (unit + gap) + gap);
  const double z_start = 0.5 * (size.z() - (rows * row_pitch - aisle));
  for (int r = 0; r < rows; ++r) {
    const int g = b.group(fmt::format("rack_row_{}", r));
    for (int u = 0; u < units_per_row(rows); ++u)
      for (const Box& part : parts) b.box(part, x_start + u * (unit + gap), z_start + r * row_pitch, 0.0, g);
  }
  return s;
}

// City blocks: a ground of 10 m tiles, buildings of random footprint and storeys (walls tiled by
// storey and bay, flat roofs) on a grid of 40 m blocks separated by streets, and an emitting sky
// quad high above, facing down. Open: light leaves at the sides, as from real city meshes. Every
// block holds its four buildings, so that cities of every size are alike (a scale family): the grid,
// square or one block longer, is the one whose expected polygon count is nearest n.
GeneratedScene city(int n, Rng& rng) {
  constexpr double block = 40.0, street = 12.0, tile = 10.0, storey = 3.5, bay = 5.0;
  constexpr double pitch = block + street;
  auto ground_tiles = [&](int blocks) { return static_cast<int>(std::ceil((blocks * pitch + street) / tile)); };
  // A building has 2 (w + d) / bay walls a storey (w, d: 1-3 bays each; 8 walls on average) on 4.5 storeys on
  // average, and a roof: 37 faces; a block, four.
  auto expected = [&](int bx, int bz) { return 148.0 * bx * bz + ground_tiles(bx) * ground_tiles(bz) + 1.0; };
  int blocks_x = 1, blocks_z = 1;
  for (int bx = 1; expected(bx, bx) < 2.0 * n; ++bx)
    for (int bz = bx; bz <= bx + 1; ++bz)
      if (std::abs(expected(bx, bz) - n) < std::abs(expected(blocks_x, blocks_z) - n)) blocks_x = bx, blocks_z = bz;
  GeneratedScene s;
  s.materials = generated_materials();
  s.materials[kLight].emission = Rgb(1.0, 1.0, 1.0);  // the sky: exitance 1
  Builder b(s);
  const double size_x = blocks_x * pitch + street, size_z = blocks_z * pitch + street;
  s.cells_x = blocks_x;
  s.cells_z = blocks_z;
  const int ground_group = b.group("ground"), sky_group = b.group("sky");
  for (int i = 0; i < ground_tiles(blocks_x); ++i)
    for (int k = 0; k < ground_tiles(blocks_z); ++k) {
      const double x0 = i * tile, x1 = std::min(size_x, x0 + tile), z0 = k * tile, z1 = std::min(size_z, z0 + tile);
      b.quad({{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}, Vec3::UnitY(), kFloor, ground_group);
    }
  const double size = std::max(size_x, size_z), sky = 4.0 * size;
  b.quad({{-size, sky, -size}, {2 * size, sky, -size}, {2 * size, sky, 2 * size}, {-size, sky, 2 * size}},
         -Vec3::UnitY(), kLight, sky_group);
  int buildings = 0;
  for (int bi = 0; bi < blocks_x; ++bi)
    for (int bk = 0; bk < blocks_z; ++bk) {
      // Four buildings per block in its quarters, each inset from the quarter's edges.
      for (int q = 0; q < 4; ++q) {
        const double qx = street + bi * pitch + (q % 2) * block / 2, qz = street + bk * pitch + (q / 2) * block / 2;
        const double w = bay * (1 + static_cast<int>(rng.below(3))), d = bay * (1 + static_cast<int>(rng.below(3)));
        const double x0 = qx + rng.uniform(0.5, block / 2 - w - 0.5), z0 = qz + rng.uniform(0.5, block / 2 - d - 0.5);
        const double x1 = x0 + w, z1 = z0 + d;
        const int floors = 1 + static_cast<int>(rng.below(8));
        const double h = floors * storey;
        const int g = b.group(fmt::format("building_{}", buildings++));
        const int material = rng.below(2) == 0 ? kWall : kCardboard;
        for (int f = 0; f < floors; ++f) {
          const double y0 = f * storey, y1 = y0 + storey;
          for (double a = x0; a < x1 - 1e-9; a += bay) {
            b.quad({{a, y0, z0}, {a + bay, y0, z0}, {a + bay, y1, z0}, {a, y1, z0}}, -Vec3::UnitZ(), material, g);
            b.quad({{a, y0, z1}, {a + bay, y0, z1}, {a + bay, y1, z1}, {a, y1, z1}}, Vec3::UnitZ(), material, g);
          }
          for (double a = z0; a < z1 - 1e-9; a += bay) {
            b.quad({{x0, y0, a}, {x0, y0, a + bay}, {x0, y1, a + bay}, {x0, y1, a}}, -Vec3::UnitX(), material, g);
            b.quad({{x1, y0, a}, {x1, y0, a + bay}, {x1, y1, a + bay}, {x1, y1, a}}, Vec3::UnitX(), material, g);
          }
        }
        b.quad({{x0, h, z0}, {x1, h, z0}, {x1, h, z1}, {x0, h, z1}}, Vec3::UnitY(), kWood, g);
      }
    }
  s.room_size = Vec3(size_x, sky, size_z);
  return s;
}

}  // namespace

SceneLayout parse_scene_layout(std::string_view text) {
  if (text == "office") return SceneLayout::kOffice;
  if (text == "pillars") return SceneLayout::kPillars;
  if (text == "city") return SceneLayout::kCity;
  if (text == "shelves") return SceneLayout::kShelves;
  throw Error(fmt::format("--kind must be office, pillars, shelves, city or urban, got '{}'", text));
}

GeneratedScene generate_scene(const SceneGeneratorOptions& options) {
  const int n = options.polygons;
  if (n < kMinGeneratedPolygons || n > 10'000'000)
    throw Error(fmt::format("--polygons must be in [{}, 10000000], got {}", kMinGeneratedPolygons, n));
  if (options.layout == SceneLayout::kPillars) return pillar_hall(n);
  if (options.layout == SceneLayout::kShelves) return warehouse(n);
  if (options.layout == SceneLayout::kCity) {
    Rng city_rng(options.seed);
    return city(n, city_rng);
  }
  GeneratedScene s;
  s.materials = generated_materials();
  Builder b(s);
  Rng rng(options.seed);

  // About 44 polygons per cell on average (8 tiles and a group); size the floor for 36 per cell,
  // so that the groups exhaust the budget before the cells run out.
  const int cells = std::max(1, n / 36);
  const int nx = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(cells)))));
  const int nz = std::max(1, (cells + nx - 1) / nx);
  s.cells_x = nx;
  s.cells_z = nz;
  const double sx = nx * kCell, sz = nz * kCell;
  s.room_size = Vec3(sx, kHeight, sz);
  const Vec3 inside(sx / 2, kHeight / 2, sz / 2);

  // Room: 1.25 m tiles on floor and ceiling, 1.25 x 1.5 m on the walls, all facing inwards.
  const double t = kCell / 2;
  const int floor_group = b.group("floor"), ceiling_group = b.group("ceiling"), wall_group = b.group("walls"),
            light_group = b.group("lights");
  for (int i = 0; i < 2 * nx; ++i)
    for (int k = 0; k < 2 * nz; ++k) {
      const double x0 = i * t, x1 = (i + 1) * t, z0 = k * t, z1 = (k + 1) * t;
      b.quad({{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}, Vec3::UnitY(), kFloor, floor_group);
    }
  for (int i = 0; i < 2 * nx; ++i)
    for (int k = 0; k < 2 * nz; ++k) {
      const double x0 = i * t, x1 = (i + 1) * t, z0 = k * t, z1 = (k + 1) * t;
      // A light on the first tile of every other cell (checkerboard), at least one per room.
      const bool light = i % 2 == 0 && k % 2 == 0 && (i / 2 + k / 2) % 2 == 0;
      b.quad({{x0, kHeight, z0}, {x1, kHeight, z0}, {x1, kHeight, z1}, {x0, kHeight, z1}}, -Vec3::UnitY(),
             light ? kLight : kCeiling, light ? light_group : ceiling_group);
    }
  for (int row = 0; row < 2; ++row) {
    const double y0 = row * kHeight / 2, y1 = (row + 1) * kHeight / 2;
    for (int i = 0; i < 2 * nx; ++i) {
      const double x0 = i * t, x1 = (i + 1) * t;
      b.quad({{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}}, Vec3::UnitZ(), kWall, wall_group);
      b.quad({{x0, y0, sz}, {x1, y0, sz}, {x1, y1, sz}, {x0, y1, sz}}, -Vec3::UnitZ(), kWall, wall_group);
    }
    for (int k = 0; k < 2 * nz; ++k) {
      const double z0 = k * t, z1 = (k + 1) * t;
      b.quad({{0, y0, z0}, {0, y0, z1}, {0, y1, z1}, {0, y1, z0}}, Vec3::UnitX(), kWall, wall_group);
      b.quad({{sx, y0, z0}, {sx, y0, z1}, {sx, y1, z1}, {sx, y1, z0}}, -Vec3::UnitX(), kWall, wall_group);
    }
  }
  if (static_cast<int>(s.faces.size()) > n - 6)
    throw Error(fmt::format("--polygons {} is too few for a {} x {} cell room ({} tiles)", n, nx, nz, s.faces.size()));

  // Furniture: one group per cell, cells in a random order, until the budget is spent.
  std::vector<int> order(static_cast<std::size_t>(nx * nz));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[static_cast<std::size_t>(rng.below(i))]);
  int objects = 0;
  auto budget = [&] { return n - static_cast<int>(s.faces.size()); };
  for (const int cell : order) {
    if (budget() < 6) break;
    const double cx = (cell % nx + 0.5) * kCell, cz = (cell / nx + 0.5) * kCell;
    auto [name, parts] = furniture(rng, budget());
    if (parts.empty()) continue;
    const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const int g = b.group(fmt::format("{}_{}", name, objects++));
    for (const Box& part : parts) b.box(part, cx, cz, angle, g);
  }
  // Whatever is left (rare): 15 cm cubes in the cells' corners, outside every group's circle.
  for (int cell = 0; cell < nx * nz && budget() >= 6; ++cell) {
    const double cx = (cell % nx + 0.5) * kCell, cz = (cell / nx + 0.5) * kCell;
    for (const auto& [dx, dz] : {std::pair{0.95, 0.95}, {-1.1, 0.95}, {0.95, -1.1}, {-1.1, -1.1}}) {
      if (budget() < 6) break;
      const int g = b.group(fmt::format("cube_{}", objects++));
      b.box({dx, dx + 0.15, kFloorGap, 0.16, dz, dz + 0.15, kCardboard}, cx, cz, 0.0, g);
    }
  }
  static_assert(kGroupRadius < kCell / 2 - 0.1, "groups keep 10 cm from their cell's border");
  return s;
}

GeneratedScene triangulated(GeneratedScene g) {
  std::vector<GeneratedScene::Face> faces;
  faces.reserve(2 * g.faces.size());
  for (GeneratedScene::Face& f : g.faces) {
    if (f.vertices.size() <= 3) {
      faces.push_back(std::move(f));
      continue;
    }
    for (std::size_t k = 1; k + 1 < f.vertices.size(); ++k)
      faces.push_back({{f.vertices[0], f.vertices[k], f.vertices[k + 1]}, f.material, f.group});
  }
  g.faces = std::move(faces);
  return g;
}

Scene to_scene(const GeneratedScene& g) {
  Scene scene;
  scene.path = "generated";
  scene.materials = g.materials;
  scene.patches.reserve(g.faces.size());
  scene.faces.reserve(g.faces.size());
  for (const GeneratedScene::Face& f : g.faces) {
    Patch p;
    p.vertices = f.vertices;
    p.normal = newell_normal(f.vertices).normalized();
    p.area = polygon_area(f.vertices);
    p.material = f.material;
    p.face = static_cast<int>(scene.faces.size());
    p.group = g.groups[static_cast<std::size_t>(f.group)];
    scene.faces.push_back({p.group, f.material, 0, p.area, {static_cast<int>(scene.patches.size())}});
    scene.patches.push_back(std::move(p));
  }
  return scene;
}

std::string generated_mtl_path(const std::string& obj_path) {
  return std::filesystem::path(obj_path).replace_extension(".mtl").string();
}

void write_generated_scene(const GeneratedScene& g, const std::string& obj_path, const ProgressSink& progress_sink) {
  namespace fs = std::filesystem;
  const fs::path mtl = generated_mtl_path(obj_path);
  write_file_atomically(mtl.string(), [&](std::ostream& out) {
    out << "# hrad scene generate: materials\n";
    for (const Material& m : g.materials) {
      out << fmt::format("\nnewmtl {}\nKd {} {} {}\n", m.name, m.reflectance[0], m.reflectance[1], m.reflectance[2]);
      if (m.is_emitter()) out << fmt::format("Ke {} {} {}\n", m.emission[0], m.emission[1], m.emission[2]);
    }
  });
  write_file_atomically(obj_path, [&](std::ostream& out) {
    out << fmt::format("# hrad scene generate: {} polygons, {} x {} cells, room {} x {} x {} m\nmtllib {}\n",
                       g.faces.size(), g.cells_x, g.cells_z, g.room_size.x(), g.room_size.y(), g.room_size.z(),
                       mtl.filename().string());
    int group = -1, material = -1;
    ProgressReporter progress("scene generate: writing", g.faces.size(), "polygons", progress_sink);
    for (const GeneratedScene::Face& f : g.faces) {
      progress.advance();
      if (f.group != group) out << "\no " << g.groups[static_cast<std::size_t>(group = f.group)] << "\n";
      if (f.material != material)
        out << "usemtl " << g.materials[static_cast<std::size_t>(material = f.material)].name << "\n";
      for (const Vec3& v : f.vertices) out << fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
      out << "f";
      for (int k = static_cast<int>(f.vertices.size()); k >= 1; --k) out << " -" << k;
      out << "\n";
    }
    progress.finish();
  });
}

}  // namespace hrad
