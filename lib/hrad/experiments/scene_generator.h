// Scale scenes for benchmarks, sized to about a requested number of input polygons and
// deterministic in a seed. Four layouts:
//  * office: a closed, tiled room (an open-plan office) with ceiling lights and furniture built from
//    closed boxes (below);
//  * pillars: a closed hall whose floor and ceiling tiles are pierced by a grid of square pillars
//    from floor to ceiling, every pillar face tiled, lights in the ceiling: every shaft between two
//    surfaces crosses many occluders, as in halls and car parks;
//  * shelves: a closed warehouse with rows of shelving racks (uprights and shelves, closed boxes)
//    between aisles, lights in the ceiling;
//  * city: blocks of four box buildings each (walls tiled by storey, flat roofs) on a tiled ground
//    under an emitting sky quad, open at the sides like real city meshes.
//
// Layout: the floor is a grid of 2.5 m cells; floor and ceiling are tiled with 1.25 m quads, the
// walls with 1.25 x 1.5 m quads (3 m high), all facing into the room; every other cell's first
// ceiling tile (checkerboard) is a light. Each cell holds one furniture group (a table with legs
// and sometimes a monitor, a chair, a cabinet, or a stack of boxes), turned by a random angle about
// the vertical, every part a closed box with 6 outward faces, 1 cm above the floor and separated
// from the other parts by >= 5 mm. So every front face sees only front faces: the scene is closed
// (no light is lost through gaps or onto back faces), like the rooms of the closed-form tests.
#pragma once

#include "hrad/core/progress.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

enum class SceneLayout { kOffice, kPillars, kShelves, kCity };

struct SceneGeneratorOptions {
  int polygons = 1000;     ///< requested input polygons (>= kMinGeneratedPolygons)
  std::uint64_t seed = 1;  ///< the same seed and count give the same scene, bit for bit
  SceneLayout layout = SceneLayout::kOffice;
};

/// Parses "office" | "pillars" | "shelves" | "city"; hrad::Error naming --kind otherwise.
SceneLayout parse_scene_layout(std::string_view text);

/// Fewest polygons a generated room can have (a 1 x 1 cell room's tiles and one group).
inline constexpr int kMinGeneratedPolygons = 64;

/// A generated scene before it becomes a file or a Scene: quads with a material and a group name.
struct GeneratedScene {
  struct Face {
    std::vector<Vec3> vertices;  ///< counter-clockwise seen from the front
    int material = 0;
    int group = 0;  ///< index into groups
  };
  std::vector<Material> materials;
  std::vector<std::string> groups;
  std::vector<Face> faces;
  int cells_x = 0, cells_z = 0;   ///< the grid: an office's 2.5 m floor cells, a hall's tiles, a city's blocks
  Vec3 room_size = Vec3::Zero();  ///< the room is [0, x] x [0, y] x [0, z] (metres)
};

/// An office's polygon count lies in [polygons - kGeneratedPolygonSlack, polygons]. A pillar hall,
/// a warehouse and a city are whole grids (every pillar, rack row and block complete, so that the sizes of a layout
/// are alike): a grid sized for the request, within kGeneratedGridSlack of it (a city's buildings
/// have random storeys and footprints, 37 +- 22 faces each: at 1k polygons one standard deviation
/// of the count is ~10%, on top of the grid's step).
inline constexpr int kGeneratedPolygonSlack = 5;
inline constexpr double kGeneratedGridSlack = 0.4;

/// Generates the room. hrad::Error naming --polygons when options.polygons < kMinGeneratedPolygons
/// or > 10,000,000.
GeneratedScene generate_scene(const SceneGeneratorOptions& options);

/// Each face of more than three corners as a fan of triangles from its first corner, in its
/// orientation (the generated faces are convex): the scene as a triangle mesh, as exporters write
/// it (`hrad scene generate --triangles`).
GeneratedScene triangulated(GeneratedScene generated);

/// The same as a Scene (one patch per face, normals and areas computed), for benchmarks without files.
Scene to_scene(const GeneratedScene& generated);

/// The material library's path for `obj_path`: the same name with .mtl.
std::string generated_mtl_path(const std::string& obj_path);

/// Writes `obj_path` and the material library beside it (same stem, .mtl), each atomically.
void write_generated_scene(const GeneratedScene& generated, const std::string& obj_path,
                           const ProgressSink& progress = {});

}  // namespace hrad
