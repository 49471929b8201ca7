// hrad scene generate --polygons N [--kind office|pillars|shelves|city|urban] [--seed S] [--triangles]
//                     --out FILE.obj
//
// Writes a scale scene for benchmarks (lib/hrad/experiments/scene_generator.h), the same for the
// same N, kind and seed:
//   office   a closed, tiled open-plan office 3 m high with checkerboard ceiling lights and
//            furniture made of closed boxes (desks with chairs and monitors, tables, cabinets,
//            stacks of boxes, each turned at random), between N - 5 and N input polygons;
//   pillars  a closed 4 m hall with a grid of floor-to-ceiling pillars (one per 3 x 3 m), every
//            surface tiled, lights on a checkerboard of ceiling tiles: heavily occluded, about N;
//   shelves  a closed 6 m warehouse with rows of shelving racks (uprights and four shelves, closed
//            boxes) between 3 m aisles, lights on every other ceiling tile: heavily occluded, about N;
//   city     blocks of four box buildings each (walls tiled per storey and 5 m bay) on a tiled
//            ground under an emitting sky quad, open at the sides; every block built, about N;
//   urban    blocks of buildings on a ground, open and not watertight like city meshes
//            (lib/hrad/experiments/urban_generator.h), for view factors at scale, about N facets.
// The material library is written beside FILE.obj (same name, .mtl); both atomically.
//
//   --polygons N   input polygons wanted (64 .. 10,000,000)
//   --kind K       office (default), pillars, shelves, city or urban
//   --seed S       placement seed (default 1)
//   --triangles    each polygon as a fan of triangles (a triangle mesh, as exporters write it)
//   --out FILE     the OBJ file to write
#include <iostream>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/core/memory.h"
#include "hrad/experiments/scene_generator.h"
#include "hrad/experiments/urban_generator.h"
#include "hrad/io/atomic_file.h"
#include "seed_option.h"

namespace hrad::cli {

void add_scene_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("scene", "Scene utilities: generate scale scenes for benchmarks");
  cmd->require_subcommand(1);
  auto* gen = cmd->add_subcommand(
      "generate",
      "Write a scale scene (office, pillar hall, warehouse or city) with about N input polygons (OBJ + MTL)");
  struct Args {
    int polygons = 0;
    std::uint64_t seed = 1;
    std::string out, kind = "office";
    bool triangles = false;
  };
  auto args = std::make_shared<Args>();
  gen->add_option("--polygons", args->polygons, "Input polygons wanted (64 .. 10000000)")->required();
  gen->add_option("--seed", args->seed, "Placement seed (default 1)")->check(cli::seed_validator());
  gen->add_option("--kind", args->kind,
                  "office (default) | pillars (closed rooms) | shelves (a closed warehouse) | city (blocks under an "
                  "emitting sky) | urban (buildings on a ground, for view factors)");
  gen->add_option("--out", args->out, "OBJ file to write (the .mtl goes beside it)")->required();
  gen->add_flag("--triangles", args->triangles,
                "Write each polygon as triangles (a triangle mesh, as exporters write)");
  gen->callback([args] {
    if (args->out.empty()) throw Error("--out must name a file");
    // Each polygon holds its corners, group and material (~200 bytes) while the OBJ is written:
    // 512 bytes is an upper bound. Refused up front rather than std::bad_alloc.
    const double bytes = 512.0 * args->polygons * (args->triangles ? 2 : 1), available = available_memory_bytes();
    if (available > 0.0 && bytes > 0.8 * available)
      throw Error(fmt::format("--polygons: {} polygons need about {} and this process may use {}: ask for fewer",
                              args->polygons, format_bytes(bytes), format_bytes(available)));
    SceneGeneratorOptions o;
    o.polygons = args->polygons;
    o.seed = args->seed;
    if (args->kind != "urban") o.layout = parse_scene_layout(args->kind);
    OutputFiles outputs;
    outputs.declare("--out", args->out);
    outputs.declare("the material library beside --out", generated_mtl_path(args->out));
    const AllocationScope allocating(fmt::format("the {} generated polygons", args->polygons),
                                     "ask for fewer --polygons");
    GeneratedScene scene = args->kind == "urban" ? generate_urban({args->polygons, args->seed}) : generate_scene(o);
    if (args->triangles) scene = triangulated(std::move(scene));
    write_generated_scene(scene, args->out, [](std::string_view line) { std::cerr << "hrad " << line << "\n"; });
    outputs.commit();
    std::cout << fmt::format("{}: {} polygons, {} x {} cells, room {} x {} x {} m\n", args->out, scene.faces.size(),
                             scene.cells_x, scene.cells_z, scene.room_size.x(), scene.room_size.y(),
                             scene.room_size.z());
  });
}

}  // namespace hrad::cli
