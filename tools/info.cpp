// hrad info SCENE [--json]
//
// Reads a scene and prints its summary: patches, input faces, emitters, total area and the
// materials. With --json, the summary is a JSON object on stdout:
//   patches    number of patches (input faces after triangulation of non-planar/non-convex faces)
//   faces      one entry per input face in file order: line, group, material, area, patches
//   emitters   the faces whose material emits
//   area       total area, in the scene's unit squared
//   materials  {name: {reflectance: [r,g,b], emission: [r,g,b]}}
//   emission_units  {unit: "lm/m2" | "W/m2", declared_at: "file:line"}, when the scene declares it
// Warnings go to stderr: skipped or split faces, faces without a material, and what would make the
// answer look wrong (no emitter, lights exported without emission, normals facing out of the room,
// no light reaching any surface: core/scene_checks.h).
#include <iostream>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/scene_checks.h"
#include "hrad/io/near_faces.h"
#include "hrad/io/scene_json.h"
#include "hrad/io/scene_reader.h"

namespace hrad::cli {

void add_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Print a summary of a scene (OBJ + MTL, PLY or glTF)");
  struct Args {
    std::string scene;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SCENE", args->scene, "Scene file (.obj)")->required();
  cmd->add_flag("--json", args->json, "Print the summary as JSON");
  cmd->callback([args] {
    std::vector<std::string> warnings;
    // Read whole to name the near faces, then as the solvers read it (cut along them) for the summary.
    ObjReadOptions whole;
    whole.cut_near_faces = false;
    Scene scene = read_scene(args->scene, &warnings, whole);
    for (const std::string& w : warnings) std::cerr << w << "\n";
    for (const std::string& w : scene_warnings(scene)) std::cerr << scene.path << ": warning: " << w << "\n";
    if (const NearCuts near = find_near_faces(scene); near.pairs > 0) {
      const std::size_t before = scene.patches.size();
      Scene cut = read_scene(args->scene);
      const std::string note =
          near_faces_note(scene, near, cut.patches.size() > before ? cut.patches.size() - before : 0);
      if (!note.empty()) std::cerr << note << "\n";
      scene = std::move(cut);
    }
    const nlohmann::json j = scene_summary_json(scene);
    if (args->json) {
      std::cout << j.dump(2) << "\n";
      return;
    }
    std::cout << fmt::format("{}: {} input faces, {} patches, {} emitters, area {:.6g}\n", scene.path,
                             scene.faces.size(), scene.patches.size(), scene.emitter_count(), scene.total_area());
    if (scene.emission_units)
      std::cout << fmt::format("  emission in {} (declared at {})\n", to_string(scene.emission_units->units),
                               scene.emission_units->where);
    for (const Material& m : scene.materials)
      std::cout << fmt::format("  material {:<12} reflectance {:.4f} {:.4f} {:.4f}  emission {:.4g} {:.4g} {:.4g}\n",
                               m.name, m.reflectance[0], m.reflectance[1], m.reflectance[2], m.emission[0],
                               m.emission[1], m.emission[2]);
  });
}

}  // namespace hrad::cli
